//! Property tests (proptest) for what `castellan serve` and the commands read from users:
//! arbitrary and mutated TRAINING.json and LINES.json text through the parsers and validators
//! the binary uses, and arbitrary request bodies through the API routes. Nothing may panic, and
//! every refusal must be a 4xx with a JSON `{"error": …}` body. PROPTEST_CASES sets the number
//! of cases (default 128 per test, a few seconds); docs/serve.md gives the long run.

use std::sync::OnceLock;

use axum::body::Body;
use axum::http::{Request, StatusCode};
use facade::classify::Training;
use facade::rectify::ManualLines;
use proptest::prelude::*;

use super::tests::{app, demo_project, send};
use crate::fuzz_tests::config;

const TRAINING: &str = r#"{"classes": {"window": [[10, 10, 20, 20], [30.5, 10, 40, 22]],
 "wall": [[0, 0, 60, 8]], "background": [[0, 40, 64, 48]]}}"#;
const LINES: &str = r#"{"horizontal": [[10, 10, 90, 12], [10, 90, 90, 88]],
 "vertical": [[10, 10, 12, 90], [90, 10, 88, 90]]}"#;

/// Numbers as a hostile file writes them.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        (-1e3f64..1e3).prop_map(|v| format!("{v}")),
        (-100i64..1000).prop_map(|v| v.to_string()),
        Just("1e400".to_string()),
        Just("-1e400".to_string()),
        Just("-0".to_string()),
        Just("1e-320".to_string()),
        Just("18446744073709551616".to_string()),
        Just("null".to_string()),
        Just("\"3\"".to_string()),
    ]
}

fn boxes() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::collection::vec(number(), 0..6), 0..6).prop_map(|bs| {
        let inner: Vec<String> = bs.iter().map(|b| format!("[{}]", b.join(","))).collect();
        format!("[{}]", inner.join(","))
    })
}

/// TRAINING.json-like text: known and unknown classes, boxes of any arity and numbers.
fn training_text() -> impl Strategy<Value = String> {
    let class = prop_oneof![
        Just("window"),
        Just("wall"),
        Just("background"),
        Just("door"),
        Just("")
    ];
    prop::collection::vec((class, boxes()), 0..5).prop_map(|cs| {
        let inner: Vec<String> = cs.iter().map(|(c, b)| format!("\"{c}\": {b}")).collect();
        format!("{{\"classes\": {{{}}}}}", inner.join(", "))
    })
}

fn lines_text() -> impl Strategy<Value = String> {
    (boxes(), boxes(), prop::bool::ANY).prop_map(|(h, v, extra)| {
        if extra {
            format!("{{\"horizontal\": {h}, \"vertical\": {v}, \"x\": 1}}")
        } else {
            format!("{{\"horizontal\": {h}, \"vertical\": {v}}}")
        }
    })
}

/// `text` with a few bytes replaced, inserted or removed.
fn mutated(text: &'static str) -> impl Strategy<Value = String> {
    prop::collection::vec((any::<prop::sample::Index>(), any::<u8>(), 0..3u8), 0..8).prop_map(
        move |edits| {
            let mut b = text.as_bytes().to_vec();
            for (at, byte, op) in edits {
                let i = at.index(b.len().max(1));
                match op {
                    0 if i < b.len() => b[i] = byte,
                    1 => b.insert(i.min(b.len()), byte),
                    _ if i < b.len() => {
                        b.remove(i);
                    }
                    _ => {}
                }
            }
            String::from_utf8_lossy(&b).into_owned()
        },
    )
}

fn any_text() -> impl Strategy<Value = String> {
    prop::collection::vec(any::<u8>(), 0..200)
        .prop_map(|b| String::from_utf8_lossy(&b).into_owned())
}

/// The checks `castellan facade`, `gothic --training`, `reconstruct` and the server make.
fn check_training(text: &str) {
    let Ok(t) = serde_json::from_str::<Training>(text) else {
        return;
    };
    for (w, h) in [(64, 48), (1, 1), (0, 0)] {
        let _ = t.validate(w, h);
        if let Ok(classes) = t.boxes(w, h) {
            for b in classes.values().flatten() {
                assert!(
                    b[0] < b[2] && b[2] <= w && b[1] < b[3] && b[3] <= h,
                    "{b:?}"
                );
            }
        }
    }
}

