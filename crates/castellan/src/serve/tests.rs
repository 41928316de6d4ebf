//! The API driven through the router (tower's `oneshot`), on the bundled demo project or an
//! empty folder: status codes, JSON errors, and what lands in the project folder.

use std::path::Path;

use axum::body::Body;
use axum::http::{Request, StatusCode};
use http_body_util::BodyExt;
use serde_json::Value;
use tower::ServiceExt;

use super::{app, router, store};

pub(super) fn demo_project() -> tempfile::TempDir {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/demo");
    let dir = tempfile::tempdir().unwrap();
    for e in std::fs::read_dir(src).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, dir.path().join(p.file_name().unwrap())).unwrap();
    }
    dir
}

/// PROJECT.toml as saved (a façade may still wait for its correspondence).
pub(super) fn saved_project(dir: &Path) -> integrate::project::Project {
    store::Store::open(dir).unwrap().load().unwrap().unwrap()
}

/// The token and address the test apps use.
pub(super) const TOKEN: &str = "0123456789abcdef";
pub(super) const HOST: &str = "127.0.0.1:8080";

pub(super) fn app(dir: &Path, max_upload: usize) -> axum::Router {
    let access = super::Access::new(
        TOKEN.into(),
        HOST.parse().unwrap(),
        std::time::Duration::from_secs(5),
    );
    router(app::App::new(
        store::Store::open(dir).unwrap(),
        max_upload,
        access,
        Default::default(),
    ))
}

/// Sends `req` as the page would: with the server's Host and the token, unless it has its own.
pub(super) async fn send(app: &axum::Router, req: Request<Body>) -> (StatusCode, Vec<u8>) {
    send_as_is(app, with_token(req)).await
}

/// `req` with the server's Host and the token, unless it has its own.
fn with_token(mut req: Request<Body>) -> Request<Body> {
    let h = req.headers_mut();
    h.entry("host").or_insert(HOST.parse().unwrap());
    h.entry(super::access::TOKEN_HEADER)
        .or_insert(TOKEN.parse().unwrap());
    req
}

/// Sends `req` without adding anything.
pub(super) async fn send_as_is(app: &axum::Router, req: Request<Body>) -> (StatusCode, Vec<u8>) {
    let res = app.clone().oneshot(req).await.unwrap();
    let status = res.status();
    let body = res.into_body().collect().await.unwrap().to_bytes().to_vec();
    (status, body)
}

pub(super) async fn get(app: &axum::Router, uri: &str) -> (StatusCode, Vec<u8>) {
    send(app, Request::get(uri).body(Body::empty()).unwrap()).await
}

pub(super) async fn json(
    app: &axum::Router,
    method: &str,
    uri: &str,
    body: &str,
) -> (StatusCode, Value) {
    let req = Request::builder()
        .method(method)
        .uri(uri)
        .header("content-type", "application/json")
        .body(Body::from(body.to_string()))
        .unwrap();
    let (s, b) = send(app, req).await;
    (s, serde_json::from_slice(&b).unwrap_or(Value::Null))
}

pub(super) fn multipart(kind: &str, file_name: &str, bytes: &[u8]) -> Request<Body> {
    let b = "castellanboundary";
    let mut body = format!(
        "--{b}\r\nContent-Disposition: form-data; name=\"kind\"\r\n\r\n{kind}\r\n--{b}\r\nContent-Disposition: form-data; name=\"file\"; filename=\"{file_name}\"\r\nContent-Type: application/octet-stream\r\n\r\n"
    )
    .into_bytes();
    body.extend_from_slice(bytes);
    body.extend_from_slice(format!("\r\n--{b}--\r\n").as_bytes());
    Request::post("/api/upload")
        .header("content-type", format!("multipart/form-data; boundary={b}"))
        .body(Body::from(body))
        .unwrap()
}

