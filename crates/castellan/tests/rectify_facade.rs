//! `castellan rectify` and `castellan facade` as a user runs them: outputs on success, one
//! clear message naming the file and no output on failure.

mod fixtures;

use assert_cmd::Command;
use image::{Rgb, RgbImage};
use std::path::Path;

fn castellan() -> Command {
    Command::cargo_bin("castellan").unwrap()
}

/// `castellan facade IMAGE --training TRAINING -o OUT`, for more flags to be added.
fn facade(image: &Path, training: &Path, out: &Path) -> Command {
    let mut cmd = castellan();
    cmd.arg("facade")
        .arg(image)
        .arg("--training")
        .arg(training)
        .arg("-o")
        .arg(out);
    cmd
}

/// The text a finished command wrote to stderr.
fn stderr(a: &assert_cmd::assert::Assert) -> String {
    String::from_utf8_lossy(&a.get_output().stderr).to_string()
}

#[test]
fn rectify_with_manual_lines_writes_every_output() {
    let dir = tempfile::tempdir().unwrap();
    let img_path = dir.path().join("photo.png");
    fixtures::facade_image().save(&img_path).unwrap();
    let lines = dir.path().join("lines.json");
    std::fs::write(
        &lines,
        r#"{"horizontal": [[10, 20, 110, 25], [10, 70, 110, 68]], "vertical": [[20, 10, 22, 80], [100, 10, 98, 80]]}"#,
    )
    .unwrap();
    let (out, h, ov) = (
        dir.path().join("r.png"),
        dir.path().join("h.json"),
        dir.path().join("o.png"),
    );
    castellan()
        .arg("rectify")
        .arg(&img_path)
        .arg("-o")
        .arg(&out)
        .arg("--lines")
        .arg(&lines)
        .arg("--homography")
        .arg(&h)
        .arg("--overlay")
        .arg(&ov)
        .assert()
        .success();
    let hj: serde_json::Value = serde_json::from_slice(&std::fs::read(&h).unwrap()).unwrap();
    let rows = hj["H"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    assert!(rows.iter().all(|r| r.as_array().unwrap().len() == 3));
    let r = image::open(&out).unwrap();
    assert_eq!(
        (r.width() as u64, r.height() as u64),
        (
            hj["width"].as_u64().unwrap(),
            hj["height"].as_u64().unwrap()
        )
    );
    assert_eq!(image::open(&ov).unwrap().width(), 120);
}

#[test]
fn rectify_of_a_single_colour_image_fails_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let img_path = dir.path().join("flat.png");
    RgbImage::from_pixel(64, 64, Rgb([90, 90, 90]))
        .save(&img_path)
        .unwrap();
    let out = dir.path().join("r.png");
    let a = castellan()
        .arg("rectify")
        .arg(&img_path)
        .arg("-o")
        .arg(&out)
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&a.get_output().stderr).to_string();
    assert!(err.contains("flat.png") && err.contains("--lines"), "{err}");
    assert!(!out.exists());
}

#[test]
fn facade_writes_the_model_labels_and_overlay() {
    let dir = tempfile::tempdir().unwrap();
    let img_path = dir.path().join("f.png");
    fixtures::facade_image().save(&img_path).unwrap();
    let training = dir.path().join("t.json");
    std::fs::write(
        &training,
        r#"{"classes": {"window": [[14, 27, 30, 43], [52, 62, 68, 78]], "wall": [[2, 50, 10, 58], [40, 17, 100, 23]], "background": [[5, 2, 115, 12]]}}"#,
    )
    .unwrap();
    let (out, labels, ov) = (
        dir.path().join("f.json"),
        dir.path().join("l.png"),
        dir.path().join("o.png"),
    );
    let assert = facade(&img_path, &training, &out)
        .arg("--labels")
        .arg(&labels)
        .arg("--overlay")
        .arg(&ov)
        .assert()
        .success();
    // A plausible model: nothing to warn about.
    let said = stderr(&assert);
    assert!(!said.contains("warning"), "{said}");
    let m: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(m["width"], 120);
    let f = &m["facades"][0];
    assert_eq!(f["bbox"].as_array().unwrap().len(), 4);
    assert_eq!(f["params"].as_object().unwrap().len(), 18);
    assert_eq!(f["params"]["n_w"], 3);
    let l = image::open(&labels).unwrap().to_luma8();
    assert_eq!(l.get_pixel(20, 35)[0], 2);
    assert_eq!(l.get_pixel(60, 5)[0], 0);
    assert!(ov.exists());
}

