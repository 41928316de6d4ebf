//! The user's rectification segments in `castellan serve` (§3.1.1, the manual override): the
//! page drags the detected segments' endpoints, adds or removes segments, and saves them as the
//! façade's LINES.json (`lines` of its [[facade]]), which rectification then uses instead.

use std::sync::Arc;

use axum::Json;
use axum::extract::{Path, State};
use axum::http::{HeaderMap, StatusCode};
use facade::rectify::{ManualLines, RectifyParams, Segment, rectify_with_lines};
use serde_json::{Value, json};

use super::api::{
    ApiError, App, Saved, blocking, check_version, err, facade_for_edit, file_url, find_facade,
    if_match, versioned,
};
use integrate::textures::safe_stem as stem;

/// Most segments per family one LINES.json may hold.
pub const MAX_SEGMENTS: usize = 2000;

/// Segments as LINES.json writes them, `[x0, y0, x1, y1]`.
pub fn as_json(segments: &[Segment]) -> Vec<[f64; 4]> {
    let round = |v: f64| (v * 100.0).round() / 100.0;
    segments
        .iter()
        .map(|s| [round(s.x0), round(s.y0), round(s.x1), round(s.y1)])
        .collect()
}

/// Refuses segments the rectification cannot use, with its own message, before they are saved.
pub fn check(lines: &ManualLines, width: u32, height: u32) -> Result<(), String> {
    for (name, family) in [
        ("horizontal", &lines.horizontal),
        ("vertical", &lines.vertical),
    ] {
        if family.len() > MAX_SEGMENTS {
            return Err(format!(
                "{} {name} segments, more than the limit of {MAX_SEGMENTS}",
                family.len()
            ));
        }
    }
    rectify_with_lines(width, height, lines, &RectifyParams::default())
        .map(|_| ())
        .map_err(|e| e.to_string())
}

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
        check(&lines, w, h)
            .map_err(|m| ApiError(StatusCode::BAD_REQUEST, format!("{name}: {m}")))?;
        let file = f
            .lines
            .clone()
            .unwrap_or_else(|| format!("{}.lines.json", stem(&f.image)));
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

#[cfg(test)]
mod tests {
    use super::*;

    fn square_lines() -> ManualLines {
        ManualLines {
            horizontal: vec![[10.0, 10.0, 90.0, 10.0], [10.0, 90.0, 90.0, 90.0]],
            vertical: vec![[10.0, 10.0, 10.0, 90.0], [90.0, 10.0, 90.0, 90.0]],
        }
    }

    #[test]
    fn usable_segments_pass_and_the_rectification_says_why_others_fail() {
        assert_eq!(check(&square_lines(), 100, 100), Ok(()));
        let mut one = square_lines();
        one.vertical.pop();
        let e = check(&one, 100, 100).unwrap_err();
        assert!(e.contains("two vertical"), "{e}");
        let mut dot = square_lines();
        dot.horizontal[0] = [5.0, 5.0, 5.0, 5.0];
        assert!(
            check(&dot, 100, 100)
                .unwrap_err()
                .contains("non-zero length")
        );
        let mut many = square_lines();
        many.horizontal = vec![[0.0, 0.0, 10.0, 0.0]; MAX_SEGMENTS + 1];
        assert!(check(&many, 100, 100).unwrap_err().contains("limit"));
    }

    #[test]
    fn segments_are_written_to_a_hundredth_of_a_pixel() {
        let s = Segment::new(1.234_56, 2.0, 3.005_1, 4.999_9);
        assert_eq!(as_json(&[s]), vec![[1.23, 2.0, 3.01, 5.0]]);
    }
}
