//! POST /api/facades/{name}/preview (issue 21): the pixel classifier's class probabilities for
//! the boxes the user has drawn so far, over the photo, as ilastik shows them live — so the user
//! sees after each box what the classifier has learned, before saving or running the search.
//! Nothing is written; the boxes are the request's, not the project's.

use std::sync::Arc;
use std::time::Instant;

use axum::Json;
use axum::extract::{Path, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use facade::classify::{ClassifyParams, Training};
use facade::repeat::RepeatParams;

use super::app::{ApiError, App, blocking, err, find_facade};
use super::stages::read_photo;

/// The PNG of the photo tinted by class probability (`facade::draw::probability_overlay`) as
/// the façade search will read it: when the window boxes are whole windows, with their
/// repeats' evidence added and the repeats outlined (`facade::classify_with_repeats`). Headers:
/// `x-castellan-ms`, the classifier's time; `x-castellan-repeats`, the windows proposed (0 when
/// the step did not run). 422 names the bad box or the missing class.
pub async fn preview(
    State(app): State<Arc<App>>,
    Path(name): Path<String>,
    Json(training): Json<Training>,
) -> Result<Response, ApiError> {
    let (png, ms, repeats) = blocking(app, "preview", move |app| {
        let p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let f = find_facade(&p, &name)?;
        let photo = read_photo(app, f)?;
        let t = Instant::now();
        let params = ClassifyParams::with(app.options.classifier, app.options.seed_for(&p));
        let unprocessable = |e: facade::FacadeError| {
            ApiError(StatusCode::UNPROCESSABLE_ENTITY, format!("{name}: {e}"))
        };
        let (ll, repeats) =
            facade::classify_with_repeats(&photo, &training, &params, &RepeatParams::default())
                .map_err(unprocessable)?;
        let ms = t.elapsed().as_millis();
        let mut map = facade::draw::probability_overlay(&photo, &ll);
        let proposed = repeats.map_or(Vec::new(), |r| r.windows);
        facade::draw::outline_windows(&mut map, &proposed);
        let png = crate::images::png(&map, std::path::Path::new("preview.png"))
            .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
        Ok((png, ms, proposed.len()))
    })
    .await?;
    Ok((
        [
            (header::CONTENT_TYPE, "image/png".to_string()),
            (header::CACHE_CONTROL, "no-store".to_string()),
            (
                header::HeaderName::from_static("x-castellan-ms"),
                ms.to_string(),
            ),
            (
                header::HeaderName::from_static("x-castellan-repeats"),
                repeats.to_string(),
            ),
        ],
        png,
    )
        .into_response())
}
