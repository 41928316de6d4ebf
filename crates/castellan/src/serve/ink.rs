//! The learned wall ink in `castellan serve` (issue 26, ilastik's workflow): the user paints
//! "wall" / "not wall" on a few pixels of the plan, or chooses the rules instead; both are
//! saved in PROJECT.toml (`ink`, `[[ink_stroke]]`), so `castellan reconstruct` reads the walls
//! the same way, and the plan stage is run again by the page.

use std::sync::Arc;

use axum::Json;
use axum::extract::State;
use axum::http::{HeaderMap, StatusCode};
use integrate::pipeline::Files;
use plan::ink::InkMethod;
use plan::ink::refine::{InkStroke, check};
use serde::Deserialize;
use serde_json::json;

use super::app::{ApiError, App, Saved, blocking, check_version, err, if_match, versioned};

/// The body of PUT /api/plan/ink.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InkBody {
    pub ink: InkMethod,
    pub strokes: Vec<InkStroke>,
}

/// PUT /api/plan/ink: how the plan's walls are read and the user's strokes, checked against
/// the plan drawing's size and saved in PROJECT.toml.
pub async fn save(
    State(app): State<Arc<App>>,
    headers: HeaderMap,
    Json(body): Json<InkBody>,
) -> Saved {
    let if_match = if_match(&headers);
    blocking(app, "wall ink", move |app| {
        let mut p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        check_version(&app.store, if_match.as_deref())?;
        let image = app
            .store
            .image(&p.plan)
            .map_err(|e| ApiError(StatusCode::CONFLICT, e))?;
        check(&body.strokes, image.width(), image.height())
            .map_err(|e| ApiError(StatusCode::BAD_REQUEST, format!("wall ink: {e}")))?;
        p.ink = (body.ink != InkMethod::default()).then_some(body.ink);
        p.ink_strokes = body.strokes;
        app.store
            .commit(Some(&p), vec![])
            .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
        versioned(
            &app.store,
            json!({ "ink": body.ink, "strokes": p.ink_strokes.len() }),
        )
    })
    .await
}
