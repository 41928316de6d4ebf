//! Towers the plan finds as bulges of the curtain, with no room of their own (`plan::bulges`),
//! are built: each becomes a solid cylindrical tower structure (`tower{n}` after the tower
//! rooms, label tower_wall) at the bulge's centre and radius, at the §5.3 tower height, whose
//! generated shaft is a closed solid of volume π r² h; a bulge on a tower whose room the plan
//! found is not built twice.

use plan::label::Label;
use plan::scale::GivenScale;

use std::f64::consts::PI;

use integrate::estimate::{Estimate, Footprint, Kind, Structure};
use integrate::{Inputs, integrate, program, synth::Castle};
use plan::bulges::BulgeTower;
use vsg::shape::Tessellation;

fn parse(castle: &Castle) -> plan::ParsedPlan {
    plan::parse(
        &image::DynamicImage::ImageLuma8(castle.plan()),
        &plan::Options::default(),
    )
    .unwrap()
}

fn estimate(plan: &plan::ParsedPlan, scale: Option<f64>) -> Estimate {
    integrate(&Inputs {
        plan,
        plan_image: "plan.png",
        scale: scale.map_or(GivenScale::Unknown, GivenScale::MetresPerPixel),
        facades: &[],
        gothics: &[],
        correspondences: &[],
        structure_fixes: &[],
    })
    .unwrap()
    .estimate
}

/// The towers (the keep, numbered apart as `keep1`, is not one of them).
fn towers(e: &Estimate) -> Vec<&Structure> {
    e.structures
        .iter()
        .filter(|s| s.role == integrate::estimate::Role::Tower)
        .collect()
}

fn solid_towers(e: &Estimate) -> Vec<&Structure> {
    e.structures
        .iter()
        .filter(|s| s.kind == Kind::SolidCylindrical)
        .collect()
}

fn circle(s: &Structure) -> ([f64; 2], f64) {
    match s.footprint {
        Footprint::Circle { center, radius } => (center, radius),
        ref f => panic!("{}: {f:?}", s.id),
    }
}

/// Three solid discs on the south curtain (y = 400 ± 5 px) and one on the east one (x = 530),
/// each leaving the wall's outer face by more than 1.5 wall thicknesses.
fn studded() -> Castle {
    Castle {
        solid_towers: vec![
            ([220.0, 410.0], 18.0),
            ([320.0, 410.0], 18.0),
            ([420.0, 410.0], 18.0),
            ([540.0, 250.0], 20.0),
        ],
        ..Castle::default()
    }
}

