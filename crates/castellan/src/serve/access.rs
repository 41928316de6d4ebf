//! Who may drive `castellan serve` (issue 19): the run's secret token and the names the server
//! answers to — the Host headers naming the server itself (a DNS-rebinding page names its own
//! host), the Origins of its own page, and the token from a header or, for reads, a cookie.
//! guard.rs applies these checks to every request.

use std::net::SocketAddr;
use std::time::Duration;

use axum::http::{HeaderMap, Method, header};

/// The header the page sends the token in. A custom header makes a cross-origin request
/// "non-simple", so a browser first asks with a preflight OPTIONS, which this server never grants.
pub const TOKEN_HEADER: &str = "x-castellan-token";

/// The run's secret and the names the server answers to.
#[derive(Clone)]
pub struct Access {
    pub token: String,
    /// Host header values accepted (lower case): `127.0.0.1:PORT`, `localhost:PORT`,
    /// `[::1]:PORT`, and the listen address when it is not loopback.
    hosts: Vec<String>,
    /// The cookie that carries the token for `<img src>` and download links, which cannot send
    /// headers; per port, since cookies do not tell ports apart.
    pub cookie: String,
    /// How long the request body may take to arrive.
    pub body_timeout: Duration,
}

impl Access {
    pub fn new(token: String, addr: SocketAddr, body_timeout: Duration) -> Access {
        let port = addr.port();
        let mut names = vec![
            "127.0.0.1".to_string(),
            "localhost".to_string(),
            "[::1]".to_string(),
        ];
        if !addr.ip().is_loopback() {
            names.push(match addr {
                SocketAddr::V4(a) => a.ip().to_string(),
                SocketAddr::V6(a) => format!("[{}]", a.ip()),
            });
        }
        let mut hosts: Vec<String> = names.iter().map(|n| format!("{n}:{port}")).collect();
        if port == 80 {
            // Browsers leave the default port out of Host.
            hosts.extend(names);
        }
        Access {
            token,
            hosts,
            cookie: format!("castellan_token_{port}"),
            body_timeout,
        }
    }

    /// A fresh token of 32 bytes from the operating system's entropy, as hex.
    pub fn random_token() -> anyhow::Result<String> {
        let mut bytes = [0u8; 32];
        getrandom::fill(&mut bytes)
            .map_err(|e| anyhow::anyhow!("no random numbers from the system: {e}"))?;
        Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
    }

    pub(super) fn host_ok(&self, host: &str) -> bool {
        let host = host.to_ascii_lowercase();
        self.hosts.contains(&host)
    }

    pub(super) fn origin_ok(&self, origin: &str) -> bool {
        origin
            .strip_prefix("http://")
            .is_some_and(|host| self.host_ok(host))
    }

    pub(super) fn token_ok(&self, given: &[u8]) -> bool {
        // Compared in constant time, so the answer's timing does not leak a prefix.
        let want = self.token.as_bytes();
        given.len() == want.len() && given.iter().zip(want).fold(0u8, |d, (a, b)| d | (a ^ b)) == 0
    }

    /// The token from the header or, for reads (images, downloads), from the cookie.
    pub(super) fn request_has_token(&self, method: &Method, headers: &HeaderMap) -> bool {
        if let Some(v) = headers.get(TOKEN_HEADER) {
            return self.token_ok(v.as_bytes());
        }
        // Writes need the header: a cookie travels with requests the page did not make.
        if method != Method::GET && method != Method::HEAD {
            return false;
        }
        headers
            .get_all(header::COOKIE)
            .iter()
            .filter_map(|v| v.to_str().ok())
            .flat_map(|v| v.split(';'))
            .filter_map(|kv| kv.trim().split_once('='))
            .any(|(k, v)| k == self.cookie && self.token_ok(v.as_bytes()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use axum::http::HeaderValue;

    fn access(addr: &str) -> Access {
        Access::new("ab12".into(), addr.parse().unwrap(), Duration::from_secs(1))
    }

    #[test]
    fn the_server_answers_to_its_loopback_names_and_its_listen_address_only() {
        let a = access("127.0.0.1:8080");
        for h in [
            "127.0.0.1:8080",
            "localhost:8080",
            "LOCALHOST:8080",
            "[::1]:8080",
        ] {
            assert!(a.host_ok(h), "{h}");
        }
        for h in [
            "attacker.example",
            "attacker.example:8080",
            "127.0.0.1:8081",
            "127.0.0.1",
        ] {
            assert!(!a.host_ok(h), "{h}");
        }
        let a = access("192.168.1.5:9000");
        assert!(a.host_ok("192.168.1.5:9000") && a.host_ok("localhost:9000"));
        assert!(a.origin_ok("http://192.168.1.5:9000"));
        assert!(!a.origin_ok("https://192.168.1.5:9000") && !a.origin_ok("null"));
        let a = access("[::1]:80");
        assert!(a.host_ok("[::1]") && a.host_ok("localhost"));
    }

    #[test]
    fn the_token_must_match_exactly_and_a_cookie_only_reads() {
        let a = access("127.0.0.1:8080");
        let mut h = HeaderMap::new();
        assert!(!a.request_has_token(&Method::GET, &h));
        h.insert(TOKEN_HEADER, HeaderValue::from_static("ab1"));
        assert!(!a.request_has_token(&Method::GET, &h));
        h.insert(TOKEN_HEADER, HeaderValue::from_static("ab12"));
        assert!(a.request_has_token(&Method::PUT, &h));
        let mut h = HeaderMap::new();
        h.insert(
            header::COOKIE,
            HeaderValue::from_static("x=1; castellan_token_8080=ab12"),
        );
        assert!(a.request_has_token(&Method::GET, &h));
        assert!(!a.request_has_token(&Method::POST, &h));
    }
}
