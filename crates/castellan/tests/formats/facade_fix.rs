//! `[facade.fix]` (issue 22): the schema and the code agree on the user's façade corrections —
//! a full table passes both, and each a step away is refused by both.

use serde_json::{Value, json};

use crate::schemas::*;

const FIX: &str = r#"
[facade.fix]
floor_lines = [193, 288]
columns = [[10, 40], [60, 90.5]]
add_windows = [[92, 194, 100, 202]]
remove_windows = [[148, 160]]
blind_floors = [1]
"#;

/// The demo project with `fix` under its first façade, as TOML text.
fn demo_with(fix: &str) -> String {
    let text = std::fs::read_to_string(repo().join("examples/demo/PROJECT.toml")).unwrap();
    let first = "training = \"keep_south_near.training.json\"\n";
    assert!(text.contains(first));
    text.replacen(first, &format!("{first}{fix}"), 1)
}

#[test]
fn facade_fixes_follow_the_project_schema_and_the_code() {
    let text = demo_with(FIX);
    let doc = toml_to_json(&text, "PROJECT.toml with [facade.fix]");
    assert_valid("project", "PROJECT.toml with [facade.fix]", &doc);
    let p = integrate::project::Project::from_toml(&text).unwrap();
    assert_eq!(p.facades[0].fix.blind_floors, vec![1]);

    let refused_by_code =
        |fix: &str| integrate::project::Project::from_toml(&demo_with(fix)).is_err();
    for (why, at, value, fix) in [
        (
            "an unknown key in [facade.fix]",
            "/facade/0/fix/floors",
            json!([1]),
            "[facade.fix]\nfloors = [1]\n",
        ),
        (
            "a box of three numbers",
            "/facade/0/fix/add_windows",
            json!([[1, 2, 3]]),
            "[facade.fix]\nadd_windows = [[1, 2, 3]]\n",
        ),
        (
            "a floor number below 1",
            "/facade/0/fix/blind_floors",
            json!([-1]),
            "[facade.fix]\nblind_floors = [-1]\n",
        ),
        (
            "a column of one number",
            "/facade/0/fix/columns",
            json!([[4]]),
            "[facade.fix]\ncolumns = [[4]]\n",
        ),
    ] {
        let bad: Value = match at.rsplit_once('/') {
            Some((parent, key)) => with_key(&doc, parent, key, value),
            None => unreachable!(),
        };
        assert_refused("project", why, &bad);
        assert!(refused_by_code(fix), "the code accepts {why}");
    }
}
