//! `castellan serve [PROJECT_DIR]` (issue 10): the semi-automatic workflow of the dissertation
//! (training boxes §3.1.2, rectification §3.1.1, plan cleaning §5.1.1 and parsing §5.1,
//! correspondences §6.1.1) as a local
//! web app — an HTTP API over one project folder and a page embedded in the binary.

mod access;
mod app;
mod clean;
mod conn;
mod corrections;
#[cfg(test)]
mod corrections_tests;
#[cfg(test)]
mod edit_tests;
mod facade_fix;
#[cfg(test)]
mod facade_fix_tests;
#[cfg(test)]
mod fuzz_tests;
mod gothic;
mod guard;
#[cfg(test)]
mod guard_tests;
mod ink;
mod lines;
mod preview;
mod project;
#[cfg(test)]
mod simulated_user_tests;
mod stages;
mod store;
#[cfg(test)]
mod tests;

use std::net::{IpAddr, Ipv4Addr};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use anyhow::{Context, Result};
use axum::Router;
use axum::extract::DefaultBodyLimit;
use axum::http::header;
use axum::response::IntoResponse;
use axum::routing::{get, post, put};
use clap::Args;

pub use access::Access;

/// `castellan serve` flags.
#[derive(Debug, Args)]
pub struct ServeArgs {
    /// The project folder (created when missing); its PROJECT.toml is written once a plan is uploaded.
    #[arg(default_value = ".")]
    pub project_dir: PathBuf,
    /// TCP port; 0 picks a free one (the URL is printed).
    #[arg(long, default_value_t = 8080)]
    pub port: u16,
    /// Address to listen on. The default is loopback only: the API writes to the project folder
    /// and its only protection is the token in the printed URL, which travels unencrypted, so
    /// expose it to a network only if you trust everyone on it.
    #[arg(long, default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST))]
    pub host: IpAddr,
    /// Largest upload (and request body) accepted, in MiB, 1 to 4096.
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u64).range(1..=4096))]
    pub max_upload_mb: u64,
    /// Seconds a client may take to send a request's headers (and to start its next request
    /// on a kept-alive connection).
    #[arg(long, default_value_t = 30, hide = true, value_parser = clap::value_parser!(u64).range(1..=3600))]
    pub header_timeout_secs: u64,
    /// Seconds a client may take to send a request's body.
    #[arg(long, default_value_t = 120, hide = true, value_parser = clap::value_parser!(u64).range(1..=3600))]
    pub body_timeout_secs: u64,
    /// Seconds a client may leave an answer unread before the connection is closed.
    #[arg(long, default_value_t = 60, hide = true, value_parser = clap::value_parser!(u64).range(1..=3600))]
    pub write_timeout_secs: u64,
    /// Most connections served at once.
    #[arg(long, default_value_t = 64, hide = true, value_parser = clap::value_parser!(u64).range(1..=10_000))]
    pub max_connections: u64,
    /// Per-pixel classifier of the façade photos (the façade stage, the live probability map
    /// and the model): forest or gmm (§3.1.3–3.1.4's mixtures).
    #[arg(long, default_value = "forest", value_parser = crate::flags::classifier)]
    pub classifier: facade::classify::Method,
}

const INDEX_HTML: &str = include_str!("../../web/index.html");
const APP_CSS: &str = include_str!("../../web/app.css");
/// web/src/app.js with the viewer and three.js, bundled by build.rs.
const APP_JS: &str = include_str!(concat!(env!("OUT_DIR"), "/app.js"));

pub fn run(args: &ServeArgs) -> Result<()> {
    let store = store::Store::open(&args.project_dir)?;
    let dir = store.dir.clone();
    let token = Access::random_token()?;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .context("cannot start the server's runtime")?;
    runtime.block_on(async {
        let listener = tokio::net::TcpListener::bind((args.host, args.port))
            .await
            .with_context(|| format!("cannot listen on {}:{}", args.host, args.port))?;
        let addr = listener.local_addr()?;
        let access = Access::new(token, addr, Duration::from_secs(args.body_timeout_secs));
        let url = format!("http://{addr}/?token={}", access.token);
        // The flag's range keeps the shift in bounds (4096 MiB = 2^32 bytes).
        let app = router(app::App::new(
            store,
            (args.max_upload_mb as usize) << 20,
            access,
            args.classifier,
        ));
        if !args.host.is_loopback() {
            eprintln!(
                "warning: listening on {addr}: anyone who can reach it and learns the token \
                 (it travels unencrypted) can read and change {}",
                dir.display()
            );
        }
        // Tests and scripts read this line for the address and the token.
        println!("castellan serve: {url} (project {})", dir.display());
        let limits = conn::Limits {
            header: Duration::from_secs(args.header_timeout_secs),
            write: Duration::from_secs(args.write_timeout_secs),
            connections: args.max_connections as usize,
        };
        conn::serve(listener, app, limits)
            .await
            .context("the server stopped")
    })
}

