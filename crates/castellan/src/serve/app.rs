//! What the HTTP handlers of `castellan serve` share (docs/serve.md has the routes): the
//! server's state, errors as JSON, the blocking runner holding the project's lock and reporting
//! progress, the project's version (ETag, If-Match), file URLs, façade lookups, the saved plan
//! cleaning and the list of a reconstruction's outputs. The handlers are in project.rs,
//! stages.rs, clean.rs and lines.rs.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

use axum::Json;
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};
use image::GrayImage;
use integrate::pipeline::{self, Files};
use integrate::project::{FacadeEntry, Project};
use plan::ParsedPlan;
use plan::clean::Cleaning;
use serde_json::{Value, json};

use super::access::Access;
use super::store::{CLEANING_FILE, Store};

/// The server's state: one project and what it is doing.
pub struct App {
    pub store: Store,
    pub max_upload: usize,
    /// The token and the addresses the server answers to (access.rs, checked by guard.rs).
    pub access: Access,
    /// The seed and classifier of every stage run (`castellan serve --classifier`).
    pub options: integrate::pipeline::Options,
    progress: Mutex<Progress>,
    /// How long each step took last time, so the page can show how far along a step is.
    durations: Mutex<HashMap<String, u128>>,
    /// The plan as last parsed, before the user's corrections (issue 22).
    kept_parse: Mutex<Option<KeptParse>>,
}

/// The plan as §5.1.2–5.1.6 last parsed it, before the user's corrections, and a hash of what
/// it was parsed from (the drawing's bytes and the plan options): a correction redraws the
/// overlay from it at once instead of parsing again.
struct KeptParse {
    key: u64,
    parsed: ParsedPlan,
    grey: GrayImage,
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
    pub fn new(
        store: Store,
        max_upload: usize,
        access: Access,
        classifier: facade::classify::Method,
    ) -> Arc<App> {
        Arc::new(App {
            store,
            max_upload,
            access,
            options: integrate::pipeline::Options {
                seed: None,
                classifier,
            },
            progress: Mutex::new(Progress::default()),
            durations: Mutex::new(HashMap::new()),
            kept_parse: Mutex::new(None),
        })
    }

    /// What GET /api/progress answers: the running step with the time it has taken so far,
    /// and the last step that ended.
    pub(super) fn progress_now(&self) -> Value {
        let mut p = self
            .progress
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone();
        p.elapsed_ms = p.started.map(|t| t.elapsed().as_millis()).unwrap_or(0);
        serde_json::to_value(p).unwrap_or_default()
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

/// The project's plan parsed (§5.1.2–5.1.6), before the user's corrections: kept from the last
/// parse when neither the drawing nor the plan options changed since.
pub(super) fn parsed_plan(app: &App, p: &Project) -> Result<(ParsedPlan, GrayImage), ApiError> {
    use std::hash::{Hash, Hasher};
    let path = app.store.path(&p.plan).map_err(err(StatusCode::CONFLICT))?;
    let bytes = std::fs::read(&path)
        .map_err(|e| ApiError(StatusCode::CONFLICT, format!("plan = \"{}\": {e}", p.plan)))?;
    let mut h = std::hash::DefaultHasher::new();
    bytes.hash(&mut h);
    format!(
        "{:?} {:?} {:?} {:?} {:?} {:?} {:?}",
        p.thin_lines, p.hatching, p.one_building, p.trim_ink, p.ink, p.ink_strokes, p.seed
    )
    .hash(&mut h);
    let key = h.finish();
    let mut kept = app
        .kept_parse
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    if let Some(k) = kept.as_ref().filter(|k| k.key == key) {
        return Ok((k.parsed.clone(), k.grey.clone()));
    }
    let image = app
        .store
        .image(&p.plan)
        .map_err(|e| ApiError(StatusCode::CONFLICT, e))?;
    let parsed = plan::parse(&image, &p.plan_options()).map_err(|e| {
        ApiError(
            StatusCode::UNPROCESSABLE_ENTITY,
            format!("plan = \"{}\": {e}", p.plan),
        )
    })?;
    let grey = image.to_luma8();
    *kept = Some(KeptParse {
        key,
        parsed: parsed.clone(),
        grey: grey.clone(),
    });
    Ok((parsed, grey))
}

/// The plan stage as `reconstruct` makes it: the parse (kept when unchanged) with the user's
/// corrections, and its overlays.
pub(super) fn plan_stage(app: &App, p: &Project) -> Result<pipeline::PlanStage, ApiError> {
    let (parsed, grey) = parsed_plan(app, p)?;
    pipeline::corrected_stage(p, parsed, &grey, p.ink.unwrap_or_default())
        .map_err(|e| ApiError(StatusCode::UNPROCESSABLE_ENTITY, e.to_string()))
}

/// Writes one output file of a stage into the project.
pub(super) fn save(app: &App, name: &str, bytes: Vec<u8>) -> Result<(), ApiError> {
    app.store
        .commit(None, vec![(name.to_string(), bytes)])
        .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))
}

/// Writes a pipeline overlay under out/, as `reconstruct` does; returns its project name.
pub(super) fn write_overlay(app: &App, overlay: &pipeline::Overlay) -> Result<String, ApiError> {
    let name = format!("out/{}", overlay.name);
    let bytes = overlay
        .picture
        .png()
        .map_err(|e| ApiError(StatusCode::INTERNAL_SERVER_ERROR, format!("{name}: {e}")))?;
    save(app, &name, bytes)?;
    Ok(name)
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

/// The saved cleaning, or none yet: the project's plan is then the original.
pub(super) fn load_cleaning(app: &App, p: &Project) -> Result<Cleaning, ApiError> {
    match app
        .store
        .existing(CLEANING_FILE)
        .map_err(err(StatusCode::CONFLICT))?
    {
        None => Ok(Cleaning {
            original: p.plan.clone(),
            strokes: vec![],
        }),
        Some(path) => {
            crate::text::read_json(&path, "a plan_cleaning.json").map_err(err(StatusCode::CONFLICT))
        }
    }
}

/// plan_cleaning.json for a newly uploaded drawing: nothing painted yet.
pub(super) fn fresh_cleaning(original: &str) -> (String, Vec<u8>) {
    let c = Cleaning {
        original: original.to_string(),
        strokes: vec![],
    };
    (
        CLEANING_FILE.to_string(),
        serde_json::to_vec_pretty(&c).unwrap_or_default(),
    )
}

/// The files of a reconstruction, as URLs (the answers of /api/reconstruct and /api/project).
pub(super) fn outputs() -> Value {
    json!({
        "report": file_url("out/index.html"), "glb": file_url("out/model.glb"),
        "obj": file_url("out/model.obj"), "vsg": file_url("out/model.vsg"),
        "cityjson": file_url("out/model.city.json"), "ifc": file_url("out/model.ifc"),
        "json": file_url("out/estimate.json"), "stats": file_url("out/stats.json"),
    })
}
