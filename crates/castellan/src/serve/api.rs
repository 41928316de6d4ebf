//! The HTTP API of `castellan serve` (docs/serve.md has the table): uploads, each pipeline stage
//! with its overlay (plan ch. 5, rectification §3.1.1, façade search §3.1.2–3.1.7), training
//! boxes and correspondences (§6.1.1) saved to the project, and the whole reconstruction.
//! Pipeline work runs on a blocking thread holding the project's lock.

use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

use axum::Json;
use axum::extract::{Multipart, Path, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use facade::classify::Training;
use integrate::project::{Correspondence, FacadeEntry, Project, TrainingSource};
use serde_json::{Value, json};

use super::store::{Store, upload_name};
use crate::images::{MAX_ALLOC, MAX_SIDE, png, read_image};
use crate::reconstruct_cmd::stem;

/// The server's state: one project and what it is doing.
pub struct App {
    pub store: Store,
    pub max_upload: usize,
    progress: Mutex<Progress>,
}

/// What the page polls while a long step runs.
#[derive(Default, Clone, serde::Serialize)]
struct Progress {
    /// The step running now.
    running: Option<String>,
    #[serde(skip)]
    started: Option<Instant>,
    elapsed_ms: u128,
    /// The last step that ended, with its outcome.
    last: Option<Value>,
}

impl App {
    pub fn new(store: Store, max_upload: usize) -> Arc<App> {
        Arc::new(App {
            store,
            max_upload,
            progress: Mutex::new(Progress::default()),
        })
    }
}

/// An error answered as `{"error": message}` with a status.
pub struct ApiError(StatusCode, String);

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        (self.0, Json(json!({ "error": self.1 }))).into_response()
    }
}

fn err(status: StatusCode) -> impl Fn(anyhow::Error) -> ApiError {
    move |e| ApiError(status, format!("{e:#}"))
}

type Reply = Result<Json<Value>, ApiError>;

/// Runs `work` on a blocking thread under the project lock, reporting it as step `step`.
async fn blocking<T, F>(app: Arc<App>, step: &str, work: F) -> Result<T, ApiError>
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
        set(Progress {
            running: Some(step.clone()),
            started: Some(t),
            ..Default::default()
        });
        let result = work(&app);
        let outcome = match &result {
            Ok(_) => json!({ "step": step, "ok": true, "ms": t.elapsed().as_millis() }),
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

fn file_url(name: &str) -> String {
    format!("/files/{name}")
}

fn find_facade<'a>(p: &'a Project, name: &str) -> Result<&'a FacadeEntry, ApiError> {
    p.facades.iter().find(|f| f.image == name).ok_or_else(|| {
        ApiError(
            StatusCode::NOT_FOUND,
            format!("no façade \"{name}\" in the project"),
        )
    })
}

/// GET /api/project
pub async fn project(State(app): State<Arc<App>>) -> Reply {
    blocking(app, "project", |app| {
        let p = app.store.load().map_err(err(StatusCode::CONFLICT))?;
        let mut training = serde_json::Map::new();
        for f in p.iter().flat_map(|p| &p.facades) {
            let t = app.store.training(f).map_err(err(StatusCode::CONFLICT))?;
            training.insert(f.image.clone(), serde_json::to_value(t).unwrap_or_default());
        }
        let model = app
            .store
            .existing("out/model.glb")
            .ok()
            .flatten()
            .map(|_| outputs());
        Ok(Json(json!({
            "dir": app.store.dir.display().to_string(),
            "project": p,
            "training": training,
            "outputs": model,
        })))
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
pub async fn upload(State(app): State<Arc<App>>, mut form: Multipart) -> Reply {
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
        let (format, width, height) = check_image(&client_name, &bytes)?;
        let name = upload_name(&client_name, format);
        let mut project = app.store.load().map_err(err(StatusCode::CONFLICT))?;
        let mut files = vec![(name.clone(), bytes.to_vec())];
        match (kind.as_str(), project.as_mut()) {
            ("plan", Some(p)) => p.plan = name.clone(),
            ("plan", None) => {
                project = Some(Project {
                    plan: name.clone(),
                    scale: None,
                    seed: None,
                    facades: vec![],
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
                    });
                }
            }
        }
        app.store
            .commit(project.as_ref(), files)
            .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
        Ok(Json(json!({
            "name": name, "kind": kind, "width": width, "height": height, "url": file_url(&name),
        })))
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

/// Decodes the upload (bounded like every image castellan reads) to prove it is an image.
fn check_image(name: &str, bytes: &[u8]) -> Result<(image::ImageFormat, u32, u32), ApiError> {
    let unsupported = |m: String| ApiError(StatusCode::UNSUPPORTED_MEDIA_TYPE, m);
    let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| unsupported(format!("{name}: {e}")))?;
    let format = reader.format().ok_or_else(|| {
        unsupported(format!(
            "{name}: not an image castellan reads (PNG, JPEG or PNM)"
        ))
    })?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_SIDE);
    limits.max_image_height = Some(MAX_SIDE);
    limits.max_alloc = Some(MAX_ALLOC);
    reader.limits(limits);
    let img = reader
        .decode()
        .map_err(|e| unsupported(format!("{name}: not a readable image ({e})")))?;
    Ok((format, img.width(), img.height()))
}

fn write_png<P, C>(app: &App, name: &str, img: &image::ImageBuffer<P, C>) -> Result<(), ApiError>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    let bytes = png(img, std::path::Path::new(name)).map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
    app.store
        .commit(None, vec![(name.to_string(), bytes)])
        .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))
}