pub(super) async fn upload(
    app: &axum::Router,
    kind: &str,
    name: &str,
    bytes: &[u8],
) -> (StatusCode, Value) {
    let (s, b) = send(app, multipart(kind, name, bytes)).await;
    (s, serde_json::from_slice(&b).unwrap())
}

pub(super) fn png_bytes(w: u32, h: u32) -> Vec<u8> {
    let img = image::RgbImage::from_fn(w, h, |x, y| image::Rgb([(x * 7) as u8, (y * 5) as u8, 90]));
    crate::images::png(&img, Path::new("t.png")).unwrap()
}

#[tokio::test]
async fn the_page_and_its_script_are_served_from_the_binary() {
    let dir = tempfile::tempdir().unwrap();
    let app = app(dir.path(), 1 << 20);
    let (s, html) = get(&app, "/").await;
    assert_eq!(s, StatusCode::OK);
    let html = String::from_utf8(html).unwrap();
    assert!(html.contains("/app.js") && html.contains("/app.css"));
    // Nothing from the network: no absolute URL in the page.
    assert!(
        !html.contains("http://") && !html.contains("https://"),
        "{html}"
    );
    let (s, js) = get(&app, "/app.js").await;
    assert_eq!(s, StatusCode::OK);
    assert!(
        js.len() > 100_000,
        "three.js is bundled: {} bytes",
        js.len()
    );
}

#[tokio::test]
async fn the_demo_project_is_read_with_its_training_boxes() {
    let dir = demo_project();
    let (s, v) = json(&app(dir.path(), 1 << 20), "GET", "/api/project", "").await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(v["project"]["plan"], "plan.png");
    assert_eq!(v["project"]["facade"].as_array().unwrap().len(), 2);
    assert!(v["training"]["keep_south_near.png"]["classes"]["window"].is_array());
}

#[tokio::test]
async fn files_outside_the_project_are_refused() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let (s, b) = get(&app, "/files/PROJECT.toml").await;
    assert_eq!(s, StatusCode::OK);
    assert!(String::from_utf8(b).unwrap().contains("plan.png"));
    for uri in [
        "/files/..%2F..%2Fetc%2Fpasswd",
        "/files/%2Fetc%2Fpasswd",
        "/files/out/..%2F..%2FPROJECT.toml",
        "/files/.git%2Fconfig",
    ] {
        let (s, b) = get(&app, uri).await;
        assert_eq!(s, StatusCode::FORBIDDEN, "{uri}");
        let e: Value = serde_json::from_slice(&b).unwrap();
        assert!(
            e["error"].as_str().unwrap().contains("inside the project"),
            "{e}"
        );
    }
    assert_eq!(
        get(&app, "/files/nothing.png").await.0,
        StatusCode::NOT_FOUND
    );
}

#[tokio::test]
async fn oversized_and_non_image_uploads_are_refused_with_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let app = app(dir.path(), 64 << 10);
    let (s, e) = upload(&app, "plan", "big.png", &vec![0u8; 200 << 10]).await;
    assert_eq!(s, StatusCode::PAYLOAD_TOO_LARGE);
    assert!(e["error"].as_str().unwrap().contains("limit"), "{e}");
    let (s, e) = upload(&app, "plan", "plan.png", b"#!/bin/sh\necho not a picture\n").await;
    assert_eq!(s, StatusCode::UNSUPPORTED_MEDIA_TYPE);
    assert!(
        e["error"]
            .as_str()
            .unwrap()
            .contains("not a readable image"),
        "{e}"
    );
    // A PNG signature with a broken body is caught by decoding, not by the name.
    let mut broken = png_bytes(8, 8);
    broken.truncate(40);
    let (s, e) = upload(&app, "plan", "plan.png", &broken).await;
    assert_eq!(s, StatusCode::UNSUPPORTED_MEDIA_TYPE, "{e}");
    assert!(!dir.path().join("plan.png").exists());
    assert!(!dir.path().join("PROJECT.toml").exists());
}

