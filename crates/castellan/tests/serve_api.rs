//! `castellan serve` as a real process on a loopback port: the API answers over TCP, files
//! outside the project are refused, and saved changes reach PROJECT.toml.

mod serve_support;

use serve_support::{Server, demo_project};

#[test]
fn the_real_server_serves_the_page_the_project_and_refuses_traversal() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = demo_project(tmp.path());
    let server = Server::start(&dir);
    assert!(server.addr.starts_with("127.0.0.1:"), "{}", server.addr);

    let (status, page) = server.request("GET", "/", b"");
    assert_eq!(status, 200);
    assert!(String::from_utf8_lossy(&page).contains("<script src=\"/app.js\">"));

    let (status, body) = server.request("GET", "/api/project", b"");
    assert_eq!(status, 200);
    let v: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(v["project"]["plan"], "plan.png");

    for path in [
        "/files/..%2F..%2F..%2Fetc%2Fpasswd",
        "/files/%2Fetc%2Fpasswd",
    ] {
        let (status, body) = server.request("GET", path, b"");
        assert_eq!(status, 403, "{path}");
        assert!(String::from_utf8_lossy(&body).contains("inside the project folder"));
    }

    // A client normalises `..` away; a raw request keeps it and is refused too.
    let (status, _) = server.request("GET", "/files/../PROJECT.toml", b"");
    assert!(status == 403 || status == 404, "{status}");

    let list =
        br#"[{"facade":"keep_south_near.png","facade_point":[255,235],"plan_points":[[320,303]]}]"#;
    let (status, body) = server.request("PUT", "/api/correspondences", list);
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    let saved = std::fs::read_to_string(dir.join("PROJECT.toml")).unwrap();
    assert_eq!(saved.matches("[[correspondence]]").count(), 1, "{saved}");
}
