//! Corrections in `castellan serve` (issue 22): the plan's region labels, towers and merged
//! regions (`plan::corrections`), the structures' heights, roofs, crenellation and keep
//! (`integrate::corrections`), the scale from two clicked points, and the plan settings — each
//! checked as `castellan reconstruct` checks it, then saved in PROJECT.toml by plan point, and
//! the labels overlay redrawn at once from the kept parse (no new parse for a relabel).

use std::sync::Arc;
use std::time::Instant;

use axum::Json;
use axum::extract::{Query, State};
use axum::http::{HeaderMap, StatusCode};
use integrate::corrections::{ScaleLine, StructureFix};
use integrate::estimate::Estimate;
use integrate::project::Project;
use plan::corrections::{LabelFix, MergeFix, TowerFix};
use serde::{Deserialize, Serialize};
use serde_json::json;

use super::app::{
    ApiError, App, Reply, Saved, blocking, check_version, err, file_url, if_match, parsed_plan,
    plan_stage, versioned, write_overlay,
};

/// Every correction of the project: the body of PUT /api/corrections and the answer of GET.
/// The keys are PROJECT.toml's.
#[derive(Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Corrections {
    #[serde(default)]
    pub label: Vec<LabelFix>,
    #[serde(default)]
    pub tower: Vec<TowerFix>,
    #[serde(default)]
    pub merge: Vec<MergeFix>,
    #[serde(default)]
    pub structure: Vec<StructureFix>,
    #[serde(default)]
    pub scale_line: Option<ScaleLine>,
}

/// At most this many corrections of each kind in one request (a request is bounded).
const MAX_CORRECTIONS: usize = 2000;

impl Corrections {
    fn of(p: &Project) -> Corrections {
        Corrections {
            label: p.label_fixes.clone(),
            tower: p.tower_fixes.clone(),
            merge: p.merges.clone(),
            structure: p.structure_fixes.clone(),
            scale_line: p.scale_line.clone(),
        }
    }

    fn set(self, p: &mut Project) {
        p.label_fixes = self.label;
        p.tower_fixes = self.tower;
        p.merges = self.merge;
        p.structure_fixes = self.structure;
        p.scale_line = self.scale_line;
    }
}

/// GET /api/corrections: the project's corrections.
pub async fn get(State(app): State<Arc<App>>) -> Saved {
    blocking(app, "corrections", |app| {
        let p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let mut out = json!(Corrections::of(&p));
        // The labels' names and colours (the overlay's legend; walls take no region label).
        out["labels"] = plan::label::Label::ALL
            .iter()
            .map(|l| json!({ "name": l.name(), "colour": l.color(), "region": !l.is_wall() }))
            .collect();
        versioned(&app.store, out)
    })
    .await
}

/// PUT /api/corrections: every correction at once (the page sends the whole list, so undo is
/// sending the previous one). Checked on the kept parse as `reconstruct` applies them — an
/// entry that cannot apply is refused (422) naming it, and nothing is saved — then saved, and
/// the labels overlay redrawn.
pub async fn put(
    State(app): State<Arc<App>>,
    headers: HeaderMap,
    Json(body): Json<Corrections>,
) -> Saved {
    let if_match = if_match(&headers);
    blocking(app, "corrections", move |app| {
        let t = Instant::now();
        let mut p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        check_version(&app.store, if_match.as_deref())?;
        let counts = [
            body.label.len(),
            body.tower.len(),
            body.merge.len(),
            body.structure.len(),
        ];
        if counts.iter().any(|&n| n > MAX_CORRECTIONS) {
            return Err(ApiError(
                StatusCode::PAYLOAD_TOO_LARGE,
                format!("at most {MAX_CORRECTIONS} corrections of each kind"),
            ));
        }
        if let Some(Err(why)) = body.scale_line.as_ref().map(ScaleLine::check) {
            return Err(ApiError(
                StatusCode::UNPROCESSABLE_ENTITY,
                format!("scale_line: {why}"),
            ));
        }
        body.set(&mut p);
        let stage = plan_stage(app, &p)?;
        check_structures(&p, &stage.parsed)?;
        app.store
            .commit(Some(&p), vec![])
            .map_err(err(StatusCode::UNPROCESSABLE_ENTITY))?;
        let overlay = write_overlay(app, &stage.overlay)?;
        let parsed = &stage.parsed;
        versioned(
            &app.store,
            json!({
                "overlay": file_url(&overlay),
                "towers": parsed.towers,
                "tower_list": towers_of(parsed),
                "faces": parsed.faces.len(),
                "warnings": parsed.warnings,
                "scale": p.scale_line.as_ref().map(ScaleLine::metres_per_pixel),
                "saved": counts.iter().sum::<usize>() + usize::from(p.scale_line.is_some()),
                "ms": t.elapsed().as_millis(),
            }),
        )
    })
    .await
}

