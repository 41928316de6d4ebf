//! A simulated user correcting the development set through the HTTP API (issue 22): on every
//! plan of `crates/plan/tests/data/devset.json`, each annotated point the parse labels wrongly
//! is clicked with its true label, towers the parse invented (no annotated tower point in
//! them) are removed smallest first and annotated tower points outside every tower are added,
//! until the count is the drawn one; the user then looks again and clicks the points still
//! wrong (three looks at most); then the model is rebuilt and every annotated tower and room
//! must have a structure of its kind. Prints the corrections per plan. Skipped, with a
//! message, when `../shared/data/castle_drawings_pd` is absent.

use std::path::{Path, PathBuf};

use axum::http::StatusCode;
use plan::eval::{DevPoint, DevSet, label_near};
use plan::label::Label;
use serde_json::{Value, json as json_value};

use super::tests::{app, json};

fn drawings() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/castle_drawings_pd");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!(
            "SKIPPED simulated user: {} is absent (the shared public-domain drawings)",
            dir.display()
        );
        None
    }
}

/// What the simulated user did and found on one plan.
struct Outcome {
    file: String,
    corrections: usize,
    wrong_before: usize,
    /// Clicks the server refused (the drawing must be cleaned there first).
    refused: usize,
    wrong_after: usize,
    /// How many times the user looked at the overlay and clicked what was wrong.
    rounds: usize,
    towers: [u64; 3],
    /// Rooms and towers with a structure of their kind within the tolerance, and at the very
    /// pixel.
    structures_right: usize,
    structures_right_at_pixel: usize,
    structures_checked: usize,
}

/// The plan as `castellan reconstruct` reads it from the saved project: parsed, corrected.
fn corrected(dir: &Path) -> plan::ParsedPlan {
    let store = super::store::Store::open(dir).unwrap();
    let project = store.require().unwrap();
    integrate::pipeline::parse_plan(&project, &store)
        .unwrap()
        .parsed
}

fn holds(tower: &Value, p: &DevPoint) -> bool {
    let c = &tower["center"];
    let (cx, cy) = (c[0].as_f64().unwrap(), c[1].as_f64().unwrap());
    (f64::from(p.x) - cx).hypot(f64::from(p.y) - cy) <= tower["radius"].as_f64().unwrap() + 2.0
}

fn is_tower(l: Label) -> bool {
    matches!(l, Label::TowerRoom | Label::TowerWall)
}

/// PUT /api/corrections with the whole list.
async fn put(app: &axum::Router, fixes: &Value) -> (StatusCode, Value) {
    json(app, "PUT", "/api/corrections", &fixes.to_string()).await
}

/// Invented towers out, smallest first; missed ones in, at the annotated tower points; until
/// the count is the drawn one or nothing more can be done. Returns the corrections and the
/// server's last answer.
async fn towers(
    app: &axum::Router,
    file: &str,
    truth: &plan::eval::DevPlan,
    mut fixes: Value,
    mut answer: Value,
) -> (Value, Value) {
    let target = truth.towers as u64;
    let tower_points: Vec<&DevPoint> = truth.points.iter().filter(|p| is_tower(p.label)).collect();
    for _ in 0..64 {
        let count = answer["towers"].as_u64().unwrap();
        let list = answer["tower_list"].as_array().unwrap().clone();
        let fix = if count > target {
            let mut invented: Vec<&Value> = list
                .iter()
                .filter(|t| !tower_points.iter().any(|p| holds(t, p)))
                .collect();
            invented.sort_by(|a, b| {
                a["radius"]
                    .as_f64()
                    .unwrap()
                    .total_cmp(&b["radius"].as_f64().unwrap())
            });
            invented
                .first()
                .map(|t| json_value!({"point": t["center"], "remove": true}))
        } else if count < target {
            tower_points
                .iter()
                .find(|p| !list.iter().any(|t| holds(t, p)))
                .map(|p| json_value!({"point": [p.x, p.y]}))
        } else {
            None
        };
        let Some(fix) = fix else { break };
        fixes["tower"].as_array_mut().unwrap().push(fix);
        let (mut s, mut v) = put(app, &fixes).await;
        if s == StatusCode::UNPROCESSABLE_ENTITY {
            // Neither in a room nor on ink: the user drags the tower's radius, as large as the
            // plan's other towers (median), or 10 px.
            let mut radii: Vec<f64> = list.iter().filter_map(|t| t["radius"].as_f64()).collect();
            radii.sort_by(f64::total_cmp);
            let radius = radii.get(radii.len() / 2).copied().unwrap_or(10.0).max(3.0);
            let last = fixes["tower"].as_array_mut().unwrap().last_mut().unwrap();
            last["radius"] = json_value!(radius.round());
            (s, v) = put(app, &fixes).await;
        }
        assert_eq!(s, StatusCode::OK, "{file}: {v}");
        answer = v;
    }
    (fixes, answer)
}

