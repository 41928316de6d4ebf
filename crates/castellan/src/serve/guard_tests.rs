//! The hardening of issue 19 driven through the router: foreign hosts, origins and missing
//! tokens refused; stale edits refused with 412; uploads that never overwrite; a hand-written
//! PROJECT.toml kept; the pixel budget, box checks and body limits; every error as JSON.

use std::path::Path;
use std::pin::Pin;
use std::task::{Context, Poll};

use axum::body::{Body, Bytes};
use axum::http::{Request, StatusCode};
use serde_json::Value;

use super::tests::{
    HOST, TOKEN, app, demo_project, get, json, multipart, png_bytes, saved_project, send,
    send_as_is, upload,
};

fn error_of(body: &[u8]) -> String {
    let v: Value = serde_json::from_slice(body)
        .unwrap_or_else(|_| panic!("not JSON: {}", String::from_utf8_lossy(body)));
    v["error"]
        .as_str()
        .unwrap_or_else(|| panic!("no error in {v}"))
        .to_string()
}

fn file(dir: &Path, name: &str) -> Vec<u8> {
    std::fs::read(dir.join(name)).unwrap()
}

#[tokio::test]
async fn a_cross_origin_upload_is_refused() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let before = file(dir.path(), "plan.png");
    // What a form on another site posts: the right Host (the user's browser), a foreign Origin
    // and, since a page cannot read it, no token; then even with the token.
    for token in [None, Some(TOKEN)] {
        let mut req = multipart("plan", "plan.png", &png_bytes(8, 8));
        req.headers_mut()
            .insert("origin", "http://evil.example".parse().unwrap());
        req.headers_mut().insert("host", HOST.parse().unwrap());
        if let Some(t) = token {
            req.headers_mut()
                .insert(super::access::TOKEN_HEADER, t.parse().unwrap());
        }
        let (s, b) = send_as_is(&app, req).await;
        assert_eq!(s, StatusCode::FORBIDDEN);
        assert!(error_of(&b).contains("other sites"), "{}", error_of(&b));
    }
    for uri in ["/api/reconstruct", "/api/plan"] {
        let req = Request::post(uri)
            .header("origin", "http://evil.example")
            .body(Body::empty())
            .unwrap();
        assert_eq!(send(&app, req).await.0, StatusCode::FORBIDDEN, "{uri}");
    }
    // A fetch from another local site (another port) says so in Sec-Fetch-Site.
    let req = Request::get("/api/project")
        .header("sec-fetch-site", "same-site")
        .body(Body::empty())
        .unwrap();
    assert_eq!(send(&app, req).await.0, StatusCode::FORBIDDEN);
    assert_eq!(file(dir.path(), "plan.png"), before);
    assert!(!dir.path().join("out").exists());
    // The page's own origin passes.
    let req = Request::get("/api/project")
        .header("origin", format!("http://{HOST}"))
        .header("sec-fetch-site", "same-origin")
        .body(Body::empty())
        .unwrap();
    assert_eq!(send(&app, req).await.0, StatusCode::OK);
}

#[tokio::test]
async fn a_foreign_host_header_is_refused() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    // DNS rebinding: the attacker's name resolves to 127.0.0.1, the browser sends its Host.
    for uri in [
        "/",
        "/app.js",
        "/api/project",
        "/files/PROJECT.toml",
        "/nothing",
    ] {
        for host in [
            "attacker.example",
            "attacker.example:8080",
            "127.0.0.1:9999",
        ] {
            let req = Request::get(uri)
                .header("host", host)
                .body(Body::empty())
                .unwrap();
            let (s, b) = send(&app, req).await;
            assert_eq!(s, StatusCode::FORBIDDEN, "{uri} {host}");
            assert!(error_of(&b).contains(host), "{}", error_of(&b));
        }
    }
    for host in ["localhost:8080", "[::1]:8080", HOST] {
        let req = Request::get("/api/project")
            .header("host", host)
            .body(Body::empty())
            .unwrap();
        assert_eq!(send(&app, req).await.0, StatusCode::OK, "{host}");
    }
}

