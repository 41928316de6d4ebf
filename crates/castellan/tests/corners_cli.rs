//! `castellan corners` and `castellan corners-eval` as a user runs them: CORNERS.json and the
//! overlay appear on success; bad input gives one clear message and no output file.

use std::path::Path;

use assert_cmd::Command;

fn castellan() -> Command {
    Command::cargo_bin("castellan").unwrap()
}

/// A bright axis-aligned square (pixels x0..x1, y0..y1) on a dark background.
fn square(w: u32, h: u32, x0: u32, y0: u32, side: u32) -> image::GrayImage {
    image::GrayImage::from_fn(w, h, |x, y| {
        let inside = (x0..x0 + side).contains(&x) && (y0..y0 + side).contains(&y);
        image::Luma([if inside { 210 } else { 40 }])
    })
}

fn corners_json(path: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

#[test]
fn writes_corners_json_and_overlay() {
    let dir = tempfile::tempdir().unwrap();
    let img = dir.path().join("sq.png");
    square(80, 60, 20, 15, 30).save(&img).unwrap();
    let out = dir.path().join("out/c.json");
    let overlay = dir.path().join("out/o.png");
    castellan()
        .arg("corners")
        .arg(&img)
        .arg("-o")
        .arg(&out)
        .arg("--overlay")
        .arg(&overlay)
        .assert()
        .success();
    let v = corners_json(&out);
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64()),
        (Some(80), Some(60))
    );
    let cs = v["corners"].as_array().unwrap();
    assert_eq!(cs.len(), 4);
    for c in cs {
        for key in ["x", "y", "epsilon", "lambda", "delta", "psi"] {
            assert!(c[key].is_number(), "{key} in {c}");
        }
        let d = c["directions"].as_array().unwrap();
        assert_eq!(d.len(), 2);
        let (dx, dy) = (d[0][0].as_f64().unwrap(), d[0][1].as_f64().unwrap());
        assert!(((dx * dx + dy * dy) - 1.0).abs() < 1e-9);
    }
    let o = image::open(&overlay).unwrap();
    assert_eq!((o.width(), o.height()), (80, 60));
}

#[test]
fn sixteen_bit_and_rgba_images_are_converted() {
    let dir = tempfile::tempdir().unwrap();
    let g = square(80, 60, 20, 15, 30);
    let g16: image::ImageBuffer<image::Luma<u16>, Vec<u16>> =
        image::ImageBuffer::from_fn(80, 60, |x, y| {
            image::Luma([g.get_pixel(x, y)[0] as u16 * 257])
        });
    let p16 = dir.path().join("g16.png");
    g16.save(&p16).unwrap();
    let prgba = dir.path().join("rgba.png");
    image::DynamicImage::ImageLuma8(g)
        .to_rgba8()
        .save(&prgba)
        .unwrap();
    for p in [p16, prgba] {
        let out = dir.path().join("c.json");
        castellan()
            .arg("corners")
            .arg(&p)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        assert_eq!(
            corners_json(&out)["corners"].as_array().unwrap().len(),
            4,
            "{}",
            p.display()
        );
    }
}

#[test]
fn tiny_and_edgeless_images_give_no_corners() {
    let dir = tempfile::tempdir().unwrap();
    for (name, w, h) in [("one.png", 1, 1), ("flat.png", 50, 40)] {
        let p = dir.path().join(name);
        image::GrayImage::from_pixel(w, h, image::Luma([128]))
            .save(&p)
            .unwrap();
        let out = dir.path().join("c.json");
        castellan()
            .arg("corners")
            .arg(&p)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        let v = corners_json(&out);
        assert_eq!(v["corners"].as_array().unwrap().len(), 0);
        assert_eq!(v["width"].as_u64(), Some(w as u64));
    }
}

#[test]
fn unreadable_files_fail_with_their_name_and_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("not_an_image.png");
    std::fs::write(&bad, b"hello").unwrap();
    let missing = dir.path().join("missing.png");
    for p in [bad, missing] {
        let out = dir.path().join("c.json");
        let assert = castellan()
            .arg("corners")
            .arg(&p)
            .arg("-o")
            .arg(&out)
            .assert()
            .failure();
        let err = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
        assert!(
            err.contains(&*p.file_name().unwrap().to_string_lossy()),
            "{err}"
        );
        assert!(!out.exists());
    }
}

#[test]
fn eval_on_a_shifted_sequence_with_peers() {
    // img_k is img1 moved by (3k, 2k): H1tokp is that translation. IPFIT finds the same four
    // corners every time; a fake peer with one stray point per image scores 4 of 5.
    let dir = tempfile::tempdir().unwrap();
    let seq = dir.path().join("shift");
    std::fs::create_dir(&seq).unwrap();
    let peers = dir.path().join("peers");
    std::fs::create_dir(&peers).unwrap();
    let mut fake = Vec::new();
    for k in 1..=3u32 {
        let (dx, dy) = (3 * (k - 1), 2 * (k - 1));
        square(120, 100, 30 + dx, 25 + dy, 40)
            .save(seq.join(format!("img{k}.png")))
            .unwrap();
        if k > 1 {
            std::fs::write(
                seq.join(format!("H1to{k}p")),
                format!("1 0 {dx}\n0 1 {dy}\n0 0 1\n"),
            )
            .unwrap();
        }
        let (x, y) = ((30 + dx) as f64 - 0.5, (25 + dy) as f64 - 0.5);
        let stray = [10.0 + 30.0 * k as f64, 90.0];
        fake.push(vec![
            [x, y],
            [x + 40.0, y],
            [x, y + 40.0],
            [x + 40.0, y + 40.0],
            stray,
        ]);
    }
    let peer =
        serde_json::json!({"detectors": {"Fake": fake}, "time_ms": {"Fake": [1.0, 1.0, 1.0]}});
    std::fs::write(peers.join("shift.json"), peer.to_string()).unwrap();
    let out = dir.path().join("eval");
    castellan()
        .arg("corners-eval")
        .arg(&seq)
        .arg("-o")
        .arg(&out)
        .arg("--peers")
        .arg(&peers)
        .args(["--threads", "1", "--overlays", "0.5"])
        .assert()
        .success();
    let csv = std::fs::read_to_string(out.join("repeatability.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), 6);
    for r in &rows {
        let rate = r[10];
        match (r[1], r[2]) {
            (_, "1") => assert_eq!(rate, ""),
            ("IPFIT", _) => assert_eq!((r[5], rate), ("4", "1.0000"), "{r:?}"),
            ("Fake", _) => assert_eq!(rate, "0.8000", "{r:?}"),
            other => panic!("unexpected row {other:?}"),
        }
    }
    let md = std::fs::read_to_string(out.join("repeatability.md")).unwrap();
    assert!(md.contains("| shift | 1.000 | 0.800 |"), "{md}");
    assert!(image::open(out.join("shift.png")).is_ok());
    assert_eq!(
        image::open(out.join("shift_overlay.png")).unwrap().width(),
        60
    );
}

#[test]
fn eval_without_homographies_fails_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let seq = dir.path().join("seq");
    std::fs::create_dir(&seq).unwrap();
    for k in 1..=2 {
        square(40, 40, 10, 10, 20)
            .save(seq.join(format!("img{k}.png")))
            .unwrap();
    }
    let out = dir.path().join("eval");
    let assert = castellan()
        .arg("corners-eval")
        .arg(&seq)
        .arg("-o")
        .arg(&out)
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(err.contains("H1to2p"), "{err}");
    assert!(!out.exists());
}
