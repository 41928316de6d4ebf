//! Issue 22: every picture the single-stage commands write for a person carries its key, and
//! each index image (LABELS.png, MASONRY.png) has a view in colour beside it
//! (`NAME.view.png`).

mod fixtures;

use std::path::Path;

use assert_cmd::Command;
use image::RgbImage;

fn castellan() -> Command {
    Command::cargo_bin("castellan").unwrap()
}

/// The key's frame colour (`raster::legend`).
const FRAME: [u8; 3] = [60, 60, 60];

fn rgb(path: &Path) -> RgbImage {
    image::open(path).unwrap().to_rgb8()
}

/// With nothing to avoid, the key sits in the bottom-right corner: its frame ends there.
fn keyed_bottom_right(img: &RgbImage) -> bool {
    img.get_pixel(img.width() - 1, img.height() - 1).0 == FRAME
}

#[test]
fn plan_overlays_carry_the_key_and_labels_have_a_coloured_view() {
    let dir = tempfile::tempdir().unwrap();
    let input =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plans/sully-sur-loire.png");
    let out = |n: &str| dir.path().join(n);
    castellan()
        .arg("plan")
        .arg(&input)
        .arg("-o")
        .arg(out("plan.json"))
        .arg("--labels")
        .arg(out("labels.png"))
        .arg("--overlay")
        .arg(out("overlay.png"))
        .arg("--walls")
        .arg(out("walls.png"))
        .assert()
        .success();
    let labels = image::open(out("labels.png")).unwrap().to_luma8();
    let view = rgb(&out("labels.view.png"));
    assert_eq!(view.dimensions(), labels.dimensions());
    // Outside the key, each pixel is its label's colour.
    let colours: Vec<[u8; 3]> = plan::label::Label::ALL.iter().map(|l| l.color()).collect();
    let frame = |img: &RgbImage| img.pixels().filter(|p| p.0 == FRAME).count();
    let mut same = 0;
    for (x, y, l) in labels.enumerate_pixels() {
        same += usize::from(view.get_pixel(x, y).0 == colours[usize::from(l[0])]);
    }
    let (w, h) = labels.dimensions();
    assert!(same > (w * h) as usize * 9 / 10, "{same} of {}", w * h);
    // A key box's frame in each picture: at least its two long sides.
    for pic in [&view, &rgb(&out("overlay.png")), &rgb(&out("walls.png"))] {
        assert!(frame(pic) > 100, "{} frame pixels", frame(pic));
    }
}

#[test]
fn facade_labels_have_a_coloured_view_and_the_overlay_a_key() {
    let dir = tempfile::tempdir().unwrap();
    let img_path = dir.path().join("f.png");
    fixtures::facade_image().save(&img_path).unwrap();
    let training = dir.path().join("t.json");
    std::fs::write(
        &training,
        r#"{"classes": {"window": [[14, 27, 30, 43], [52, 62, 68, 78]], "wall": [[2, 50, 10, 58], [40, 17, 100, 23]], "background": [[5, 2, 115, 12]]}}"#,
    )
    .unwrap();
    let (labels, overlay) = (dir.path().join("l.png"), dir.path().join("o.png"));
    castellan()
        .arg("facade")
        .arg(&img_path)
        .arg("--training")
        .arg(&training)
        .arg("-o")
        .arg(dir.path().join("f.json"))
        .arg("--labels")
        .arg(&labels)
        .arg("--overlay")
        .arg(&overlay)
        .assert()
        .success();
    let view = rgb(&dir.path().join("l.view.png"));
    // The window at (20, 35) in the window colour, the background at (60, 5) in red.
    assert_eq!(view.get_pixel(20, 35).0, [0, 220, 0]);
    assert_eq!(view.get_pixel(60, 5).0, [255, 40, 40]);
    assert!(keyed_bottom_right(&view));
    assert!(keyed_bottom_right(&rgb(&overlay)));
}

#[test]
fn gothic_masonry_has_a_coloured_view_and_the_overlay_a_key() {
    let dir = tempfile::tempdir().unwrap();
    let img = dir.path().join("facade.png");
    facade::gothic::synth::synthetic_facade(&fixtures::gothic_bay(), 4)
        .image
        .save(&img)
        .unwrap();
    let (masonry, overlay) = (dir.path().join("m.png"), dir.path().join("o.png"));
    castellan()
        .arg("gothic")
        .arg(&img)
        .arg("-o")
        .arg(dir.path().join("g.json"))
        .arg("--masonry")
        .arg(&masonry)
        .arg("--overlay")
        .arg(&overlay)
        .assert()
        .success();
    let m = image::open(&masonry).unwrap().to_luma8();
    let view = rgb(&dir.path().join("m.view.png"));
    assert_eq!(view.dimensions(), m.dimensions());
    // Mortar (1) in yellow, stone (2) in grey, where the key is not.
    let at = |v: u8| m.enumerate_pixels().find(|(_, _, p)| p[0] == v).unwrap();
    let (x, y, _) = at(1);
    assert_eq!(view.get_pixel(x, y).0, [230, 200, 60]);
    let (x, y, _) = at(2);
    assert_eq!(view.get_pixel(x, y).0, [150, 150, 150]);
    assert!(keyed_bottom_right(&view));
    assert!(keyed_bottom_right(&rgb(&overlay)));
}

/// A photo too small for its key (under twice the key's size) is left without one; at twice
/// the fixture's size the line overlay has it.
#[test]
fn the_rectify_line_overlay_carries_its_key() {
    let dir = tempfile::tempdir().unwrap();
    let img_path = dir.path().join("photo.png");
    let photo = fixtures::facade_image();
    image::imageops::resize(&photo, 240, 180, image::imageops::FilterType::Nearest)
        .save(&img_path)
        .unwrap();
    let lines = dir.path().join("lines.json");
    std::fs::write(
        &lines,
        r#"{"horizontal": [[20, 40, 220, 50], [20, 140, 220, 136]], "vertical": [[40, 20, 44, 160], [200, 20, 196, 160]]}"#,
    )
    .unwrap();
    let overlay = dir.path().join("o.png");
    castellan()
        .arg("rectify")
        .arg(&img_path)
        .arg("-o")
        .arg(dir.path().join("r.png"))
        .arg("--lines")
        .arg(&lines)
        .arg("--overlay")
        .arg(&overlay)
        .assert()
        .success();
    let o = rgb(&overlay);
    assert_eq!(o.dimensions(), (240, 180));
    assert!(keyed_bottom_right(&o));
}
