//! The façade corrections' routes (issue 22) through the router on the bundled demo project:
//! a correction that runs is saved into PROJECT.toml under the façade's entry and answered with
//! the corrected tree; a bad one is refused naming the entry, and nothing changes.

use axum::http::StatusCode;

use super::tests::{app, assert_one_warning, demo_project, json, saved_project};

const NEAR: &str = "/api/facades/keep_south_near.png";

#[tokio::test]
async fn corrections_are_run_then_saved_and_bad_ones_change_nothing() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let (s, tree) = json(&app, "POST", &format!("{NEAR}/tree"), "").await;
    assert_eq!(s, StatusCode::OK, "{tree}");
    let height = tree["height"].as_f64().unwrap();
    let floors = tree["facades"][0]["floors"].as_array().unwrap();
    assert!(floors.len() >= 3, "{tree}");
    assert!(saved_project(dir.path()).facades[0].fix.is_empty());
    // The demo's model is plausible: nothing to warn of.
    assert_eq!(tree["warnings"], serde_json::json!([]), "{tree}");

    // A window added over the whole façade: the corrected model is more glass than wall, and
    // the answer says so (`facade::plausibility`); the correction is still saved.
    let bbox: Vec<f64> = (0..4)
        .map(|i| tree["facades"][0]["bbox"][i].as_f64().unwrap())
        .collect();
    let body = format!(
        r#"{{"add_windows": [[{}, {}, {}, {}]]}}"#,
        bbox[0], bbox[1], bbox[2], bbox[3]
    );
    let (s, r) = json(&app, "PUT", &format!("{NEAR}/fixes"), &body).await;
    assert_eq!(s, StatusCode::OK, "{r}");
    assert_one_warning(&r, "the windows cover");
    assert_eq!(
        saved_project(dir.path()).facades[0].fix.add_windows.len(),
        1
    );

    // Two floor lines, the ground floor blind.
    let lines = [
        floors[1]["y0"].as_f64().unwrap() + 3.0,
        floors[2]["y0"].as_f64().unwrap(),
    ];
    let body = format!(
        r#"{{"floor_lines": [{}, {}], "blind_floors": [1]}}"#,
        lines[0], lines[1]
    );
    let (s, r) = json(&app, "PUT", &format!("{NEAR}/fixes"), &body).await;
    assert_eq!(s, StatusCode::OK, "{r}");
    let got = r["facades"][0]["floors"].as_array().unwrap();
    assert_eq!(got.len(), 3, "{r}");
    assert_eq!(got[1]["y0"].as_f64(), Some(lines[0]));
    assert_eq!(
        got[2]["windows"].as_array().unwrap().len(),
        0,
        "blind ground floor"
    );
    let saved = saved_project(dir.path()).facades[0].fix.clone();
    assert_eq!(saved.floor_lines, Some(lines.to_vec()));
    assert_eq!(saved.blind_floors, vec![1]);
    let text = std::fs::read_to_string(dir.path().join("PROJECT.toml")).unwrap();
    assert!(text.contains("[facade.fix]"), "{text}");

    // A floor line below the rectified photo: refused by name, the saved fix unchanged.
    let before = std::fs::read(dir.path().join("PROJECT.toml")).unwrap();
    let bad = format!(r#"{{"floor_lines": [{}]}}"#, height + 100.0);
    let (s, r) = json(&app, "PUT", &format!("{NEAR}/fixes"), &bad).await;
    assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY, "{r}");
    let e = r["error"].as_str().unwrap();
    assert!(
        e.starts_with("[[facade]] #1 (image = \"keep_south_near.png\")")
            && e.contains("below the façade"),
        "{e}"
    );
    assert_eq!(
        std::fs::read(dir.path().join("PROJECT.toml")).unwrap(),
        before
    );
    // An unknown key is refused before anything runs.
    let (s, _) = json(&app, "PUT", &format!("{NEAR}/fixes"), r#"{"floors": [10]}"#).await;
    assert!(s.is_client_error(), "{s}");
    assert_eq!(
        std::fs::read(dir.path().join("PROJECT.toml")).unwrap(),
        before
    );

    // DELETE: back to the search's own estimate.
    let (s, r) = json(&app, "DELETE", &format!("{NEAR}/fixes"), "").await;
    assert_eq!(s, StatusCode::OK, "{r}");
    assert!(saved_project(dir.path()).facades[0].fix.is_empty());
    assert_eq!(
        r["facades"][0]["floors"].as_array().unwrap().len(),
        floors.len()
    );
    let (s, _) = json(&app, "PUT", "/api/facades/nope.png/fixes", "{}").await;
    assert_eq!(s, StatusCode::NOT_FOUND);
}
