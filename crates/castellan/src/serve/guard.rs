//! The middleware in front of every route of `castellan serve` (issue 19): every request must
//! name the server itself in its Host header, may carry no foreign Origin (a page of another
//! site posting a form), and every `/api/*` and `/files/*` request must carry the run's secret
//! token (the checks are access.rs's). Also here, for every route: the request body read within
//! a time limit and a size limit, and every error answered as JSON `{"error": …}`, axum's own
//! refusals included.

use std::sync::Arc;
use std::time::Duration;

use axum::Json;
use axum::body::{Body, Bytes};
use axum::extract::{Request, State};
use axum::http::{HeaderValue, Method, StatusCode, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use http_body_util::{BodyExt, LengthLimitError, Limited};
use serde_json::json;

use super::app::{ApiError, App};

fn forbidden(m: impl Into<String>) -> Response {
    ApiError(StatusCode::FORBIDDEN, m.into()).into_response()
}

/// The `token` parameter of a query string.
fn query_token(query: Option<&str>) -> Option<&str> {
    query?
        .split('&')
        .filter_map(|kv| kv.split_once('='))
        .find(|(k, _)| *k == "token")
        .map(|(_, v)| v)
}

/// The middleware in front of every route.
pub async fn check(State(app): State<Arc<App>>, req: Request, next: Next) -> Response {
    let access = &app.access;
    let (parts, body) = req.into_parts();
    let host = parts
        .headers
        .get(header::HOST)
        .and_then(|h| h.to_str().ok())
        .or_else(|| parts.uri.authority().map(|a| a.as_str()));
    match host {
        Some(h) if access.host_ok(h) => {}
        Some(h) => {
            return forbidden(format!(
                "this server answers to its own address only, not to Host \"{h}\" (open the URL \
                 castellan serve printed)"
            ));
        }
        None => return forbidden("a request without a Host header is refused"),
    }
    if let Some(origin) = parts.headers.get(header::ORIGIN) {
        let origin = origin.to_str().unwrap_or("");
        if !access.origin_ok(origin) {
            return forbidden(format!(
                "requests from other sites are refused (Origin \"{origin}\")"
            ));
        }
    }
    // Browsers say where a request comes from; only the page itself and typed URLs pass.
    if let Some(site) = parts.headers.get("sec-fetch-site")
        && !matches!(site.as_bytes(), b"same-origin" | b"none")
    {
        return forbidden("requests from other sites are refused (Sec-Fetch-Site)");
    }
    let path = parts.uri.path().to_string();
    let guarded = path.starts_with("/api/") || path == "/api" || path.starts_with("/files/");
    if guarded && !access.request_has_token(&parts.method, &parts.headers) {
        return forbidden(
            "missing or wrong token: open the URL castellan serve printed (it ends in ?token=…)",
        );
    }
    // The page's URL carries the token once; a cookie then lets <img> tags load files.
    let set_cookie = (path == "/")
        .then(|| query_token(parts.uri.query()))
        .flatten()
        .map(|t| access.token_ok(t.as_bytes()));
    if set_cookie == Some(false) {
        return forbidden("wrong token: open the URL castellan serve printed");
    }
    let bytes = match read_body(body, app.max_upload, access.body_timeout).await {
        Ok(b) => b,
        Err(e) => return e.into_response(),
    };
    let method = parts.method.clone();
    let mut res = next
        .run(Request::from_parts(parts, Body::from(bytes)))
        .await;
    let h = res.headers_mut();
    h.insert("referrer-policy", HeaderValue::from_static("no-referrer"));
    h.insert(
        "x-content-type-options",
        HeaderValue::from_static("nosniff"),
    );
    h.insert("x-frame-options", HeaderValue::from_static("DENY"));
    if set_cookie == Some(true)
        && let Ok(v) = HeaderValue::from_str(&format!(
            "{}={}; Path=/; HttpOnly; SameSite=Strict",
            access.cookie, access.token
        ))
    {
        h.insert(header::SET_COOKIE, v);
    }
    as_json_error(res, &method, &path).await
}

/// The whole request body, refused past `limit` bytes (413) or `timeout` (408): a client that
/// trickles its body would otherwise hold a connection and a buffer for ever.
async fn read_body(body: Body, limit: usize, timeout: Duration) -> Result<Bytes, ApiError> {
    let read = Limited::new(body, limit).collect();
    match tokio::time::timeout(timeout, read).await {
        Err(_) => Err(ApiError(
            StatusCode::REQUEST_TIMEOUT,
            format!(
                "the request body did not arrive within {} s",
                timeout.as_secs()
            ),
        )),
        Ok(Ok(collected)) => Ok(collected.to_bytes()),
        Ok(Err(e)) if e.downcast_ref::<LengthLimitError>().is_some() => Err(ApiError(
            StatusCode::PAYLOAD_TOO_LARGE,
            format!(
                "the request is larger than the limit of {} MB (--max-upload-mb)",
                limit >> 20
            ),
        )),
        Ok(Err(e)) => Err(ApiError(
            StatusCode::BAD_REQUEST,
            format!("cannot read the request body: {e}"),
        )),
    }
}

/// An error answer that is not JSON yet (axum's refusals of a body, an unknown route, a wrong
/// method) turned into `{"error": …}` with the same status.
async fn as_json_error(res: Response, method: &Method, path: &str) -> Response {
    let status = res.status();
    let is_json = res
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|v| v.as_bytes().starts_with(b"application/json"));
    if !(status.is_client_error() || status.is_server_error()) || is_json {
        return res;
    }
    let (mut parts, body) = res.into_parts();
    let text = match Limited::new(body, 64 << 10).collect().await {
        Ok(c) => String::from_utf8_lossy(&c.to_bytes()).trim().to_string(),
        Err(_) => String::new(),
    };
    let message = match status {
        StatusCode::NOT_FOUND if text.is_empty() => format!("no such page or API route: {path}"),
        StatusCode::METHOD_NOT_ALLOWED => format!("{method} is not allowed on {path}"),
        _ if text.is_empty() => status
            .canonical_reason()
            .unwrap_or("request refused")
            .to_string(),
        _ => text,
    };
    parts.headers.remove(header::CONTENT_LENGTH);
    parts.headers.insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static("application/json"),
    );
    let body = Json(json!({ "error": message }))
        .into_response()
        .into_body();
    Response::from_parts(parts, body)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_token_is_read_from_the_query_string() {
        assert_eq!(query_token(Some("a=1&token=xyz")), Some("xyz"));
    }
}
