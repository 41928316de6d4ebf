//! The pipeline's handlers in `castellan serve`: each stage with its overlay — plan
//! (ch. 5), rectification (§3.1.1), façade search (§3.1.2–3.1.7) — the user's training boxes and
//! correspondences (§6.1.1) saved to the project, and the whole reconstruction (ch. 6–7).

use std::sync::Arc;
use std::time::Instant;

use axum::Json;
use axum::extract::{Path, State};
use axum::http::{HeaderMap, StatusCode};
use facade::classify::Training;
use facade::rectify::ManualLines;
use integrate::pipeline;
use integrate::project::{Correspondence, FacadeEntry, TrainingSource};
use integrate::textures::safe_stem;
use serde_json::{Value, json};

use super::app::{
    ApiError, App, Reply, Saved, blocking, check_version, err, facade_for_edit, facade_index,
    file_url, find_facade, if_match, outputs, plan_stage, save, versioned, write_overlay,
};
use super::store::PROJECT_FILE;
use crate::images::{png, read_image};

/// The façade's LINES.json (user-set rectification segments), if it names one.
fn read_lines(app: &App, f: &FacadeEntry) -> Result<Option<ManualLines>, ApiError> {
    let Some(name) = &f.lines else {
        return Ok(None);
    };
    let path = app.store.path(name).map_err(err(StatusCode::CONFLICT))?;
    crate::text::read_json(&path, "a LINES.json")
        .map(Some)
        .map_err(err(StatusCode::CONFLICT))
}

/// A façade photo of the project, decoded.
pub(super) fn read_photo(app: &App, f: &FacadeEntry) -> Result<image::RgbImage, ApiError> {
    let path = app
        .store
        .path(&f.image)
        .map_err(err(StatusCode::CONFLICT))?;
    Ok(read_image(&path)
        .map_err(err(StatusCode::UNPROCESSABLE_ENTITY))?
        .to_rgb8())
}

fn write_png<P, C>(app: &App, name: &str, img: &image::ImageBuffer<P, C>) -> Result<(), ApiError>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    let bytes =
        png(img, std::path::Path::new(name)).map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
    save(app, name, bytes)
}

/// POST /api/plan: the plan stage (ch. 5) → label and wall overlays, as `reconstruct` makes
/// them.
pub async fn plan(State(app): State<Arc<App>>) -> Reply {
    blocking(app, "plan", |app| {
        let p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let t = Instant::now();
        let stage = plan_stage(app, &p)?;
        let overlay = write_overlay(app, &stage.overlay)?;
        let walls = write_overlay(app, &stage.walls)?;
        let parsed = &stage.parsed;
        Ok(Json(json!({
            "overlay": file_url(&overlay),
            "walls": file_url(&walls),
            "ink": p.ink.unwrap_or_default(),
            "ink_strokes": p.ink_strokes.len(),
            "width": parsed.width, "height": parsed.height,
            "faces": parsed.faces.len(), "edges": parsed.edges.len(),
            "towers": parsed.towers,
            "warnings": parsed.warnings,
            "ms": t.elapsed().as_millis(),
        })))
    })
    .await
}

/// POST /api/facades/{name}/rectify: §3.1.1 → line-family overlay and the rectified photo.
pub async fn rectify(State(app): State<Arc<App>>, Path(name): Path<String>) -> Reply {
    blocking(app, "rectify", move |app| {
        let p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let f = find_facade(&p, &name)?;
        let t = Instant::now();
        let img = read_photo(app, f)?;
        let lines = read_lines(app, f)?;
        // Rectified even when the photo is marked as an elevation, so the user sees the lines.
        let rectified = integrate::photo::rectify_photo(&f.image, &img, lines.as_ref(), false)
            .map_err(|e| ApiError(StatusCode::UNPROCESSABLE_ENTITY, e.to_string()))?;
        let warped = rectified.image;
        let Some(r) = rectified.rectification else {
            return Err(ApiError(
                StatusCode::INTERNAL_SERVER_ERROR,
                format!("{name}: rectification gave no homography"),
            ));
        };
        let s = safe_stem(&f.image);
        let (overlay, rectified) = (
            format!("out/overlays/{s}_lines.png"),
            format!("out/{s}_rectified.png"),
        );
        write_png(app, &overlay, &facade::rectify::draw_overlay(&img, &r))?;
        write_png(app, &rectified, &warped)?;
        Ok(Json(json!({
            "overlay": file_url(&overlay), "rectified": file_url(&rectified),
            "width": r.width, "height": r.height,
            "horizontal": r.horizontal.len(), "vertical": r.vertical.len(),
            // The segments used, as handles for the page to drag (LINES.json's format).
            "lines": facade::rectify::ManualLines::from_segments(&r.horizontal, &r.vertical),
            "manual": lines.is_some(),
            "ms": t.elapsed().as_millis(),
        })))
    })
    .await
}

