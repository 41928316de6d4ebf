//! The user's edits through the API on the demo project: plan cleaning (§5.1.1) reaching the
//! plan stage and the reconstruction, and rectification segments (§3.1.1) reaching LINES.json,
//! PROJECT.toml and the rectification.

use std::path::Path;

use axum::http::StatusCode;
use serde_json::{Value, json as json_value};

use super::tests::{app, demo_project, get, json, saved_project, upload};

/// A wall across the demo ward below the keep, from beyond its west wall to beyond its east one:
/// the ward becomes two faces.
fn wall_across_the_ward() -> Value {
    json_value!({"strokes": [{"ink": true, "radius": 7.0, "points": [[100.0, 360.0], [540.0, 360.0]]}]})
}

fn grey_at(dir: &Path, file: &str, x: u32, y: u32) -> u8 {
    image::open(dir.join(file))
        .unwrap()
        .to_luma8()
        .get_pixel(x, y)[0]
}

#[tokio::test]
async fn the_binary_plan_is_black_walls_on_white_paper() {
    let dir = demo_project();
    let (s, bytes) = get(&app(dir.path(), 1 << 20), "/api/plan/binary").await;
    assert_eq!(s, StatusCode::OK);
    let img = image::load_from_memory(&bytes).unwrap().to_luma8();
    assert_eq!(img.dimensions(), (640, 480));
    assert!(img.pixels().all(|p| p[0] == 0 || p[0] == 255));
    // The west curtain wall and the open ward.
    assert_eq!(img.get_pixel(110, 250)[0], 0);
    assert_eq!(img.get_pixel(320, 360)[0], 255);
}

#[tokio::test]
async fn a_cleaned_plan_is_what_the_plan_stage_and_reconstruct_read() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let (s, before) = json(&app, "POST", "/api/plan", "").await;
    assert_eq!(s, StatusCode::OK, "{before}");
    let overlay_before = std::fs::read(dir.path().join("out/overlays/plan_labels.png")).unwrap();

    let (s, v) = json(
        &app,
        "PUT",
        "/api/plan/cleaning",
        &wall_across_the_ward().to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(v["plan"], "plan.cleaned.png");
    assert!(v["changed_pixels"].as_u64().unwrap() > 3000, "{v}");
    assert_eq!(saved_project(dir.path()).plan, "plan.cleaned.png");
    assert_eq!(grey_at(dir.path(), "plan.cleaned.png", 320, 360), 0);
    // The upload is kept as it was.
    let original = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/demo/plan.png");
    assert_eq!(
        std::fs::read(dir.path().join("plan.png")).unwrap(),
        std::fs::read(original).unwrap()
    );
    let (_, p) = json(&app, "GET", "/api/project", "").await;
    assert_eq!(p["cleaning"]["original"], "plan.png");
    assert_eq!(p["cleaning"]["strokes"].as_array().unwrap().len(), 1);

    let (s, after) = json(&app, "POST", "/api/plan", "").await;
    assert_eq!(s, StatusCode::OK, "{after}");
    assert_eq!(
        after["faces"].as_u64().unwrap(),
        before["faces"].as_u64().unwrap() + 1,
        "the new wall splits the ward: {before} → {after}"
    );
    let overlay_after = std::fs::read(dir.path().join("out/overlays/plan_labels.png")).unwrap();
    assert_ne!(overlay_before, overlay_after);

    // `castellan reconstruct` reads PROJECT.toml's plan: the new wall is a new structure.
    let (s, model) = json(&app, "POST", "/api/reconstruct", "").await;
    assert_eq!(s, StatusCode::OK, "{model}");
    let structures = model["structures"].as_u64().unwrap();

    // No strokes: the original drawing again.
    let (s, v) = json(&app, "PUT", "/api/plan/cleaning", r#"{"strokes": []}"#).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(saved_project(dir.path()).plan, "plan.png");
    let (_, again) = json(&app, "POST", "/api/plan", "").await;
    assert_eq!(again["faces"], before["faces"]);
    let (_, model) = json(&app, "POST", "/api/reconstruct", "").await;
    assert_ne!(
        model["structures"].as_u64().unwrap(),
        structures,
        "the cleaned plan's wall changes the estimated structures"
    );
}

#[tokio::test]
async fn bad_strokes_are_refused_and_nothing_is_written() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let toml = std::fs::read(dir.path().join("PROJECT.toml")).unwrap();
    for (body, says) in [
        (
            r#"{"strokes": [{"ink": true, "radius": 0, "points": [[1, 1]]}]}"#,
            "stroke 0: radius",
        ),
        (
            r#"{"strokes": [{"ink": true, "radius": 3, "points": []}]}"#,
            "stroke 0: needs",
        ),
    ] {
        let (s, v) = json(&app, "PUT", "/api/plan/cleaning", body).await;
        assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
        assert!(v["error"].as_str().unwrap().contains(says), "{v}");
    }
    let (s, _) = json(&app, "PUT", "/api/plan/cleaning", r#"{"strokes": 3}"#).await;
    assert!(s.is_client_error());
    assert_eq!(
        std::fs::read(dir.path().join("PROJECT.toml")).unwrap(),
        toml
    );
    assert!(!dir.path().join("plan_cleaning.json").exists());
    assert!(!dir.path().join("plan.cleaned.png").exists());
}

#[tokio::test]
async fn a_new_plan_upload_starts_a_new_cleaning() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let (s, _) = json(
        &app,
        "PUT",
        "/api/plan/cleaning",
        &wall_across_the_ward().to_string(),
    )
    .await;
    assert_eq!(s, StatusCode::OK);
    let (s, v) = upload(&app, "plan", "other.png", &super::tests::png_bytes(64, 48)).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    let (_, p) = json(&app, "GET", "/api/project", "").await;
    assert_eq!(p["project"]["plan"], "other.png");
    assert_eq!(p["cleaning"]["original"], "other.png");
    assert_eq!(p["cleaning"]["strokes"].as_array().unwrap().len(), 0);
    let (s, bytes) = get(&app, "/api/plan/binary").await;
    assert_eq!(s, StatusCode::OK);
    let img = image::load_from_memory(&bytes).unwrap();
    assert_eq!((img.width(), img.height()), (64, 48));
}