pub fn router(app: Arc<app::App>) -> Router {
    let limit = app.max_upload;
    Router::new()
        .route(
            "/",
            get(|| async { asset("text/html; charset=utf-8", INDEX_HTML) }),
        )
        .route("/app.css", get(|| async { asset("text/css", APP_CSS) }))
        .route(
            "/app.js",
            get(|| async { asset("text/javascript", APP_JS) }),
        )
        .route("/api/project", get(project::project))
        .route("/api/progress", get(project::progress))
        .route("/api/upload", post(project::upload))
        .route("/api/plan", post(stages::plan))
        .route("/api/plan/binary", get(clean::binary))
        .route("/api/plan/cleaning", put(clean::save))
        .route("/api/plan/ink", put(ink::save))
        .route("/api/plan/settings", put(corrections::settings))
        .route(
            "/api/corrections",
            get(corrections::get).put(corrections::put),
        )
        .route("/api/structure", get(corrections::at))
        .route("/api/plan/at", get(corrections::label_at))
        .route("/api/facades/{name}/rectify", post(stages::rectify))
        .route("/api/facades/{name}/training", put(stages::training))
        .route(
            "/api/facades/{name}/lines",
            put(lines::save).delete(lines::remove),
        )
        .route("/api/facades/{name}/facade", post(stages::facade_stage))
        .route("/api/facades/{name}/preview", post(preview::preview))
        .route(
            "/api/facades/{name}/fixes",
            put(facade_fix::save).delete(facade_fix::remove),
        )
        .route("/api/facades/{name}/tree", post(facade_fix::tree))
        .route("/api/gothic/{name}", post(gothic::estimate))
        .route("/api/gothic/{name}/elements", put(gothic::save_elements))
        .route("/api/correspondences", put(stages::correspondences))
        .route("/api/reconstruct", post(stages::reconstruct))
        .route("/files/{*path}", get(project::file))
        .layer(DefaultBodyLimit::max(limit))
        .layer(axum::middleware::from_fn_with_state(
            app.clone(),
            guard::check,
        ))
        .with_state(app)
}

fn asset(content_type: &'static str, body: &'static str) -> impl IntoResponse {
    ([(header::CONTENT_TYPE, content_type)], body)
}

#[cfg(test)]
mod flag_tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: ServeArgs,
    }

    #[test]
    fn serve_defaults_to_loopback_port_8080_and_the_current_folder() {
        let c = Cli::try_parse_from(["x"]).unwrap().args;
        assert_eq!(c.project_dir, PathBuf::from("."));
        assert_eq!(c.port, 8080);
        assert!(c.host.is_loopback());
        let c = Cli::try_parse_from(["x", "proj", "--port", "0", "--host", "0.0.0.0"])
            .unwrap()
            .args;
        assert_eq!((c.project_dir, c.port), (PathBuf::from("proj"), 0));
        assert!(!c.host.is_loopback());
        assert!(Cli::try_parse_from(["x", "--port", "70000"]).is_err());
    }

    #[test]
    fn an_upload_limit_that_would_overflow_is_refused() {
        let e = Cli::try_parse_from(["x", "--max-upload-mb", "17592186044416"])
            .err()
            .unwrap()
            .to_string();
        assert!(
            e.contains("--max-upload-mb") && e.contains("1..=4096"),
            "{e}"
        );
        assert!(Cli::try_parse_from(["x", "--max-upload-mb", "0"]).is_err());
        let c = Cli::try_parse_from(["x", "--max-upload-mb", "4096"])
            .unwrap()
            .args;
        assert_eq!((c.max_upload_mb as usize) << 20, 1 << 32);
    }
}