/// PUT /api/facades/{name}/training: the user's boxes (TRAINING.json, photo pixels).
pub async fn training(
    State(app): State<Arc<App>>,
    Path(name): Path<String>,
    headers: HeaderMap,
    Json(training): Json<Training>,
) -> Saved {
    let if_match = if_match(&headers);
    blocking(app, "training", move |app| {
        let (mut p, f, (w, h)) = facade_for_edit(&app.store, &name)?;
        check_version(&app.store, if_match.as_deref())?;
        // The library's checks (box count, inverted, empty, non-finite, outside the photo), as
        // every command makes them; window and wall boxes may still be missing while the user
        // draws (an empty set is saved when the user clears the boxes).
        training
            .validate(w as usize, h as usize)
            .map_err(|e| ApiError(StatusCode::BAD_REQUEST, format!("{name}: {e}")))?;
        let file = match &f.training {
            TrainingSource::File(file) => file.clone(),
            TrainingSource::Inline(_) => format!("{}.training.json", safe_stem(&f.image)),
        };
        for g in p.facades.iter_mut().filter(|g| g.image == name) {
            g.training = TrainingSource::File(file.clone());
        }
        let bytes = serde_json::to_vec_pretty(&training).unwrap_or_default();
        app.store
            .commit(Some(&p), vec![(file.clone(), bytes)])
            .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
        let boxes: usize = training.classes.values().map(Vec::len).sum();
        versioned(&app.store, json!({ "saved": file, "boxes": boxes }))
    })
    .await
}

/// POST /api/facades/{name}/facade: ch. 3 on one photo → the façade tree over the rectified
/// photo (the overlays of `reconstruct`).
pub async fn facade_stage(State(app): State<Arc<App>>, Path(name): Path<String>) -> Reply {
    blocking(app, "facade", move |app| {
        let p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let index = facade_index(&p, &name)?;
        let t = Instant::now();
        let (e, overlays) = pipeline::estimate_photo(&p, index, &app.store, &app.options)
            .map_err(|e| ApiError(StatusCode::UNPROCESSABLE_ENTITY, e.to_string()))?;
        let mut written = Vec::new();
        for o in &overlays {
            written.push(write_overlay(app, o)?);
        }
        let overlay = written
            .iter()
            .find(|n| n.ends_with("_facade.png"))
            .cloned()
            .unwrap_or_default();
        let floors: usize = e.model.facades.iter().map(|f| f.floors.len()).sum();
        let windows: usize = e
            .model
            .facades
            .iter()
            .flat_map(|f| &f.floors)
            .map(|fl| fl.windows.len())
            .sum();
        // What looks implausible (`facade::plausibility`), as `castellan facade` says it.
        let warnings: Vec<String> = facade::plausibility::check(&e.model, &e.training)
            .iter()
            .map(ToString::to_string)
            .collect();
        Ok(Json(json!({
            "overlay": file_url(&overlay), "facades": e.model.facades.len(),
            "floors": floors, "windows": windows, "ms": t.elapsed().as_millis(),
            "warnings": warnings,
            // Where a correspondence's photo click may land (photo pixels, issue 22).
            "outlines": e.outlines_in_photo(),
        })))
    })
    .await
}

/// PUT /api/correspondences: the whole list (§6.1.1), replacing the project's.
pub async fn correspondences(
    State(app): State<Arc<App>>,
    headers: HeaderMap,
    Json(list): Json<Vec<Correspondence>>,
) -> Saved {
    let if_match = if_match(&headers);
    blocking(app, "correspondences", move |app| {
        let mut p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        check_version(&app.store, if_match.as_deref())?;
        p.correspondences = list;
        app.store
            .commit(Some(&p), vec![])
            .map_err(err(StatusCode::BAD_REQUEST))?;
        versioned(&app.store, json!({ "saved": p.correspondences.len() }))
    })
    .await
}

/// POST /api/reconstruct: `castellan reconstruct PROJECT.toml -o out`.
pub async fn reconstruct(State(app): State<Arc<App>>) -> Reply {
    blocking(app, "reconstruct", |app| {
        app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let s = crate::reconstruction::reconstruct(
            &app.store.dir.join(PROJECT_FILE),
            &app.store.dir.join("out"),
            &app.options,
        )
        .map_err(err(StatusCode::UNPROCESSABLE_ENTITY))?;
        let stages: serde_json::Map<String, Value> = s
            .stages
            .iter()
            .map(|(k, v)| (k.name().to_string(), json!(v.round())))
            .collect();
        Ok(Json(json!({
            "outputs": outputs(),
            "structures": s.estimate.structures.len(),
            "terminals": s.terminals,
            "stages_ms": stages,
            // The plausibility warnings, shown on the page as in the report (issue 22).
            "warnings": s.warnings,
        })))
    })
    .await
}
