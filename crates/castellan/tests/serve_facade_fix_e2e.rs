//! End-to-end: the façade corrections of `castellan serve` (issue 22) on the demo project,
//! driven by Debian's Chromium through playwright-core (tests/e2e/facade_fix.e2e.mjs): a floor
//! line dragged, a window added, one deleted, a floor marked without windows, one undo; then
//! PROJECT.toml on disk holds the corrections and `castellan reconstruct` honours them. Outside
//! CI it skips, saying why, when Chromium, Node.js or tests/e2e/node_modules (`npm ci` there) is
//! missing; under CI=true those are failures.

mod serve_support;

use std::process::Command;

use serve_support::{Server, browser_test, demo_project, screenshots};

#[test]
fn facade_corrections_are_made_in_chromium_and_honoured_by_reconstruct() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = demo_project(tmp.path());
    let server = Server::start(&dir);
    let shots = screenshots(&tmp.path().join("screenshots"));
    let Some(figures) = browser_test(
        "serve_facade_fix_e2e",
        "facade_fix.e2e.mjs",
        &server,
        &shots,
        &[],
    ) else {
        return;
    };
    eprintln!("façade corrections e2e figures: {figures}");
    drop(server);
    let shot = image::open(shots.join("facade-fix.png")).unwrap();
    assert!(shot.width() > 100 && shot.height() > 100);

    // PROJECT.toml on disk: the corrections left after the undo, under the near photo's entry.
    let text = std::fs::read_to_string(dir.join("PROJECT.toml")).unwrap();
    let project = integrate::project::Project::from_toml(&text).unwrap();
    let fix = &project.facades[0].fix;
    assert_eq!(project.facades[0].image, "keep_south_near.png");
    let start_floors = figures["start"]["floors"].as_u64().unwrap() as usize;
    assert_eq!(
        fix.floor_lines.as_ref().map(Vec::len),
        Some(start_floors - 1),
        "{text}"
    );
    assert_eq!(
        (fix.add_windows.len(), fix.remove_windows.len()),
        (1, 1),
        "{text}"
    );
    assert!(fix.blind_floors.is_empty(), "undone: {text}");
    assert!(project.facades[1].fix.is_empty(), "{text}");
    assert!(text.contains("[facade.fix]"), "{text}");

    // `castellan reconstruct` honours them: the near photo's façade has the page's window count
    // and the user as the source of its corrected parameters.
    let outdir = tmp.path().join("out");
    let run = Command::new(env!("CARGO_BIN_EXE_castellan"))
        .args(["reconstruct"])
        .arg(dir.join("PROJECT.toml"))
        .arg("-o")
        .arg(&outdir)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let estimate: serde_json::Value =
        serde_json::from_slice(&std::fs::read(outdir.join("estimate.json")).unwrap()).unwrap();
    let keep = estimate["structures"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| {
            s["facades"]
                .as_array()
                .is_some_and(|f| f.iter().any(|f| f["image"] == "keep_south_near.png"))
        })
        .unwrap();
    let near = keep["facades"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["image"] == "keep_south_near.png")
        .unwrap();
    let floors = near["floors"].as_array().unwrap();
    let windows: u64 = floors.iter().map(|f| f["windows"].as_u64().unwrap()).sum();
    let last = figures["steps"].as_array().unwrap().last().unwrap();
    assert_eq!(floors.len() as u64, last["floors"].as_u64().unwrap());
    assert_eq!(windows, last["windows"].as_u64().unwrap());
    let side = near["side"].as_str().unwrap();
    for parameter in ["floors", "floor_windows"] {
        let p = &keep["provenance"][format!("facade.keep_south_near.png.{side}.{parameter}")];
        assert_eq!(p["image"], "user", "{parameter}: {p}");
    }
}