#[test]
fn every_bulge_tower_becomes_one_solid_tower_of_its_centre_and_radius() {
    let plain = Castle::default();
    let castle = studded();
    let k = castle.solid_towers.len();
    let s = castle.metres_per_pixel;
    let before = estimate(&parse(&plain), Some(s));
    let plan = parse(&castle);
    assert_eq!(plan.bulge_towers.len(), k, "{:?}", plan.bulge_towers);
    let after = estimate(&plan, Some(s));
    assert_eq!(
        towers(&after).len(),
        towers(&before).len() + k,
        "{:?}",
        towers(&after).iter().map(|t| &t.id).collect::<Vec<_>>()
    );
    let solid = solid_towers(&after);
    assert_eq!(solid.len(), k);
    let rooms = towers(&before).len();
    let curtain = after
        .structures
        .iter()
        .find(|x| x.label == Label::CastleOuterWall)
        .expect("a curtain")
        .height;
    for (i, (t, b)) in solid.iter().zip(&plan.bulge_towers).enumerate() {
        // Named after the tower rooms, labelled as the plan labels a bulge's pixels.
        assert_eq!(t.id, format!("tower{}", rooms + i + 1));
        assert_eq!(t.label, Label::TowerWall);
        assert_eq!(
            t.children
                .iter()
                .map(|c| c.kind.as_str())
                .collect::<Vec<_>>(),
            ["wall", "fill"]
        );
        // The bulge's circle, scaled into metres.
        let (c, r) = circle(t);
        assert!((c[0] - b.center[0] * s).abs() < 1e-9 && (c[1] - b.center[1] * s).abs() < 1e-9);
        assert!((r - b.radius * s).abs() < 1e-9, "{r} vs {b:?}");
        // … which is the disc drawn, within a pixel or two.
        let (truth, tr) = castle
            .solid_towers
            .iter()
            .map(|&(tc, tr)| ([tc[0] * s, tc[1] * s], tr * s))
            .min_by(|a, b| {
                let d = |p: [f64; 2]| (p[0] - c[0]).hypot(p[1] - c[1]);
                d(a.0).total_cmp(&d(b.0))
            })
            .unwrap();
        eprintln!(
            "{}: centre off the drawn disc by {:.3} m, radius {r:.3} m (drawn {tr:.3} m)",
            t.id,
            (truth[0] - c[0]).hypot(truth[1] - c[1])
        );
        assert!(
            (truth[0] - c[0]).hypot(truth[1] - c[1]) < 0.25,
            "{}: centre {c:?}, drawn {truth:?}",
            t.id
        );
        assert!((r - tr).abs() < 0.25, "{}: radius {r}, drawn {tr}", t.id);
        // The §5.3 tower height, above the curtain it studs.
        assert_eq!(t.height, 20.0);
        assert!(t.height > curtain);
        assert!(t.wall_thickness > 0.0 && t.wall_thickness <= r / 2.0);
    }

    // The program runs; each solid tower's shaft is closed, stands where the bulge is and
    // holds π r² h (the 32-gon's area is 0.6 % under the circle's), under a roof.
    let src = program::generate(&after, &program::Options::default());
    let model = vsg::run_with(
        "model.vsg",
        &src,
        &vsg::RunOptions::default(),
        &mut integrate::library::Library::default(),
    )
    .unwrap_or_else(|e| panic!("{}\n{src}", e.render("model.vsg", &src)));
    let tess = Tessellation::default();
    for t in &solid {
        let (c, r) = circle(t);
        let prefix = format!("{}.", t.id);
        let (mut shaft, mut roofs, mut lo, mut hi) = (0.0, 0, [f64::MAX; 3], [f64::MIN; 3]);
        for (i, n) in model.nodes.iter().enumerate() {
            let symbol = model.symbol(n);
            if !n.is_leaf() || !symbol.starts_with(&prefix) {
                continue;
            }
            let solid = model.solid(i as u32).unwrap();
            let mesh = solid.mesh(&tess);
            assert!(mesh.is_closed_oriented(), "{symbol} is not closed");
            if symbol.ends_with(".roof") {
                roofs += 1;
                continue;
            }
            shaft += mesh.signed_volume();
            for p in &mesh.positions {
                let w = n.world * nalgebra::Point3::new(p[0], p[1], p[2]);
                for a in 0..3 {
                    lo[a] = lo[a].min(w[a]);
                    hi[a] = hi[a].max(w[a]);
                }
            }
        }
        let v = PI * r * r * t.height;
        eprintln!(
            "{}: shaft volume {shaft:.2} m³ = {:.4} π r² h",
            t.id,
            shaft / v
        );
        assert!(
            (shaft - v).abs() < 0.02 * v,
            "{}: shaft volume {shaft} vs π r² h = {v}",
            t.id
        );
        assert_eq!(roofs, 1, "{}: one roof", t.id);
        // (The program writes numbers to 4 decimals.)
        assert!(
            ((lo[0] + hi[0]) / 2.0 - c[0]).abs() < 1e-3
                && ((lo[2] + hi[2]) / 2.0 - c[1]).abs() < 1e-3,
            "{}: shaft at {lo:?}..{hi:?}, centre {c:?}",
            t.id
        );
        assert!(lo[1].abs() < 1e-3 && (hi[1] - t.height).abs() < 1e-3);
        assert!(
            ((hi[0] - lo[0]) / 2.0 - r).abs() < 1e-3,
            "{}: shaft radius",
            t.id
        );
    }
}