#[tokio::test]
async fn a_request_without_the_right_token_is_refused() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    for token in [None, Some("0123456789abcdeF"), Some("")] {
        for (method, uri) in [
            ("GET", "/api/project"),
            ("GET", "/files/PROJECT.toml"),
            ("PUT", "/api/correspondences"),
            ("POST", "/api/reconstruct"),
        ] {
            let mut req = Request::builder()
                .method(method)
                .uri(uri)
                .header("host", HOST)
                .header("content-type", "application/json");
            if let Some(t) = token {
                req = req.header(super::access::TOKEN_HEADER, t);
            }
            let (s, b) = send_as_is(&app, req.body(Body::from("[]")).unwrap()).await;
            assert_eq!(s, StatusCode::FORBIDDEN, "{method} {uri} {token:?}");
            assert!(error_of(&b).contains("token"), "{}", error_of(&b));
        }
    }
    assert_eq!(saved_project(dir.path()).correspondences.len(), 2);
    // The page and its script need no token (the page reads it from its own URL).
    let req = Request::get("/")
        .header("host", HOST)
        .body(Body::empty())
        .unwrap();
    assert_eq!(send_as_is(&app, req).await.0, StatusCode::OK);
}

#[tokio::test]
async fn the_page_with_its_token_sets_a_cookie_that_only_reads() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let res = tower::ServiceExt::oneshot(
        app.clone(),
        Request::get(format!("/?token={TOKEN}"))
            .header("host", HOST)
            .body(Body::empty())
            .unwrap(),
    )
    .await
    .unwrap();
    assert_eq!(res.status(), StatusCode::OK);
    let cookie = res.headers()["set-cookie"].to_str().unwrap().to_string();
    assert!(
        cookie.contains("HttpOnly") && cookie.contains("SameSite=Strict"),
        "{cookie}"
    );
    let pair = cookie.split(';').next().unwrap().to_string();
    assert_eq!(pair, format!("castellan_token_8080={TOKEN}"));
    // <img src="/files/…"> sends the cookie, not the header.
    let req = Request::get("/files/plan.png")
        .header("host", HOST)
        .header("cookie", &pair)
        .body(Body::empty())
        .unwrap();
    assert_eq!(send_as_is(&app, req).await.0, StatusCode::OK);
    // A change needs the header.
    let req = Request::put("/api/correspondences")
        .header("host", HOST)
        .header("cookie", &pair)
        .header("content-type", "application/json")
        .body(Body::from("[]"))
        .unwrap();
    assert_eq!(send_as_is(&app, req).await.0, StatusCode::FORBIDDEN);
    // A wrong token in the page's URL is refused rather than silently ignored.
    let (s, _) = get(&app, "/?token=nope").await;
    assert_eq!(s, StatusCode::FORBIDDEN);
}

async fn etag(app: &axum::Router) -> String {
    let res = tower::ServiceExt::oneshot(
        app.clone(),
        Request::get("/api/project")
            .header("host", HOST)
            .header(super::access::TOKEN_HEADER, TOKEN)
            .body(Body::empty())
            .unwrap(),
    )
    .await
    .unwrap();
    assert_eq!(res.status(), StatusCode::OK);
    res.headers()["etag"].to_str().unwrap().to_string()
}

async fn put_if_match(app: &axum::Router, uri: &str, tag: &str, body: &str) -> (StatusCode, Value) {
    let req = Request::put(uri)
        .header("content-type", "application/json")
        .header("if-match", tag)
        .body(Body::from(body.to_string()))
        .unwrap();
    let (s, b) = send(app, req).await;
    (s, serde_json::from_slice(&b).unwrap_or(Value::Null))
}