#[tokio::test]
async fn dragged_segments_are_saved_and_the_rectification_uses_them() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let uri = "/api/facades/keep_south_near.png";
    let (s, auto) = json(&app, "POST", &format!("{uri}/rectify"), "").await;
    assert_eq!(s, StatusCode::OK, "{auto}");
    assert_eq!(auto["manual"], false);
    let mut lines = auto["lines"].clone();
    assert_eq!(
        lines["horizontal"].as_array().unwrap().len() as u64,
        auto["horizontal"].as_u64().unwrap()
    );
    assert!(lines["vertical"].as_array().unwrap().len() >= 2, "{lines}");
    // The user drags one end of the first horizontal segment and drops the last vertical one.
    lines["horizontal"][0][1] = json_value!(lines["horizontal"][0][1].as_f64().unwrap() + 4.0);
    lines["vertical"].as_array_mut().unwrap().pop();

    let (s, v) = json(&app, "PUT", &format!("{uri}/lines"), &lines.to_string()).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(v["saved"], "keep_south_near.lines.json");
    let f = saved_project(dir.path()).facades[0].clone();
    assert_eq!(f.lines.as_deref(), Some("keep_south_near.lines.json"));
    let file: Value = serde_json::from_slice(
        &std::fs::read(dir.path().join("keep_south_near.lines.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(file, lines);

    let (s, manual) = json(&app, "POST", &format!("{uri}/rectify"), "").await;
    assert_eq!(s, StatusCode::OK, "{manual}");
    assert_eq!(manual["manual"], true);
    assert_eq!(manual["lines"], lines);
    assert_ne!(
        (&manual["width"], &manual["height"]),
        (&auto["width"], &auto["height"]),
        "a moved segment moves the vanishing point and so the rectified size"
    );

    let (s, v) = json(&app, "DELETE", &format!("{uri}/lines"), "").await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(saved_project(dir.path()).facades[0].lines, None);
    let (_, again) = json(&app, "POST", &format!("{uri}/rectify"), "").await;
    assert_eq!(again["manual"], false);
    assert_eq!(again["lines"], auto["lines"]);
}

#[tokio::test]
async fn segments_the_rectification_cannot_use_are_refused() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let toml = std::fs::read(dir.path().join("PROJECT.toml")).unwrap();
    let one_vertical = r#"{"horizontal": [[0,0,100,0],[0,50,100,52]], "vertical": [[0,0,0,100]]}"#;
    let (s, v) = json(
        &app,
        "PUT",
        "/api/facades/keep_south_near.png/lines",
        one_vertical,
    )
    .await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{v}");
    let e = v["error"].as_str().unwrap();
    assert!(
        e.contains("keep_south_near.png") && e.contains("two vertical"),
        "{e}"
    );
    let (s, _) = json(&app, "PUT", "/api/facades/nope.png/lines", one_vertical).await;
    assert_eq!(s, StatusCode::NOT_FOUND);
    assert_eq!(
        std::fs::read(dir.path().join("PROJECT.toml")).unwrap(),
        toml
    );
    assert!(!dir.path().join("keep_south_near.lines.json").exists());
}
