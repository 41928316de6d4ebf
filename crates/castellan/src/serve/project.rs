//! The project's handlers in `castellan serve` (docs/serve.md has the table): the project as the
//! page loads it, progress of the running step, uploads (decoded within the pixel budget, never
//! overwriting a file) and files confined to the project. The pipeline stages are in stages.rs,
//! what the handlers share in app.rs.

use std::sync::Arc;

use axum::Json;
use axum::extract::{Multipart, Path, State};
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};
use integrate::project::{FacadeEntry, GothicEntry, Project, TrainingSource};
use integrate::textures::safe_stem;
use serde_json::{Value, json};

use super::app::{
    ApiError, App, Saved, blocking, check_version, err, file_url, fresh_cleaning, if_match,
    load_cleaning, outputs, versioned,
};
use super::store::upload_name;

/// GET /api/project
pub async fn project(State(app): State<Arc<App>>) -> Saved {
    blocking(app, "project", |app| {
        let p = app.store.load().map_err(err(StatusCode::CONFLICT))?;
        let cleaning = match &p {
            Some(p) => Some(load_cleaning(app, p)?),
            None => None,
        };
        // The boxes of each façade; one that cannot be read shows no boxes and says why (the
        // façade stage refuses it with the same message).
        let mut training = serde_json::Map::new();
        let mut problems = Vec::new();
        for f in p.iter().flat_map(|p| &p.facades) {
            let t = integrate::pipeline::training(f, &app.store).unwrap_or_else(|e| {
                problems.push(format!("[[facade]] image = \"{}\": {e}", f.image));
                facade::classify::Training::default()
            });
            training.insert(f.image.clone(), serde_json::to_value(t).unwrap_or_default());
        }
        let model = app
            .store
            .existing("out/model.glb")
            .ok()
            .flatten()
            .map(|_| outputs());
        // The last parse's overlays, shown again when the page is reloaded.
        let overlays = app
            .store
            .existing("out/overlays/plan_labels.png")
            .ok()
            .flatten()
            .map(|_| {
                json!({
                    "labels": file_url("out/overlays/plan_labels.png"),
                    "walls": file_url("out/overlays/plan_walls.png"),
                })
            });
        versioned(
            &app.store,
            json!({
                "dir": app.store.dir.display().to_string(),
                "project": p,
                "training": training,
                "problems": problems,
                "cleaning": cleaning,
                "outputs": model,
                "plan_overlays": overlays,
            }),
        )
    })
    .await
}

/// GET /api/progress
pub async fn progress(State(app): State<Arc<App>>) -> Json<Value> {
    Json(app.progress_now())
}

