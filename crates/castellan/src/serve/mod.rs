//! `castellan serve [PROJECT_DIR]` (issue 10): the semi-automatic workflow of the dissertation
//! (training boxes §3.1.2, rectification §3.1.1, plan cleaning §5.1.1 and parsing §5.1,
//! correspondences §6.1.1) as a local
//! web app — an HTTP API over one project folder and a page embedded in the binary.

mod api;
mod clean;
#[cfg(test)]
mod edit_tests;
mod lines;
mod stages;
mod store;
#[cfg(test)]
mod tests;

use std::net::{IpAddr, Ipv4Addr};
use std::path::PathBuf;
use std::sync::Arc;

use anyhow::{Context, Result};
use axum::Router;
use axum::extract::DefaultBodyLimit;
use axum::http::header;
use axum::response::IntoResponse;
use axum::routing::{get, post, put};
use clap::Args;

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
    /// and has no authentication, so expose it to a network only if you trust everyone on it.
    #[arg(long, default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST))]
    pub host: IpAddr,
    /// Largest upload accepted, in MiB.
    #[arg(long, default_value_t = 64)]
    pub max_upload_mb: usize,
}

const INDEX_HTML: &str = include_str!("../../web/index.html");
const APP_CSS: &str = include_str!("../../web/app.css");
/// web/src/app.js with the viewer and three.js, bundled by build.rs.
const APP_JS: &str = include_str!(concat!(env!("OUT_DIR"), "/app.js"));

pub fn run(args: &ServeArgs) -> Result<()> {
    let store = store::Store::open(&args.project_dir)?;
    let dir = store.dir.clone();
    let app = router(api::App::new(store, args.max_upload_mb << 20));
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .context("cannot start the server's runtime")?;
    runtime.block_on(async {
        let listener = tokio::net::TcpListener::bind((args.host, args.port))
            .await
            .with_context(|| format!("cannot listen on {}:{}", args.host, args.port))?;
        let addr = listener.local_addr()?;
        if !args.host.is_loopback() {
            eprintln!(
                "warning: listening on {addr}: anyone who can reach it can read and change {}",
                dir.display()
            );
        }
        // Tests and scripts read this line for the port.
        println!(
            "castellan serve: http://{addr}/ (project {})",
            dir.display()
        );
        axum::serve(listener, app)
            .await
            .context("the server stopped")
    })
}

pub fn router(app: Arc<api::App>) -> Router {
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
        .route("/api/project", get(api::project))
        .route("/api/progress", get(api::progress))
        .route("/api/upload", post(api::upload))
        .route("/api/plan", post(stages::plan))
        .route("/api/plan/binary", get(clean::binary))
        .route("/api/plan/cleaning", put(clean::save))
        .route("/api/facades/{name}/rectify", post(stages::rectify))
        .route("/api/facades/{name}/training", put(stages::training))
        .route(
            "/api/facades/{name}/lines",
            put(lines::save).delete(lines::remove),
        )
        .route("/api/facades/{name}/facade", post(stages::facade_stage))
        .route("/api/correspondences", put(stages::correspondences))
        .route("/api/reconstruct", post(stages::reconstruct))
        .route("/files/{*path}", get(api::file))
        .layer(DefaultBodyLimit::max(limit))
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
}
