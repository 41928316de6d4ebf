//! The user's `[[structure]]` corrections (issue 22) on the synthetic castle (`synth::Castle`:
//! a rectangular curtain, two round corner towers, a free-standing rectangular keep), whose
//! answers are known: the keep the user names, heights, roofs and crenellation with the source
//! "user", the errors that name the entry, and every roof built with its exact volume.

use integrate::corrections::StructureFix;
use integrate::estimate::{Estimate, Footprint, Role, Roof, Source};
use integrate::{Inputs, integrate, program, synth::Castle};
use plan::scale::GivenScale;

fn estimate(fixes: &[StructureFix]) -> Result<Estimate, String> {
    let castle = Castle::default();
    let plan = plan::parse(
        &image::DynamicImage::ImageLuma8(castle.plan()),
        &plan::Options::default(),
    )
    .unwrap();
    integrate(&Inputs {
        plan: &plan,
        plan_image: "plan.png",
        scale: GivenScale::MetresPerPixel(castle.metres_per_pixel),
        facades: &[],
        gothics: &[],
        correspondences: &[],
        structure_fixes: fixes,
    })
    .map(|i| i.estimate)
    .map_err(|e| e.to_string())
}

fn fix(point: [f64; 2]) -> StructureFix {
    StructureFix {
        point,
        height: None,
        roof: None,
        crenellated: None,
        keep: None,
    }
}

/// The keep's centre and a tower's (plan pixels, `Castle::default`).
const KEEP: [f64; 2] = [320.0, 270.0];
const TOWER: [f64; 2] = [530.0, 100.0];

fn model(e: &Estimate) -> vsg::Model {
    let src = program::generate(e, &program::Options::default());
    vsg::run_with(
        "model.vsg",
        &src,
        &vsg::RunOptions::default(),
        &mut integrate::library::Library::default(),
    )
    .unwrap_or_else(|err| panic!("{}\n{src}", err.render("model.vsg", &src)))
}

/// The summed exact volume of the terminals of `symbol` (m³).
fn volume_of(model: &vsg::Model, symbol: &str) -> (usize, f64) {
    let mut out = (0, 0.0);
    for (i, n) in model.nodes.iter().enumerate() {
        if model.symbol(n) == symbol
            && let Some(s) = model.solid(i as u32)
        {
            out.0 += 1;
            out.1 += s.volume();
        }
    }
    out
}

#[test]
fn the_keep_the_user_names_is_the_keep_at_the_height_set() {
    let before = estimate(&[]).unwrap();
    let keep = before
        .structures
        .iter()
        .find(|s| s.role == Role::Keep)
        .unwrap();
    assert!(matches!(keep.footprint, Footprint::Rectangle { .. }));
    let e = estimate(&[StructureFix {
        height: Some(40.0),
        roof: Some(Roof::Pyramid),
        crenellated: Some(true),
        keep: Some(true),
        ..fix(TOWER)
    }])
    .unwrap();
    let keeps: Vec<_> = e
        .structures
        .iter()
        .filter(|s| s.role == Role::Keep)
        .collect();
    assert_eq!(keeps.len(), 1);
    let k = keeps[0];
    assert!(matches!(k.footprint, Footprint::Circle { .. }));
    assert_eq!(k.height, 40.0);
    assert_eq!((k.roof, k.crenellated), (Some(Roof::Pyramid), Some(true)));
    for key in ["role", "height", "roof", "crenellated"] {
        assert_eq!(k.provenance[key].source(), Source::User, "{key}");
        assert_eq!(k.provenance[key].step, "[[structure]] #1");
    }
    // The parser's keep is a building of its ward now.
    let old = e.structures.iter().find(|s| s.id == keep.id).unwrap();
    assert_eq!(old.role, Role::Room);
    let tallest = e
        .structures
        .iter()
        .max_by(|a, b| a.height.total_cmp(&b.height))
        .unwrap();
    assert_eq!(tallest.id, k.id);
    // The library's cone gives way to four faces of a pyramid, and battlements stand on top.
    let src = program::generate(&e, &program::Options::default());
    assert!(src.contains("ownRoof = 0"), "{src}");
    let m = model(&e);
    let Footprint::Circle { radius, .. } = k.footprint else {
        unreachable!()
    };
    let (faces, v) = volume_of(&m, &format!("{}Roof", k.id));
    assert_eq!(faces, 4);
    let (side, rise) = (2.0 * radius, radius);
    let expected = side * side * rise / 3.0;
    // The program writes 4 decimals.
    assert!((v - expected).abs() < 1e-3 * expected, "{v} ≠ {expected}");
    assert!(volume_of(&m, &format!("{}BattlementRing", k.id)).0 > 0);
}

