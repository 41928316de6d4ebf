//! End-to-end: the Gothic step of `castellan serve` (issue 22) in Debian's Chromium through
//! playwright-core (tests/e2e/gothic_fix.e2e.mjs): a synthetic Gothic photo
//! (`facade::gothic::synth`) uploaded, its elements found, an apex dragged, a window deleted
//! and the deletion undone; PROJECT.toml then holds exactly the dragged apex. Outside CI it
//! skips, saying why, when Chromium, Node.js or tests/e2e/node_modules (`npm ci` there) is
//! missing; under CI=true those are failures.

mod serve_support;

use facade::gothic::synth::{SynthSpec, synthetic_facade};
use integrate::project::Project;
use serve_support::{Server, browser_test, demo_project, screenshots};

/// How far (rectified pixels) the page drags the apex up.
const APEX_DRAG: f64 = 8.0;

#[test]
fn gothic_elements_are_dragged_deleted_and_undone_in_chromium() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = demo_project(tmp.path());
    // The photo comes from outside the project, as a user's would.
    let photo = tmp.path().join("portal.png");
    synthetic_facade(&SynthSpec::small(), 1)
        .image
        .save(&photo)
        .unwrap();
    let server = Server::start(&dir);
    let shots = screenshots(&tmp.path().join("screenshots"));
    let Some(figures) = browser_test(
        "serve_gothic_fix_e2e",
        "gothic_fix.e2e.mjs",
        &server,
        &shots,
        &[
            ("GOTHIC_PHOTO", photo.display().to_string()),
            ("APEX_DRAG", APEX_DRAG.to_string()),
        ],
    ) else {
        return;
    };
    eprintln!("gothic e2e figures: {figures}");
    let found = figures["elements"].as_u64().unwrap();
    assert_eq!(figures["after_delete"].as_u64(), Some(found - 1));
    assert_eq!(figures["after_undo"].as_u64(), Some(found));
    assert_eq!(figures["after_add"].as_u64(), Some(found + 1));
    for shot in ["gothic.png", "gothic-corrected.png"] {
        let img = image::open(shots.join(shot)).unwrap();
        assert!(img.width() > 100 && img.height() > 100, "{shot}");
    }
    // PROJECT.toml: the photo as a [[gothic]] entry, marked as an elevation, with two
    // corrections — the apex, where the page dragged it, and the element added by its box; the
    // undone deletion is gone.
    let text = std::fs::read_to_string(dir.join("PROJECT.toml")).unwrap();
    let project = Project::parse_unchecked(&text).unwrap();
    assert_eq!(project.gothics.len(), 1, "{text}");
    let g = &project.gothics[0];
    assert_eq!(g.image, "portal.png");
    assert!(g.rectified);
    assert_eq!(g.elements.len(), 2, "{text}");
    let c = &g.elements[0];
    assert!(!c.delete && !c.add);
    let wanted = figures["apex"]["wanted"].as_f64().unwrap();
    let apex = c.apex.expect("the dragged apex is saved");
    assert!((apex - wanted).abs() <= 1.5, "{apex} vs {wanted}");
    assert!((figures["apex"]["returned"].as_f64().unwrap() - apex).abs() <= 0.05);
    let added = &g.elements[1];
    assert!(added.add && !added.delete, "{text}");
    let (apex, sill) = (added.apex.unwrap(), added.sill.unwrap());
    assert!((apex - figures["added"]["apex"].as_f64().unwrap()).abs() <= 0.05);
    assert!((sill - figures["added"]["sill"].as_f64().unwrap()).abs() <= 0.05);
    // Drawn as an equilateral pointed arch, or all arch when the box is lower than that.
    let (width, springing) = (added.width.unwrap(), added.springing.unwrap());
    let rise = springing - apex;
    assert!(
        (rise - (3f64.sqrt() / 2.0 * width).min(sill - apex)).abs() <= 0.2,
        "{text}"
    );
    // The façade photos of the demo are untouched.
    assert_eq!(project.facades.len(), 2);
}