/// Every tower of the corrected plan: tower rooms (their fitted circle, or the circle of their
/// area) and towers drawn solid, each `{center, radius, solid}` in plan pixels.
fn towers_of(parsed: &plan::ParsedPlan) -> Vec<serde_json::Value> {
    let rooms = parsed
        .faces
        .iter()
        .filter(|f| f.label == plan::label::Label::TowerRoom)
        .map(|f| {
            let (center, radius) = match f.shape {
                Some(plan::fit::Fit::Circle { center, radius, .. }) => (center, radius),
                _ => (f.centroid, (f.area as f64 / std::f64::consts::PI).sqrt()),
            };
            json!({ "center": center, "radius": radius, "solid": false })
        });
    let solid = parsed
        .bulge_towers
        .iter()
        .map(|t| json!({ "center": t.center, "radius": t.radius, "solid": true }));
    rooms.chain(solid).collect()
}

/// GET /api/plan/at?x=&y=: the label the corrected plan has at a plan point (what the overlay
/// shows there, for the page's pointer and for scripts).
pub async fn label_at(State(app): State<Arc<App>>, Query(q): Query<PlanPoint>) -> Reply {
    blocking(app, "label", move |app| {
        let p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        let (mut parsed, _) = parsed_plan(app, &p)?;
        plan::corrections::apply(&mut parsed, p.plan_fixes())
            .map_err(|e| ApiError(StatusCode::UNPROCESSABLE_ENTITY, e.to_string()))?;
        let inside = q.x >= 0.0
            && q.y >= 0.0
            && q.x < f64::from(parsed.width)
            && q.y < f64::from(parsed.height);
        if !inside {
            return Err(ApiError(
                StatusCode::BAD_REQUEST,
                format!(
                    "[{}, {}] is outside the plan ({} × {} px)",
                    q.x, q.y, parsed.width, parsed.height
                ),
            ));
        }
        Ok(Json(json!({
            "label": parsed.label_at(q.x as u32, q.y as u32).name(),
            "towers": towers_of(&parsed),
        })))
    })
    .await
}

/// The `[[structure]]` entries checked on the structures the corrected plan gives, as
/// `integrate` applies them.
fn check_structures(p: &Project, parsed: &plan::ParsedPlan) -> Result<(), ApiError> {
    if p.structure_fixes.is_empty() {
        return Ok(());
    }
    let refuse = |m: String| ApiError(StatusCode::UNPROCESSABLE_ENTITY, m);
    let (frame, _) = plan::scale::ModelScale::decide(parsed, p.given_scale());
    let mut structures = integrate::structures::from_plan(parsed, &p.plan, &frame);
    let targets = integrate::corrections::targets(&structures, &p.structure_fixes, parsed, &frame)
        .map_err(refuse)?;
    integrate::corrections::apply_roles(&mut structures, &p.structure_fixes, &targets);
    integrate::corrections::apply_values(&mut structures, &p.structure_fixes, &targets, &frame)
        .map_err(refuse)
}

