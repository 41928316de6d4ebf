//! Measures plan–model agreement (issue 25, `integrate::agreement`) over the plans castellan is
//! judged on: the bundled Coucy demo (examples/coucy, its PROJECT.toml with the tower
//! elevation), then every plan of the development set (crates/plan/tests/data/devset.json)
//! and of the gallery (scripts/gallery.py's `PLANS`, with its scales and options),
//! reconstructed plan-only through `pipeline::reconstruct`. Prints per plan the model
//! footprint's IoU, precision and recall against the plan's built area, rooms and towers
//! present, and the medians; then where the recall goes (built pixels left bare, by label)
//! and where the precision goes (the model's pixels on unbuilt plan, by structure kind). The
//! drawings are read from `../shared/data/castle_drawings_pd`; without it only Coucy is
//! measured. Run: `cargo run --release -p integrate --example
//! plan_model_agreement [-- --limit N] [--absent] [--trim-ink]`; `--absent` lists the rooms
//! and towers the model leaves uncovered, `--trim-ink` trims every learned plan's walls to
//! the drawing (PROJECT.toml `trim_ink`).

use std::path::{Path, PathBuf};

use integrate::pipeline::{self, Files};
use integrate::project::Project;

/// A project's files, read from a folder.
struct Folder(PathBuf);

impl Files for Folder {
    fn image(&self, name: &str) -> Result<image::DynamicImage, String> {
        image::open(self.0.join(name)).map_err(|e| format!("{name}: {e}"))
    }

    fn json<T: serde::de::DeserializeOwned>(&self, name: &str, what: &str) -> Result<T, String> {
        let text =
            std::fs::read_to_string(self.0.join(name)).map_err(|e| format!("{name}: {e}"))?;
        serde_json::from_str(&text).map_err(|e| format!("{name} is not {what}: {e}"))
    }
}

/// One plan to measure: where it is, which sets it belongs to, its PROJECT.toml.
struct Case {
    name: String,
    sets: String,
    folder: PathBuf,
    project: String,
}

fn main() {
    let repo = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let detail = std::env::args().any(|a| a == "--absent");
    let trim_ink = std::env::args().any(|a| a == "--trim-ink");
    let limit = arg_value("--limit").map_or(usize::MAX, |v| v.parse().expect("--limit N"));
    let coucy = repo.join("examples/coucy");
    let mut cases = vec![Case {
        name: "examples/coucy (with its façade)".into(),
        sets: "demo".into(),
        folder: coucy.clone(),
        project: std::fs::read_to_string(coucy.join("PROJECT.toml")).expect("Coucy's PROJECT.toml"),
    }];
    let data = repo.join("../shared/data/castle_drawings_pd");
    if data.is_dir() {
        cases.extend(shared_cases(&repo, &data).into_iter().take(limit));
    } else {
        eprintln!(
            "skipped the development set and the gallery: {} not found (the public-domain castle drawings of ../shared)",
            data.display()
        );
    }
    println!(
        "| plan | set | IoU | precision | recall | rooms present | towers present | structures |"
    );
    println!("| --- | --- | --- | --- | --- | --- | --- | --- |");
    let mut rows = Vec::new();
    // Where the precision goes: the model's pixels on unbuilt plan, by structure kind (the id
    // without its number), over every plan but the demo.
    let mut spilled: std::collections::BTreeMap<String, usize> = Default::default();
    for case in &cases {
        match measure(case, trim_ink) {
            Ok((a, ids)) => {
                let structures = ids.len();
                println!(
                    "| {} | {} | {:.3} | {:.3} | {:.3} | {} / {} | {} / {} | {} |",
                    case.name,
                    case.sets,
                    a.iou,
                    a.precision,
                    a.recall,
                    a.rooms_present(),
                    a.rooms.len(),
                    a.towers_present(),
                    a.towers.len(),
                    structures
                );
                if detail {
                    for (what, list) in [("room", &a.rooms), ("tower", &a.towers)] {
                        for p in list.iter().filter(|p| !p.present()) {
                            println!(
                                "|   absent {what}: {} of {} px at ({:.0}, {:.0}), {:.0} % covered{} | | | | | | | |",
                                p.label.name(),
                                p.pixels,
                                p.centroid[0],
                                p.centroid[1],
                                100.0 * p.covered,
                                p.structure
                                    .as_ref()
                                    .map(|s| format!(", most by {s}"))
                                    .unwrap_or_default()
                            );
                        }
                    }
                }
                if case.sets != "demo" {
                    for (id, k) in ids.iter().zip(&a.spilled_by_structure) {
                        *spilled
                            .entry(id.trim_end_matches(|c: char| c.is_ascii_digit()).into())
                            .or_default() += k;
                    }
                    rows.push(a);
                }
            }
            Err(e) => println!("| {} | {} | failed: {e} | | | | | |", case.name, case.sets),
        }
    }
    if rows.is_empty() {
        return;
    }
    let med = |f: &dyn Fn(&integrate::agreement::Agreement) -> f64| {
        let mut v: Vec<f64> = rows.iter().map(f).collect();
        v.sort_by(f64::total_cmp);
        let n = v.len();
        if n % 2 == 1 {
            v[n / 2]
        } else {
            (v[n / 2 - 1] + v[n / 2]) / 2.0
        }
    };
    let share = |present: usize, all: usize| {
        if all == 0 {
            1.0
        } else {
            present as f64 / all as f64
        }
    };
    println!(
        "\nmedian over {} plans of ../shared (failures left out): IoU {:.3}, precision {:.3}, recall {:.3}, rooms present {:.2}, towers present {:.2}",
        rows.len(),
        med(&|a| a.iou),
        med(&|a| a.precision),
        med(&|a| a.recall),
        med(&|a| share(a.rooms_present(), a.rooms.len())),
        med(&|a| share(a.towers_present(), a.towers.len())),
    );
    let (rp, r): (usize, usize) = rows.iter().fold((0, 0), |(p, n), a| {
        (p + a.rooms_present(), n + a.rooms.len())
    });
    let (tp, t): (usize, usize) = rows.iter().fold((0, 0), |(p, n), a| {
        (p + a.towers_present(), n + a.towers.len())
    });
    println!("in all: rooms present {rp} / {r}, towers present {tp} / {t}");
    // Where the recall goes: the plan's built pixels left bare, by label, over every plan.
    let mut missed = [0usize; 11];
    for a in &rows {
        for (m, k) in missed.iter_mut().zip(a.missed_by_label) {
            *m += k;
        }
    }
    let total: usize = missed.iter().sum();
    let by_label: Vec<String> = plan::label::Label::ALL
        .iter()
        .zip(missed)
        .filter(|(_, k)| *k > 0)
        .map(|(l, k)| {
            format!(
                "{} {:.0} %",
                l.name(),
                100.0 * k as f64 / total.max(1) as f64
            )
        })
        .collect();
    println!("built pixels left bare, by label: {}", by_label.join(", "));
    let total: usize = spilled.values().sum();
    let by_kind: Vec<String> = spilled
        .iter()
        .filter(|(_, k)| **k > 0)
        .map(|(kind, k)| format!("{kind} {:.0} %", 100.0 * *k as f64 / total.max(1) as f64))
        .collect();
    println!(
        "model pixels on unbuilt plan, by structure kind: {}",
        by_kind.join(", ")
    );
}

