//! The user's corrections of a parsed plan (issue 22, `plan::corrections`): relabelled
//! regions and their walls, towers added and removed, regions merged, and the errors that name
//! the entry; on a drawn castle whose answers are known.

use image::{DynamicImage, GrayImage, Luma};
use plan::corrections::{LabelFix, MergeFix, PlanFixes, TowerFix, apply};
use plan::label::Label;

/// 400 × 300 sheet: enceinte (20..380) × (20..280) with 8-px walls; a cross wall at x
/// 226..234 (two wards); in the east ward a room against the north wall, walls at x 300..308
/// and y 92..100 (open 308..372 × 28..92); a solid disc of ink, radius 14, at (212, 150)
/// against the cross wall (a tower drawn solid, which §5.1.6 prunes as a stub).
fn castle() -> GrayImage {
    GrayImage::from_fn(400, 300, |x, y| {
        let in_box =
            |x0: u32, x1: u32, y0: u32, y1: u32| (x0..=x1).contains(&x) && (y0..=y1).contains(&y);
        let enceinte = in_box(20, 380, 20, 280) && !in_box(28, 372, 28, 272);
        let cross = in_box(226, 234, 20, 280);
        let room = in_box(300, 308, 20, 100) || in_box(300, 380, 92, 100);
        let disc = (f64::from(x) - 212.0).hypot(f64::from(y) - 150.0) <= 14.0;
        Luma([if enceinte || cross || room || disc {
            0
        } else {
            255
        }])
    })
}

fn parsed() -> plan::ParsedPlan {
    parse(castle())
}

/// `drawing` parsed as these tests parse: the rule chain, at its own size.
fn parse(drawing: GrayImage) -> plan::ParsedPlan {
    let opts = plan::Options {
        upsample_below: 0,
        ink: plan::ink::InkMethod::Rules,
        ..Default::default()
    };
    plan::parse(&DynamicImage::ImageLuma8(drawing), &opts).unwrap()
}

const ROOM: [f64; 2] = [340.0, 60.0];
const ROOM_WALL: (u32, u32) = (304, 60);
const WEST: [f64; 2] = [80.0, 240.0];
const EAST: [f64; 2] = [300.0, 200.0];

