//! The user's façade corrections in `castellan serve` (issue 22; `[facade.fix]` of a [[facade]]
//! entry): floor lines and window columns dragged, windows added or removed, floors without
//! windows. Every change re-runs the façade step (§3.1.2–3.1.7) with the new corrections, which
//! checks them against the rectified photo; only a change that runs is saved, with its overlay.

use std::sync::Arc;
use std::time::Instant;

use axum::Json;
use axum::extract::{Path, State};
use axum::http::{HeaderMap, StatusCode};
use facade::fixes::FacadeFixes;
use integrate::pipeline;
use integrate::project::Project;
use serde_json::{Value, json};

use super::app::{
    ApiError, App, Reply, Saved, blocking, check_version, err, facade_index, file_url, if_match,
    versioned,
};

/// The façade step on photo `index` of `p` (with its corrections): overlays written under out/
/// (with `p` itself when `save`), and what the page draws its handles from — the façade tree in
/// rectified pixels, the corrections, the overlay, the counts and what looks implausible about
/// the corrected model (`facade::plausibility`, as `castellan facade` says it).
fn run(app: &App, p: &Project, index: usize, save: bool) -> Result<Value, ApiError> {
    let t = Instant::now();
    let (e, overlays) = pipeline::estimate_photo(p, index, &app.store, &app.options)
        .map_err(|e| ApiError(StatusCode::UNPROCESSABLE_ENTITY, e.to_string()))?;
    let mut files = Vec::new();
    for o in &overlays {
        let name = format!("out/{}", o.name);
        let bytes = o
            .picture
            .png()
            .map_err(|e| ApiError(StatusCode::INTERNAL_SERVER_ERROR, format!("{name}: {e}")))?;
        files.push((name, bytes));
    }
    let overlay = files
        .iter()
        .map(|(n, _)| n)
        .find(|n| n.ends_with("_facade.png"))
        .cloned()
        .unwrap_or_default();
    app.store
        .commit(save.then_some(p), files)
        .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
    let floors: usize = e.model.facades.iter().map(|f| f.floors.len()).sum();
    let windows: usize = e
        .model
        .facades
        .iter()
        .flat_map(|f| &f.floors)
        .map(|fl| fl.windows.len())
        .sum();
    let facades: Vec<Value> = e
        .model
        .facades
        .iter()
        .map(|f| json!({ "bbox": f.bbox, "floors": f.floors }))
        .collect();
    let warnings: Vec<String> = facade::plausibility::check(&e.model, &e.training)
        .iter()
        .map(ToString::to_string)
        .collect();
    Ok(json!({
        "overlay": file_url(&overlay),
        "width": e.model.width, "height": e.model.height,
        "facades": facades, "floors": floors, "windows": windows,
        "fix": p.facades[index].fix,
        "warnings": warnings,
        "ms": t.elapsed().as_millis(),
    }))
}

/// Replaces the corrections of façade `name` with `fix` after the façade step ran with them.
fn replace(app: &App, name: &str, if_match: Option<&str>, fix: FacadeFixes) -> Saved {
    let mut p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
    let index = facade_index(&p, name)?;
    check_version(&app.store, if_match)?;
    p.facades[index].fix = fix;
    let body = run(app, &p, index, true)?;
    versioned(&app.store, body)
}

/// PUT /api/facades/{name}/fixes: the façade's corrections, whole (`[facade.fix]`'s keys);
/// the façade step runs with them, and they are saved only if it does.
pub async fn save(
    State(app): State<Arc<App>>,
    Path(name): Path<String>,
    headers: HeaderMap,
    Json(fix): Json<FacadeFixes>,
) -> Saved {
    let if_match = if_match(&headers);
    blocking(app, "facade", move |app| {
        replace(app, &name, if_match.as_deref(), fix)
    })
    .await
}

/// DELETE /api/facades/{name}/fixes: back to the search's own estimate.
pub async fn remove(
    State(app): State<Arc<App>>,
    Path(name): Path<String>,
    headers: HeaderMap,
) -> Saved {
    let if_match = if_match(&headers);
    blocking(app, "facade", move |app| {
        replace(app, &name, if_match.as_deref(), FacadeFixes::default())
    })
    .await
}

/// POST /api/facades/{name}/tree: the façade step with the saved corrections, answered with
/// the tree the page edits; the project is not changed.
pub async fn tree(State(app): State<Arc<App>>, Path(name): Path<String>) -> Reply {
    blocking(app, "facade", move |app| {
        let p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let index = facade_index(&p, &name)?;
        run(app, &p, index, false).map(Json)
    })
    .await
}