#[tokio::test]
async fn uploads_create_the_project_and_register_facades() {
    let dir = tempfile::tempdir().unwrap();
    let app = app(dir.path(), 1 << 20);
    let (s, e) = upload(&app, "facade", "f.png", &png_bytes(40, 30)).await;
    assert_eq!(s, StatusCode::CONFLICT, "the plan comes first: {e}");
    let (s, v) = upload(&app, "plan", "../My Plan.png", &png_bytes(50, 40)).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(v["name"], "My_Plan.png");
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64()),
        (Some(50), Some(40))
    );
    let (s, v) = upload(&app, "facade", "keep.png", &png_bytes(40, 30)).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    let p = saved_project(dir.path());
    assert_eq!(p.plan, "My_Plan.png");
    assert_eq!(p.facades.len(), 1);
    assert!(dir.path().join("keep.training.json").exists());
    // Uploading a photo of the same name adds it under a fresh name (guard_tests.rs).
    let (s, v) = upload(&app, "facade", "keep.png", &png_bytes(40, 30)).await;
    assert_eq!(
        (s, v["name"].as_str()),
        (StatusCode::OK, Some("keep-2.png"))
    );
    assert_eq!(saved_project(dir.path()).facades.len(), 2);
}

#[tokio::test]
async fn training_boxes_and_correspondences_are_checked_and_saved() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let uri = "/api/facades/keep_south_near.png/training";
    let (s, e) = json(
        &app,
        "PUT",
        uri,
        r#"{"classes":{"door":[[0,0,50,10]],"wall":[[0,0,4,4]]}}"#,
    )
    .await;
    // An unknown class is refused as the body is parsed (facade::classify::Class).
    assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY, "{e}");
    assert!(e["error"].as_str().unwrap().contains("door"), "{e}");
    let boxes = r#"{"classes":{"window":[[10,10,20,20]],"wall":[[30,30,60,60]]}}"#;
    let (s, v) = json(&app, "PUT", uri, boxes).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    let saved: Value = serde_json::from_slice(
        &std::fs::read(dir.path().join("keep_south_near.training.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(saved["classes"]["wall"][0][2], 60.0);
    let (s, _) = json(&app, "PUT", "/api/facades/nope.png/training", boxes).await;
    assert_eq!(s, StatusCode::NOT_FOUND);

    let list = r#"[{"facade":"keep_south_far.png","facade_point":[1,2],"plan_points":[[3,4]]}]"#;
    let (s, v) = json(&app, "PUT", "/api/correspondences", list).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    let p = saved_project(dir.path());
    assert_eq!(p.correspondences.len(), 1);
    assert_eq!(p.correspondences[0].plan_points, vec![[3.0, 4.0]]);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 4)]
async fn concurrent_saves_leave_a_valid_project() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let mut tasks = Vec::new();
    for k in 0..16u32 {
        let app = app.clone();
        tasks.push(tokio::spawn(async move {
            let body = if k % 2 == 0 {
                format!(r#"{{"classes":{{"window":[[{k},0,{},9]],"wall":[[30,30,60,60]]}}}}"#, k + 5)
            } else {
                format!(r#"[{{"facade":"keep_south_near.png","facade_point":[{k},1],"plan_points":[[3,4]]}}]"#)
            };
            let (method, uri) = if k % 2 == 0 {
                ("PUT", "/api/facades/keep_south_near.png/training")
            } else {
                ("PUT", "/api/correspondences")
            };
            json(&app, method, uri, &body).await.0
        }));
    }
    for t in tasks {
        assert_eq!(t.await.unwrap(), StatusCode::OK);
    }
    let p = saved_project(dir.path());
    assert_eq!((p.facades.len(), p.correspondences.len()), (2, 1));
    let t: facade::classify::Training = serde_json::from_slice(
        &std::fs::read(dir.path().join("keep_south_near.training.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(t.classes[&facade::classify::Class::Window].len(), 1);
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

#[tokio::test]
async fn the_plan_stage_writes_its_label_overlay() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let (s, v) = json(&app, "POST", "/api/plan", "").await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert!(v["faces"].as_u64().unwrap() >= 4, "{v}");
    let (s, png) = get(&app, v["overlay"].as_str().unwrap()).await;
    assert_eq!(s, StatusCode::OK);
    let overlay = image::load_from_memory(&png).unwrap();
    let plan = image::open(dir.path().join("plan.png")).unwrap();
    assert_eq!(overlay.width(), plan.width());
    let (_, p) = json(&app, "GET", "/api/progress", "").await;
    assert_eq!(p["last"]["step"], "plan");
    assert_eq!(p["last"]["ok"], true);
}

/// Issue 26: the user's wall / not-wall strokes and the choice of the rules are saved in
/// PROJECT.toml and change the walls the plan stage reads; bad strokes are refused by name.
#[tokio::test]
async fn wall_ink_strokes_are_saved_and_change_the_walls_read() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let (s, v) = json(&app, "POST", "/api/plan", "").await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(
        (v["ink"].as_str(), v["ink_strokes"].as_u64()),
        (Some("learned"), Some(0))
    );
    let walls = |v: &serde_json::Value| {
        let path = v["walls"]
            .as_str()
            .unwrap()
            .trim_start_matches("/files/")
            .to_string();
        std::fs::read(dir.path().join(path)).unwrap()
    };
    let before = walls(&v);
    let plan = image::open(dir.path().join("plan.png")).unwrap();
    let (w, h) = (plan.width() as f64, plan.height() as f64);
    // A broad "not wall" stroke across the middle of the drawing, over whatever walls are
    // there, and a "wall" dot in a corner.
    let body = serde_json::json!({"ink": "learned", "strokes": [
        {"wall": false, "radius": 12, "points": [[w * 0.2, h * 0.5], [w * 0.8, h * 0.5]]},
        {"wall": true, "radius": 3, "points": [[5, 5]]},
    ]});
    let (s, r) = json(&app, "PUT", "/api/plan/ink", &body.to_string()).await;
    assert_eq!(s, StatusCode::OK, "{r}");
    assert_eq!(saved_project(dir.path()).ink_strokes.len(), 2);
    let (_, v) = json(&app, "POST", "/api/plan", "").await;
    assert_eq!(v["ink_strokes"].as_u64(), Some(2), "{v}");
    assert_ne!(
        walls(&v),
        before,
        "the strokes changed no pixel of the walls"
    );
    // The rules instead: saved, and reported by the plan stage.
    let rules = serde_json::json!({"ink": "rules", "strokes": []});
    let (s, _) = json(&app, "PUT", "/api/plan/ink", &rules.to_string()).await;
    assert_eq!(s, StatusCode::OK);
    assert_eq!(
        saved_project(dir.path()).ink,
        Some(plan::ink::InkMethod::Rules)
    );
    let (_, v) = json(&app, "POST", "/api/plan", "").await;
    assert_eq!(v["ink"].as_str(), Some("rules"), "{v}");
    // A stroke off the drawing is refused, naming it; nothing is saved.
    let off = serde_json::json!({"ink": "learned", "strokes": [
        {"wall": true, "radius": 2, "points": [[w + 50.0, 5]]},
    ]});
    let (s, e) = json(&app, "PUT", "/api/plan/ink", &off.to_string()).await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{e}");
    assert!(e["error"].as_str().unwrap().contains("ink stroke 0"), "{e}");
    assert_eq!(
        saved_project(dir.path()).ink,
        Some(plan::ink::InkMethod::Rules)
    );
}

#[tokio::test]
async fn a_stage_without_a_plan_is_a_conflict_not_a_crash() {
    let dir = tempfile::tempdir().unwrap();
    let app = app(dir.path(), 1 << 20);
    for uri in [
        "/api/plan",
        "/api/reconstruct",
        "/api/facades/x.png/rectify",
    ] {
        let (s, e) = json(&app, "POST", uri, "").await;
        assert_eq!(s, StatusCode::CONFLICT, "{uri}: {e}");
        assert!(e["error"].as_str().unwrap().contains("plan"), "{e}");
    }
}

#[tokio::test]
async fn the_facade_stages_write_their_overlays() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let (s, r) = json(&app, "POST", "/api/facades/keep_south_near.png/rectify", "").await;
    assert_eq!(s, StatusCode::OK, "{r}");
    let (_, png) = get(&app, r["overlay"].as_str().unwrap()).await;
    let overlay = image::load_from_memory(&png).unwrap();
    assert_eq!(
        (overlay.width(), overlay.height()),
        (510, 470),
        "drawn over the photo"
    );
    let (_, png) = get(&app, r["rectified"].as_str().unwrap()).await;
    let rectified = image::load_from_memory(&png).unwrap();
    assert_eq!(
        (u64::from(rectified.width()), u64::from(rectified.height())),
        (r["width"].as_u64().unwrap(), r["height"].as_u64().unwrap())
    );
    let (s, f) = json(&app, "POST", "/api/facades/keep_south_near.png/facade", "").await;
    assert_eq!(s, StatusCode::OK, "{f}");
    // The keep's south façade has 3 floors of 4 windows (examples/demo/TRUTH.json).
    assert!(f["windows"].as_u64().unwrap() >= 12, "{f}");
    // A plausible model: the page has no warning to show (`facade::plausibility`).
    assert_eq!(f["warnings"], serde_json::json!([]), "{f}");
    // One outline per façade, in the photo's pixels, holding the demo's own click (issue 22:
    // the page shows where a correspondence's photo point may land).
    let outlines = f["outlines"].as_array().unwrap();
    assert_eq!(outlines.len() as u64, f["facades"].as_u64().unwrap(), "{f}");
    let holds = |q: &Value, [x, y]: [f64; 2]| {
        let xs: Vec<f64> = (0..4).map(|i| q[i][0].as_f64().unwrap()).collect();
        let ys: Vec<f64> = (0..4).map(|i| q[i][1].as_f64().unwrap()).collect();
        let within = |v: &[f64], t: f64| v.iter().any(|&a| a <= t) && v.iter().any(|&a| a >= t);
        within(&xs, x) && within(&ys, y)
    };
    assert!(outlines.iter().any(|q| holds(q, [255.0, 235.0])), "{f}");
    assert!(!outlines.iter().any(|q| holds(q, [2.0, 2.0])), "{f}");
    assert_eq!(
        get(&app, f["overlay"].as_str().unwrap()).await.0,
        StatusCode::OK
    );
}

#[tokio::test]
async fn reconstruct_names_a_facade_still_without_correspondence() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let only_near =
        r#"[{"facade":"keep_south_near.png","facade_point":[255,235],"plan_points":[[320,303]]}]"#;
    assert_eq!(
        json(&app, "PUT", "/api/correspondences", only_near).await.0,
        StatusCode::OK
    );
    let (s, e) = json(&app, "POST", "/api/reconstruct", "").await;
    assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY, "{e}");
    assert!(
        e["error"].as_str().unwrap().contains("keep_south_far.png"),
        "{e}"
    );
    assert!(!dir.path().join("out/model.glb").exists());
}

/// Every file of the project folder with its bytes, to see that a request wrote nothing.
fn folder(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<_> = walk(dir)
        .into_iter()
        .map(|p| (p.display().to_string(), std::fs::read(&p).unwrap()))
        .collect();
    v.sort();
    v
}

fn walk(dir: &Path) -> Vec<std::path::PathBuf> {
    std::fs::read_dir(dir)
        .unwrap()
        .flat_map(|e| {
            let p = e.unwrap().path();
            if p.is_dir() { walk(&p) } else { vec![p] }
        })
        .collect()
}

#[tokio::test]
async fn the_live_probability_map_follows_the_boxes_and_writes_nothing() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let before = folder(dir.path());
    let uri = "/api/facades/keep_south_near.png/preview";
    let photo = image::open(dir.path().join("keep_south_near.png")).unwrap();
    // Boxes on the demo photo's wall (top left) and on a window, as the demo's own training has.
    let t: Value = serde_json::from_slice(
        &std::fs::read(dir.path().join("keep_south_near.training.json")).unwrap(),
    )
    .unwrap();
    let req = Request::post(uri)
        .header("content-type", "application/json")
        .body(Body::from(t.to_string()))
        .unwrap();
    let res = app.clone().oneshot(with_token(req)).await.unwrap();
    assert_eq!(res.status(), StatusCode::OK);
    assert_eq!(res.headers()["content-type"], "image/png");
    assert!(
        res.headers()["x-castellan-ms"]
            .to_str()
            .unwrap()
            .parse::<u64>()
            .is_ok()
    );
    let body = res.into_body().collect().await.unwrap().to_bytes();
    let map = image::load_from_memory(&body).unwrap();
    assert_eq!(map.width(), photo.width());
    assert_eq!(map.height(), photo.height());
    assert_ne!(map.to_rgb8(), photo.to_rgb8(), "the map tints the photo");

    // One class only, a box outside the photo, an inverted box: 422 naming the class or box.
    for (body, words) in [
        (r#"{"classes":{"window":[[10,10,20,20]]}}"#, "no wall boxes"),
        (
            r#"{"classes":{"window":[[10,10,20,20]],"wall":[[30,30,60,60],[9000,9000,9100,9100]]}}"#,
            "wall box 1",
        ),
        (
            r#"{"classes":{"window":[[20,10,10,20]],"wall":[[30,30,60,60]]}}"#,
            "window box 0",
        ),
    ] {
        let (s, e) = json(&app, "POST", uri, body).await;
        assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY, "{e}");
        let m = e["error"].as_str().unwrap();
        assert!(
            m.contains(words) && m.contains("keep_south_near.png"),
            "{m}"
        );
    }
    let (s, _) = json(
        &app,
        "POST",
        "/api/facades/nope.png/preview",
        "{\"classes\":{}}",
    )
    .await;
    assert_eq!(s, StatusCode::NOT_FOUND);
    assert_eq!(folder(dir.path()), before, "a preview writes nothing");
}

