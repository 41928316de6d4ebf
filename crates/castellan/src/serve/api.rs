//! The HTTP API of `castellan serve` (docs/serve.md has the table), part 1: the server's state,
//! errors as JSON, the blocking runner holding the project's lock, the project's version (ETag,
//! If-Match), progress, uploads (decoded within the pixel budget, never overwriting a file) and
//! files confined to the project. The stages are in stages.rs.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

use axum::Json;
use axum::extract::{Multipart, Path, State};
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};
use integrate::project::{FacadeEntry, Project, TrainingSource};
use serde_json::{Value, json};

use super::guard::Access;
use super::store::{Store, upload_name};
use integrate::textures::safe_stem as stem;

/// The server's state: one project and what it is doing.
pub struct App {
    pub store: Store,
    pub max_upload: usize,
    /// The token and the addresses the server answers to (guard.rs).
    pub access: Access,
    progress: Mutex<Progress>,
    /// How long each step took last time, so the page can show how far along a step is.
    durations: Mutex<HashMap<String, u128>>,
}

/// What the page polls while a long step runs.
#[derive(Default, Clone, serde::Serialize)]
struct Progress {
    /// The step running now.
    running: Option<String>,
    #[serde(skip)]
    started: Option<Instant>,
    elapsed_ms: u128,
    /// The running step's duration last time it succeeded, if it ran before.
    expected_ms: Option<u128>,
    /// The last step that ended, with its outcome.
    last: Option<Value>,
}

impl App {
    pub fn new(store: Store, max_upload: usize, access: Access) -> Arc<App> {
        Arc::new(App {
            store,
            max_upload,
            access,
            progress: Mutex::new(Progress::default()),
            durations: Mutex::new(HashMap::new()),
        })
    }
}

/// An error answered as `{"error": message}` with a status.
pub struct ApiError(pub StatusCode, pub String);

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        (self.0, Json(json!({ "error": self.1 }))).into_response()
    }
}

pub(super) fn err(status: StatusCode) -> impl Fn(anyhow::Error) -> ApiError {
    move |e| ApiError(status, format!("{e:#}"))
}

pub(super) type Reply = Result<Json<Value>, ApiError>;

/// An answer carrying the project's version after the request (its `ETag`), so the page can
/// send it back as `If-Match` with its next change.
pub struct Versioned(pub Value, pub String);

impl IntoResponse for Versioned {
    fn into_response(self) -> Response {
        ([(header::ETAG, self.1)], Json(self.0)).into_response()
    }
}

/// The answer of a request that reads or changes the project's saved state.
pub(super) type Saved = Result<Versioned, ApiError>;

/// The If-Match header of a request, if any.
pub(super) fn if_match(headers: &HeaderMap) -> Option<String> {
    headers
        .get(header::IF_MATCH)
        .map(|v| String::from_utf8_lossy(v.as_bytes()).into_owned())
}

/// Refuses (412) a change made against another version of the project than the saved one: two
/// tabs, or a tab and an editor, would otherwise each overwrite the other's work unseen. Call
/// it holding the lock, before changing anything; no If-Match means no check (scripts, curl).
pub(super) fn check_version(store: &Store, if_match: Option<&str>) -> Result<(), ApiError> {
    let Some(wanted) = if_match else {
        return Ok(());
    };
    let current = store.version();
    let matches = wanted
        .split(',')
        .map(str::trim)
        .any(|t| t == "*" || t.strip_prefix("W/").unwrap_or(t) == current);
    if matches {
        Ok(())
    } else {
        Err(ApiError(
            StatusCode::PRECONDITION_FAILED,
            "the project was changed since this page loaded it (in another tab or an editor); \
             reload the page to see the changes, then make yours again"
                .into(),
        ))
    }
}

/// `body` with the project's version, read under the lock the caller holds.
pub(super) fn versioned(store: &Store, body: Value) -> Saved {
    Ok(Versioned(body, store.version()))
}

/// Runs `work` on a blocking thread under the project lock, reporting it as step `step`.
pub(super) async fn blocking<T, F>(app: Arc<App>, step: &str, work: F) -> Result<T, ApiError>
where
    T: Send + 'static,
    F: FnOnce(&App) -> Result<T, ApiError> + Send + 'static,
{
    let step = step.to_string();
    let name = step.clone();
    tokio::task::spawn_blocking(move || {
        let _guard = app.store.lock();
        let set = |p: Progress| *app.progress.lock().unwrap_or_else(PoisonError::into_inner) = p;
        let t = Instant::now();
        let durations = || app.durations.lock().unwrap_or_else(PoisonError::into_inner);
        set(Progress {
            running: Some(step.clone()),
            started: Some(t),
            expected_ms: durations().get(&step).copied(),
            ..Default::default()
        });
        let result = work(&app);
        let ms = t.elapsed().as_millis();
        let outcome = match &result {
            Ok(_) => {
                durations().insert(step.clone(), ms);
                json!({ "step": step, "ok": true, "ms": ms })
            }
            Err(ApiError(_, m)) => json!({ "step": step, "ok": false, "error": m }),
        };
        set(Progress {
            last: Some(outcome),
            ..Default::default()
        });
        result
    })
    .await
    .map_err(|e| ApiError(StatusCode::INTERNAL_SERVER_ERROR, format!("{name}: {e}")))?
}

