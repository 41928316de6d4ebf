//! End-to-end: `castellan serve` on the demo project driven by Debian's Chromium through
//! playwright-core (tests/e2e/serve.e2e.mjs): overlays appear, the plan is cleaned with the brush
//! and the rectification segments dragged, the model is drawn with the expected structures in
//! the outline and its walls peeled away. Outside CI it skips, saying why, when Chromium, Node.js
//! or tests/e2e/node_modules (`npm ci` there) is missing; under CI=true those are failures.
//! Screenshots go to $CASTELLAN_E2E_SCREENSHOTS (docs/serve for the docs) or a temporary folder.

mod serve_support;

use std::path::{Path, PathBuf};
use std::process::Command;

use serve_support::{Server, demo_project};

/// The demo castle (examples/demo/TRUTH.json: a keep, two round towers and the curtain wall
/// between them) is estimated as 5 structures — the keep, 2 towers and the curtain as two runs
/// (the north wall between the towers, and the rest round from tower to tower; issue 25) —
/// and the outline lists each, plus the keep's gable roof as its own entry.
const DEMO_ESTIMATED_STRUCTURES: usize = 5;
const DEMO_STRUCTURES: usize = DEMO_ESTIMATED_STRUCTURES + 1;

fn missing(what: &str) {
    let ci = std::env::var("CI").is_ok_and(|v| v == "true" || v == "1");
    assert!(!ci, "CI=true but {what}: .ci/run installs it");
    eprintln!("SKIPPED serve_e2e: {what} (see docs/serve.md, Tests)");
}

#[test]
fn the_demo_workflow_runs_in_chromium() {
    let chromium = std::env::var_os("CHROMIUM")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/usr/bin/chromium"));
    if !chromium.is_file() {
        return missing(&format!("no Chromium at {}", chromium.display()));
    }
    let e2e = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/e2e");
    if !e2e.join("node_modules/playwright-core").is_dir() {
        return missing(&format!(
            "playwright-core is not installed: run `npm ci` in {}",
            e2e.display()
        ));
    }
    let tmp = tempfile::tempdir().unwrap();
    let dir = demo_project(tmp.path());
    let server = Server::start(&dir);
    let shots = std::env::var_os("CASTELLAN_E2E_SCREENSHOTS")
        .map(PathBuf::from)
        .unwrap_or_else(|| tmp.path().join("screenshots"));
    let out = match Command::new("node")
        .arg("serve.e2e.mjs")
        .current_dir(&e2e)
        .env("CASTELLAN_URL", &server.url)
        .env("SCREENSHOTS", &shots)
        .env("CHROMIUM", &chromium)
        .env("EXPECT_STRUCTURES", DEMO_STRUCTURES.to_string())
        .output()
    {
        Ok(o) => o,
        Err(e) => return missing(&format!("cannot run node ({e})")),
    };
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "the browser test failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let figures: serde_json::Value =
        serde_json::from_str(stdout.lines().last().unwrap_or("")).unwrap();
    eprintln!("serve e2e figures: {figures}");
    assert_eq!(figures["structures"], DEMO_STRUCTURES);
    assert!(figures["model_pixel_fraction"].as_f64().unwrap() > 0.02);
    for shot in [
        "plan.png",
        "plan-cleaning.png",
        "facades.png",
        "lines.png",
        "correspondences.png",
        "model.png",
        "model-peeled.png",
        "model-cut.png",
    ] {
        let img = image::open(shots.join(shot)).unwrap();
        assert!(img.width() > 100 && img.height() > 100, "{shot}");
    }
    // The page saved its changes: the project still reconstructs from disk.
    assert!(dir.join("out/model.glb").is_file());
    let estimate: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out/estimate.json")).unwrap()).unwrap();
    assert_eq!(
        estimate["structures"].as_array().unwrap().len(),
        DEMO_ESTIMATED_STRUCTURES
    );
    assert!(
        dir.join("out/overlays/keep_south_near_facade.png")
            .is_file()
    );
    // The page cleaned the plan and undid it, saved segments and went back to automatic ones:
    // the files stay, PROJECT.toml names the originals.
    let project = std::fs::read_to_string(dir.join("PROJECT.toml")).unwrap();
    assert!(project.contains("plan = \"plan.png\""), "{project}");
    assert!(!project.contains("lines ="), "{project}");
    assert!(dir.join("plan.cleaned.png").is_file());
    let lines: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("keep_south_near.lines.json")).unwrap())
            .unwrap();
    assert!(lines["horizontal"].as_array().unwrap().len() >= 2);
}