/// The agreement of a case's reconstruction and its structures' ids; with `trim_ink`, a
/// learned plan's walls trimmed to the drawing.
fn measure(
    case: &Case,
    trim_ink: bool,
) -> Result<(integrate::agreement::Agreement, Vec<String>), String> {
    let mut project = Project::from_toml(&case.project).map_err(|e| e.to_string())?;
    if trim_ink && project.ink != Some(plan::ink::InkMethod::Rules) {
        project.trim_ink = Some(true);
    }
    let r = pipeline::reconstruct(
        &project,
        &Folder(case.folder.clone()),
        &pipeline::Options::default(),
        &|_| {},
    )
    .map_err(|e| e.to_string())?;
    Ok((
        r.agreement,
        r.estimate.structures.iter().map(|s| s.id.clone()).collect(),
    ))
}

/// The development set's plans, then the gallery's that are not among them; a plan in both
/// is reconstructed once, with the gallery's scale and options (what its page shows).
fn shared_cases(repo: &Path, data: &Path) -> Vec<Case> {
    let devset: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(repo.join("crates/plan/tests/data/devset.json"))
            .expect("devset.json"),
    )
    .expect("devset.json is JSON");
    let gallery = gallery_plans(
        &std::fs::read_to_string(repo.join("scripts/gallery.py")).expect("scripts/gallery.py"),
    );
    let mut files: Vec<String> = devset["plans"]
        .as_array()
        .expect("devset.json: plans")
        .iter()
        .filter_map(|p| p["file"].as_str().map(str::to_string))
        .collect();
    for (file, _, _) in &gallery {
        if !files.contains(file) {
            files.push(file.clone());
        }
    }
    files
        .into_iter()
        .map(|file| {
            let in_devset = devset["plans"]
                .as_array()
                .is_some_and(|ps| ps.iter().any(|p| p["file"] == file.as_str()));
            let in_gallery = gallery.iter().find(|(f, _, _)| *f == file);
            let sets = match (in_devset, in_gallery.is_some()) {
                (true, true) => "devset, gallery",
                (true, false) => "devset",
                _ => "gallery",
            };
            let mut project = format!("plan = {file:?}\n");
            if let Some((_, scale, options)) = in_gallery {
                if let Some(s) = scale {
                    project += &format!("scale = {s}\n");
                }
                for o in options {
                    project += &format!("{o} = true\n");
                }
            }
            let name = file.rsplit('/').next().unwrap_or(&file).to_string();
            Case {
                name,
                sets: sets.into(),
                folder: data.to_path_buf(),
                project,
            }
        })
        .collect()
}

/// scripts/gallery.py's `PLANS`: one `("plans/FILE", SCALE or None[, ["option", …]])` a line
/// between `PLANS = [` and `]`; the options are PROJECT.toml switches, as the script writes
/// them into its projects.
fn gallery_plans(script: &str) -> Vec<(String, Option<f64>, Vec<String>)> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in script.lines() {
        let line = line.trim();
        if line.starts_with("PLANS = [") {
            inside = true;
            continue;
        }
        if !inside {
            continue;
        }
        if line.starts_with(']') {
            break;
        }
        let quoted: Vec<&str> = line.split('"').skip(1).step_by(2).collect();
        let Some(file) = quoted.first() else {
            continue;
        };
        let after = line.split('"').nth(2).unwrap_or("");
        let scale = after
            .trim_start_matches(',')
            .split([',', ')'])
            .next()
            .and_then(|s| s.trim().parse::<f64>().ok());
        let options = quoted[1..].iter().map(|s| s.to_string()).collect();
        out.push((file.to_string(), scale, options));
    }
    out
}

fn arg_value(flag: &str) -> Option<String> {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == flag)
        .and_then(|i| args.get(i + 1).cloned())
}