#[tokio::test]
async fn a_stale_if_match_is_refused_with_412() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    // Two tabs load the project.
    let tab_a = etag(&app).await;
    let tab_b = etag(&app).await;
    assert_eq!(tab_a, tab_b);
    let training = "/api/facades/keep_south_near.png/training";
    let boxes = r#"{"classes":{"window":[[10,10,20,20]],"wall":[[30,30,60,60]]}}"#;
    let (s, v) = put_if_match(&app, training, &tab_a, boxes).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    let saved = file(dir.path(), "keep_south_near.training.json");
    // Tab B saves over what it loaded: refused, nothing written.
    let other = r#"{"classes":{"window":[[1,1,5,5]],"wall":[[30,30,60,60]]}}"#;
    let (s, e) = put_if_match(&app, training, &tab_b, other).await;
    assert_eq!(s, StatusCode::PRECONDITION_FAILED, "{e}");
    assert!(e["error"].as_str().unwrap().contains("reload"), "{e}");
    let list = r#"[{"facade":"keep_south_far.png","facade_point":[1,2],"plan_points":[[3,4]]}]"#;
    let (s, _) = put_if_match(&app, "/api/correspondences", &tab_b, list).await;
    assert_eq!(s, StatusCode::PRECONDITION_FAILED);
    assert_eq!(file(dir.path(), "keep_south_near.training.json"), saved);
    assert_eq!(saved_project(dir.path()).correspondences.len(), 2);
    // The answer's ETag is the new version: tab A goes on saving with it.
    let res = tower::ServiceExt::oneshot(
        app.clone(),
        Request::put(training)
            .header("host", HOST)
            .header(super::access::TOKEN_HEADER, TOKEN)
            .header("content-type", "application/json")
            .header("if-match", etag(&app).await)
            .body(Body::from(boxes))
            .unwrap(),
    )
    .await
    .unwrap();
    assert_eq!(res.status(), StatusCode::OK);
    let next = res.headers()["etag"].to_str().unwrap().to_string();
    let (s, v) = put_if_match(&app, "/api/correspondences", &next, list).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    // A hand edit of a training file changes the version too.
    let now = etag(&app).await;
    std::fs::write(
        dir.path().join("keep_south_near.training.json"),
        r#"{"classes":{}}"#,
    )
    .unwrap();
    let (s, _) = put_if_match(&app, "/api/correspondences", &now, list).await;
    assert_eq!(s, StatusCode::PRECONDITION_FAILED);
}

#[tokio::test]
async fn a_hand_written_project_keeps_its_comments() {
    let dir = demo_project();
    let hand = "# My castle, surveyed in 2024.\n\
        plan = \"plan.png\"   # the 1:500 drawing\n\
        scale = 0.25\n\n\
        # The keep, from the south.\n\
        [[facade]]\n\
        image = \"keep_south_near.png\"\n\
        training = \"keep_south_near.training.json\"  # drawn by hand\n\n\
        [[facade]]\n\
        image = \"keep_south_far.png\"\n\
        training = \"keep_south_far.training.json\"\n\n\
        # Clicked on the printed plan.\n\
        [[correspondence]]\n\
        facade = \"keep_south_near.png\"\n\
        facade_point = [255, 235]\n\
        plan_points = [[320, 303]]   # the keep's south-west corner\n";
    std::fs::write(dir.path().join("PROJECT.toml"), hand).unwrap();
    let app = app(dir.path(), 1 << 20);
    let list = r#"[{"facade":"keep_south_near.png","facade_point":[255,235],"plan_points":[[320,303]]},
                   {"facade":"keep_south_far.png","facade_point":[160,150],"plan_points":[[330,300]]}]"#;
    let (s, v) = json(&app, "PUT", "/api/correspondences", list).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    let saved = String::from_utf8(file(dir.path(), "PROJECT.toml")).unwrap();
    for kept in [
        "# My castle, surveyed in 2024.\n",
        "plan = \"plan.png\"   # the 1:500 drawing\n",
        "# The keep, from the south.\n",
        "training = \"keep_south_near.training.json\"  # drawn by hand\n",
        "# Clicked on the printed plan.\n",
        "plan_points = [[320, 303]]   # the keep's south-west corner\n",
    ] {
        assert!(saved.contains(kept), "lost {kept:?} in:\n{saved}");
    }
    let p = saved_project(dir.path());
    assert_eq!(p.correspondences.len(), 2);
    assert_eq!(p.correspondences[1].plan_points, vec![[330.0, 300.0]]);
    assert_eq!(p.metres_per_pixel, Some(0.25));
    // A changed value keeps its comment.
    let list =
        r#"[{"facade":"keep_south_near.png","facade_point":[255,235],"plan_points":[[321,304]]}]"#;
    assert_eq!(
        json(&app, "PUT", "/api/correspondences", list).await.0,
        StatusCode::OK
    );
    let saved = String::from_utf8(file(dir.path(), "PROJECT.toml")).unwrap();
    assert!(saved.contains("# the keep's south-west corner"), "{saved}");
    assert!(saved.contains("# My castle"), "{saved}");
    assert_eq!(
        saved_project(dir.path()).correspondences[0].plan_points,
        vec![[321.0, 304.0]]
    );
}

