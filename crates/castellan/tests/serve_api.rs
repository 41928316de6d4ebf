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

fn error_of(body: &[u8]) -> String {
    let v: serde_json::Value = serde_json::from_slice(body)
        .unwrap_or_else(|_| panic!("not JSON: {}", String::from_utf8_lossy(body)));
    v["error"].as_str().unwrap().to_string()
}

#[test]
fn the_real_server_refuses_other_sites_foreign_hosts_and_missing_tokens() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = demo_project(tmp.path());
    let server = Server::start(&dir);
    assert_eq!(server.token.len(), 64, "{}", server.url);
    assert!(
        server
            .url
            .starts_with(&format!("http://{}/?token=", server.addr))
    );
    let plan = std::fs::read(dir.join("plan.png")).unwrap();
    let list = br#"[]"#;
    // A form posted by another site: the browser adds its Origin, the page cannot add the token.
    let (status, body) = server.request_with(
        "PUT",
        "/api/correspondences",
        &format!("Host: {}\r\nOrigin: http://evil.example\r\n", server.addr),
        list,
    );
    assert_eq!(status, 403);
    assert!(error_of(&body).contains("other sites"));
    // DNS rebinding: the attacker's name for 127.0.0.1, with the token even.
    let (status, body) = server.request_with(
        "GET",
        "/api/project",
        &format!(
            "Host: attacker.example\r\nX-Castellan-Token: {}\r\n",
            server.token
        ),
        b"",
    );
    assert_eq!(status, 403);
    assert!(error_of(&body).contains("attacker.example"));
    let (status, _) = server.request_with("GET", "/", "Host: attacker.example\r\n", b"");
    assert_eq!(status, 403);
    // No token.
    let (status, body) = server.request_with(
        "PUT",
        "/api/correspondences",
        &format!("Host: {}\r\n", server.addr),
        list,
    );
    assert_eq!(status, 403);
    assert!(error_of(&body).contains("token"));
    assert_eq!(std::fs::read(dir.join("plan.png")).unwrap(), plan);
    assert!(
        std::fs::read_to_string(dir.join("PROJECT.toml"))
            .unwrap()
            .contains("[[correspondence]]")
    );
    // Each run has its own token.
    let again = Server::start(&dir);
    assert_ne!(again.token, server.token);
}

#[test]
fn a_client_that_stalls_its_headers_or_idles_is_disconnected() {
    use std::io::{Read, Write};
    use std::time::{Duration, Instant};
    let tmp = tempfile::tempdir().unwrap();
    let dir = demo_project(tmp.path());
    let server = Server::start_with(&dir, &["--header-timeout-secs", "1"]);
    // Half a request, then nothing.
    let mut s = std::net::TcpStream::connect(&server.addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    let t = Instant::now();
    s.write_all(b"GET / HTTP/1.1\r\nHost: x").unwrap();
    let mut rest = Vec::new();
    let _ = s.read_to_end(&mut rest);
    assert!(t.elapsed() < Duration::from_secs(8), "{:?}", t.elapsed());
    // A whole request on a kept-alive connection, then idle.
    let mut s = std::net::TcpStream::connect(&server.addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    let t = Instant::now();
    write!(s, "GET /app.css HTTP/1.1\r\nHost: {}\r\n\r\n", server.addr).unwrap();
    let mut answer = Vec::new();
    s.read_to_end(&mut answer).unwrap();
    assert!(answer.starts_with(b"HTTP/1.1 200"));
    assert!(t.elapsed() < Duration::from_secs(8), "{:?}", t.elapsed());
    // The server still serves.
    assert_eq!(server.request("GET", "/api/progress", b"").0, 200);
}

/// PNG bytes declaring `w` × `h` grey pixels: a 1 × 1 image whose IHDR (and its CRC) says
/// otherwise. Only a decoder that trusts the header would allocate the 400 MB.
fn png_claiming(w: u32, h: u32) -> Vec<u8> {
    let mut bytes = Vec::new();
    image::GrayImage::new(1, 1)
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    bytes[16..20].copy_from_slice(&w.to_be_bytes());
    bytes[20..24].copy_from_slice(&h.to_be_bytes());
    let crc = crc32fast::hash(&bytes[12..29]);
    bytes[29..33].copy_from_slice(&crc.to_be_bytes());
    bytes
}

#[test]
fn a_20000_square_png_upload_is_refused_without_the_server_growing() {
    use std::io::{Read, Write};
    let tmp = tempfile::tempdir().unwrap();
    let dir = demo_project(tmp.path());
    let server = Server::start(&dir);
    let b = "castellanboundary";
    let mut body = format!(
        "--{b}\r\nContent-Disposition: form-data; name=\"kind\"\r\n\r\nfacade\r\n--{b}\r\nContent-Disposition: form-data; name=\"file\"; filename=\"huge.png\"\r\nContent-Type: image/png\r\n\r\n"
    )
    .into_bytes();
    body.extend_from_slice(&png_claiming(20_000, 20_000));
    body.extend_from_slice(format!("\r\n--{b}--\r\n").as_bytes());
    let mut s = std::net::TcpStream::connect(&server.addr).unwrap();
    write!(
        s,
        "POST /api/upload HTTP/1.1\r\nHost: {}\r\nX-Castellan-Token: {}\r\nContent-Type: multipart/form-data; boundary={b}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
        server.addr,
        server.token,
        body.len()
    )
    .unwrap();
    s.write_all(&body).unwrap();
    let mut raw = Vec::new();
    s.read_to_end(&mut raw).unwrap();
    let text = String::from_utf8_lossy(&raw);
    assert!(text.starts_with("HTTP/1.1 413"), "{text}");
    assert!(
        text.contains("huge.png") && text.contains("40 Mpx"),
        "{text}"
    );
    assert!(!dir.join("huge.png").exists());
    if let Some(kib) = server.peak_rss_kib() {
        eprintln!(
            "server peak RSS after the 20000 x 20000 upload: {} MiB",
            kib >> 10
        );
        assert!(kib < 300 << 10, "the server grew to {} MiB", kib >> 10);
    }
}

#[test]
fn bad_serve_flags_and_a_malformed_project_are_reported_clearly() {
    let tmp = tempfile::tempdir().unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_castellan"))
        .args(["serve", tmp.path().to_str().unwrap(), "--port", "0"])
        .args(["--max-upload-mb", "17592186044416"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(
        e.contains("--max-upload-mb") && e.contains("1..=4096"),
        "{e}"
    );
    std::fs::write(
        tmp.path().join("PROJECT.toml"),
        "plan = \"plan.png\"\nscale = 0.1\n[[facade]\nimage = \"f.png\"\n",
    )
    .unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_castellan"))
        .args(["serve", tmp.path().to_str().unwrap(), "--port", "0"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(e.contains("PROJECT.toml:3:"), "{e}");
}
