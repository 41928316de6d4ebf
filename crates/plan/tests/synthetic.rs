//! Plans drawn in the test: a curtain-wall polygon with round and square towers, a great hall,
//! a chapel and rooms, plus grid lines, text-like blobs and specks. Checks tower counts and
//! labels at known points.

use std::sync::OnceLock;

use image::{DynamicImage, GrayImage};
use plan::label::Label;
use plan::synth::castle;

/// Parsed at the drawing's own resolution (the enlargement of small drawings is exercised by
/// the crate example and `bad_input.rs`).
fn parse(img: GrayImage) -> plan::ParsedPlan {
    let opts = plan::Options {
        upsample_below: 0,
        ..Default::default()
    };
    plan::parse(&DynamicImage::ImageLuma8(img), &opts).unwrap()
}

/// One parse shared by the tests (a debug build parses a 900 × 700 sheet in a few seconds).
fn parsed() -> &'static (plan::ParsedPlan, plan::synth::Truth) {
    static P: OnceLock<(plan::ParsedPlan, plan::synth::Truth)> = OnceLock::new();
    P.get_or_init(|| {
        let (img, truth) = castle(7, 1.0, 900, 700);
        (parse(img), truth)
    })
}

#[test]
fn castle_towers_and_labels_at_known_points() {
    let (p, truth) = parsed();
    assert_eq!(p.towers, 6, "towers; warnings {:?}", p.warnings);
    let towers = p
        .faces
        .iter()
        .filter(|f| f.label == Label::TowerRoom)
        .count();
    assert_eq!(towers, 6);
    let wrong: Vec<_> = truth
        .iter()
        .filter(|(xy, l)| p.label_at(xy.0, xy.1) != *l)
        .map(|(xy, l)| (xy, l, p.label_at(xy.0, xy.1)))
        .collect();
    assert!(wrong.is_empty(), "{wrong:?}");
}

#[test]
fn round_tower_rooms_fit_circles() {
    let (p, _) = parsed();
    let circles = p
        .faces
        .iter()
        .filter(|f| f.label == Label::TowerRoom)
        .filter(|f| matches!(f.shape, Some(plan::fit::Fit::Circle { .. })))
        .count();
    assert!(
        circles >= 4,
        "{:?}",
        p.faces
            .iter()
            .map(|f| (&f.label, &f.shape))
            .collect::<Vec<_>>()
    );
}

#[test]
fn every_pixel_has_a_legend_label() {
    let (p, _) = parsed();
    assert_eq!(p.labels.len(), 900 * 700);
    assert!(p.labels.iter().all(|&l| (l as usize) < Label::ALL.len()));
    // Walls take wall labels, open space room labels.
    for (i, &l) in p.labels.iter().enumerate() {
        assert_eq!(
            Label::ALL[l as usize].is_wall(),
            p.walls.data[i] == 1,
            "pixel {i}"
        );
    }
}

#[test]
fn extrusion_program_runs_and_towers_stand_highest() {
    let (p, _) = parsed();
    let src = plan::extrude::to_vsg(p, &plan::scale::ModelScale::metric(0.1));
    let model = vsg::run(&src, &vsg::RunOptions::default()).unwrap();
    let stats = vsg::stats::Stats::of(&model, &vsg::shape::Tessellation::default());
    for name in [
        "tower_wall",
        "castle_outer_wall",
        "great_hall_wall",
        "tower_room",
    ] {
        assert!(
            stats.by_symbol.get(name).copied().unwrap_or(0) > 0,
            "{name}: {:?}",
            stats.by_symbol
        );
    }
    // The surroundings stay at ground level: never extruded.
    assert!(!stats.by_symbol.contains_key("castle_surroundings"));
    // Walls are boxes of their class height: 20 m towers (centre at 10 m), 12 m outer walls.
    assert!(src.contains(", 10.0000, ") && src.contains(", 6.0000, "));
}