#[tokio::test]
async fn a_facade_upload_never_replaces_a_photo_or_the_plan() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let photo = file(dir.path(), "keep_south_near.png");
    let boxes = file(dir.path(), "keep_south_near.training.json");
    let plan = file(dir.path(), "plan.png");
    let (s, v) = upload(&app, "facade", "keep_south_near.png", &png_bytes(40, 30)).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(v["name"], "keep_south_near-2.png");
    let (s, v) = upload(&app, "facade", "plan.png", &png_bytes(40, 30)).await;
    assert_eq!(s, StatusCode::OK, "{v}");
    assert_eq!(v["name"], "plan-2.png");
    assert_eq!(file(dir.path(), "keep_south_near.png"), photo);
    assert_eq!(file(dir.path(), "keep_south_near.training.json"), boxes);
    assert_eq!(file(dir.path(), "plan.png"), plan);
    let p = saved_project(dir.path());
    assert_eq!(p.plan, "plan.png");
    let images: Vec<&str> = p.facades.iter().map(|f| f.image.as_str()).collect();
    assert_eq!(
        images,
        [
            "keep_south_near.png",
            "keep_south_far.png",
            "keep_south_near-2.png",
            "plan-2.png"
        ]
    );
    // The new photo starts with no boxes of its own.
    let t: Value =
        serde_json::from_slice(&file(dir.path(), "keep_south_near-2.training.json")).unwrap();
    assert_eq!(t["classes"], serde_json::json!({}));
}

