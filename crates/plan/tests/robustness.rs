//! What real drawings add to the synthetic castle (issue 11): vault ribs drawn across the
//! round tower rooms. Each test parses with and without the step that copes with it, so it
//! shows both that the step is needed and that it works.

use image::{DynamicImage, GrayImage};
use plan::fit::Fit;
use plan::label::Label;
use plan::synth::{Canvas, castle};

/// With the rule chain (the thin-lines step is one of its clean-up steps), or with the
/// learned wall ink when `thin_lines` is `None`.
fn parse(img: &GrayImage, thin_lines: Option<f64>) -> plan::ParsedPlan {
    let opts = plan::Options {
        upsample_below: 0,
        thin_lines: thin_lines.unwrap_or(0.0),
        ink: if thin_lines.is_some() {
            plan::ink::InkMethod::Rules
        } else {
            plan::ink::InkMethod::Learned
        },
        ..Default::default()
    };
    plan::parse(&DynamicImage::ImageLuma8(img.clone()), &opts).unwrap()
}

/// Tower rooms that fit a circle.
fn round_tower_rooms(p: &plan::ParsedPlan) -> usize {
    p.faces
        .iter()
        .filter(|f| f.label == Label::TowerRoom)
        .filter(|f| matches!(f.shape, Some(Fit::Circle { .. })))
        .count()
}

/// The synthetic castle with two 3-px vault ribs (four wedges, each larger than a speck) across
/// each round tower room.
fn ribbed_castle() -> GrayImage {
    let (img, _) = castle(7, 1.0, 900, 700);
    let mut c = Canvas(img);
    for centre in [
        (200.0, 150.0),
        (600.0, 130.0),
        (620.0, 560.0),
        (230.0, 570.0),
    ] {
        c.ribs(centre, 27.0, 2, 3.0);
    }
    c.0
}

#[test]
fn vault_ribs_split_round_tower_rooms_unless_thin_lines_are_removed() {
    let img = ribbed_castle();
    let kept = parse(&img, Some(0.0));
    let removed = parse(&img, Some(plan::Options::default().thin_lines.max(0.25)));
    assert!(
        round_tower_rooms(&kept) < 4,
        "with ribs kept: {} round tower rooms",
        round_tower_rooms(&kept)
    );
    assert!(removed.pre.thin_line_pixels > 0);
    assert!(
        round_tower_rooms(&removed) >= 4,
        "with ribs removed: {} round tower rooms",
        round_tower_rooms(&removed)
    );
    assert_eq!(removed.towers, 6);
    assert_eq!(removed.label_at(200, 150), Label::TowerRoom);
}