/// POST /api/upload: multipart fields `kind` (`plan`, `facade` or `gothic`) and `file`.
pub async fn upload(State(app): State<Arc<App>>, headers: HeaderMap, mut form: Multipart) -> Saved {
    let if_match = if_match(&headers);
    let mut kind = None;
    let mut file = None;
    loop {
        let field = match form.next_field().await {
            Ok(Some(f)) => f,
            Ok(None) => break,
            Err(e) => return Err(multipart_error(&app, e)),
        };
        match field.name() {
            Some("kind") => kind = Some(field.text().await.map_err(|e| multipart_error(&app, e))?),
            Some("file") => {
                let name = field.file_name().unwrap_or("upload").to_string();
                let bytes = field.bytes().await.map_err(|e| multipart_error(&app, e))?;
                file = Some((name, bytes));
            }
            _ => {}
        }
    }
    let bad = |m: &str| ApiError(StatusCode::BAD_REQUEST, m.to_string());
    let kind =
        kind.ok_or_else(|| bad("the upload has no `kind` field (plan, facade or gothic)"))?;
    if !["plan", "facade", "gothic"].contains(&kind.as_str()) {
        return Err(bad("`kind` must be plan, facade or gothic"));
    }
    let (client_name, bytes) = file.ok_or_else(|| bad("the upload has no `file` field"))?;
    blocking(app, "upload", move |app| {
        check_version(&app.store, if_match.as_deref())?;
        let (format, width, height) = check_image(&client_name, &bytes)?;
        // Never over an existing file: a photo's boxes describe that photo, and a façade
        // called like the plan must not replace the drawing.
        let name = app
            .store
            .fresh_name(&upload_name(&client_name, format), kind != "plan")
            .map_err(err(StatusCode::CONFLICT))?;
        let mut project = app.store.load().map_err(err(StatusCode::CONFLICT))?;
        let mut files = vec![(name.clone(), bytes.to_vec())];
        if kind == "plan" {
            // A new drawing starts a new cleaning (the old one's strokes belong to the old drawing).
            files.push(fresh_cleaning(&name));
        }
        match (kind.as_str(), project.as_mut()) {
            ("plan", Some(p)) => {
                // Strokes, corrections and a clicked scale on the old drawing mean nothing on a
                // new one.
                p.plan = name.clone();
                p.ink_strokes.clear();
                p.scale_line = None;
                p.label_fixes.clear();
                p.tower_fixes.clear();
                p.merges.clear();
                p.structure_fixes.clear();
            }
            ("plan", None) => {
                project = Some(Project {
                    plan: name.clone(),
                    metres_per_pixel: None,
                    scale_bar_metres: None,
                    thin_lines: None,
                    hatching: None,
                    one_building: None,
                    trim_ink: None,
                    ink: None,
                    ink_strokes: vec![],
                    seed: None,
                    scale_line: None,
                    site: None,
                    label_fixes: vec![],
                    tower_fixes: vec![],
                    merges: vec![],
                    structure_fixes: vec![],
                    facades: vec![],
                    gothics: vec![],
                    correspondences: vec![],
                    textures: vec![],
                })
            }
            (_, None) => {
                return Err(ApiError(
                    StatusCode::CONFLICT,
                    "upload the plan drawing before the façade photos".into(),
                ));
            }
            ("gothic", Some(p)) => {
                // A Gothic façade photo (ch. 4): its elements are found and corrected in the
                // Gothic step (serve/gothic.rs).
                if !p.gothics.iter().any(|g| g.image == name) {
                    p.gothics.push(GothicEntry {
                        image: name.clone(),
                        bbox: None,
                        lines: None,
                        rectified: false,
                        elements: vec![],
                    });
                }
            }
            (_, Some(p)) => {
                if !p.facades.iter().any(|f| f.image == name) {
                    let training = format!("{}.training.json", safe_stem(&name));
                    if app.store.existing(&training).ok().flatten().is_none() {
                        files.push((training.clone(), br#"{"classes": {}}"#.to_vec()));
                    }
                    p.facades.push(FacadeEntry {
                        image: name.clone(),
                        training: TrainingSource::File(training),
                        lines: None,
                        rectified: false,
                        bbox: None,
                        metres_per_pixel: None,
                        fix: Default::default(),
                    });
                }
            }
        }
        app.store
            .commit(project.as_ref(), files)
            .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
        versioned(
            &app.store,
            json!({
                "name": name, "kind": kind, "width": width, "height": height,
                "url": file_url(&name),
            }),
        )
    })
    .await
}

fn multipart_error(app: &App, e: axum::extract::multipart::MultipartError) -> ApiError {
    let status = e.status();
    if status == StatusCode::PAYLOAD_TOO_LARGE {
        ApiError(
            status,
            format!(
                "the upload is larger than the limit of {} MB",
                app.max_upload >> 20
            ),
        )
    } else {
        ApiError(status, format!("not a valid upload: {}", e.body_text()))
    }
}

/// Decodes the upload with every image read's bounds (`images::decode`: the pixel budget
/// checked from the header before any pixel is decoded) to prove it is an image. An image over
/// the budget is 413, anything that does not decode 415.
fn check_image(name: &str, bytes: &[u8]) -> Result<(image::ImageFormat, u32, u32), ApiError> {
    let (img, format) = crate::images::decode(bytes, name).map_err(|e| {
        let status = if e.is::<crate::images::OverBudget>() {
            StatusCode::PAYLOAD_TOO_LARGE
        } else {
            StatusCode::UNSUPPORTED_MEDIA_TYPE
        };
        ApiError(status, format!("{e:#}"))
    })?;
    Ok((format, img.width(), img.height()))
}

/// GET /files/{*path}: a file inside the project folder.
pub async fn file(State(app): State<Arc<App>>, Path(name): Path<String>) -> Response {
    let found = match app.store.existing(&name) {
        Err(e) => return ApiError(StatusCode::FORBIDDEN, format!("{e:#}")).into_response(),
        Ok(None) => {
            return ApiError(
                StatusCode::NOT_FOUND,
                format!("no file \"{name}\" in the project"),
            )
            .into_response();
        }
        Ok(Some(path)) => path,
    };
    match tokio::fs::read(&found).await {
        Ok(bytes) => ([(header::CONTENT_TYPE, content_type(&name))], bytes).into_response(),
        Err(e) => {
            ApiError(StatusCode::INTERNAL_SERVER_ERROR, format!("{name}: {e}")).into_response()
        }
    }
}

fn content_type(name: &str) -> &'static str {
    let ext = std::path::Path::new(name)
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "png" => "image/png",
        "jpg" | "jpeg" => "image/jpeg",
        "html" => "text/html; charset=utf-8",
        "json" => "application/json",
        "svg" => "image/svg+xml",
        "glb" => "model/gltf-binary",
        "toml" | "vsg" | "obj" | "mtl" | "txt" => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}
