//! The user's rectification segments in `castellan serve` (§3.1.1, the manual override): the
//! page drags the detected segments' endpoints, adds or removes segments, and saves them as the
//! façade's LINES.json (`lines` of its [[facade]]), which rectification then uses instead. The
//! segments are checked by `facade::rectify::ManualLines::validate` before they are saved.

use std::sync::Arc;

use axum::Json;
use axum::extract::{Path, State};
use axum::http::{HeaderMap, StatusCode};
use facade::rectify::ManualLines;
use integrate::textures::safe_stem;
use serde_json::{Value, json};

use super::app::{
    ApiError, App, Saved, blocking, check_version, err, facade_for_edit, file_url, find_facade,
    if_match, versioned,
};

/// PUT /api/facades/{name}/lines: saves LINES.json and points the façade at it.
pub async fn save(
    State(app): State<Arc<App>>,
    Path(name): Path<String>,
    headers: HeaderMap,
    Json(lines): Json<ManualLines>,
) -> Saved {
    let if_match = if_match(&headers);
    blocking(app, "lines", move |app| {
        let (mut p, f, (w, h)) = facade_for_edit(&app.store, &name)?;
        check_version(&app.store, if_match.as_deref())?;
        lines
            .validate(w, h)
            .map_err(|m| ApiError(StatusCode::BAD_REQUEST, format!("{name}: {m}")))?;
        let file = f
            .lines
            .clone()
            .unwrap_or_else(|| format!("{}.lines.json", safe_stem(&f.image)));
        for g in p.facades.iter_mut().filter(|g| g.image == name) {
            g.lines = Some(file.clone());
        }
        let bytes = serde_json::to_vec_pretty(&lines).unwrap_or_default();
        app.store
            .commit(Some(&p), vec![(file.clone(), bytes)])
            .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
        versioned(
            &app.store,
            json!({
                "saved": file, "url": file_url(&file),
                "horizontal": lines.horizontal.len(), "vertical": lines.vertical.len(),
            }),
        )
    })
    .await
}

/// DELETE /api/facades/{name}/lines: back to the automatic segments (the file is kept).
pub async fn remove(
    State(app): State<Arc<App>>,
    Path(name): Path<String>,
    headers: HeaderMap,
) -> Saved {
    let if_match = if_match(&headers);
    blocking(app, "lines", move |app| {
        let mut p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        find_facade(&p, &name)?;
        check_version(&app.store, if_match.as_deref())?;
        for g in p.facades.iter_mut().filter(|g| g.image == name) {
            g.lines = None;
        }
        app.store
            .commit(Some(&p), vec![])
            .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
        versioned(&app.store, json!({ "saved": Value::Null }))
    })
    .await
}
