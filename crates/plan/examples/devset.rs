//! Prints the development-set table (issue 11): labels at the annotated points and tower
//! counts per plan, totals, frequent confusions and the time per drawing. Reads
//! `../shared/data/castle_drawings_pd`. Run: `cargo run --release -p plan --example devset
//! [-- --no-close-gaps] [--no-gates] [--trim-ink] [--one-building] [--no-inner-towers]
//! [--no-drop-marks] [--no-bulge-towers] [--no-thick-towers] [--no-ring-towers] [--ward-ratio R] [--thin-lines F] [--hatching] [--hachures] [--no-dashes] [--rules] [--more] [--ink-model FILE] [--net] [--ink-net FILE] [--overlays DIR] [--confusions] [--all] [--closed]`; `--confusions` lists each plan's wrong points (true → found); `--rules` parses with the issue-11 rule chain instead of the learned wall ink; `--more` reads `devset_more.json` (other hands); `--ink-model` reads a wall-ink model written by `train_ink --out FILE` instead of the shipped one; `--net` parses with the wall-ink network, `--ink-net` with a network written by `train_net --out FILE`; `--closed` lists each plan's closed outer wall and towers; `--overlays` writes each plan's label overlay; `--all` also parses all 236 plans of the manifest and prints
//! how many parse (also apart for the 4-bit grey scans of 300–700 px), give a closed outer wall (a courtyard) and a tower, and the warnings by kind.

#[path = "../tests/common/mod.rs"]
mod common;
use std::path::PathBuf;
use std::time::Instant;

use plan::eval::{DevSet, score, table};

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let Some(data) = common::castle_drawings() else {
        return;
    };
    let args: Vec<String> = std::env::args().collect();
    let file = if args.iter().any(|a| a == "--more") {
        "tests/data/devset_more.json"
    } else {
        "tests/data/devset.json"
    };
    let text = std::fs::read_to_string(root.join(file)).unwrap();
    let set = DevSet::from_json(&text).unwrap();
    let opts = plan::Options {
        close_gaps: !args.iter().any(|a| a == "--no-close-gaps"),
        close_gates: !args.iter().any(|a| a == "--no-gates"),
        trim_ink: args.iter().any(|a| a == "--trim-ink"),
        one_building: args.iter().any(|a| a == "--one-building"),
        inner_ward_towers: !args.iter().any(|a| a == "--no-inner-towers"),
        drop_marks: !args.iter().any(|a| a == "--no-drop-marks"),
        ward_ratio: arg_value("--ward-ratio").map_or(0.3, |v| v.parse().unwrap()),
        thin_lines: arg_value("--thin-lines").map_or(0.0, |v| v.parse().unwrap()),
        bulge_towers: !args.iter().any(|a| a == "--no-bulge-towers"),
        thick_towers: !args.iter().any(|a| a == "--no-thick-towers"),
        ring_towers: !args.iter().any(|a| a == "--no-ring-towers"),
        hatching: args.iter().any(|a| a == "--hatching"),
        hachures: args.iter().any(|a| a == "--hachures"),
        dashes: !args.iter().any(|a| a == "--no-dashes"),
        ink: if args.iter().any(|a| a == "--rules") {
            plan::ink::InkMethod::Rules
        } else if args.iter().any(|a| a == "--net") || arg_value("--ink-net").is_some() {
            plan::ink::InkMethod::Network
        } else {
            plan::ink::InkMethod::Learned
        },
        ink_net: arg_value("--ink-net").map(|f| {
            let bytes = std::fs::read(&f).unwrap_or_else(|e| panic!("{f}: {e}"));
            std::sync::Arc::new(
                plan::ink::net::WallNet::from_bytes(&bytes).unwrap_or_else(|e| panic!("{f}: {e}")),
            )
        }),
        ink_model: arg_value("--ink-model").map(|f| {
            let bytes = std::fs::read(&f).unwrap_or_else(|e| panic!("{f}: {e}"));
            std::sync::Arc::new(
                plan::ink::WallInk::from_bytes(&bytes).unwrap_or_else(|e| panic!("{f}: {e}")),
            )
        }),
        ..Default::default()
    };
    let mut scores = Vec::new();
    let mut times = Vec::new();
    for p in &set.plans {
        let img = image::open(data.join(&p.file)).unwrap();
        let t = Instant::now();
        let parsed = plan::parse(&img, &opts).ok();
        times.push(t.elapsed().as_secs_f64());
        if let (Some(dir), Some(pp)) = (arg_value("--overlays"), parsed.as_ref()) {
            let name = p.file.rsplit('/').next().unwrap_or(&p.file);
            let out = std::path::Path::new(&dir).join(format!("{name}.overlay.png"));
            plan::output::overlay(pp, &img.to_luma8())
                .save(out)
                .unwrap();
        }
        scores.push(score(parsed.as_ref(), p, set.tolerance_px));
    }
    println!("{}", table(&scores));
    if args_has("--confusions") {
        for s in scores.iter().filter(|s| !s.confusions.is_empty()) {
            let wrong: Vec<String> = s
                .confusions
                .iter()
                .map(|(t, f)| format!("{} → {}", t.name(), f.name()))
                .collect();
            println!("{}: {}", s.file, wrong.join(", "));
        }
    }
    for (name, four) in [("4-bit grey 300-700 px", true), ("other scans", false)] {
        let part: Vec<_> = scores
            .iter()
            .zip(&set.plans)
            .filter(|(_, p)| is_four_bit_small(&data.join(&p.file)) == four)
            .map(|(s, _)| s.clone())
            .collect();
        let t = plan::eval::Totals::of(&part);
        println!(
            "{name}: {} plans, {} / {} points right, {} towers exact, tower error {}",
            t.plans, t.right, t.points, t.towers_exact, t.tower_abs_error
        );
    }
    times.sort_by(f64::total_cmp);
    println!(
        "time per drawing: median {:.2} s, longest {:.2} s",
        times[times.len() / 2],
        times[times.len() - 1]
    );
    if args.iter().any(|a| a == "--all") {
        all_plans(&data, &opts);
    }
}

