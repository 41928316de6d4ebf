//! The Gothic step of `castellan serve` (ch. 4, issue 22): a `[[gothic]]` photo's elements
//! found and shown with their handles, and the user's corrections (`[[gothic.element]]`:
//! delete, or move the springing line, apex, width) saved to PROJECT.toml. Detection (§4.2,
//! the slow half) is kept in memory per photo, so a correction re-runs only the grouping,
//! enclosing arches and nesting.

use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

use axum::Json;
use axum::extract::{Path, State};
use axum::http::{HeaderMap, StatusCode};
use facade::gothic::corrections::Handles;
use facade::gothic::{Applied, CorrectedEstimate, Detection, ElementCorrection};
use integrate::gothic::{GothicCutout, GothicPhoto};
use integrate::project::{GothicEntry, Project, gothic_element_entry};
use integrate::textures::safe_stem;
use serde::Deserialize;
use serde_json::{Value, json};

use super::app::{
    ApiError, App, Saved, blocking, check_version, err, file_url, if_match, versioned,
};
use crate::images::png;

/// What detection depends on: the photo's bytes and how it is rectified and cut.
#[derive(PartialEq)]
struct Key {
    dir: std::path::PathBuf,
    image: String,
    photo: u64,
    lines: Option<u64>,
    bbox: Option<[u64; 4]>,
    rectified: bool,
}

/// The last photo detected (one is enough: the user works on one photo at a time).
struct Cached {
    key: Key,
    cutout: Arc<GothicCutout>,
    detection: Arc<Detection>,
}

/// Shared by every server of the process (tests run several): keyed by the project folder.
static LAST: Mutex<Option<Cached>> = Mutex::new(None);

fn hash(bytes: &[u8]) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::hash::DefaultHasher::new();
    bytes.hash(&mut h);
    h.finish()
}

fn entry_index(p: &Project, name: &str) -> Result<usize, ApiError> {
    p.gothics
        .iter()
        .position(|g| g.image == name)
        .ok_or_else(|| {
            ApiError(
                StatusCode::NOT_FOUND,
                format!("no Gothic photo \"{name}\" in the project"),
            )
        })
}

fn read(app: &App, name: &str) -> Result<Vec<u8>, ApiError> {
    let path = app.store.path(name).map_err(err(StatusCode::CONFLICT))?;
    std::fs::read(&path).map_err(|e| ApiError(StatusCode::CONFLICT, format!("{name}: {e}")))
}

/// The photo rectified and cut to its façade, and its detected elements: from memory when
/// nothing they depend on changed. The bool says whether detection ran now.
fn detected(
    app: &App,
    g: &GothicEntry,
) -> Result<(Arc<GothicCutout>, Arc<Detection>, bool), ApiError> {
    let bytes = read(app, &g.image)?;
    let lines_bytes = g.lines.as_deref().map(|l| read(app, l)).transpose()?;
    let key = Key {
        dir: app.store.dir.clone(),
        image: g.image.clone(),
        photo: hash(&bytes),
        lines: lines_bytes.as_deref().map(hash),
        bbox: g.bbox.map(|b| b.map(f64::to_bits)),
        rectified: g.rectified,
    };
    if let Some(c) = LAST
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .as_ref()
        .filter(|c| c.key == key)
    {
        return Ok((c.cutout.clone(), c.detection.clone(), false));
    }
    let unprocessable = |e: String| ApiError(StatusCode::UNPROCESSABLE_ENTITY, e);
    let photo = crate::images::decode(&bytes, &g.image)
        .map_err(|e| unprocessable(format!("{e:#}")))?
        .0
        .to_rgb8();
    let lines = match (&g.lines, &lines_bytes) {
        (Some(name), Some(b)) => Some(
            serde_json::from_slice::<facade::rectify::ManualLines>(b)
                .map_err(|e| ApiError(StatusCode::CONFLICT, format!("{name}: {e}")))?,
        ),
        _ => None,
    };
    let gp = GothicPhoto {
        name: &g.image,
        image: &photo,
        bbox: g.bbox,
        lines: lines.as_ref(),
        rectified: g.rectified,
        corrections: &[],
    };
    let cutout = integrate::gothic::cut_out(&gp).map_err(|e| unprocessable(e.to_string()))?;
    let detection =
        integrate::gothic::detect(&g.image, &cutout).map_err(|e| unprocessable(e.to_string()))?;
    let (cutout, detection) = (Arc::new(cutout), Arc::new(detection));
    *LAST.lock().unwrap_or_else(PoisonError::into_inner) = Some(Cached {
        key,
        cutout: cutout.clone(),
        detection: detection.clone(),
    });
    Ok((cutout, detection, true))
}

/// One element as the page draws it: handles in rectified photo pixels, the correction that
/// set it (its index in `[[gothic.element]]`) if any.
fn element_json(e: &facade::gothic::Element, origin: [f64; 2], applied: &[Applied]) -> Value {
    let h = Handles::of(&e.theta());
    let correction = applied
        .iter()
        .find(|a| a.element == Some(e.id))
        .map(|a| a.correction);
    json!({
        "id": e.id, "kind": e.kind, "parent": e.parent, "group": e.group, "depth": e.depth,
        "springing": h.springing + origin[1], "apex": h.apex + origin[1],
        "width": h.width, "centre": h.centre + origin[0], "sill": h.sill + origin[1],
        "correction": correction,
    })
}

