//! Shared by the `castellan serve` integration tests: the demo project copied to a temporary
//! folder and the real server on an ephemeral loopback port, stopped when dropped.

#![allow(dead_code)] // each test file uses part of it
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

pub fn demo_project(into: &Path) -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/demo");
    let dir = into.join("project");
    std::fs::create_dir_all(&dir).unwrap();
    for e in std::fs::read_dir(src).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, dir.join(p.file_name().unwrap())).unwrap();
    }
    dir
}

pub struct Server {
    child: Child,
    /// The printed URL, with the token: `http://127.0.0.1:PORT/?token=…`.
    pub url: String,
    /// `127.0.0.1:PORT`.
    pub addr: String,
    pub token: String,
}

impl Server {
    pub fn start(project: &Path) -> Server {
        Server::start_with(project, &[])
    }

    /// The server with more flags.
    pub fn start_with(project: &Path, flags: &[&str]) -> Server {
        let mut child = Command::new(env!("CARGO_BIN_EXE_castellan"))
            .args(["serve", project.to_str().unwrap(), "--port", "0"])
            .args(flags)
            .stdout(Stdio::piped())
            .spawn()
            .unwrap();
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let url = line
            .split_whitespace()
            .find(|w| w.starts_with("http://"))
            .unwrap_or_else(|| panic!("no URL in the server's first line: {line:?}"))
            .to_string();
        let rest = url.trim_start_matches("http://");
        let addr = rest.split('/').next().unwrap().to_string();
        let token = rest
            .split_once("?token=")
            .map(|(_, t)| t.to_string())
            .unwrap_or_else(|| panic!("no token in the server's URL: {url}"));
        Server {
            child,
            url,
            addr,
            token,
        }
    }

    /// One HTTP/1.1 request as the page makes it (the server's Host, the token); the status
    /// code and the body.
    pub fn request(&self, method: &str, path: &str, body: &[u8]) -> (u16, Vec<u8>) {
        let headers = format!(
            "Host: {}\r\nX-Castellan-Token: {}\r\n",
            self.addr, self.token
        );
        self.request_with(method, path, &headers, body)
    }

    /// One HTTP/1.1 request with exactly `headers` (each ending in CRLF) besides the body's.
    pub fn request_with(
        &self,
        method: &str,
        path: &str,
        headers: &str,
        body: &[u8],
    ) -> (u16, Vec<u8>) {
        let mut s = TcpStream::connect(&self.addr).unwrap();
        write!(
            s,
            "{method} {path} HTTP/1.1\r\n{headers}Content-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
            body.len()
        )
        .unwrap();
        s.write_all(body).unwrap();
        let mut raw = Vec::new();
        s.read_to_end(&mut raw).unwrap();
        let split = raw
            .windows(4)
            .position(|w| w == b"\r\n\r\n")
            .expect("an HTTP response");
        let head = String::from_utf8_lossy(&raw[..split]).to_string();
        let status = head.split_whitespace().nth(1).unwrap().parse().unwrap();
        (status, raw[split + 4..].to_vec())
    }
}

impl Server {
    /// The server's peak resident memory (VmHWM), in KiB, where /proc tells it.
    pub fn peak_rss_kib(&self) -> Option<u64> {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.child.id())).ok()?;
        status
            .lines()
            .find_map(|l| l.strip_prefix("VmHWM:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Where a browser test's screenshots go: $CASTELLAN_E2E_SCREENSHOTS (docs/serve for the docs),
/// or `fallback`.
pub fn screenshots(fallback: &Path) -> PathBuf {
    std::env::var_os("CASTELLAN_E2E_SCREENSHOTS")
        .map(PathBuf::from)
        .unwrap_or_else(|| fallback.to_path_buf())
}

/// Runs the browser test tests/e2e/`script` with Node.js and playwright-core in Debian's
/// Chromium (or $CHROMIUM) against `server`, with CASTELLAN_URL, SCREENSHOTS (`shots`) and
/// CHROMIUM set and `env` besides; the script must succeed. Returns the JSON figures it prints
/// last, or None after saying why `test` skips when Chromium, playwright-core (`npm ci` in
/// tests/e2e) or Node.js is missing — under CI=true, which .ci/run sets, those are failures.
pub fn browser_test(
    test: &str,
    script: &str,
    server: &Server,
    shots: &Path,
    env: &[(&str, String)],
) -> Option<serde_json::Value> {
    let skip = |what: String| {
        let ci = std::env::var("CI").is_ok_and(|v| v == "true" || v == "1");
        assert!(!ci, "CI=true but {what}: .ci/run installs it");
        eprintln!("SKIPPED {test}: {what} (see docs/serve.md, Tests)");
        None
    };
    let chromium = std::env::var_os("CHROMIUM")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/usr/bin/chromium"));
    if !chromium.is_file() {
        return skip(format!("no Chromium at {}", chromium.display()));
    }
    let e2e = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/e2e");
    if !e2e.join("node_modules/playwright-core").is_dir() {
        return skip(format!(
            "playwright-core is not installed: run `npm ci` in {}",
            e2e.display()
        ));
    }
    let out = match Command::new("node")
        .arg(script)
        .current_dir(&e2e)
        .env("CASTELLAN_URL", &server.url)
        .env("SCREENSHOTS", shots)
        .env("CHROMIUM", &chromium)
        .envs(env.iter().map(|(k, v)| (*k, v.as_str())))
        .output()
    {
        Ok(o) => o,
        Err(e) => return skip(format!("cannot run node ({e})")),
    };
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "the browser test failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    Some(serde_json::from_str(stdout.lines().last().unwrap_or("")).unwrap())
}
