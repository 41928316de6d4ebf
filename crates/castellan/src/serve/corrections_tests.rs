//! Corrections through the API on the demo project (issue 22): saved in PROJECT.toml by plan
//! point, the overlay redrawn, refused naming the entry with nothing saved, undone by sending
//! the previous list, and honoured by the reconstruction.

use axum::http::StatusCode;
use serde_json::json as json_value;

use super::tests::{app, demo_project, json, saved_project};

/// The demo plan (examples/demo, 0.1 m per pixel): the ward, a tower's centre, the keep's.
const WARD: [f64; 2] = [320.0, 380.0];
const TOWER: [f64; 2] = [530.0, 100.0];
const KEEP: [f64; 2] = [320.0, 270.0];

#[tokio::test]
async fn a_relabel_is_saved_by_point_and_redraws_the_overlay() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let (s, plan) = json(&app, "POST", "/api/plan", "").await;
    assert_eq!(s, StatusCode::OK, "{plan}");
    let before = std::fs::read(dir.path().join("out/overlays/plan_labels.png")).unwrap();
    let body = json_value!({"label": [{"point": WARD, "label": "chapel"}]});
    let (s, v) = json(&app, "PUT", "/api/corrections", &body.to_string()).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(v["saved"], 1);
    assert_eq!(v["towers"], plan["towers"]);
    let after = std::fs::read(dir.path().join("out/overlays/plan_labels.png")).unwrap();
    assert_ne!(before, after);
    let overlay = image::load_from_memory(&after).unwrap().to_rgb8();
    let px = overlay
        .get_pixel(WARD[0] as u32, WARD[1] as u32)
        .0
        .map(i32::from);
    // The overlay tints the paper with the label's colour: the chapel's cyan (40, 220, 220),
    // green and blue alike, red well below; the courtyard's blue before had them apart.
    assert!((px[1] - px[2]).abs() < 10 && px[1] - px[0] > 50, "{px:?}");
    let saved = saved_project(dir.path());
    assert_eq!(saved.label_fixes.len(), 1);
    assert_eq!(saved.label_fixes[0].point, WARD);
    let text = std::fs::read_to_string(dir.path().join("PROJECT.toml")).unwrap();
    assert!(text.contains("[[label]]"), "{text}");
    assert!(text.contains("label = \"chapel\""), "{text}");
    // The comments of the user's file stay.
    assert!(text.contains("# metres per plan pixel"), "{text}");
    let (s, at) = json(&app, "GET", "/api/plan/at?x=320&y=380", "").await;
    assert_eq!(s, StatusCode::OK, "{at}");
    assert_eq!(at["label"], "chapel");
    assert_eq!(at["towers"].as_array().unwrap().len(), 2);
    let (_, got) = json(&app, "GET", "/api/corrections", "").await;
    assert_eq!(got["label"][0]["label"], "chapel");
    assert_eq!(got["labels"].as_array().unwrap().len(), 11);
}

#[tokio::test]
async fn a_correction_that_cannot_apply_is_refused_naming_it_and_nothing_is_saved() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let text = std::fs::read_to_string(dir.path().join("PROJECT.toml")).unwrap();
    for (body, message) in [
        (
            json_value!({"label": [{"point": WARD, "label": "chapel"}, {"point": [9999, 0], "label": "chapel"}]}),
            "[[label]] #2: point [9999, 0] is outside the plan (640 × 480 px)",
        ),
        (
            json_value!({"merge": [{"points": [WARD, WARD]}]}),
            "[[merge]] #1: both points are in one region",
        ),
        (
            json_value!({"structure": [{"point": [5, 5], "height": 30}]}),
            "[[structure]] #1: no structure is built at [5, 5]",
        ),
        (
            json_value!({"structure": [{"point": KEEP, "roof": "dome"}]}),
            "unknown variant `dome`",
        ),
        (
            json_value!({"scale_line": {"points": [[0, 0], [100, 0]], "metres": 1e6}}),
            "scale_line: ",
        ),
    ] {
        let (s, v) = json(&app, "PUT", "/api/corrections", &body.to_string()).await;
        assert!(s.is_client_error(), "{body}: {s} {v}");
        assert!(
            v["error"].as_str().unwrap().contains(message),
            "{body}: {v}"
        );
        assert_eq!(
            std::fs::read_to_string(dir.path().join("PROJECT.toml")).unwrap(),
            text
        );
    }
}

#[tokio::test]
async fn towers_removed_and_undone_and_the_keep_honoured_by_the_reconstruction() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let (_, plan) = json(&app, "POST", "/api/plan", "").await;
    let towers = plan["towers"].as_u64().unwrap();
    assert_eq!(towers, 2, "{plan}");
    let removed = json_value!({"tower": [{"point": TOWER, "remove": true}]});
    let (s, v) = json(&app, "PUT", "/api/corrections", &removed.to_string()).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(v["towers"], 1);
    // Undo: the page sends the list as it was.
    let (s, v) = json(&app, "PUT", "/api/corrections", "{}").await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(v["towers"], 2);
    assert!(saved_project(dir.path()).tower_fixes.is_empty());

    let (s, _) = json(&app, "POST", "/api/reconstruct", "").await;
    assert_eq!(s, StatusCode::OK);
    let uri = format!("/api/structure?x={}&y={}", KEEP[0], KEEP[1]);
    let (s, keep) = json(&app, "GET", &uri, "").await;
    assert_eq!(s, StatusCode::OK, "{keep}");
    assert_eq!(keep["role"], "keep");
    assert_eq!(keep["units"], "m");

    let body = json_value!({"structure": [{"point": TOWER, "keep": true, "height": 40.0, "roof": "pyramid"}]});
    let (s, v) = json(&app, "PUT", "/api/corrections", &body.to_string()).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    let (s, _) = json(&app, "POST", "/api/reconstruct", "").await;
    assert_eq!(s, StatusCode::OK);
    let uri = format!("/api/structure?x={}&y={}", TOWER[0], TOWER[1]);
    let (_, tower) = json(&app, "GET", &uri, "").await;
    assert_eq!(tower["role"], "keep", "{tower}");
    assert_eq!(tower["height"], 40.0);
    assert_eq!(tower["roof"], "pyramid");
    assert_eq!(tower["sources"]["height"], "user: [[structure]] #1");
}

#[tokio::test]
async fn plan_settings_are_checked_as_project_toml_is() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let ok = json_value!({"scale": 0.2, "thin_lines": 0.5, "hatching": true, "one_building": true, "trim_ink": true});
    let (s, v) = json(&app, "PUT", "/api/plan/settings", &ok.to_string()).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    let p = saved_project(dir.path());
    assert_eq!(
        (
            p.metres_per_pixel,
            p.thin_lines,
            p.hatching,
            p.one_building,
            p.trim_ink
        ),
        (Some(0.2), Some(0.5), Some(true), Some(true), Some(true))
    );
    assert!(p.plan_options().one_building && p.plan_options().trim_ink);
    let both = json_value!({"scale": 0.2, "scale_bar": 30.0});
    let (s, v) = json(&app, "PUT", "/api/plan/settings", &both.to_string()).await;
    assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY, "{v}");
    assert!(v["error"].as_str().unwrap().contains("not both"), "{v}");
    assert_eq!(saved_project(dir.path()).scale_bar_metres, None);
}