/// Runs the Gothic step for entry `index` of `p` with `corrections` (rectified pixels): the
/// estimate, its overlay written, the answer's body.
fn run(
    app: &App,
    p: &Project,
    index: usize,
    corrections: &[ElementCorrection],
) -> Result<Value, ApiError> {
    let g = &p.gothics[index];
    let t = Instant::now();
    let (cutout, detection, ran) = detected(app, g)?;
    let detect_ms = t.elapsed().as_millis();
    let origin = [cutout.bbox[0], cutout.bbox[1]];
    let CorrectedEstimate {
        estimate: est,
        applied,
        dropped,
    } = integrate::gothic::organise(&detection, corrections, origin).map_err(|e| {
        ApiError(
            StatusCode::UNPROCESSABLE_ENTITY,
            format!(
                "{}: {}",
                gothic_element_entry(index, e.index, &g.image),
                e.problem
            ),
        )
    })?;
    let stem = safe_stem(&g.image);
    let facade_file = format!("out/{stem}_gothic_facade.png");
    let overlay_file = format!("out/overlays/{stem}_gothic.png");
    let mut files = vec![(
        overlay_file.clone(),
        encode(
            &facade::gothic::draw::overlay(&cutout.facade, &est, None),
            &overlay_file,
        )?,
    )];
    if ran || app.store.existing(&facade_file).ok().flatten().is_none() {
        files.push((facade_file.clone(), encode(&cutout.facade, &facade_file)?));
    }
    app.store
        .commit(None, files)
        .map_err(err(StatusCode::INTERNAL_SERVER_ERROR))?;
    let deleted: Vec<Value> = applied
        .iter()
        .filter(|a| a.element.is_none())
        .map(|a| json!({ "correction": a.correction }))
        .collect();
    Ok(json!({
        "image": file_url(&facade_file), "overlay": file_url(&overlay_file),
        "offset": origin, "width": est.width, "height": est.height,
        "elements": est.elements.iter().map(|e| element_json(e, origin, &applied)).collect::<Vec<_>>(),
        "groups": est.groups.len(),
        // Elements the learned check took out as unlike openings (issue 23).
        "dropped": dropped,
        "deleted": deleted,
        "corrections": corrections,
        "rectified": g.rectified,
        "detected_now": ran,
        "detect_ms": detect_ms,
        "ms": t.elapsed().as_millis(),
    }))
}

fn encode(img: &image::RgbImage, name: &str) -> Result<Vec<u8>, ApiError> {
    png(img, std::path::Path::new(name)).map_err(err(StatusCode::INTERNAL_SERVER_ERROR))
}

/// POST /api/gothic/{image}'s optional body.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct RunOptions {
    /// The photo is an elevation already (saved as the entry's `rectified`).
    rectified: Option<bool>,
}

/// POST /api/gothic/{image}: ch. 4 on the photo with its saved corrections → the elements with
/// their handles and the overlay. The body is optional (empty: change nothing).
pub async fn estimate(
    State(app): State<Arc<App>>,
    Path(name): Path<String>,
    headers: HeaderMap,
    body: axum::body::Bytes,
) -> Saved {
    let if_match = if_match(&headers);
    let options: RunOptions = if body.iter().all(u8::is_ascii_whitespace) {
        RunOptions::default()
    } else {
        serde_json::from_slice(&body)
            .map_err(|e| ApiError(StatusCode::BAD_REQUEST, format!("the body: {e}")))?
    };
    blocking(app, "gothic", move |app| {
        let mut p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let index = entry_index(&p, &name)?;
        if let Some(r) = options.rectified
            && r != p.gothics[index].rectified
        {
            check_version(&app.store, if_match.as_deref())?;
            p.gothics[index].rectified = r;
            app.store
                .commit(Some(&p), vec![])
                .map_err(err(StatusCode::BAD_REQUEST))?;
        }
        let corrections = p.gothics[index].elements.clone();
        let body = run(app, &p, index, &corrections)?;
        versioned(&app.store, body)
    })
    .await
}

/// PUT /api/gothic/{image}/elements: the whole list of corrections (rectified pixels),
/// checked by applying it, then saved as the entry's `[[gothic.element]]`.
pub async fn save_elements(
    State(app): State<Arc<App>>,
    Path(name): Path<String>,
    headers: HeaderMap,
    Json(corrections): Json<Vec<ElementCorrection>>,
) -> Saved {
    let if_match = if_match(&headers);
    blocking(app, "gothic corrections", move |app| {
        let mut p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        check_version(&app.store, if_match.as_deref())?;
        let index = entry_index(&p, &name)?;
        for (j, c) in corrections.iter().enumerate() {
            c.action().map_err(|why| {
                ApiError(
                    StatusCode::BAD_REQUEST,
                    format!("{}: {why}", gothic_element_entry(index, j, &name)),
                )
            })?;
        }
        // Applied before anything is saved: a list that cannot apply is refused whole.
        let body = run(app, &p, index, &corrections)?;
        p.gothics[index].elements = corrections;
        app.store
            .commit(Some(&p), vec![])
            .map_err(err(StatusCode::BAD_REQUEST))?;
        versioned(&app.store, body)
    })
    .await
}
