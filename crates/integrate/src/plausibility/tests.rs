//! The plausibility checks' thresholds on literal plans and estimates.

use super::*;
use crate::estimate::{Kind, MappedFacade, PlanSource, Provenance, Side, WindowColumns};
use plan::scale::ModelScale;
use std::collections::BTreeMap;

/// A 100 × 80 plan whose built area is the box [x0, x1) × [y0, y1), with `edges` walls.
fn plan(edges: usize, built: [usize; 4]) -> ParsedPlan {
    let (w, h) = (100u32, 80u32);
    let mut labels = vec![Label::CastleSurroundings as u8; (w * h) as usize];
    for y in built[1]..built[3] {
        for x in built[0]..built[2] {
            labels[y * w as usize + x] = Label::Courtyard as u8;
        }
    }
    ParsedPlan {
        edges: (0..edges)
            .map(|_| plan::PlanEdge {
                from: 0,
                to: 0,
                label: Label::CastleOuterWall,
                points: vec![],
                fit: None,
                thickness: 3.0,
            })
            .collect(),
        labels,
        ..ParsedPlan::empty(w, h)
    }
}

fn structure(id: &str, role: Role, radius: f64, height: f64, source: &str) -> Structure {
    let mut provenance = BTreeMap::new();
    provenance.insert(
        "height".to_string(),
        Provenance::new(source, "test height", None),
    );
    Structure {
        id: id.into(),
        label: Label::TowerRoom,
        role,
        kind: Kind::HollowCylindrical,
        footprint: Footprint::Circle {
            center: [0.0, 0.0],
            radius,
        },
        height,
        wall_thickness: 1.0,
        facades: vec![],
        roof: None,
        crenellated: None,
        children: vec![],
        provenance,
    }
}

fn mapped(image: &str) -> MappedFacade {
    MappedFacade {
        image: image.into(),
        side: Side::Arc,
        arc: None,
        scale: 1.0,
        height_factor: 1.0,
        width: 10.0,
        height: 30.0,
        floors: vec![],
        windows: WindowColumns {
            count: 0,
            offset: 0.0,
            width: 0.0,
            gap: 0.0,
        },
        joint: false,
        bbox: [0.0, 0.0, 10.0, 30.0],
        texture: None,
        gothic: None,
    }
}

fn estimate(structures: Vec<Structure>) -> Estimate {
    Estimate {
        scale: ModelScale::metric(1.0),
        plan: PlanSource {
            image: "plan.png".into(),
            width: 100,
            height: 80,
            towers: 0,
        },
        structures,
        assumptions: vec![],
    }
}

fn agreement(recall: f64) -> Agreement {
    Agreement {
        iou: recall,
        precision: 1.0,
        recall,
        plan_pixels: 1000,
        model_pixels: (1000.0 * recall) as usize,
        overlap_pixels: (1000.0 * recall) as usize,
        missed_by_label: [0; 11],
        spilled_by_structure: Vec::new(),
        rooms: vec![],
        towers: vec![],
    }
}

/// A measured tower (photo) 20 across among default towers of 15 and a default keep.
fn castle(tower_height: f64) -> Vec<Structure> {
    let mut measured = structure("tower1", Role::Tower, 10.0, tower_height, "tower.jpg");
    measured.facades.push(mapped("tower.jpg"));
    vec![
        measured,
        structure("tower2", Role::Tower, 10.0, 15.0, "default"),
        structure("keep1", Role::Keep, 16.0, 1.5 * tower_height, "default"),
    ]
}

#[test]
fn a_plan_without_walls_warns_once_and_names_the_drawing() {
    let p = plan(0, [0, 0, 0, 0]);
    let w = plan_warnings(&p, "rochester.png", &ScaleNote::Given, Units::Metres, 0.5);
    assert_eq!(
        w,
        vec![Warning::NoWalls {
            plan: "rochester.png".into()
        }]
    );
    let text = w[0].to_string();
    assert!(text.starts_with("no walls were read from rochester.png: is it a castle plan?"));
    assert!(text.contains("ink = \"rules\""), "{text}");
    // The model checks add nothing to it.
    assert!(model_warnings(&p, &estimate(vec![]), &agreement(0.0)).is_empty());
}

#[test]
fn walls_without_structures_warn() {
    let p = plan(4, [10, 10, 60, 60]);
    assert_eq!(
        model_warnings(&p, &estimate(vec![]), &agreement(0.0)),
        vec![Warning::NoStructures {
            plan: "plan.png".into()
        }]
    );
}

#[test]
fn most_of_the_ink_unbuilt_warns_below_half_the_recall() {
    let p = plan(4, [10, 10, 60, 60]);
    let e = estimate(vec![structure("tower1", Role::Tower, 5.0, 15.0, "default")]);
    assert!(model_warnings(&p, &e, &agreement(0.5)).is_empty());
    let w = model_warnings(&p, &e, &agreement(0.38));
    assert_eq!(
        w,
        vec![Warning::InkLeftUnbuilt {
            plan: "plan.png".into(),
            recall: 0.38
        }]
    );
    assert!(
        w[0].to_string()
            .starts_with("only 38 % of plan.png's built area")
    );
}

