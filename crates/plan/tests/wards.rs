//! Several enclosures (issue 11): a castle of two wards split by a cross wall, with a round
//! tower standing inside the larger ward against the cross wall, and letters and an arrow
//! drawn among the walls. Checks the further-ward rule ((5') of `label::heuristics`), the
//! inner-ward tower test ((4')) and the dropping of marks (`binarize::drop_marks`).

use image::{DynamicImage, GrayImage, Luma};
use plan::label::Label;

/// 400 × 300 sheet: enceinte (20..380) × (20..280) with 8-px walls, a cross wall at x 226..234
/// (wards of about 198 and 138 px wide), a ring tower (radii 14..22) centred at (204, 150)
/// inside the west ward against the cross wall, a solid 8 × 12 "letter" in the west ward and
/// a "north arrow" cross in the east ward.
fn two_wards() -> GrayImage {
    GrayImage::from_fn(400, 300, |x, y| {
        let in_box =
            |x0: u32, x1: u32, y0: u32, y1: u32| (x0..=x1).contains(&x) && (y0..=y1).contains(&y);
        let enceinte = in_box(20, 380, 20, 280) && !in_box(28, 372, 28, 272);
        let cross = in_box(226, 234, 20, 280);
        let d = (f64::from(x) - 204.0).hypot(f64::from(y) - 150.0);
        let ring = (14.0..=22.0).contains(&d);
        let letter = in_box(80, 87, 60, 71);
        let arrow = in_box(299, 301, 73, 87) || in_box(293, 307, 79, 81);
        let ink = enceinte || (cross && d > 14.0) || ring || letter || arrow;
        Luma([if ink { 0 } else { 255 }])
    })
}

fn parse(opts: plan::Options) -> plan::ParsedPlan {
    let opts = plan::Options {
        upsample_below: 0,
        close_gaps: false,
        ..opts
    };
    plan::parse(&DynamicImage::ImageLuma8(two_wards()), &opts).unwrap()
}

#[test]
fn the_second_ward_is_a_courtyard_not_the_great_hall() {
    let p = parse(plan::Options::default());
    assert_eq!(p.label_at(120, 150), Label::Courtyard);
    assert_eq!(p.label_at(300, 150), Label::Courtyard);
    // As §5.1.6 has it (one courtyard), the second ward is the great hall.
    let one = parse(plan::Options {
        ward_ratio: 0.0,
        ..Default::default()
    });
    assert_eq!(one.label_at(120, 150), Label::Courtyard);
    assert_eq!(one.label_at(300, 150), Label::GreatHall);
}

#[test]
fn a_tower_inside_the_enceinte_is_a_tower_when_inner_wards_are_tested() {
    let inner = parse(plan::Options {
        inner_ward_towers: true,
        ..Default::default()
    });
    assert_eq!(inner.towers, 1, "warnings {:?}", inner.warnings);
    assert_eq!(inner.label_at(204, 150), Label::TowerRoom);
    let outer_only = parse(plan::Options::default());
    assert_eq!(outer_only.towers, 0);
    assert_ne!(outer_only.label_at(204, 150), Label::TowerRoom);
}

#[test]
fn letters_and_arrows_are_dropped_and_are_no_walls() {
    let p = parse(plan::Options::default());
    assert!(p.pre.dropped_marks >= 2, "{:?}", p.pre);
    assert_eq!(p.label_at(83, 65), Label::Courtyard);
    assert_eq!(p.label_at(300, 80), Label::Courtyard);
    let kept = parse(plan::Options {
        drop_marks: false,
        ..Default::default()
    });
    assert!(kept.label_at(83, 65).is_wall());
}
