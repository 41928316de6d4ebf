//! Issue 23: the Gothic estimator on façades of a style its other tests never saw — a brick
//! wall, groups of 2–3 lancets under a large pointed arch whose inside is the wall itself
//! (only its moulding line drawn), a tracery bay nested two levels, a door on the ground line
//! (`gothic::synth_lancet`). Prints the figures (`--nocapture`) and asserts the goals:
//! ≥ 90 % of the elements at box IoU ≥ 0.7, ≥ 80 % of the nested ones with the right parent,
//! every group of identical siblings found whole.
//!
//! `GOTHIC_LANCET_OVERLAYS=DIR` also writes each façade and its overlay to DIR.

use facade::gothic::draw::overlay;
use facade::gothic::score::{Score, score};
use facade::gothic::synth_lancet::{LancetSpec, lancet_facade};
use facade::gothic::{GothicParams, estimate};

const MIN_IOU: f64 = 0.7;

fn measure(params: &GothicParams) -> Score {
    measure_set(params, &LancetSpec::evaluation_set())
}

fn measure_set(params: &GothicParams, set: &[LancetSpec]) -> Score {
    let dump = std::env::var_os("GOTHIC_LANCET_OVERLAYS").map(std::path::PathBuf::from);
    let mut total = Score::default();
    for spec in set {
        let spec = spec.clone();
        let f = lancet_facade(&spec);
        let est = estimate(&f.image, params).unwrap();
        let s = score(&f.truth(), &est, MIN_IOU);
        eprintln!(
            "seed {}: found {}/{}, parents {}/{}, groups {}/{}, extra {}",
            spec.seed, s.found, s.elements, s.right_parent, s.nested, s.complete, s.groups, s.extra
        );
        if let Some(dir) = &dump {
            f.image
                .save(dir.join(format!("lancets_{}.png", spec.seed)))
                .unwrap();
            overlay(&f.image, &est, None)
                .save(dir.join(format!("lancets_{}.overlay.png", spec.seed)))
                .unwrap();
            std::fs::write(
                dir.join(format!("lancets_{}.json", spec.seed)),
                serde_json::to_string_pretty(&est).unwrap(),
            )
            .unwrap();
        }
        total.add(&s);
    }
    eprintln!(
        "total: recall {:.1} % ({}/{}), right parent {:.1} % ({}/{}), groups complete {}/{}, extra {}",
        100.0 * total.recall(),
        total.found,
        total.elements,
        100.0 * total.parent_accuracy(),
        total.right_parent,
        total.nested,
        total.complete,
        total.groups,
        total.extra
    );
    total
}

#[test]
fn lancets_under_wall_coloured_arches_and_a_door() {
    let s = measure(&GothicParams::default());
    assert_eq!(s.elements, 61);
    assert!(s.recall() >= 0.9, "{s:?}");
    assert!(s.parent_accuracy() >= 0.8, "{s:?}");
    assert_eq!(s.complete, s.groups, "{s:?}");
    assert!(s.extra <= 1, "{s:?}");
}

/// The same layouts with seeds the thresholds were not set on (measured: 58 of 61 elements,
/// 38 of 43 parents, 17 of 19 groups whole; since session 27's joint fit from the best member
/// and groups by head, which were made on these and seeds 500–700, 60, 43 and 19;
/// docs/gothic.md).
#[test]
fn held_out_seeds() {
    let s = measure_set(&GothicParams::default(), &LancetSpec::set(200));
    assert!(s.recall() >= 0.9, "{s:?}");
    assert!(s.parent_accuracy() >= 0.8, "{s:?}");
    assert_eq!(s.complete, s.groups, "{s:?}");
}

/// Seeds measured once, after session 27's changes were fixed (1100–1105: before them 58 of 61
/// elements, 36 of 43 parents, 16 of 19 groups whole; after, all). Every group whole, and
/// without the two changes not.
#[test]
fn fresh_seeds_groups_whole() {
    let set = LancetSpec::set(1100);
    let s = measure_set(&GothicParams::default(), &set);
    assert!(s.recall() >= 0.9, "{s:?}");
    assert!(s.parent_accuracy() >= 0.8, "{s:?}");
    assert_eq!(s.complete, s.groups, "{s:?}");
    let without = GothicParams {
        joint_from_best: false,
        group_by_heads: false,
        ..GothicParams::default()
    };
    let before = measure_set(&without, &set);
    assert!(before.complete < before.groups, "{before:?}");
}

/// A harder moulding: (70, 60, 55), as dark as the darkest bricks' shade, so parts of its
/// edges fall below the edge threshold. Figures only:
/// `cargo test -p facade --test gothic_lancets -- --ignored --nocapture`.
#[test]
#[ignore]
fn faint_moulding() {
    let set: Vec<LancetSpec> = LancetSpec::evaluation_set()
        .into_iter()
        .map(|s| LancetSpec {
            moulding_colour: [70, 60, 55],
            ..s
        })
        .collect();
    for (name, params) in [
        ("before", GothicParams::without_issue_23()),
        ("after", GothicParams::default()),
    ] {
        eprintln!("faint moulding, {name}:");
        measure_set(&params, &set);
    }
}

/// The figures before issue 23 (its departures switched off), for docs/gothic.md:
/// `cargo test -p facade --test gothic_lancets -- --ignored --nocapture`.
#[test]
#[ignore]
fn before_issue_23() {
    let s = measure(&GothicParams::without_issue_23());
    assert!(s.recall() < 0.9, "{s:?}");
    eprintln!("held-out seeds:");
    measure_set(&GothicParams::without_issue_23(), &LancetSpec::set(200));
}