/// POST /api/plan: the plan stage (ch. 5) → label overlay.
pub async fn plan(State(app): State<Arc<App>>) -> Reply {
    blocking(app, "plan", |app| {
        let p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let t = Instant::now();
        let path = app.store.path(&p.plan).map_err(err(StatusCode::CONFLICT))?;
        let image = read_image(&path).map_err(err(StatusCode::UNPROCESSABLE_ENTITY))?;
        let parsed = plan::parse(&image, &plan::Options::default()).map_err(|e| {
            ApiError(StatusCode::UNPROCESSABLE_ENTITY, format!("{}: {e}", p.plan))
        })?;
        let overlay = "out/overlays/plan_labels.png";
        write_png(app, overlay, &plan::output::overlay(&parsed, &image.to_luma8()))?;
        Ok(Json(json!({
            "overlay": file_url(overlay),
            "width": parsed.width, "height": parsed.height,
            "faces": parsed.faces.len(), "edges": parsed.edges.len(),
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
        let path = app.store.path(&f.image).map_err(err(StatusCode::CONFLICT))?;
        let img = read_image(&path)
            .map_err(err(StatusCode::UNPROCESSABLE_ENTITY))?
            .to_rgb8();
        let params = facade::rectify::RectifyParams::default();
        let failed = |e: facade::FacadeError| {
            ApiError(StatusCode::UNPROCESSABLE_ENTITY, format!("{name}: rectification (§3.1.1): {e}"))
        };
        let r = match &f.lines {
            Some(lines) => {
                let lp = app.store.path(lines).map_err(err(StatusCode::CONFLICT))?;
                let text = std::fs::read_to_string(&lp)
                    .map_err(|e| ApiError(StatusCode::CONFLICT, format!("{lines}: {e}")))?;
                let manual = serde_json::from_str(&text)
                    .map_err(|e| ApiError(StatusCode::CONFLICT, format!("{lines}: {e}")))?;
                facade::rectify::rectify_with_lines(img.width(), img.height(), &manual, &params)
                    .map_err(failed)?
            }
            None => facade::rectify::rectify(&img, &params).map_err(failed)?,
        };
        let warped = r.warp(&img).map_err(failed)?;
        let s = stem(&f.image);
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
            "ms": t.elapsed().as_millis(),
        })))
    })
    .await
}

/// PUT /api/facades/{name}/training: the user's boxes (TRAINING.json, photo pixels).
pub async fn training(
    State(app): State<Arc<App>>,
    Path(name): Path<String>,
    Json(training): Json<Training>,
) -> Reply {
    blocking(app, "training", move |app| {
        let mut p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let f = find_facade(&p, &name)?;
        let path = app.store.path(&f.image).map_err(err(StatusCode::CONFLICT))?;
        let (w, h) = image::image_dimensions(&path)
            .map_err(|e| ApiError(StatusCode::CONFLICT, format!("{name}: {e}")))?;
        // An empty set is a valid state to save (the user clears the boxes); otherwise check.
        if training.classes.values().any(|b| !b.is_empty()) {
            training
                .boxes(w as usize, h as usize)
                .map_err(|e| ApiError(StatusCode::BAD_REQUEST, format!("{name}: {e}")))?;
        }
        let file = match &f.training {
            TrainingSource::File(file) => file.clone(),
            TrainingSource::Inline(_) => format!("{}.training.json", stem(&f.image)),
        };
        for g in p.facades.iter_mut().filter(|g| g.image == name) {
            g.training = TrainingSource::File(file.clone());
        }
        let bytes = serde_json::to_vec_pretty(&training).unwrap_or_default();
        app.store
            .commit(Some(&p), vec![(file.clone(), bytes)])
            .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
        let boxes: usize = training.classes.values().map(Vec::len).sum();
        Ok(Json(json!({ "saved": file, "boxes": boxes })))
    })
    .await
}