/// Issue 22: the plausibility warnings reach the page with the reconstruction, as the report
/// and the command line give them.
#[tokio::test]
async fn reconstruct_passes_its_warnings_to_the_page() {
    let dir = tempfile::tempdir().unwrap();
    // A drawing whose ink makes no wall graph: one black disc.
    let disc = image::GrayImage::from_fn(300, 200, |x, y| {
        let (dx, dy) = (f64::from(x) - 150.0, f64::from(y) - 100.0);
        image::Luma([if dx * dx + dy * dy < 900.0 { 0 } else { 255 }])
    });
    disc.save(dir.path().join("disc.png")).unwrap();
    std::fs::write(dir.path().join("PROJECT.toml"), "plan = \"disc.png\"\n").unwrap();
    let app = app(dir.path(), 1 << 20);
    let (s, r) = json(&app, "POST", "/api/reconstruct", "").await;
    assert_eq!(s, StatusCode::OK, "{r}");
    assert_one_warning(&r, "no walls were read from disc.png");
}

/// The answer `r` carries exactly one warning, which starts with `start`.
pub(super) fn assert_one_warning(r: &Value, start: &str) {
    let warnings = r["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 1, "{r}");
    assert!(warnings[0].as_str().unwrap().starts_with(start), "{r}");
}