fn all_plans(data: &std::path::Path, opts: &plan::Options) {
    let manifest: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(data.join("manifest.json")).unwrap())
            .unwrap();
    let files: Vec<&str> = manifest
        .iter()
        .filter(|e| e["kind"] == "plan")
        .filter_map(|e| e["file"].as_str())
        .collect();
    let (mut parsed, mut closed, mut towered, mut bars, mut marks) = (0, 0, 0, 0, 0);
    // [4-bit grey 300-700 px, other]: plans, closed outer wall, >= 1 tower.
    let mut by_kind = [[0usize; 3]; 2];
    let mut kinds: Vec<(String, usize)> = Vec::new();
    let mut times = Vec::new();
    for f in &files {
        let img = image::open(data.join(f)).unwrap();
        let t = Instant::now();
        let result = plan::parse(&img, opts);
        times.push(t.elapsed().as_secs_f64());
        let reasons = match result {
            Ok(p) => {
                parsed += 1;
                let k = usize::from(!is_four_bit_small(&data.join(f)));
                by_kind[k][0] += 1;
                by_kind[k][1] += usize::from(
                    p.faces
                        .iter()
                        .any(|f| f.label == plan::label::Label::Courtyard),
                );
                by_kind[k][2] += usize::from(p.towers > 0);
                let has_courtyard = p
                    .faces
                    .iter()
                    .any(|f| f.label == plan::label::Label::Courtyard);
                closed += usize::from(has_courtyard);
                towered += usize::from(p.towers > 0);
                bars += usize::from(p.scale_bar.is_some());
                marks += p.pre.dropped_marks;
                if args_has("--closed") {
                    println!("{f}\tclosed {}\ttowers {}", has_courtyard, p.towers);
                }
                if args_has("--bars") {
                    println!("{f}\t{:?}", p.scale_bar);
                }
                p.warnings
            }
            Err(e) => vec![e.to_string()],
        };
        for r in reasons {
            let kind = r.split(':').next().unwrap_or("").to_string();
            match kinds.iter_mut().find(|(k, _)| *k == kind) {
                Some((_, n)) => *n += 1,
                None => kinds.push((kind, 1)),
            }
        }
    }
    times.sort_by(f64::total_cmp);
    println!(
        "all {} plans: {parsed} parsed, {closed} with a closed outer wall, {towered} with a tower, {bars} with a scale bar found, {marks} marks dropped; median {:.2} s, longest {:.2} s",
        files.len(),
        times[times.len() / 2],
        times[times.len() - 1]
    );
    for (name, [n, c, t]) in ["4-bit grey 300-700 px", "other scans"].iter().zip(by_kind) {
        println!("  {name}: {n} parsed, {c} with a closed outer wall, {t} with a tower");
    }
    kinds.sort_by_key(|k| std::cmp::Reverse(k.1));
    for (k, n) in kinds {
        println!("  {n:4}  {k}");
    }
}

fn args_has(flag: &str) -> bool {
    std::env::args().any(|a| a == flag)
}

fn arg_value(flag: &str) -> Option<String> {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == flag)
        .and_then(|i| args.get(i + 1).cloned())
}

/// A PNG of at most 4 bits per pixel whose longer side is 300–700 px: the small grey scans
/// issue 11 asks to be reported apart (read from the PNG header; the decoded image no longer
/// says how many grey levels it had).
fn is_four_bit_small(path: &std::path::Path) -> bool {
    let Ok(bytes) = std::fs::read(path) else {
        return false;
    };
    if bytes.len() < 26 || &bytes[..8] != b"\x89PNG\r\n\x1a\n" {
        return false;
    }
    let dim =
        |at: usize| u32::from_be_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let long = dim(16).max(dim(20));
    bytes[24] <= 4 && (300..=700).contains(&long)
}