#[test]
fn a_relabelled_room_takes_its_walls_with_it() {
    let mut p = parsed();
    assert_ne!(p.label_at(340, 60), Label::Chapel);
    let labels = [LabelFix {
        point: ROOM,
        label: Label::Chapel,
    }];
    let notes = apply(
        &mut p,
        PlanFixes {
            labels: &labels,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(notes.is_empty(), "{notes:?}");
    assert_eq!(p.label_at(340, 60), Label::Chapel);
    assert_eq!(p.label_at(ROOM_WALL.0, ROOM_WALL.1), Label::ChapelWall);
    // A point on the room's wall names the room too.
    let labels = [LabelFix {
        point: [ROOM_WALL.0 as f64 + 2.0, ROOM_WALL.1 as f64],
        label: Label::GreatHall,
    }];
    apply(
        &mut p,
        PlanFixes {
            labels: &labels,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(p.label_at(340, 60), Label::GreatHall);
    assert_eq!(p.label_at(ROOM_WALL.0, ROOM_WALL.1), Label::GreatHallWall);
}

#[test]
fn a_wall_label_goes_on_the_wall_at_the_point() {
    let mut p = parsed();
    let labels = [LabelFix {
        point: [ROOM_WALL.0 as f64, ROOM_WALL.1 as f64],
        label: Label::ChapelWall,
    }];
    apply(
        &mut p,
        PlanFixes {
            labels: &labels,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(p.label_at(ROOM_WALL.0, ROOM_WALL.1), Label::ChapelWall);
    // The room itself keeps its label.
    assert_eq!(p.label_at(340, 60), Label::TowerRoom);
}

/// Labels have the last word (issue 22's simulated user found corrections undoing others): a
/// wall's label survives the relabelling of its region and a tower added beside it, and a
/// region's label survives a tower removed there.
#[test]
fn the_users_labels_outlast_towers_and_region_labels() {
    let mut p = parsed();
    let wall = [ROOM_WALL.0 as f64, ROOM_WALL.1 as f64];
    // In the list, the wall's label comes before its room's; the tower entries after both.
    let labels = [
        LabelFix {
            point: wall,
            label: Label::ChapelWall,
        },
        LabelFix {
            point: ROOM,
            label: Label::GreatHall,
        },
    ];
    let towers = [TowerFix {
        point: ROOM,
        radius: None,
        remove: true,
    }];
    apply(
        &mut p,
        PlanFixes {
            labels: &labels,
            towers: &towers,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(p.label_at(340, 60), Label::GreatHall);
    assert_eq!(p.label_at(ROOM_WALL.0, ROOM_WALL.1), Label::ChapelWall);
    // A tower added in the room: the room's own label still wins, and so does its wall's.
    let towers = [TowerFix {
        point: ROOM,
        radius: None,
        remove: false,
    }];
    let mut q = parsed();
    apply(
        &mut q,
        PlanFixes {
            labels: &labels,
            towers: &towers,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(q.label_at(340, 60), Label::GreatHall);
    assert_eq!(q.label_at(ROOM_WALL.0, ROOM_WALL.1), Label::ChapelWall);
}

#[test]
fn errors_name_the_entry_and_what_is_wrong() {
    let mut p = parsed();
    let labels = [
        LabelFix {
            point: ROOM,
            label: Label::Chapel,
        },
        LabelFix {
            point: [500.0, 10.0],
            label: Label::Chapel,
        },
    ];
    let e = apply(
        &mut p,
        PlanFixes {
            labels: &labels,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "[[label]] #2: point [500, 10] is outside the plan (400 × 300 px)"
    );
    let wall = [LabelFix {
        point: ROOM,
        label: Label::CastleOuterWall,
    }];
    // A wall's label goes on a wall: in the room's open space there is none.
    let e = apply(
        &mut parsed(),
        PlanFixes {
            labels: &wall,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(
        e.to_string().starts_with(
            "[[label]] #1: castle_outer_wall is a wall's label and [340, 60] is on no wall"
        ),
        "{e}"
    );
    let open = [TowerFix {
        point: [160.0, 230.0],
        radius: None,
        remove: false,
    }];
    let e = apply(
        &mut parsed(),
        PlanFixes {
            towers: &open,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("give the tower's radius"), "{e}");
}

#[test]
fn towers_are_removed_and_added_in_a_room_or_on_solid_ink() {
    let mut p = parsed();
    // §5.1.6 takes the corner room for a tower, and prunes the disc.
    assert_eq!(p.label_at(340, 60), Label::TowerRoom);
    assert_eq!((p.towers, p.bulge_towers.len()), (1, 0));
    let tower = |point, remove| TowerFix {
        point,
        radius: None,
        remove,
    };
    let remove = [tower(ROOM, true), tower(WEST, true)];
    let notes = apply(
        &mut p,
        PlanFixes {
            towers: &remove,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(p.towers, 0);
    assert_eq!(p.label_at(340, 60), Label::UnknownRoom);
    assert_eq!(p.label_at(ROOM_WALL.0, ROOM_WALL.1), Label::UnknownWall);
    assert_eq!(
        notes,
        vec!["[[tower]] #2: no tower at [80, 240] to remove (already gone)".to_string()]
    );

    let add = [tower(ROOM, false), tower([211.0, 151.0], false)];
    apply(
        &mut p,
        PlanFixes {
            towers: &add,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(p.towers, 2);
    assert_eq!(p.label_at(340, 60), Label::TowerRoom);
    assert_eq!(p.label_at(ROOM_WALL.0, ROOM_WALL.1), Label::TowerWall);
    let solid = &p.bulge_towers[0];
    assert_eq!(solid.center, [211.0, 151.0]);
    // The disc's radius, measured on the ink from a point near its centre.
    assert!((solid.radius - 14.0).abs() <= 2.0, "{}", solid.radius);
    apply(
        &mut p,
        PlanFixes {
            towers: &[tower([212.0, 150.0], true)],
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!((p.towers, p.bulge_towers.len()), (1, 0));
}

#[test]
fn a_tower_with_a_radius_is_that_circle() {
    let mut p = parsed();
    let towers = [TowerFix {
        point: ROOM,
        radius: Some(30.0),
        remove: false,
    }];
    apply(
        &mut p,
        PlanFixes {
            towers: &towers,
            ..Default::default()
        },
    )
    .unwrap();
    let f = plan::corrections::region_at(&p, ROOM).unwrap();
    match p.faces[f].shape {
        Some(plan::fit::Fit::Circle { center, radius, .. }) => {
            assert_eq!(center, ROOM);
            // The outer radius less half the room's wall (8 px).
            assert!((radius - 26.0).abs() < 1.5, "{radius}");
        }
        ref other => panic!("{other:?}"),
    }
}

#[test]
fn merged_wards_are_one_region_without_the_wall_between() {
    let mut p = parsed();
    let (faces, edges) = (p.faces.len(), p.edges.len());
    let west = plan::corrections::region_at(&p, WEST).unwrap();
    let area = p.faces[west].area + p.faces[plan::corrections::region_at(&p, EAST).unwrap()].area;
    let merges = [MergeFix {
        points: [WEST, EAST],
    }];
    apply(
        &mut p,
        PlanFixes {
            merges: &merges,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(p.faces.len(), faces - 1);
    assert!(p.edges.len() < edges);
    let merged = plan::corrections::region_at(&p, WEST).unwrap();
    assert_eq!(plan::corrections::region_at(&p, EAST), Some(merged));
    assert_eq!(p.faces[merged].area, area);
    // The cross wall's pixels belong to the merged ward.
    assert_eq!(p.label_at(230, 200), p.faces[merged].label);
    for f in &p.faces {
        assert!(f.edges.iter().all(|&e| e < p.edges.len()));
    }
    // Regions that share no wall do not merge.
    let apart = [MergeFix {
        points: [WEST, ROOM],
    }];
    let e = apply(
        &mut parsed(),
        PlanFixes {
            merges: &apart,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(e.to_string().starts_with("[[merge]] #1: the "), "{e}");
    assert!(e.to_string().contains("share no wall"), "{e}");
}

/// A region's label given on the ink beside a region the user labelled from inside goes to the
/// region across the wall (issue 22's simulated user: a tower point on its wall's ink had
/// relabelled the courtyard just labelled).
#[test]
fn a_label_on_the_ink_beside_a_labelled_region_goes_across_the_wall() {
    let mut p = parsed();
    let east = plan::corrections::region_at(&p, EAST).unwrap();
    let room = plan::corrections::region_at(&p, ROOM).unwrap();
    assert_ne!(east, room);
    let labels = [
        LabelFix {
            point: ROOM,
            label: Label::Chapel,
        },
        // On the wall's ink, nearer the room (x 309..) than the east ward (..299).
        LabelFix {
            point: [306.0, ROOM_WALL.1 as f64],
            label: Label::GreatHall,
        },
    ];
    apply(
        &mut p,
        PlanFixes {
            labels: &labels,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(p.label_at(340, 60), Label::Chapel);
    assert_eq!(p.faces[east].label, Label::GreatHall);
}

/// The parse's tower warnings follow the corrections: "no towers" goes with the tower the user
/// adds, and the warning about tower walls too long comes and goes with the walls the user
/// labels.
#[test]
fn tower_warnings_are_said_again_after_the_corrections() {
    let no_towers = "no towers found on the outer wall";
    let long = "tower walls too long to be one tower";
    let says = |p: &plan::ParsedPlan, what: &str| p.warnings.iter().any(|w| w.starts_with(what));
    // The castle without its corner room: no tower (the disc is pruned as a stub).
    let mut bare = castle();
    for (x, y, px) in bare.enumerate_pixels_mut() {
        let room = (300..=308).contains(&x) && (29..=100).contains(&y)
            || (300..=371).contains(&x) && (92..=100).contains(&y);
        if room {
            *px = Luma([255]);
        }
    }
    let mut p = parse(bare);
    assert_eq!(p.towers, 0);
    assert!(says(&p, no_towers), "{:?}", p.warnings);
    let tower = [TowerFix {
        point: [211.0, 151.0],
        radius: None,
        remove: false,
    }];
    let fixes = PlanFixes {
        towers: &tower,
        ..Default::default()
    };
    apply(&mut p, fixes).unwrap();
    assert_eq!(p.towers, 1);
    assert!(!says(&p, no_towers), "{:?}", p.warnings);

    // The whole south curtain (360 px, 8 thick) labelled tower wall is one long tower.
    let mut p = parsed();
    assert!(!says(&p, long), "{:?}", p.warnings);
    let south = |label| {
        [LabelFix {
            point: [120.0, 276.0],
            label,
        }]
    };
    let as_tower = south(Label::TowerWall);
    let fixes = PlanFixes {
        labels: &as_tower,
        ..Default::default()
    };
    apply(&mut p, fixes).unwrap();
    assert!(says(&p, long), "{:?}", p.warnings);
    let as_curtain = south(Label::CastleOuterWall);
    let fixes = PlanFixes {
        labels: &as_curtain,
        ..Default::default()
    };
    apply(&mut p, fixes).unwrap();
    assert!(!says(&p, long), "{:?}", p.warnings);
}
