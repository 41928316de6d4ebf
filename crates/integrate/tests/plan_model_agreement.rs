//! Plan–model agreement (issue 25) on the bundled projects: floors under today's figures, so a
//! change that builds less of the plan fails here and an improvement can raise them. Measured
//! figures and the whole development set: `cargo run --release -p integrate --example
//! plan_model_agreement`.

use integrate::agreement::Agreement;
use integrate::pipeline::{self, Reconstruction};

mod common;

fn reconstruct(example: &str) -> Reconstruction {
    let (project, files) = common::example(example);
    pipeline::reconstruct(&project, &files, &pipeline::Options::default(), &|_| {}).unwrap()
}

fn show(a: &Agreement) -> String {
    format!(
        "IoU {:.3}, precision {:.3}, recall {:.3}, rooms {} / {}, towers {} / {}",
        a.iou,
        a.precision,
        a.recall,
        a.rooms_present(),
        a.rooms.len(),
        a.towers_present(),
        a.towers.len()
    )
}

#[test]
fn coucy_model_covers_its_plan_at_least_as_well_as_today() {
    let r = reconstruct("coucy");
    let a = &r.agreement;
    // Measured (issue 25): IoU 0.880, precision 0.921, recall 0.952, every room (21) and tower
    // (6) built; before the masses of wall left bare (`structures::bare::masses`), 0.860, 0.921,
    // 0.929; with the pruned chains judged piece by piece, 0.829, 0.918, 0.896; with one
    // thickness per wall run, 0.802, 0.911, 0.870; before the structures of issue 25, 0.721,
    // 0.953, 0.747, 11 / 21 and 4 / 6.
    // The floors leave 0.02 for floating-point drift between builds; what is missing is the
    // hachured band round the donjon's moat and the outworks' ends
    // (overlays/plan_model.png).
    assert!(a.iou >= 0.86, "{}", show(a));
    assert!(a.recall >= 0.93, "{}", show(a));
    // The masses are few and of stone: no roof, no higher than the curtain.
    let masses: Vec<_> = r
        .estimate
        .structures
        .iter()
        .filter(|s| s.role == integrate::estimate::Role::Mass)
        .collect();
    assert!((1..=10).contains(&masses.len()), "{}", masses.len());
    let curtain = r
        .estimate
        .structures
        .iter()
        .filter(|s| s.role == integrate::estimate::Role::Curtain)
        .map(|s| s.height)
        .fold(0.0, f64::max);
    assert!(
        masses
            .iter()
            .all(|m| m.height <= curtain && m.roof.is_none())
    );
    assert_eq!(a.towers_present(), a.towers.len(), "{}", show(a));
    assert_eq!(a.rooms_present(), a.rooms.len(), "{}", show(a));
    // stats.json carries the same figures.
    assert_eq!(r.exports.stats["agreement"], a.summary());
    // Every covered pixel of a room belongs to a structure of the estimate.
    for room in a.rooms.iter().filter(|r| r.present()) {
        let id = room.structure.as_deref().unwrap();
        assert!(r.estimate.structures.iter().any(|s| s.id == id), "{id}");
    }
}

#[test]
fn the_synthetic_castle_is_built_where_it_is_drawn() {
    let r = reconstruct("demo");
    let a = &r.agreement;
    // Measured: IoU 0.957, precision 0.961, recall 0.996, rooms 3 / 3, towers 2 / 2 (0.956
    // with one thickness per wall run, 0.958 before issue 25's structures).
    assert!(a.iou >= 0.94, "{}", show(a));
    assert_eq!(a.rooms_present(), a.rooms.len(), "{}", show(a));
    assert_eq!(a.towers_present(), a.towers.len(), "{}", show(a));
    assert!(a.towers.len() >= 2, "{}", show(a));
}