/// A plan point, in the plan's pixels.
#[derive(Debug, Deserialize)]
pub struct PlanPoint {
    pub x: f64,
    pub y: f64,
}

/// GET /api/structure?x=&y=: the structure the last reconstruction built at a plan point, with
/// its values and their sources, for the page's structure panel.
pub async fn at(State(app): State<Arc<App>>, Query(q): Query<PlanPoint>) -> Reply {
    blocking(app, "structure", move |app| {
        let path = app
            .store
            .existing("out/estimate.json")
            .map_err(err(StatusCode::CONFLICT))?
            .ok_or_else(|| {
                ApiError(
                    StatusCode::CONFLICT,
                    "no model yet: reconstruct first, then click a structure".into(),
                )
            })?;
        let e: Estimate =
            crate::text::read_json(&path, "an estimate.json").map_err(err(StatusCode::CONFLICT))?;
        let s = e.scale.units_per_pixel;
        let i = integrate::correspond::structure_at(&e.structures, [q.x * s, q.y * s]).ok_or_else(
            || {
                ApiError(
                    StatusCode::NOT_FOUND,
                    format!("no structure at [{}, {}] in the last model", q.x, q.y),
                )
            },
        )?;
        let st = &e.structures[i];
        let sources: serde_json::Map<String, serde_json::Value> = st
            .provenance
            .iter()
            .map(|(k, v)| (k.clone(), json!(format!("{}: {}", v.image, v.step))))
            .collect();
        Ok(Json(json!({
            "id": st.id, "role": st.role.name(), "label": st.label.name(),
            "height": st.height, "units": e.scale.units.symbol(),
            "roof": st.roof.map(|r| r.name()), "crenellated": st.crenellated,
            "sources": sources,
        })))
    })
    .await
}

/// The body of PUT /api/plan/settings: PROJECT.toml's plan keys, absent ones removed.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSettings {
    /// Metres per plan pixel (`scale`).
    #[serde(default)]
    pub scale: Option<f64>,
    /// The drawn bar's length in metres (`scale_bar`).
    #[serde(default)]
    pub scale_bar: Option<f64>,
    /// Vault ribs out of round rooms (`thin_lines`, a fraction of the wall thickness).
    #[serde(default)]
    pub thin_lines: Option<f64>,
    /// The walls are drawn hatched (`hatching`).
    #[serde(default)]
    pub hatching: bool,
    /// The plan shows one building (`one_building`).
    #[serde(default)]
    pub one_building: bool,
    /// The learned walls are trimmed to the drawing after the parse (`trim_ink`).
    #[serde(default)]
    pub trim_ink: bool,
}

/// PUT /api/plan/settings: the scale, the scale bar, vault ribs, hatching, one building and
/// the trim, checked as PROJECT.toml is (a bad value is refused naming its key) and saved;
/// the page parses again.
pub async fn settings(
    State(app): State<Arc<App>>,
    headers: HeaderMap,
    Json(body): Json<PlanSettings>,
) -> Saved {
    let if_match = if_match(&headers);
    blocking(app, "plan settings", move |app| {
        let mut p = app.store.require().map_err(err(StatusCode::CONFLICT))?;
        check_version(&app.store, if_match.as_deref())?;
        p.metres_per_pixel = body.scale;
        p.scale_bar_metres = body.scale_bar;
        p.thin_lines = body.thin_lines;
        p.hatching = body.hatching.then_some(true);
        p.one_building = body.one_building.then_some(true);
        p.trim_ink = body.trim_ink.then_some(true);
        app.store
            .commit(Some(&p), vec![])
            .map_err(err(StatusCode::UNPROCESSABLE_ENTITY))?;
        versioned(
            &app.store,
            json!({ "scale": p.metres_per_pixel, "scale_bar": p.scale_bar_metres,
                    "thin_lines": p.thin_lines, "hatching": body.hatching,
                    "one_building": body.one_building, "trim_ink": body.trim_ink }),
        )
    })
    .await
}