/// POST /api/facades/{name}/facade: ch. 3 on one photo → the façade tree over the rectified photo.
pub async fn facade_stage(State(app): State<Arc<App>>, Path(name): Path<String>) -> Reply {
    blocking(app, "facade", move |app| {
        let p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let f = find_facade(&p, &name)?;
        let t = Instant::now();
        let path = app.store.path(&f.image).map_err(err(StatusCode::CONFLICT))?;
        let img = read_image(&path)
            .map_err(err(StatusCode::UNPROCESSABLE_ENTITY))?
            .to_rgb8();
        let training = app.store.training(f).map_err(err(StatusCode::CONFLICT))?;
        let lines = match &f.lines {
            Some(l) => {
                let lp = app.store.path(l).map_err(err(StatusCode::CONFLICT))?;
                let text = std::fs::read_to_string(&lp)
                    .map_err(|e| ApiError(StatusCode::CONFLICT, format!("{l}: {e}")))?;
                Some(
                    serde_json::from_str(&text)
                        .map_err(|e| ApiError(StatusCode::CONFLICT, format!("{l}: {e}")))?,
                )
            }
            None => None,
        };
        let e = integrate::photo::estimate_facade(&integrate::photo::FacadePhoto {
            name: &f.image,
            image: &img,
            training: &training,
            lines: lines.as_ref(),
            rectified: f.rectified,
            seed: p.seed.unwrap_or(0),
        })
        .map_err(|e| ApiError(StatusCode::UNPROCESSABLE_ENTITY, e.to_string()))?;
        let overlay = format!("out/overlays/{}_facade.png", stem(&f.image));
        write_png(
            app,
            &overlay,
            &crate::facade_cmd::label_overlay(&e.rectified, &e.model.labels()),
        )?;
        let floors: usize = e.model.facades.iter().map(|f| f.floors.len()).sum();
        let windows: usize = e
            .model
            .facades
            .iter()
            .flat_map(|f| &f.floors)
            .map(|fl| fl.windows.len())
            .sum();
        Ok(Json(json!({
            "overlay": file_url(&overlay), "facades": e.model.facades.len(),
            "floors": floors, "windows": windows, "ms": t.elapsed().as_millis(),
        })))
    })
    .await
}

/// PUT /api/correspondences: the whole list (§6.1.1), replacing the project's.
pub async fn correspondences(
    State(app): State<Arc<App>>,
    Json(list): Json<Vec<Correspondence>>,
) -> Reply {
    blocking(app, "correspondences", move |app| {
        let mut p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        p.correspondences = list;
        app.store
            .commit(Some(&p), vec![])
            .map_err(err(StatusCode::BAD_REQUEST))?;
        Ok(Json(json!({ "saved": p.correspondences.len() })))
    })
    .await
}

fn outputs() -> Value {
    json!({
        "report": file_url("out/index.html"), "glb": file_url("out/model.glb"),
        "obj": file_url("out/model.obj"), "vsg": file_url("out/model.vsg"),
        "json": file_url("out/estimate.json"), "stats": file_url("out/stats.json"),
    })
}

/// POST /api/reconstruct: `castellan reconstruct PROJECT.toml -o out`.
pub async fn reconstruct(State(app): State<Arc<App>>) -> Reply {
    blocking(app, "reconstruct", |app| {
        app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let s = crate::reconstruct_cmd::reconstruct(
            &app.store.dir.join(super::store::PROJECT_FILE),
            &app.store.dir.join("out"),
            None,
        )
        .map_err(err(StatusCode::UNPROCESSABLE_ENTITY))?;
        let stages: serde_json::Map<String, Value> =
            s.stages.iter().map(|(k, v)| (k.clone(), json!(v.round()))).collect();
        Ok(Json(json!({
            "outputs": outputs(),
            "structures": s.estimate.structures.len(),
            "terminals": s.terminals,
            "stages_ms": stages,
        })))
    })
    .await
}

/// GET /files/{*path}: a file inside the project folder.
pub async fn file(State(app): State<Arc<App>>, Path(name): Path<String>) -> Response {
    let found = match app.store.existing(&name) {
        Err(e) => return ApiError(StatusCode::FORBIDDEN, format!("{e:#}")).into_response(),
        Ok(None) => {
            return ApiError(StatusCode::NOT_FOUND, format!("no file \"{name}\" in the project"))
                .into_response();
        }
        Ok(Some(path)) => path,
    };
    match tokio::fs::read(&found).await {
        Ok(bytes) => ([(header::CONTENT_TYPE, content_type(&name))], bytes).into_response(),
        Err(e) => ApiError(StatusCode::INTERNAL_SERVER_ERROR, format!("{name}: {e}")).into_response(),
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