#[tokio::test]
async fn an_inverted_training_box_is_refused_by_the_server() {
    let dir = demo_project();
    let app = app(dir.path(), 16 << 20);
    let before = file(dir.path(), "keep_south_near.training.json");
    let uri = "/api/facades/keep_south_near.png/training";
    for (body, says) in [
        (
            r#"{"classes":{"window":[[10,10,20,20],[50,10,40,20]]}}"#,
            "window box 1",
        ),
        (r#"{"classes":{"wall":[[10,10,10,20]]}}"#, "zero area"),
        (
            r#"{"classes":{"wall":[[600,10,700,20]]}}"#,
            "no pixels inside",
        ),
        (r#"{"classes":{"wall":[[1e400,10,700,20]]}}"#, ""),
    ] {
        let (s, e) = json(&app, "PUT", uri, body).await;
        assert!(
            s == StatusCode::BAD_REQUEST || s == StatusCode::UNPROCESSABLE_ENTITY,
            "{s} {e}"
        );
        assert!(e["error"].as_str().unwrap().contains(says), "{e}");
    }
    // 200 000 boxes once took the façade stage to 1.9 GB.
    let many = format!(
        r#"{{"classes":{{"wall":[{}[1,1,5,5]]}}}}"#,
        "[1,1,5,5],".repeat(199_999)
    );
    let (s, e) = json(&app, "PUT", uri, &many).await;
    assert_eq!(s, StatusCode::BAD_REQUEST, "{e}");
    assert!(
        e["error"].as_str().unwrap().contains("limit of 1000"),
        "{e}"
    );
    assert_eq!(file(dir.path(), "keep_south_near.training.json"), before);
}

/// PNG bytes declaring `w` × `h` grey pixels: a 1 × 1 image whose IHDR says otherwise, so the
/// test does not build the 400 MB image (only a decoder that trusts the header would).
fn png_claiming(w: u32, h: u32) -> Vec<u8> {
    let mut bytes = crate::images::png(&image::GrayImage::new(1, 1), Path::new("x.png")).unwrap();
    assert_eq!(&bytes[12..16], b"IHDR");
    bytes[16..20].copy_from_slice(&w.to_be_bytes());
    bytes[20..24].copy_from_slice(&h.to_be_bytes());
    let crc = crc32fast::hash(&bytes[12..29]);
    bytes[29..33].copy_from_slice(&crc.to_be_bytes());
    bytes
}

#[tokio::test]
async fn an_image_over_the_pixel_budget_is_refused_naming_it_and_the_budget() {
    let dir = demo_project();
    let app = app(dir.path(), 1 << 20);
    let big = png_claiming(20_000, 20_000);
    let (w, h) = image::ImageReader::new(std::io::Cursor::new(&big))
        .with_guessed_format()
        .unwrap()
        .into_dimensions()
        .unwrap();
    assert_eq!((w, h), (20_000, 20_000), "the header is valid");
    let (s, e) = upload(&app, "facade", "huge.png", &big).await;
    assert_eq!(s, StatusCode::PAYLOAD_TOO_LARGE, "{e}");
    let m = e["error"].as_str().unwrap();
    assert!(m.contains("huge.png") && m.contains("40 Mpx"), "{m}");
    assert!(!dir.path().join("huge.png").exists());
    assert_eq!(saved_project(dir.path()).facades.len(), 2);
}

#[tokio::test]
async fn every_refusal_is_a_json_error() {
    let dir = demo_project();
    let app = app(dir.path(), 64 << 10);
    let put = |uri: &str, ct: &str, body: Vec<u8>| {
        Request::put(uri)
            .header("content-type", ct)
            .body(Body::from(body))
            .unwrap()
    };
    let training = "/api/facades/keep_south_near.png/training";
    let cases = [
        (
            put(training, "application/json", b"{not json".to_vec()),
            400,
        ),
        (
            put(training, "application/json", br#"{"classes": 3}"#.to_vec()),
            422,
        ),
        (put(training, "text/plain", b"{}".to_vec()), 415),
        (
            put(training, "application/json", vec![b' '; 100 << 10]),
            413,
        ),
        (
            Request::post("/api/upload")
                .header("content-type", "multipart/form-data; boundary=x")
                .body(Body::from("--x\r\ngarbage"))
                .unwrap(),
            400,
        ),
        (
            Request::post("/api/upload")
                .header("content-type", "application/json")
                .body(Body::from("{}"))
                .unwrap(),
            400,
        ),
        (
            Request::get("/api/nothing").body(Body::empty()).unwrap(),
            404,
        ),
        (
            Request::delete("/api/plan").body(Body::empty()).unwrap(),
            405,
        ),
    ];
    for (req, want) in cases {
        let what = format!("{} {}", req.method(), req.uri());
        let (s, b) = send(&app, req).await;
        assert_eq!(s.as_u16(), want, "{what}: {}", String::from_utf8_lossy(&b));
        assert!(!error_of(&b).is_empty(), "{what}");
    }
}

/// A body that never sends a byte.
struct Silent;

impl axum::body::HttpBody for Silent {
    type Data = Bytes;
    type Error = std::convert::Infallible;
    fn poll_frame(
        self: Pin<&mut Self>,
        _: &mut Context<'_>,
    ) -> Poll<Option<Result<hyper::body::Frame<Bytes>, Self::Error>>> {
        Poll::Pending
    }
}

#[tokio::test]
async fn a_body_that_never_arrives_is_cut_off() {
    let dir = tempfile::tempdir().unwrap();
    let access = super::Access::new(
        TOKEN.into(),
        HOST.parse().unwrap(),
        std::time::Duration::from_millis(300),
    );
    let app = super::router(super::app::App::new(
        super::store::Store::open(dir.path()).unwrap(),
        1 << 20,
        access,
        Default::default(),
    ));
    let req = Request::put("/api/correspondences")
        .header("content-type", "application/json")
        .body(Body::new(Silent))
        .unwrap();
    let t = std::time::Instant::now();
    let (s, b) = send(&app, req).await;
    assert_eq!(s, StatusCode::REQUEST_TIMEOUT);
    assert!(error_of(&b).contains("did not arrive"));
    assert!(t.elapsed() < std::time::Duration::from_secs(5));
}

#[test]
fn a_malformed_project_is_reported_at_its_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("PROJECT.toml"),
        "plan = \"plan.png\"\n# fine so far\nscale = = 3\n",
    )
    .unwrap();
    let e = format!("{:#}", super::store::Store::open(dir.path()).err().unwrap());
    assert!(e.contains("PROJECT.toml:3:9: "), "{e}");
}