#[test]
fn facade_warns_when_the_windows_cover_most_of_the_facade() {
    // Dark glass-coloured everywhere but a pale strip down the left edge, where the only wall
    // box is: the map calls the façade window, and the model is said to be implausible while
    // every file is still written.
    let dir = tempfile::tempdir().unwrap();
    let img_path = dir.path().join("dark.png");
    let img = RgbImage::from_fn(120, 90, |x, y| {
        let n = ((x * 7 + y * 13) % 5) as u8;
        if x < 12 {
            Rgb([200 + n, 180 + n, 150 + n])
        } else {
            Rgb([50 + n, 60 + n, 80 + n])
        }
    });
    img.save(&img_path).unwrap();
    let training = dir.path().join("t.json");
    std::fs::write(
        &training,
        r#"{"classes": {"window": [[40, 30, 50, 40], [80, 50, 90, 60]], "wall": [[2, 20, 10, 70]]}}"#,
    )
    .unwrap();
    let out = dir.path().join("f.json");
    let said = stderr(&facade(&img_path, &training, &out).assert().success());
    assert!(
        said.contains("warning: the windows cover") && said.contains("add wall boxes"),
        "{said}"
    );
    assert!(out.exists());
}

#[test]
fn facade_rejects_boxes_outside_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let img_path = dir.path().join("f.png");
    fixtures::facade_image().save(&img_path).unwrap();
    let training = dir.path().join("bad.json");
    std::fs::write(
        &training,
        r#"{"classes": {"window": [[500, 500, 520, 520]], "wall": [[2, 50, 10, 58]]}}"#,
    )
    .unwrap();
    let out = dir.path().join("f.json");
    let err = stderr(&facade(&img_path, &training, &out).assert().failure());
    assert!(
        err.contains("bad.json") && err.contains("no pixels inside"),
        "{err}"
    );
    assert!(!out.exists());
}

/// Issue 22: `--fix` (the keys of `[facade.fix]`): a window removed is wall in the labels and
/// gone from FACADE.json.
#[test]
fn facade_honours_the_users_corrections() {
    let dir = tempfile::tempdir().unwrap();
    let img_path = dir.path().join("f.png");
    fixtures::facade_image().save(&img_path).unwrap();
    let training = dir.path().join("t.json");
    std::fs::write(
        &training,
        r#"{"classes": {"window": [[14, 27, 30, 43], [52, 62, 68, 78]], "wall": [[2, 50, 10, 58], [40, 17, 100, 23]], "background": [[5, 2, 115, 12]]}}"#,
    )
    .unwrap();
    let windows = |fix: Option<&str>| {
        let (out, labels) = (dir.path().join("f.json"), dir.path().join("l.png"));
        let mut cmd = facade(&img_path, &training, &out);
        cmd.arg("--labels").arg(&labels);
        if let Some(text) = fix {
            let path = dir.path().join("fix.json");
            std::fs::write(&path, text).unwrap();
            cmd.arg("--fix").arg(&path);
        }
        cmd.assert().success();
        let m: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
        let n: usize = m["facades"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|f| f["floors"].as_array().unwrap())
            .map(|fl| fl["windows"].as_array().unwrap().len())
            .sum();
        (
            n,
            image::open(&labels).unwrap().to_luma8().get_pixel(20, 35)[0],
        )
    };
    let (found, label) = windows(None);
    assert_eq!(label, 2, "a window at (20, 35)");
    let (fixed, label) = windows(Some(r#"{"remove_windows": [[20, 35]]}"#));
    assert_eq!((fixed, label), (found - 1, 1));
}
