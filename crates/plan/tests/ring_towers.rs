//! Towers drawn as rings on a thick curtain ((5'') of `label::heuristics`, `ring_towers`;
//! issue 26): round towers that project from the curtain by less than one and a half wall
//! thicknesses, which §5.1.6 (4)'s bulge test misses, and a square room of the same size
//! against the inside of the curtain, which is no tower.

use image::DynamicImage;
use plan::label::Label;
use plan::synth::Canvas;

/// Centres of the ring towers on the north curtain (its centre line is y = 60).
const RINGS: [(f64, f64); 2] = [(200.0, 62.0), (380.0, 62.0)];

/// 560 × 400 sheet: a rectangular enceinte (60..500) × (60..340) with 12-px walls; two round
/// towers of outer radius 22 and a 10-px ring (room radius 12) centred 2 px inside the north
/// curtain's centre line, so that they project only 12 px beyond its outer face; and against
/// the inside of the south curtain a square closet 30 px wide with 3-px walls.
fn enceinte_with_rings() -> DynamicImage {
    let mut c = Canvas::new(560, 400);
    c.poly(
        &[(60.0, 60.0), (500.0, 60.0), (500.0, 340.0), (60.0, 340.0)],
        12.0,
    );
    for centre in RINGS {
        c.round_tower(centre, 22.0, 10.0);
    }
    c.poly(
        &[
            (270.0, 334.0),
            (270.0, 302.0),
            (304.0, 302.0),
            (304.0, 334.0),
        ],
        3.0,
    );
    DynamicImage::ImageLuma8(c.0)
}

/// The inner-ward test ((4'), `tests/wards.rs`) is off: it takes the closet, which projects
/// into the courtyard, for a tower of an inner ward.
fn parse(ring_towers: bool) -> plan::ParsedPlan {
    let opts = plan::Options {
        upsample_below: 0,
        ring_towers,
        inner_ward_towers: false,
        ..Default::default()
    };
    plan::parse(&enceinte_with_rings(), &opts).unwrap()
}

#[test]
fn rings_on_the_curtain_are_towers_a_room_against_it_is_not() {
    let p = parse(true);
    assert_eq!(p.towers, RINGS.len(), "warnings {:?}", p.warnings);
    assert_eq!(p.bulge_towers.len(), RINGS.len(), "{:?}", p.bulge_towers);
    for ((x, y), t) in RINGS.into_iter().zip(&p.bulge_towers) {
        assert_eq!(
            p.label_at(x as u32, y as u32),
            Label::TowerRoom,
            "({x}, {y})"
        );
        // The ring's outer arc, 17 px above the centre, is a tower wall.
        assert_eq!(
            p.label_at(x as u32, y as u32 - 17),
            Label::TowerWall,
            "({x}, {y})"
        );
        assert!((t.center[0] - x).hypot(t.center[1] - y) <= 1.0, "{t:?}");
        // The room's inset (12) and a curtain (12): the ring's outer radius 22 within 5 px.
        assert!((t.radius - 22.0).abs() <= 5.0, "{t:?}");
    }
    assert_ne!(p.label_at(287, 319), Label::TowerRoom);
}

#[test]
fn without_the_ring_test_the_rings_are_rooms_and_no_tower() {
    // §5.1.6 (4): the half-rings leave the curtain's chord by 12 px, under 1.5 walls (18).
    let p = parse(false);
    assert_eq!(p.towers, 0);
    assert!(p.bulge_towers.is_empty(), "{:?}", p.bulge_towers);
    for (x, y) in RINGS {
        assert_ne!(
            p.label_at(x as u32, y as u32),
            Label::TowerRoom,
            "({x}, {y})"
        );
    }
}

/// Centre of the free-standing round tower in `enceinte_with_keep`, and of the thin-walled
/// round room beside it.
const KEEP: (f64, f64) = (200.0, 200.0);
const THIN_ROUND_ROOM: (f64, f64) = (380.0, 200.0);

/// The same enceinte with no tower on its curtain; in its courtyard a round keep of outer
/// radius 30 and a 14-px ring (room radius 16), standing free, and a round room of the same
/// size with a 9-px wall (a well house, a stair), which is no tower.
fn enceinte_with_keep() -> DynamicImage {
    let mut c = Canvas::new(560, 400);
    c.poly(
        &[(60.0, 60.0), (500.0, 60.0), (500.0, 340.0), (60.0, 340.0)],
        12.0,
    );
    c.round_tower(KEEP, 30.0, 14.0);
    c.round_tower(THIN_ROUND_ROOM, 25.0, 9.0);
    DynamicImage::ImageLuma8(c.0)
}

#[test]
fn a_round_tower_standing_free_in_the_courtyard_is_a_tower_a_thin_round_room_is_not() {
    let opts = plan::Options {
        upsample_below: 0,
        ..Default::default()
    };
    let p = plan::parse(&enceinte_with_keep(), &opts).unwrap();
    assert_eq!(p.towers, 1, "warnings {:?}", p.warnings);
    let (x, y) = KEEP;
    assert_eq!(p.label_at(x as u32, y as u32), Label::TowerRoom);
    // The ring, 23 px from the centre, is the tower's wall.
    assert_eq!(p.label_at(x as u32 + 23, y as u32), Label::TowerWall);
    let t = &p.bulge_towers[0];
    assert!((t.center[0] - x).hypot(t.center[1] - y) <= 1.0, "{t:?}");
    let (x, y) = THIN_ROUND_ROOM;
    // A room (the largest left, so the great hall), not a tower's.
    assert_eq!(p.label_at(x as u32, y as u32), Label::GreatHall);
    // Without the ring test the keep's room is no tower's either.
    let p = plan::parse(
        &enceinte_with_keep(),
        &plan::Options {
            ring_towers: false,
            ..opts
        },
    )
    .unwrap();
    assert_eq!(p.towers, 0);
    assert_ne!(p.label_at(KEEP.0 as u32, KEEP.1 as u32), Label::TowerRoom);
}
