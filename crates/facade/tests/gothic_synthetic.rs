//! End-to-end checks of the Gothic pipeline (ch. 4) on synthetic façades with known arches:
//! parameters within a few pixels, groups per bay, windows nested in their enclosing arch, and
//! the masonry split into the drawn mortar joints and bricks.

use facade::gothic::masonry::{MasonryParams, segment};
use facade::gothic::synth::{Bay, SynthSpec, Synthetic, TrueElement, synthetic_facade};
use facade::gothic::{Element, GothicEstimate, GothicParams, VsgOptions, estimate, to_vsg};

/// The estimated element closest to a true one (by corners and apex).
fn closest<'a>(est: &'a GothicEstimate, t: &TrueElement) -> &'a Element {
    let d = |e: &Element| {
        let (a, b) = (e.theta(), t.theta);
        (a.x0 - b.x0).abs() + (a.y0 - b.y0).abs() + (a.w - b.w).abs() + (a.apex() - b.apex()).abs()
    };
    est.elements
        .iter()
        .min_by(|a, b| d(a).total_cmp(&d(b)))
        .expect("at least one element")
}

/// Checks every parameter, the parent links and the groups; returns the largest error (px).
fn check(s: &Synthetic, est: &GothicEstimate) -> f64 {
    assert_eq!(est.elements.len(), s.elements.len(), "{:#?}", est.elements);
    let matched: Vec<&Element> = s.elements.iter().map(|t| closest(est, t)).collect();
    let mut worst: f64 = 0.0;
    for (t, e) in s.elements.iter().zip(&matched) {
        let (a, b) = (e.theta(), t.theta);
        // The enclosing arches are grooves 3 px wide; the estimate may take either side.
        let tol = if t.parent.is_none() { 4.0 } else { 3.0 };
        for (name, got, want) in [
            ("x0", a.x0, b.x0),
            ("y0", a.y0, b.y0),
            ("w", a.w, b.w),
            ("h", a.h, b.h),
            ("v", a.v, b.v),
            ("apex", a.apex(), b.apex()),
        ] {
            let err = (got - want).abs();
            worst = worst.max(err);
            assert!(
                err <= tol,
                "{name}: {got:.1} vs {want:.1} for {t:?} ({e:?})"
            );
        }
        let want_parent = t.parent.map(|p| matched[p].id);
        assert_eq!(e.parent, want_parent, "parent of {e:?}");
    }
    // Windows of one bay: one group, of exactly that bay's windows, enclosed by its arch.
    let bays = s
        .elements
        .iter()
        .filter_map(|t| t.group)
        .max()
        .map_or(0, |b| b + 1);
    for bay in 0..bays {
        let ids: Vec<usize> = s
            .elements
            .iter()
            .zip(&matched)
            .filter(|(t, _)| t.group == Some(bay))
            .map(|(_, e)| e.id)
            .collect();
        let g = est.elements[ids[0]].group.expect("windows are grouped");
        let mut members = est.groups[g].members.clone();
        members.sort();
        let mut want = ids.clone();
        want.sort();
        assert_eq!(members, want, "group of bay {bay}");
        assert_eq!(est.groups[g].enclosing, est.elements[ids[0]].parent);
    }
    worst
}

#[test]
fn round_and_pointed_bays_of_two_and_three() {
    let s = synthetic_facade(&SynthSpec::small(), 1);
    let est = estimate(&s.image, &GothicParams::default()).unwrap();
    let worst = check(&s, &est);
    eprintln!("largest parameter error {worst:.2} px");
    let json = serde_json::to_string(&est).unwrap();
    assert!(json.contains("\"parent\"") && json.contains("\"group\""));
}

#[test]
fn one_bay_of_four_round_windows() {
    let spec = SynthSpec {
        bays: vec![Bay {
            windows: 4,
            pointed: false,
        }],
        ..SynthSpec::small()
    };
    let s = synthetic_facade(&spec, 2);
    let est = estimate(&s.image, &GothicParams::default()).unwrap();
    check(&s, &est);
}

