//! Fuzzing PROJECT.toml (issue 19) on stable Rust: arbitrary text, and projects built from the
//! real keys with hostile values. `Project::from_toml` must never panic; what it accepts must
//! hold the documented invariants and survive a save and reload unchanged (what `serve` does).
//!
//! CI runs a few hundred cases; a longer run for developers:
//! `PROPTEST_CASES=200000 cargo test --release -p integrate --test fuzz_project`.

use integrate::project::{Project, ProjectError};
use proptest::prelude::*;

fn cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Failures are reported, not saved into the source tree.
fn config(default: u32) -> ProptestConfig {
    ProptestConfig {
        cases: cases(default),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("1e300".to_string()),
        Just("-0.0".to_string()),
        Just("nan".to_string()),
        Just("-inf".to_string()),
        Just("0.05".to_string()),
        Just("18446744073709551616".to_string()),
        Just("\"\"".to_string()),
        Just("\"plan.png\"".to_string()),
        Just("\"a.png\"".to_string()),
        Just("\"../x.png\"".to_string()),
        Just("[1.0, 2.0]".to_string()),
        Just("[[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]]".to_string()),
        Just("[0, 0, 10, 10]".to_string()),
        Just("[10, 10, 0, 0]".to_string()),
        Just("{ classes = {} }".to_string()),
        Just("true".to_string()),
        any::<f64>().prop_map(|v| format!("{v:?}")),
        "[ -~]{0,12}",
    ]
}

fn key() -> impl Strategy<Value = &'static str> {
    prop_oneof![
        Just("plan"),
        Just("scale"),
        Just("scale_bar"),
        Just("seed"),
        Just("thin_lines"),
        Just("hatching"),
        Just("image"),
        Just("training"),
        Just("lines"),
        Just("rectified"),
        Just("bbox"),
        Just("facade"),
        Just("facade_point"),
        Just("plan_points"),
        Just("class"),
        Just("boxes"),
        Just("unknown_key"),
    ]
}

fn table() -> impl Strategy<Value = &'static str> {
    prop_oneof![
        Just(""),
        Just("[[facade]]"),
        Just("[[gothic]]"),
        Just("[[correspondence]]"),
        Just("[[texture]]"),
        Just("[plan]"),
    ]
}

/// A document of tables and key/value lines, starting from a valid plan line half the time.
fn document() -> impl Strategy<Value = String> {
    (
        any::<bool>(),
        proptest::collection::vec(
            (table(), proptest::collection::vec((key(), value()), 0..5)),
            0..5,
        ),
    )
        .prop_map(|(with_plan, tables)| {
            let mut s = if with_plan {
                "plan = \"p.png\"\n".to_string()
            } else {
                String::new()
            };
            for (t, kvs) in tables {
                s.push_str(t);
                s.push('\n');
                for (k, v) in kvs {
                    s.push_str(&format!("{k} = {v}\n"));
                }
            }
            s
        })
}

fn check_accepted(text: &str) -> Result<(), TestCaseError> {
    match Project::from_toml(text) {
        Ok(p) => {
            prop_assert!(!p.plan.trim().is_empty());
            if let Some(s) = p.metres_per_pixel {
                prop_assert!(
                    plan::scale::METRES_PER_PIXEL.contains(&s),
                    "scale {s} accepted"
                );
            }
            for f in &p.facades {
                prop_assert!(p.correspondences.iter().any(|c| c.facade == f.image));
            }
            // What serve saves must load again as the same project.
            let again = Project::from_toml(&p.to_toml());
            prop_assert_eq!(again.as_ref().ok(), Some(&p), "{:?}", again);
        }
        Err(ProjectError::Syntax { line, column, .. }) => {
            prop_assert!(line >= 1 && line <= text.lines().count().max(1) + 1);
            prop_assert!(column >= 1);
        }
        Err(ProjectError::Invalid(m)) => prop_assert!(!m.is_empty()),
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn fuzz_arbitrary_text_never_panics(text in "\\PC{0,200}") {
        check_accepted(&text)?;
    }

    #[test]
    fn fuzz_projects_of_real_keys_with_hostile_values(text in document()) {
        check_accepted(&text)?;
    }
}
