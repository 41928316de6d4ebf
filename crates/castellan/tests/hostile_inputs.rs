//! Issue 19 as a hostile but fair user meets it, through the real binary: images over the pixel
//! budget, endless and mis-encoded text files, a JPEG cut short, a killed run's leftovers. Each
//! refusal names the file, exits non-zero and writes nothing.

use std::path::Path;

use assert_cmd::Command;

fn castellan() -> Command {
    Command::cargo_bin("castellan").unwrap()
}

/// A PGM header declaring 20 000 × 20 000 pixels and no pixel data: only the header may be read.
fn huge_image(dir: &Path) -> std::path::PathBuf {
    let p = dir.join("huge.pgm");
    std::fs::write(&p, b"P5\n20000 20000\n255\n").unwrap();
    p
}

fn nothing_but(dir: &Path, inputs: &[&str]) {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let mut want: Vec<String> = inputs.iter().map(|s| s.to_string()).collect();
    want.sort();
    assert_eq!(names, want, "a refused run wrote something");
}

#[test]
fn every_image_command_refuses_an_image_over_the_pixel_budget_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let img = huge_image(d);
    std::fs::write(d.join("t.json"), r#"{"classes":{"wall":[[0,0,5,5]]}}"#).unwrap();
    let runs: [&[&str]; 5] = [
        &["plan", "huge.pgm", "-o", "p.json"],
        &["corners", "huge.pgm", "-o", "c.json"],
        &["rectify", "huge.pgm", "-o", "r.png"],
        &["facade", "huge.pgm", "--training", "t.json", "-o", "f.json"],
        &["gothic", "huge.pgm", "-o", "g.json"],
    ];
    for args in runs {
        let out = castellan().current_dir(d).args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?}");
        assert!(
            err.contains("huge.pgm: 20000 × 20000 pixels (400.0 Mpx) is over castellan's pixel budget of 40 Mpx"),
            "{args:?}: {err}"
        );
        nothing_but(d, &["huge.pgm", "t.json"]);
    }
    assert!(img.exists());
}

#[test]
fn a_project_whose_plan_is_over_the_budget_is_refused_naming_the_entry() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    huge_image(d);
    std::fs::write(d.join("PROJECT.toml"), "plan = \"huge.pgm\"\n").unwrap();
    let out = castellan()
        .current_dir(d)
        .args(["reconstruct", "PROJECT.toml", "-o", "out"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("plan = \"huge.pgm\"") && err.contains("pixel budget"),
        "{err}"
    );
    nothing_but(d, &["huge.pgm", "PROJECT.toml"]);
}

#[cfg(unix)]
#[test]
fn reconstruct_of_dev_zero_is_refused_instead_of_filling_memory() {
    let dir = tempfile::tempdir().unwrap();
    let out = castellan()
        .current_dir(dir.path())
        .args(["reconstruct", "/dev/zero", "-o", "out"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("/dev/zero: larger than 16 MiB"), "{err}");
    nothing_but(dir.path(), &[]);
}

#[test]
fn a_project_in_another_encoding_is_refused_at_the_bad_byte() {
    let dir = tempfile::tempdir().unwrap();
    // Latin-1 "é" in a comment on line 2.
    std::fs::write(
        dir.path().join("PROJECT.toml"),
        b"plan = \"p.png\"\n# ch\xE2teau\n".as_slice(),
    )
    .unwrap();
    let out = castellan()
        .current_dir(dir.path())
        .args(["reconstruct", "PROJECT.toml", "-o", "out"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("PROJECT.toml:2:5: not UTF-8 text"), "{err}");
}

#[test]
fn a_truncated_jpeg_is_refused_not_decoded_as_grey() {
    let dir = tempfile::tempdir().unwrap();
    let img = image::RgbImage::from_fn(200, 150, |x, y| image::Rgb([x as u8, y as u8, 128]));
    let mut buf = std::io::Cursor::new(Vec::new());
    img.write_to(&mut buf, image::ImageFormat::Jpeg).unwrap();
    let bytes = buf.into_inner();
    std::fs::write(dir.path().join("cut.jpg"), &bytes[..bytes.len() / 2]).unwrap();
    let out = castellan()
        .current_dir(dir.path())
        .args(["corners", "cut.jpg", "-o", "c.json"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("cut.jpg: the JPEG file is cut short"), "{err}");
    nothing_but(dir.path(), &["cut.jpg"]);
}

/// A run killed with `kill -9` leaves its staging folder; the next run removes it and replaces
/// the output folder whole.
#[test]
fn the_next_run_cleans_up_what_a_killed_run_left() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plans");
    let plan = std::fs::read_dir(&src)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "png"))
        .expect("a bundled plan drawing");
    std::fs::create_dir(d.join("in")).unwrap();
    std::fs::copy(&plan, d.join("in/castle.png")).unwrap();
    // What a killed run leaves: a pid that no longer runs.
    let mut child = std::process::Command::new("true").spawn().unwrap();
    let dead = child.id();
    child.wait().unwrap();
    let staging = d.join(format!(".castellan-{dead}-out.new"));
    std::fs::create_dir(&staging).unwrap();
    std::fs::write(staging.join("summary.csv"), "half").unwrap();
    std::fs::write(d.join(format!(".castellan-{dead}-x1.tmp")), "half").unwrap();
    castellan()
        .current_dir(d)
        .args(["plan", "--batch", "in", "-o", "out"])
        .assert()
        .success();
    nothing_but(d, &["in", "out"]);
    let summary = std::fs::read_to_string(d.join("out/summary.csv")).unwrap();
    assert!(summary.contains("castle.png,true"), "{summary}");
}
