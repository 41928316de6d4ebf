//! cjval, the CityJSON validator, for the tests (issue 24): [`assert_cjval_valid`] runs every
//! check of the crate (a dev-dependency) on a document. Shared by `crates/vsg/tests/cityjson.rs`
//! and `crates/integrate/tests/heritage.rs` (the real demo's file) through `#[path]`.

/// The cjval version of the dev-dependencies, for the messages.
const CJVAL: &str = "0.10.0";

/// cjval's checks of `text`; asserts that every check ran and passed: no error, no warning.
pub fn assert_cjval_valid(name: &str, text: &str) {
    let validator = cjval::CJValidator::from_str(text);
    let summary = validator.validate();
    let (mut errors, mut warnings) = (0, 0);
    let mut report = String::new();
    for (check, result) in &summary {
        let n = result.errors.len();
        if result.is_warning() {
            warnings += n;
        } else {
            errors += n;
        }
        report += &format!("{check}: {:?} {:?}\n", result.status, result.errors);
    }
    assert_eq!((errors, warnings), (0, 0), "cjval: {name}:\n{report}");
    // Every check ran (later ones are skipped after an error) and passed.
    assert!(
        summary.values().all(|r| r.is_valid()),
        "cjval: {name}:\n{report}"
    );
    eprintln!(
        "cjval {CJVAL}: {name}: valid, {errors} errors, {warnings} warnings ({} checks passed)",
        summary.len()
    );
}