pub(super) fn file_url(name: &str) -> String {
    format!("/files/{name}")
}

pub(super) fn find_facade<'a>(p: &'a Project, name: &str) -> Result<&'a FacadeEntry, ApiError> {
    Ok(&p.facades[facade_index(p, name)?])
}

/// The position of the façade photo `name` among the project's [[facade]] entries.
pub(super) fn facade_index(p: &Project, name: &str) -> Result<usize, ApiError> {
    p.facades
        .iter()
        .position(|f| f.image == name)
        .ok_or_else(|| {
            ApiError(
                StatusCode::NOT_FOUND,
                format!("no façade \"{name}\" in the project"),
            )
        })
}

/// What an edit of one façade checks against: the project, a copy of the façade's entry and
/// its photo's size.
pub(super) fn facade_for_edit(
    store: &Store,
    name: &str,
) -> Result<(Project, FacadeEntry, (u32, u32)), ApiError> {
    let p = store.require().map_err(err(StatusCode::CONFLICT))?;
    let f = find_facade(&p, name)?.clone();
    let path = store.path(&f.image).map_err(err(StatusCode::CONFLICT))?;
    // The header only; a photo over the pixel budget could not be worked on anyway.
    let size = image::image_dimensions(&path)
        .map_err(|e| ApiError(StatusCode::CONFLICT, format!("{name}: {e}")))?;
    crate::images::check_budget(size.0, size.1, name)
        .map_err(|e| ApiError(StatusCode::UNPROCESSABLE_ENTITY, format!("{e:#}")))?;
    Ok((p, f, size))
}

/// GET /api/project
pub async fn project(State(app): State<Arc<App>>) -> Saved {
    blocking(app, "project", |app| {
        let p = app.store.load().map_err(err(StatusCode::CONFLICT))?;
        let cleaning = match &p {
            Some(p) => Some(super::clean::load(app, p)?),
            None => None,
        };
        // The boxes of each façade; one that cannot be read shows no boxes and says why (the
        // façade stage refuses it with the same message).
        let mut training = serde_json::Map::new();
        let mut problems = Vec::new();
        for f in p.iter().flat_map(|p| &p.facades) {
            let t = integrate::pipeline::training(f, &app.store).unwrap_or_else(|e| {
                problems.push(format!("[[facade]] image = \"{}\": {e}", f.image));
                facade::classify::Training {
                    classes: Default::default(),
                }
            });
            training.insert(f.image.clone(), serde_json::to_value(t).unwrap_or_default());
        }
        let model = app
            .store
            .existing("out/model.glb")
            .ok()
            .flatten()
            .map(|_| super::stages::outputs());
        versioned(
            &app.store,
            json!({
                "dir": app.store.dir.display().to_string(),
                "project": p,
                "training": training,
                "problems": problems,
                "cleaning": cleaning,
                "outputs": model,
            }),
        )
    })
    .await
}

/// GET /api/progress
pub async fn progress(State(app): State<Arc<App>>) -> Json<Value> {
    let mut p = app
        .progress
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .clone();
    p.elapsed_ms = p.started.map(|t| t.elapsed().as_millis()).unwrap_or(0);
    Json(serde_json::to_value(p).unwrap_or_default())
}

/// POST /api/upload: multipart fields `kind` (`plan` or `facade`) and `file`.
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
    let kind = kind.ok_or_else(|| bad("the upload has no `kind` field (plan or facade)"))?;
    if kind != "plan" && kind != "facade" {
        return Err(bad("`kind` must be plan or facade"));
    }
    let (client_name, bytes) = file.ok_or_else(|| bad("the upload has no `file` field"))?;
    blocking(app, "upload", move |app| {
        check_version(&app.store, if_match.as_deref())?;
        let (format, width, height) = check_image(&client_name, &bytes)?;
        // Never over an existing file: a photo's boxes describe that photo, and a façade
        // called like the plan must not replace the drawing.
        let name = app
            .store
            .fresh_name(&upload_name(&client_name, format), kind == "facade")
            .map_err(err(StatusCode::CONFLICT))?;
        let mut project = app.store.load().map_err(err(StatusCode::CONFLICT))?;
        let mut files = vec![(name.clone(), bytes.to_vec())];
        if kind == "plan" {
            // A new drawing starts a new cleaning (the old one's strokes belong to the old drawing).
            files.push(super::clean::fresh(&name));
        }
        match (kind.as_str(), project.as_mut()) {
            ("plan", Some(p)) => p.plan = name.clone(),
            ("plan", None) => {
                project = Some(Project {
                    plan: name.clone(),
                    metres_per_pixel: None,
                    scale_bar_metres: None,
                    thin_lines: None,
                    hatching: None,
                    seed: None,
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
            (_, Some(p)) => {
                if !p.facades.iter().any(|f| f.image == name) {
                    let training = format!("{}.training.json", stem(&name));
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
