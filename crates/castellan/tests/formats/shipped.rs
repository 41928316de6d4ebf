//! Inputs shipped in the repository follow their schemas.

use std::path::{Path, PathBuf};

use serde_json::json;

use crate::fixtures;
use crate::schemas::*;

/// Files under `dir` (recursively) whose name `keep` accepts.
fn files_under(dir: &Path, keep: &dyn Fn(&str) -> bool, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files_under(&path, keep, out);
        } else if keep(&path.file_name().unwrap().to_string_lossy()) {
            out.push(path);
        }
    }
}

/// `examples/` and every `crates/*/tests/data`.
fn shipped(keep: &dyn Fn(&str) -> bool) -> Vec<PathBuf> {
    let mut out = Vec::new();
    files_under(&repo().join("examples"), keep, &mut out);
    for krate in std::fs::read_dir(repo().join("crates")).unwrap() {
        files_under(&krate.unwrap().path().join("tests/data"), keep, &mut out);
    }
    out.sort();
    out
}

fn shown(path: &Path) -> String {
    path.strip_prefix(repo())
        .unwrap_or(path)
        .display()
        .to_string()
}

#[test]
fn shipped_projects_follow_the_project_schema() {
    let projects = shipped(&|n| n == "PROJECT.toml" || n.ends_with(".project.toml"));
    assert!(
        projects.len() >= 2,
        "examples/coucy and examples/demo: {projects:?}"
    );
    for path in &projects {
        let text = std::fs::read_to_string(path).unwrap();
        let doc = toml_to_json(&text, &shown(path));
        assert_valid("project", &shown(path), &doc);
        // Inline training boxes follow the TRAINING.json contract too.
        for (i, f) in doc["facade"].as_array().into_iter().flatten().enumerate() {
            if f["training"].is_object() {
                let at = format!("{} [[facade]] #{} training", shown(path), i + 1);
                assert_valid("training", &at, &f["training"]);
            }
        }
    }
}

#[test]
fn shipped_training_and_lines_files_follow_their_schemas() {
    let training = shipped(&|n| n == "TRAINING.json" || n.ends_with(".training.json"));
    assert!(training.len() >= 2, "examples/demo: {training:?}");
    for path in &training {
        assert_valid("training", &shown(path), &read_json(path));
    }
    // No LINES.json ships today; any that does is checked.
    for path in shipped(&|n| n == "LINES.json" || n.ends_with(".lines.json")) {
        assert_valid("lines", &shown(&path), &read_json(&path));
    }
}

/// LINES.json has no shipped example: the file `castellan rectify --lines` accepts (as in
/// tests/rectify_facade.rs) follows the schema, and one it refuses breaks it.
#[test]
fn lines_json_the_binary_accepts_follows_the_schema_and_one_it_refuses_breaks_it() {
    let dir = tempfile::tempdir().unwrap();
    let img = dir.path().join("photo.png");
    fixtures::facade_image().save(&img).unwrap();
    let good = json!({
        "horizontal": [[10, 20, 110, 25], [10, 70, 110, 68]],
        "vertical": [[20, 10, 22, 80], [100, 10, 98, 80]]
    });
    let one = with(&good, "/vertical", json!([[20, 10, 22, 80]]));
    for (doc, ok) in [(&good, true), (&one, false)] {
        let lines = dir.path().join("lines.json");
        std::fs::write(&lines, doc.to_string()).unwrap();
        let run = castellan()
            .arg("rectify")
            .arg(&img)
            .arg("-o")
            .arg(dir.path().join("r.png"))
            .arg("--lines")
            .arg(&lines)
            .assert();
        if ok {
            run.success();
            assert_valid("lines", "lines.json (accepted by rectify)", doc);
        } else {
            run.failure();
            assert_refused("lines", "a single vertical segment", doc);
        }
    }
    assert_refused(
        "lines",
        "a segment of three numbers",
        &with(&good, "/horizontal/0", json!([1, 2, 3])),
    );
    assert_refused(
        "lines",
        "no vertical family",
        &without(&good, "", "vertical"),
    );
}