async fn correct(plan: &Path, file: &str, truth: &plan::eval::DevPlan, tolerance: u32) -> Outcome {
    let dir = tempfile::tempdir().unwrap();
    let name = Path::new(file).file_name().unwrap().to_str().unwrap();
    std::fs::copy(plan, dir.path().join(name)).unwrap();
    std::fs::write(
        dir.path().join("PROJECT.toml"),
        format!("plan = \"{name}\"\n"),
    )
    .unwrap();
    let app = app(dir.path(), 1 << 26);
    let (s, first) = json(&app, "POST", "/api/plan", "").await;
    assert_eq!(s, StatusCode::OK, "{file}: {first}");
    let mut fixes = json_value!({"label": [], "tower": []});
    let (s, mut answer) = put(&app, &fixes).await;
    assert_eq!(s, StatusCode::OK, "{answer}");
    let (mut wrong_before, mut refused) = (0, 0);
    // Wrong as the development set's evaluation counts it (the nearest pixel of the same kind
    // within its tolerance).
    let wrong = |dir: &Path| -> Vec<&DevPoint> {
        let parsed = corrected(dir);
        truth
            .points
            .iter()
            .filter(|p| label_near(&parsed, p, tolerance) != p.label)
            .collect()
    };
    // The user looks at the overlay again after the towers and clicks what is still wrong,
    // twice at most; a point clicked before and still wrong is not clicked again.
    let mut clicked: Vec<(u32, u32)> = Vec::new();
    let mut rounds = 0;
    for round in 0..3 {
        if round == 1 {
            (fixes, answer) = towers(&app, file, truth, fixes, answer).await;
        }
        let now = wrong(dir.path());
        if round == 0 {
            wrong_before = now.len();
        }
        let todo: Vec<&DevPoint> = now
            .into_iter()
            .filter(|p| !clicked.contains(&(p.x, p.y)))
            .collect();
        if todo.is_empty() && round > 0 {
            break;
        }
        rounds = round + 1;
        for p in todo {
            clicked.push((p.x, p.y));
            let mut next = fixes.clone();
            next["label"]
                .as_array_mut()
                .unwrap()
                .push(json_value!({"point": [p.x, p.y], "label": p.label}));
            // A click the server refuses (a region label on ink no region touches: the
            // drawing needs the eraser first) is not kept.
            let (s, v) = put(&app, &next).await;
            if s == StatusCode::OK {
                fixes = next;
                answer = v;
            } else {
                assert_eq!(s, StatusCode::UNPROCESSABLE_ENTITY, "{v}");
                refused += 1;
            }
        }
    }
    let before = first["towers"].as_u64().unwrap();
    let after = answer["towers"].as_u64().unwrap();
    let still = wrong(dir.path());
    let parsed = corrected(dir.path());
    for p in &still {
        let on_ink = parsed.walls.data[(p.y * parsed.width + p.x) as usize] == 1;
        eprintln!(
            "{file}: still wrong at [{}, {}]: {} read as {}{}",
            p.x,
            p.y,
            p.label.name(),
            label_near(&parsed, p, tolerance).name(),
            if on_ink {
                " (the point is on wall ink)"
            } else {
                ""
            }
        );
    }
    let wrong_after = still.len();
    let (s, r) = json(&app, "POST", "/api/reconstruct", "").await;
    assert_eq!(s, StatusCode::OK, "{file}: {r}");
    let (mut right, mut right_at_pixel, mut checked) = (0, 0, 0);
    // A structure of the point's kind at the point, or within the development set's tolerance
    // of it as its labels are read (`label_near`): an annotated room point may lie on the ink
    // of the room's wall, where the wall is the structure.
    for p in truth.points.iter().filter(|p| p.label.is_room()) {
        checked += 1;
        let r = f64::from(tolerance);
        let probes = std::iter::once((0.0, 0.0)).chain((0..8).map(|k| {
            let a = f64::from(k) * std::f64::consts::FRAC_PI_4;
            (r * a.cos(), r * a.sin())
        }));
        let mut found = Vec::new();
        for (i, (dx, dy)) in probes.enumerate() {
            let (x, y) = (f64::from(p.x) + dx, f64::from(p.y) + dy);
            let (s, st) = json(&app, "GET", &format!("/api/structure?x={x}&y={y}"), "").await;
            let role = st["role"].as_str().unwrap_or("");
            let ok = s == StatusCode::OK
                && if p.label == Label::TowerRoom {
                    matches!(role, "tower" | "keep")
                } else {
                    st["label"] == json_value!(p.label) && matches!(role, "range" | "room" | "keep")
                };
            if ok {
                found.push(i);
                break;
            }
            if i == 0 {
                eprintln!(
                    "{file}: at [{}, {}] ({}) the model has {st}",
                    p.x,
                    p.y,
                    p.label.name()
                );
            }
        }
        match found.first() {
            Some(0) => (right, right_at_pixel) = (right + 1, right_at_pixel + 1),
            Some(_) => right += 1,
            None => {}
        }
    }
    let corrections =
        fixes["label"].as_array().unwrap().len() + fixes["tower"].as_array().unwrap().len();
    Outcome {
        file: file.to_string(),
        corrections,
        wrong_before,
        refused,
        wrong_after,
        rounds,
        towers: [before, after, truth.towers as u64],
        structures_right: right,
        structures_right_at_pixel: right_at_pixel,
        structures_checked: checked,
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_simulated_user_corrects_every_development_plan() {
    let Some(data) = drawings() else { return };
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../plan/tests/data/devset.json");
    let set = DevSet::from_json(&std::fs::read_to_string(root).unwrap()).unwrap();
    let mut outcomes = Vec::new();
    for p in &set.plans {
        outcomes.push(correct(&data.join(&p.file), &p.file, p, set.tolerance_px).await);
    }
    eprintln!(
        "plan | corrections | points wrong before → after (clicks refused) | looks | towers parsed → corrected (drawn) | rooms and towers built right"
    );
    for o in &outcomes {
        eprintln!(
            "{} | {} | {} → {} ({}) | {} | {} → {} ({}) | {}/{}",
            o.file,
            o.corrections,
            o.wrong_before,
            o.wrong_after,
            o.refused,
            o.rounds,
            o.towers[0],
            o.towers[1],
            o.towers[2],
            o.structures_right,
            o.structures_checked
        );
    }
    let mut counts: Vec<usize> = outcomes.iter().map(|o| o.corrections).collect();
    counts.sort_unstable();
    let median = counts[counts.len() / 2];
    let worst = counts[counts.len() - 1];
    let points: usize = set.plans.iter().map(|p| p.points.len()).sum();
    let wrong_before: usize = outcomes.iter().map(|o| o.wrong_before).sum();
    let wrong_after: usize = outcomes.iter().map(|o| o.wrong_after).sum();
    let exact = outcomes
        .iter()
        .filter(|o| o.towers[1] == o.towers[2])
        .count();
    let exact_before = outcomes
        .iter()
        .filter(|o| o.towers[0] == o.towers[2])
        .count();
    let right: usize = outcomes.iter().map(|o| o.structures_right).sum();
    let right_at_pixel: usize = outcomes.iter().map(|o| o.structures_right_at_pixel).sum();
    let checked: usize = outcomes.iter().map(|o| o.structures_checked).sum();
    let refused: usize = outcomes.iter().map(|o| o.refused).sum();
    eprintln!(
        "simulated user, {} plans: corrections per plan median {median}, worst {worst}; points wrong {wrong_before} → {wrong_after} of {points} ({refused} clicks refused); exact tower counts {exact_before} → {exact}; rooms and towers built right {right}/{checked} within {} px ({right_at_pixel} at the very pixel)",
        outcomes.len(),
        set.tolerance_px
    );
    // Floors at the figures measured (docs/serve.md, "Corrections by a simulated user"): 40 →
    // 16 points wrong of 169, exact tower counts 2 → 6 of 31 (the user knows where towers are
    // only at annotated tower points), every annotated room and tower built as its kind within
    // the set's tolerance (37 of 38 at the very pixel: Chambord's tower point lies on wall ink).
    assert!(
        wrong_after <= 17,
        "{wrong_after} of {points} points still wrong"
    );
    assert!(wrong_after < wrong_before, "{wrong_before} → {wrong_after}");
    assert!(exact >= 6, "{exact} exact tower counts");
    assert_eq!(right, checked, "rooms and towers built right");
}
