//! `castellan serve`'s Gothic step through its HTTP API (issue 22): the elements of a synthetic
//! Gothic photo with their handles, corrections saved to PROJECT.toml only when they apply,
//! errors naming the `[[gothic]]` entry and element, detection kept between corrections.

mod serve_support;

use facade::gothic::synth::{SynthSpec, synthetic_facade};
use integrate::project::Project;
use serde_json::{Value, json};
use serve_support::{Server, demo_project};

fn body(raw: &[u8]) -> Value {
    serde_json::from_slice(raw).unwrap_or_else(|_| panic!("{}", String::from_utf8_lossy(raw)))
}

#[test]
fn gothic_corrections_are_checked_applied_and_saved() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = demo_project(tmp.path());
    let synth = synthetic_facade(&SynthSpec::small(), 1);
    synth.image.save(dir.join("portal.png")).unwrap();
    let mut text = std::fs::read_to_string(dir.join("PROJECT.toml")).unwrap();
    text.push_str("\n[[gothic]]\nimage = \"portal.png\"\n");
    std::fs::write(dir.join("PROJECT.toml"), &text).unwrap();
    let server = Server::start(&dir);
    let project = || std::fs::read_to_string(dir.join("PROJECT.toml")).unwrap();

    let (status, raw) = server.request("POST", "/api/gothic/nope.png", b"");
    assert_eq!(status, 404, "{}", String::from_utf8_lossy(&raw));

    // The photo is an elevation: saved with the first run.
    let run = json!({ "rectified": true }).to_string();
    let (status, raw) = server.request("POST", "/api/gothic/portal.png", run.as_bytes());
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&raw));
    let first = body(&raw);
    assert_eq!(
        first["elements"].as_array().unwrap().len(),
        synth.elements.len()
    );
    assert_eq!(first["detected_now"], true);
    // The learned check keeps every element of a clean façade, and says so (issue 23).
    assert_eq!(first["dropped"], 0);
    assert_eq!(first["offset"], json!([0.0, 0.0]));
    assert!(project().contains("rectified = true"));
    let saved = project();

    // A window: its handles are the true ones within the detection's few pixels.
    let window = synth.elements[1].theta;
    let found = first["elements"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| {
            (e["centre"].as_f64().unwrap() - (window.x0 + window.w / 2.0)).abs() < 3.0
                && (e["apex"].as_f64().unwrap() - window.apex()).abs() < 3.0
        })
        .expect("the window is found")
        .clone();
    assert_eq!(found["correction"], Value::Null);
    let inside = [window.x0 + window.w / 2.0, window.y0 - window.h / 2.0];

    // Wrong on its own: 400, naming the entry and element; nothing written.
    let bad = json!([{ "point": inside, "apex": 10.0 }, { "point": inside, "width": 0.0 }]);
    let (status, raw) = server.request(
        "PUT",
        "/api/gothic/portal.png/elements",
        bad.to_string().as_bytes(),
    );
    assert_eq!(status, 400);
    let e = body(&raw)["error"].as_str().unwrap().to_string();
    assert!(
        e.starts_with("[[gothic]] #1 element #2 (image = \"portal.png\"): width = 0"),
        "{e}"
    );
    assert_eq!(project(), saved);

    // Cannot apply (outside the photo, two on one element): 422, nothing written.
    for (list, wanted) in [
        (
            json!([{ "point": [900.0, 10.0], "delete": true }]),
            "outside the photo",
        ),
        (
            json!([{ "point": inside, "delete": true }, { "point": inside, "apex": 100.0 }]),
            "same element as element #1",
        ),
    ] {
        let (status, raw) = server.request(
            "PUT",
            "/api/gothic/portal.png/elements",
            list.to_string().as_bytes(),
        );
        assert_eq!(status, 422);
        let e = body(&raw)["error"].as_str().unwrap().to_string();
        assert!(e.contains(wanted), "{e}");
        assert_eq!(project(), saved);
    }

    // Delete the window and move another's apex: saved, applied without detecting again.
    let other = synth.elements[4].theta;
    let apex = other.apex() - 5.0;
    let list = json!([
        { "point": inside, "delete": true },
        { "point": [other.x0 + other.w / 2.0, other.y0 - other.h / 2.0], "apex": apex },
    ]);
    let (status, raw) = server.request(
        "PUT",
        "/api/gothic/portal.png/elements",
        list.to_string().as_bytes(),
    );
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&raw));
    let after = body(&raw);
    assert_eq!(after["detected_now"], false);
    let elements = after["elements"].as_array().unwrap();
    assert_eq!(elements.len(), synth.elements.len() - 1);
    assert_eq!(after["deleted"], json!([{ "correction": 0 }]));
    let moved = elements.iter().find(|e| e["correction"] == 1).unwrap();
    assert!((moved["apex"].as_f64().unwrap() - apex).abs() <= 0.5);
    let p = Project::parse_unchecked(&project()).unwrap();
    let g = &p.gothics[0];
    assert_eq!(g.elements.len(), 2);
    assert!(g.elements[0].delete);
    assert_eq!(g.elements[1].apex, Some(apex));
    // The demo's façades and comments are kept.
    assert_eq!(p.facades.len(), 2);
    assert!(project().contains("# The demo castle"), "{}", project());
    assert!(
        project().contains("facade_point = [255.0, 235.0]"),
        "{}",
        project()
    );

    // A later run applies the saved corrections.
    let (status, raw) = server.request("POST", "/api/gothic/portal.png", b"");
    assert_eq!(status, 200);
    assert_eq!(
        body(&raw)["elements"].as_array().unwrap().len(),
        synth.elements.len() - 1
    );
}
