//! Plan cleaning in `castellan serve` (§5.1.1, painted by `plan::clean`): the HTTP handlers, and
//! the cleaned drawing saved as `STEM.cleaned.png`, which PROJECT.toml's `plan` names, beside
//! plan_cleaning.json (the original and every stroke; read by app.rs's `load_cleaning`, which
//! the project's handler shares).

use std::sync::Arc;

use axum::Json;
use axum::extract::State;
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};
use image::GrayImage;
use integrate::textures::safe_stem;
use plan::clean::{Cleaning, Strokes, binary_drawing, check, paint};
use serde_json::json;

use super::app::{
    ApiError, App, Saved, blocking, check_version, err, file_url, if_match, load_cleaning,
    versioned,
};
use super::store::CLEANING_FILE;
use crate::images::{png, read_image};

fn original_binary(app: &App, cleaning: &Cleaning) -> Result<GrayImage, ApiError> {
    let path = app
        .store
        .path(&cleaning.original)
        .map_err(err(StatusCode::CONFLICT))?;
    let image = read_image(&path).map_err(err(StatusCode::UNPROCESSABLE_ENTITY))?;
    Ok(binary_drawing(&image.to_luma8()))
}

/// GET /api/plan/binary: the original drawing's binary image, as PNG.
pub async fn binary(State(app): State<Arc<App>>) -> Result<Response, ApiError> {
    let bytes = blocking(app, "plan binary", |app| {
        let p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let cleaning = load_cleaning(app, &p)?;
        let img = original_binary(app, &cleaning)?;
        png(&img, std::path::Path::new("binary plan"))
            .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))
    })
    .await?;
    Ok(([(header::CONTENT_TYPE, "image/png")], bytes).into_response())
}

/// PUT /api/plan/cleaning: paints every stroke on the original's binary image and makes the
/// result the project's plan (`STEM.cleaned.png`); no strokes restores the original.
pub async fn save(
    State(app): State<Arc<App>>,
    headers: HeaderMap,
    Json(body): Json<Strokes>,
) -> Saved {
    let if_match = if_match(&headers);
    blocking(app, "plan cleaning", move |app| {
        let mut p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        check_version(&app.store, if_match.as_deref())?;
        let mut cleaning = load_cleaning(app, &p)?;
        let mut img = original_binary(app, &cleaning)?;
        check(&body.strokes, img.width(), img.height())
            .map_err(|m| ApiError(StatusCode::BAD_REQUEST, format!("plan cleaning: {m}")))?;
        let changed = paint(&mut img, &body.strokes);
        cleaning.strokes = body.strokes;
        let mut files = vec![];
        if cleaning.strokes.is_empty() {
            p.plan = cleaning.original.clone();
        } else {
            p.plan = format!("{}.cleaned.png", safe_stem(&cleaning.original));
            let bytes = png(&img, std::path::Path::new(&p.plan))
                .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
            files.push((p.plan.clone(), bytes));
        }
        files.push((
            CLEANING_FILE.to_string(),
            serde_json::to_vec_pretty(&cleaning).unwrap_or_default(),
        ));
        app.store
            .commit(Some(&p), files)
            .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
        versioned(
            &app.store,
            json!({
                "plan": p.plan, "url": file_url(&p.plan), "original": cleaning.original,
                "strokes": cleaning.strokes.len(), "changed_pixels": changed,
            }),
        )
    })
    .await
}
