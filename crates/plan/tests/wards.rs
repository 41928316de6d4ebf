//! Several enclosures (issue 11): a castle of two wards split by a cross wall, with a round
//! tower standing inside the larger ward against the cross wall, and letters and an arrow
//! drawn among the walls; and a castle with an inner ward whose towers bulge into the outer
//! bailey beside a free-standing building. Checks the further-ward rule ((5') of
//! `label::heuristics`), the inner-ward tower test ((4'), `inner_towers`) and the dropping of
//! marks (`binarize::drop_marks`).

use image::{DynamicImage, GrayImage, Luma};
use plan::label::Label;
use plan::synth::Canvas;

/// 400 × 300 sheet: enceinte (20..380) × (20..280) with 8-px walls, a cross wall at x 226..234
/// (wards of about 198 and 138 px wide), a ring tower (radii 12..22: a 10-px wall round a
/// room of radius 12, as thick as tower walls are) centred at (204, 150) inside the west ward
/// against the cross wall, a solid 8 × 12 "letter" in the west ward and a "north arrow" cross
/// in the east ward.
fn two_wards() -> GrayImage {
    GrayImage::from_fn(400, 300, |x, y| {
        let in_box =
            |x0: u32, x1: u32, y0: u32, y1: u32| (x0..=x1).contains(&x) && (y0..=y1).contains(&y);
        let enceinte = in_box(20, 380, 20, 280) && !in_box(28, 372, 28, 272);
        let cross = in_box(226, 234, 20, 280);
        let d = (f64::from(x) - 204.0).hypot(f64::from(y) - 150.0);
        let ring = (12.0..=22.0).contains(&d);
        let letter = in_box(80, 87, 60, 71);
        let arrow = in_box(299, 301, 73, 87) || in_box(293, 307, 79, 81);
        let ink = enceinte || (cross && d > 12.0) || ring || letter || arrow;
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
    let inner = parse(plan::Options::default());
    assert_eq!(inner.towers, 1, "warnings {:?}", inner.warnings);
    assert_eq!(inner.label_at(204, 150), Label::TowerRoom);
    // Without the inner-ward test the ring test takes it as a round tower standing free in
    // its ward (`tests/ring_towers.rs`); without both it is no tower.
    let rings_only = parse(plan::Options {
        inner_ward_towers: false,
        ..Default::default()
    });
    assert_eq!(rings_only.towers, 1);
    assert_eq!(rings_only.label_at(204, 150), Label::TowerRoom);
    let outer_only = parse(plan::Options {
        inner_ward_towers: false,
        ring_towers: false,
        ..Default::default()
    });
    assert_eq!(outer_only.towers, 0);
    assert_ne!(outer_only.label_at(204, 150), Label::TowerRoom);
}

#[test]
fn letters_and_arrows_are_dropped_and_are_no_walls() {
    // The rules threshold the letter and the arrow as ink; the marks step drops them.
    let rules = |drop_marks| {
        parse(plan::Options {
            ink: plan::ink::InkMethod::Rules,
            drop_marks,
            ..Default::default()
        })
    };
    let p = rules(true);
    assert!(p.pre.dropped_marks >= 2, "{:?}", p.pre);
    assert_eq!(p.label_at(83, 65), Label::Courtyard);
    assert_eq!(p.label_at(300, 80), Label::Courtyard);
    assert!(rules(false).label_at(83, 65).is_wall());
    // The learned wall ink does not read them as walls in the first place.
    let learned = parse(plan::Options::default());
    assert_eq!(learned.label_at(83, 65), Label::Courtyard);
    assert_eq!(learned.label_at(300, 80), Label::Courtyard);
}

/// Centres of the round towers on the inner ward's west wall.
const INNER_TOWERS: [(f64, f64); 3] = [(330.0, 170.0), (330.0, 260.0), (330.0, 350.0)];

/// 640 × 520 sheet: a square enceinte (60..580) × (60..460), 10-px walls, with round towers
/// (radius 30) at its corners; inside it, against nothing, an inner ward (340..530) ×
/// (110..410) whose west wall (x 340) carries three round towers (radius 22, 10-px ring,
/// centred 10 px in front of the wall) projecting into the outer bailey; and in the bailey a free-standing building of two rooms with 14-px
/// walls, (113..227) × (223..297), as round or square and as thick-walled as the towers.
fn inner_ward_with_building() -> GrayImage {
    let mut c = Canvas::new(640, 520);
    let enceinte = [(60.0, 60.0), (580.0, 60.0), (580.0, 460.0), (60.0, 460.0)];
    c.poly(&enceinte, 10.0);
    for q in enceinte {
        c.round_tower(q, 30.0, 10.0);
    }
    c.poly(
        &[
            (340.0, 110.0),
            (530.0, 110.0),
            (530.0, 410.0),
            (340.0, 410.0),
        ],
        10.0,
    );
    for q in INNER_TOWERS {
        c.round_tower(q, 22.0, 10.0);
    }
    c.poly(
        &[
            (120.0, 230.0),
            (220.0, 230.0),
            (220.0, 290.0),
            (120.0, 290.0),
        ],
        14.0,
    );
    c.wall((170.0, 230.0), (170.0, 290.0), 14.0);
    c.0
}

#[test]
fn the_towers_on_an_inner_ward_count_a_free_standing_building_does_not() {
    let opts = |inner_ward_towers, ring_towers| plan::Options {
        upsample_below: 0,
        close_gaps: false,
        inner_ward_towers,
        ring_towers,
        ..Default::default()
    };
    let image = DynamicImage::ImageLuma8(inner_ward_with_building());
    let p = plan::parse(&image, &opts(true, true)).unwrap();
    // The four corner towers of the enceinte (§5.1.6 (4)) and the three of the inner ward.
    assert_eq!(
        p.towers,
        4 + INNER_TOWERS.len(),
        "warnings {:?}",
        p.warnings
    );
    assert!(p.bulge_towers.is_empty(), "{:?}", p.bulge_towers);
    for (x, y) in INNER_TOWERS {
        assert_eq!(
            p.label_at(x as u32 - 6, y as u32),
            Label::TowerRoom,
            "({x}, {y})"
        );
    }
    for x in [145, 195] {
        assert_ne!(
            p.label_at(x, 260),
            Label::TowerRoom,
            "building room at x {x}"
        );
    }
    assert_eq!(p.label_at(200, 150), Label::Courtyard);
    // Without the inner-ward test and the ring test (which takes the inner ward's towers as
    // round towers standing free) only the corner towers count.
    let outer_only = plan::parse(&image, &opts(false, false)).unwrap();
    assert_eq!(outer_only.towers, 4);
    assert_ne!(outer_only.label_at(324, 170), Label::TowerRoom);
}