#[test]
fn every_roof_is_built_over_the_keep_with_its_exact_volume() {
    let e = estimate(&[]).unwrap();
    let keep = e.structures.iter().find(|s| s.role == Role::Keep).unwrap();
    let Footprint::Rectangle { size, .. } = keep.footprint else {
        unreachable!()
    };
    let (long, short) = (size[0].max(size[1]), size[0].min(size[1]));
    for (roof, pieces, volume) in [
        (Roof::Cone, 4, long * short * (0.5 * short) / 3.0),
        (Roof::Pyramid, 4, long * short * (0.5 * short) / 3.0),
        (Roof::Gable, 2, long * short * (0.4 * short) / 2.0),
        (
            Roof::Hipped,
            8,
            (long - short) * short * (0.5 * short) / 2.0 + short * short * (0.5 * short) / 3.0,
        ),
        (Roof::Flat, 1, long * short * 0.3),
        (Roof::None, 0, 0.0),
    ] {
        let e = estimate(&[StructureFix {
            roof: Some(roof),
            ..fix(KEEP)
        }])
        .unwrap();
        let m = model(&e);
        let (n, v) = volume_of(&m, &format!("{}Roof", keep.id));
        assert_eq!(n, pieces, "{roof:?}");
        // The program writes 4 decimals.
        assert!(
            (v - volume).abs() <= 1e-4 * volume.max(1.0),
            "{roof:?}: {v} ≠ {volume}"
        );
    }
}

#[test]
fn corrections_that_cannot_apply_name_their_entry() {
    let on_curtain = StructureFix {
        roof: Some(Roof::Gable),
        ..fix([320.0, 100.0])
    };
    let e = estimate(&[fix(KEEP), on_curtain]).unwrap_err();
    assert!(
        e.starts_with("[[structure]] #2: roof = \"gable\": curtain"),
        "{e}"
    );
    assert!(e.contains("walls take no roof"), "{e}");
    let e = estimate(&[fix([20.0, 20.0])]).unwrap_err();
    assert_eq!(
        e,
        "[[structure]] #1: no structure is built at [20, 20] (the plan there: castle_surroundings)"
    );
    let e = estimate(&[StructureFix {
        height: Some(-3.0),
        ..fix(KEEP)
    }])
    .unwrap_err();
    assert!(
        e.starts_with("[[structure]] #1: height -3 must be above 0"),
        "{e}"
    );
}

#[test]
fn crenellation_can_be_taken_off_the_curtain_and_put_on_a_tower() {
    let plain = estimate(&[
        StructureFix {
            crenellated: Some(false),
            ..fix([320.0, 100.0])
        },
        StructureFix {
            crenellated: Some(true),
            ..fix(TOWER)
        },
    ])
    .unwrap();
    let m = model(&plain);
    let curtain = plain
        .structures
        .iter()
        .find(|s| s.role == Role::Curtain && s.crenellated == Some(false))
        .unwrap();
    let src = program::generate(&plain, &program::Options::default());
    assert!(
        src.contains(&format!("{} :: {{curtainPlain}};", curtain.id)),
        "{src}"
    );
    let tower = plain
        .structures
        .iter()
        .find(|s| s.crenellated == Some(true))
        .unwrap();
    assert!(volume_of(&m, &format!("{}BattlementCrenel", tower.id)).0 >= 3);
}