#[test]
fn a_plain_brick_wall_has_no_elements_and_mostly_right_mortar() {
    let spec = SynthSpec {
        bays: vec![],
        ..SynthSpec::small()
    };
    let s = synthetic_facade(&spec, 3);
    let est = estimate(&s.image, &GothicParams::default()).unwrap();
    assert!(est.elements.is_empty(), "{:?}", est.elements);
    let m = segment(&s.image, &est, &MasonryParams::default());
    let right = m
        .labels
        .iter()
        .zip(&s.mortar)
        .filter(|(l, mortar)| (**l == 1) == **mortar)
        .count();
    let accuracy = right as f64 / m.labels.len() as f64;
    eprintln!(
        "mortar/stone pixel accuracy {accuracy:.3}, {} stones",
        m.stones.len()
    );
    assert!(accuracy > 0.85, "{accuracy}");
    // Bricks are 22 x 9 px with 2 px joints: about one stone per brick cell.
    let cells = (480.0 / 24.0) * (400.0 / 11.0);
    let ratio = m.stones.len() as f64 / cells;
    assert!(
        (0.7..1.3).contains(&ratio),
        "{} stones for {cells} bricks",
        m.stones.len()
    );
}

#[test]
fn masonry_around_elements_and_the_vsg_model() {
    let s = synthetic_facade(&SynthSpec::small(), 1);
    let est = estimate(&s.image, &GothicParams::default()).unwrap();
    let m = segment(&s.image, &est, &MasonryParams::default());
    let (mut right, mut wall) = (0usize, 0usize);
    for ((l, &mortar), &is_wall) in m.labels.iter().zip(&s.mortar).zip(&s.wall) {
        if is_wall {
            wall += 1;
            right += usize::from((*l == 1) == mortar && *l != 0);
        }
    }
    let accuracy = right as f64 / wall as f64;
    eprintln!("wall pixel accuracy {accuracy:.3}");
    assert!(accuracy > 0.8, "{accuracy}");
    let src = to_vsg(&est, None, &VsgOptions::default());
    let model = vsg::run(&src, &vsg::RunOptions::default())
        .unwrap_or_else(|e| panic!("{}", e.render("gothic.vsg", &src)));
    let stats = vsg::stats::Stats::of(&model, &vsg::shape::Tessellation::default());
    // Five leaf windows (jambs + light) of glass, two tympana (jambs + light).
    assert_eq!(stats.by_symbol.get("glass"), Some(&10));
    assert_eq!(stats.by_symbol.get("tympanum"), Some(&4));
}

/// Issue 19: a long photo once ran for minutes with nothing shown. The pipeline reports each
/// fitted start and each group, ending with every start fitted, and the estimate is the same
/// as without a listener.
#[test]
fn progress_is_reported_for_every_start_and_group_and_changes_nothing() {
    use facade::gothic::{Progress, estimate_with_progress};
    use std::sync::Mutex;
    let s = synthetic_facade(&SynthSpec::small(), 3);
    let params = GothicParams::default();
    let seen = Mutex::new(Vec::new());
    let est = estimate_with_progress(&s.image, &params, &|p| seen.lock().unwrap().push(p)).unwrap();
    let seen = seen.into_inner().unwrap();
    assert_eq!(seen[0], Progress::Edges);
    let detecting: Vec<(usize, usize)> = seen
        .iter()
        .filter_map(|p| match p {
            Progress::Detecting { done, total } => Some((*done, *total)),
            _ => None,
        })
        .collect();
    let total = detecting[0].1;
    assert!(total > 0);
    // 0 announced first, then one report per start (threads may report out of order).
    assert_eq!(detecting.len(), total + 1);
    assert!(detecting.iter().any(|&(d, _)| d == total));
    assert!(
        seen.iter()
            .any(|p| matches!(p, Progress::Organising { level: 1, .. })),
        "the small façade has groups: {seen:?}"
    );
    let plain = estimate(&s.image, &params).unwrap();
    assert_eq!(
        serde_json::to_string(&est).unwrap(),
        serde_json::to_string(&plain).unwrap()
    );
}