fn check_lines(text: &str) {
    if let Ok(l) = serde_json::from_str::<ManualLines>(text) {
        for (w, h) in [(100, 100), (1, 1), (0, 0)] {
            let _ = l.validate(w, h);
        }
    }
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn fuzz_training_json(text in prop_oneof![training_text(), mutated(TRAINING), any_text()]) {
        check_training(&text);
    }

    #[test]
    fn fuzz_lines_json(text in prop_oneof![lines_text(), mutated(LINES), any_text()]) {
        check_lines(&text);
    }

    #[test]
    fn fuzz_training_boxes_of_any_floats(
        bs in prop::collection::vec(prop::array::uniform4(any::<f64>()), 0..8),
        w in 0usize..100,
        h in 0usize..100,
    ) {
        let t = Training { classes: [(facade::classify::Class::Wall, bs.clone())].into(), whole_windows: bs };
        if let Ok(classes) = t.boxes(w, h) {
            for b in classes.values().flatten() {
                prop_assert!(b[0] < b[2] && b[2] <= w && b[1] < b[3] && b[3] <= h);
            }
        }
    }
}

/// One demo project and runtime shared by every API case (cases change the project, which is
/// what a user does too).
fn runtime() -> &'static (tokio::runtime::Runtime, tempfile::TempDir) {
    static R: OnceLock<(tokio::runtime::Runtime, tempfile::TempDir)> = OnceLock::new();
    R.get_or_init(|| {
        (
            tokio::runtime::Builder::new_multi_thread()
                .worker_threads(2)
                .enable_all()
                .build()
                .unwrap(),
            demo_project(),
        )
    })
}

fn route() -> impl Strategy<Value = (&'static str, &'static str)> {
    prop_oneof![
        Just(("PUT", "/api/facades/keep_south_near.png/training")),
        Just(("PUT", "/api/facades/keep_south_near.png/lines")),
        Just(("PUT", "/api/correspondences")),
        Just(("PUT", "/api/plan/cleaning")),
        Just(("POST", "/api/upload")),
        Just(("PUT", "/api/facades/nope.png/training")),
        Just(("GET", "/api/project")),
        Just(("PATCH", "/api/plan")),
    ]
}

fn body() -> impl Strategy<Value = Vec<u8>> {
    prop_oneof![
        training_text().prop_map(String::into_bytes),
        lines_text().prop_map(String::into_bytes),
        mutated(TRAINING).prop_map(String::into_bytes),
        mutated(r#"[{"facade":"keep_south_far.png","facade_point":[1,2],"plan_points":[[3,4]]}]"#)
            .prop_map(String::into_bytes),
        mutated(r#"{"strokes":[{"ink":true,"radius":3,"points":[[10,10],[20,20]]}]}"#)
            .prop_map(String::into_bytes),
        mutated("--x\r\nContent-Disposition: form-data; name=\"kind\"\r\n\r\nfacade\r\n--x\r\nContent-Disposition: form-data; name=\"file\"; filename=\"a.png\"\r\n\r\n\u{89}PNG\r\n--x--\r\n")
            .prop_map(String::into_bytes),
        prop::collection::vec(any::<u8>(), 0..300),
    ]
}

fn content_type() -> impl Strategy<Value = &'static str> {
    prop_oneof![
        Just("application/json"),
        Just("multipart/form-data; boundary=x"),
        Just("multipart/form-data"),
        Just("text/plain"),
        Just(""),
    ]
}

proptest! {
    #![proptest_config(config(128))]

    #[test]
    fn fuzz_api_routes_answer_4xx_json(
        (method, uri) in route(),
        ct in content_type(),
        body in body(),
    ) {
        let (rt, dir) = runtime();
        let app = app(dir.path(), 1 << 20);
        let mut req = Request::builder().method(method).uri(uri);
        if !ct.is_empty() {
            req = req.header("content-type", ct);
        }
        let (status, bytes) = rt.block_on(send(&app, req.body(Body::from(body)).unwrap()));
        prop_assert!(
            status.is_success() || status.is_client_error(),
            "{method} {uri}: {status} {}", String::from_utf8_lossy(&bytes)
        );
        if status != StatusCode::OK {
            let v: serde_json::Value = serde_json::from_slice(&bytes).map_err(|_| {
                TestCaseError::fail(format!("{method} {uri} {status}: not JSON: {}",
                    String::from_utf8_lossy(&bytes)))
            })?;
            prop_assert!(v["error"].as_str().is_some_and(|e| !e.is_empty()), "{v}");
        }
    }
}