#[test]
fn a_bulge_on_a_tower_with_a_room_is_built_once() {
    let castle = Castle::default();
    let mut plan = parse(&castle);
    let rooms = towers(&estimate(&plan, None)).len();
    assert_eq!(rooms, 2);
    // One bulge on the first round tower (inside its footprint), one on the south curtain.
    let [x, y] = castle.towers[0].0;
    plan.bulge_towers = vec![
        BulgeTower {
            center: [x + 20.0, y - 10.0],
            radius: 25.0,
        },
        BulgeTower {
            center: [320.0, 412.0],
            radius: 15.0,
        },
    ];
    // Without a scale the model is in plan pixels: the footprint is the bulge's own circle.
    let e = estimate(&plan, None);
    assert_eq!(towers(&e).len(), rooms + 1);
    let solid = solid_towers(&e);
    assert_eq!(solid.len(), 1);
    assert_eq!(solid[0].id, "tower3");
    assert_eq!(circle(solid[0]), ([320.0, 412.0], 15.0));
    // The tower height in pixels: 20 m at the assumed pixels per metre.
    assert!((solid[0].height - 20.0 * e.scale.units_per_metre).abs() < 1e-9);
    let src = program::generate(&e, &program::Options::default());
    assert!(
        src.contains("import \"solid_tower.vsg\" as tower3"),
        "{src}"
    );
    assert_eq!(src.matches("solid_tower.vsg").count(), 1);
}

/// The correspondences of §6.1.1 reach a solid tower like any round one: a plan point inside
/// it selects it (the smallest footprint there), the photo's façade replaces its wall in the
/// hierarchy and its height becomes the façade's, scaled by its diameter (s = d_p / w_f).
#[test]
fn a_facade_mapped_onto_a_bulge_tower_sets_its_height() {
    use integrate::photo::{FacadePhoto, estimate_facade};
    use integrate::project::Correspondence;
    let castle = studded();
    let plan = parse(&castle);
    let photo = castle.photo(20.0, 0.0, 1);
    let name = "solid_tower.png";
    let facade = estimate_facade(&FacadePhoto {
        name,
        image: &photo.image,
        training: &photo.training,
        lines: None,
        rectified: true,
        bbox: None,
        metres_per_pixel: None,
        seed: 7,
        classifier: Default::default(),
        fixes: &Default::default(),
    })
    .unwrap();
    let b = plan.bulge_towers[1];
    let e = integrate(&Inputs {
        plan: &plan,
        plan_image: "plan.png",
        scale: GivenScale::MetresPerPixel(castle.metres_per_pixel),
        facades: std::slice::from_ref(&facade),
        gothics: &[],
        correspondences: &[Correspondence {
            facade: name.into(),
            facade_point: photo.facade_point,
            plan_points: vec![b.center],
        }],
        structure_fixes: &[],
    })
    .unwrap()
    .estimate;
    let t = e
        .structures
        .iter()
        .find(|s| !s.facades.is_empty())
        .expect("a structure carries the façade");
    assert_eq!(t.kind, Kind::SolidCylindrical, "{}", t.id);
    let (_, r) = circle(t);
    let f = &t.facades[0];
    assert_eq!(f.side, integrate::estimate::Side::Arc);
    assert!((f.width - 2.0 * r).abs() < 1e-9);
    assert!((t.height - f.height).abs() < 1e-9 && t.height != 20.0);
    assert_eq!(t.provenance["height"].image, name);
    assert_eq!(t.children[0].name, format!("{}Facade1", t.id));
    let src = program::generate(&e, &program::Options::default());
    vsg::run_with(
        "model.vsg",
        &src,
        &vsg::RunOptions::default(),
        &mut integrate::library::Library::default(),
    )
    .unwrap_or_else(|e| panic!("{}\n{src}", e.render("model.vsg", &src)));
    assert!(src.contains(&format!("as {} (radius = {}", t.id, {
        let s = format!("{r:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    })));
}