#[test]
fn masses_of_wall_over_15_percent_of_the_model_warn_and_name_the_largest() {
    let p = plan(4, [10, 10, 60, 60]);
    let mass = |id: &str, side: f64| Structure {
        role: Role::Mass,
        footprint: Footprint::Blocks {
            rotation: 0.0,
            blocks: vec![crate::estimate::Block {
                center: [0.0, 0.0],
                size: [side, side],
            }],
        },
        ..structure(id, Role::Mass, 1.0, 6.0, "default")
    };
    // A tower of radius 10 (314 units²) and masses of 36 + 16: 14 % of 366, no warning.
    let mut e = estimate(vec![
        structure("tower1", Role::Tower, 10.0, 15.0, "default"),
        mass("mass1", 6.0),
        mass("mass2", 4.0),
    ]);
    assert!(model_warnings(&p, &e, &agreement(0.9)).is_empty());
    // Masses of 64 + 16 are 20 % of 394.
    e.structures[1] = mass("mass1", 8.0);
    let w = model_warnings(&p, &e, &agreement(0.9));
    let [Warning::MassesOfWall { share, largest, .. }] = &w[..] else {
        panic!("{w:?}");
    };
    assert!((share - 80.0 / (80.0 + 100.0 * std::f64::consts::PI)).abs() < 1e-9);
    assert_eq!(largest, "mass1");
    assert!(
        w[0].to_string()
            .starts_with("20 % of the model of plan.png are masses of wall")
    );
}

#[test]
fn a_facade_making_a_needle_warns_and_a_tower_does_not() {
    let p = plan(4, [10, 10, 60, 60]);
    // 35 high on 20 across (Coucy's corner tower): plausible.
    assert!(model_warnings(&p, &estimate(castle(35.0)), &agreement(0.9)).is_empty());
    // 90 high on 20 across: a needle, and 6 × the default tower beside it.
    let w = model_warnings(&p, &estimate(castle(90.0)), &agreement(0.9));
    assert_eq!(
        w,
        vec![
            Warning::Needle {
                structure: "tower1".into(),
                photos: "tower.jpg".into(),
                height: 90.0,
                width: 20.0
            },
            Warning::TowersOver {
                structure: "tower1".into(),
                photos: "tower.jpg".into(),
                height: 90.0,
                tallest_around: 15.0
            }
        ]
    );
    assert!(
        w[0].to_string()
            .starts_with("tower1 is 4.5 times taller than wide")
    );
    assert!(
        w[1].to_string()
            .contains("6.0 times the tallest structure around it")
    );
}

#[test]
fn a_facade_three_times_the_tallest_around_warns_on_a_wide_structure() {
    let p = plan(4, [10, 10, 60, 60]);
    // 50 across: 70 high is no needle, but over 3 × the default 15 (the raised keep, the
    // photo's, does not count).
    let mut s = castle(70.0);
    s[0].footprint = Footprint::Circle {
        center: [0.0, 0.0],
        radius: 25.0,
    };
    s[0].provenance.insert(
        "height".into(),
        Provenance::new("tower.jpg", "§6.1.2 façade height", None),
    );
    let w = model_warnings(&p, &estimate(s.clone()), &agreement(0.9));
    assert!(
        matches!(&w[..], [Warning::TowersOver { tallest_around, .. }] if *tallest_around == 15.0),
        "{w:?}"
    );
    // A user's 30 m beside it makes 70 plausible.
    s.push(structure("hall1", Role::Range, 8.0, 30.0, "user"));
    assert!(model_warnings(&p, &estimate(s), &agreement(0.9)).is_empty());
}

#[test]
fn a_scale_making_the_castle_a_toy_or_a_city_warns_and_pixels_do_not() {
    // Built area 50 px across.
    let p = plan(4, [10, 10, 60, 40]);
    let check = |units, s| plan_warnings(&p, "plan.png", &ScaleNote::Given, units, s);
    assert!(check(Units::Metres, 0.2).is_empty()); // 10 m
    assert!(check(Units::Metres, 40.0).is_empty()); // 2 km
    assert_eq!(
        check(Units::Metres, 0.1),
        vec![Warning::ImplausibleSize {
            plan: "plan.png".into(),
            metres_across: 5.0,
            metres_per_pixel: 0.1
        }]
    );
    let w = check(Units::Metres, 50.0);
    assert!(w[0].to_string().contains("is 2500.0 m across"), "{}", w[0]);
    // Without a scale the size is not known: nothing to say.
    assert!(check(Units::Pixels, 1.0).is_empty());
}

#[test]
fn a_scale_bar_not_found_warns_with_the_way_out() {
    let p = plan(4, [10, 10, 60, 40]);
    let note = ScaleNote::BarNotFound {
        metres: 30.0,
        assumed: "1 m = 2 px".into(),
    };
    let w = plan_warnings(&p, "plan.png", &note, Units::Pixels, 1.0);
    assert_eq!(
        w,
        vec![Warning::ScaleBarNotFound {
            plan: "plan.png".into(),
            metres: 30.0
        }]
    );
    let text = w[0].to_string();
    assert!(
        text.starts_with("scale_bar = 30: no scale bar found for the 30 m given (")
            && text.contains("continuing in plan pixels in plan = \"plan.png\"")
            && text.contains("give scale (metres per pixel) instead, or click the bar"),
        "{text}"
    );
}
