//! Prints the development-set table (issue 11): labels at the annotated points and tower
//! counts per plan, totals, frequent confusions and the time per drawing. Reads
//! `../shared/data/castle_drawings_pd`. Run: `cargo run --release -p plan --example devset
//! [-- --no-close-gaps] [--inner-towers]
//! [--no-drop-marks] [--ward-ratio R] [--overlays DIR] [--all]`; `--overlays` writes each plan's label overlay; `--all` also parses all 236 plans of the manifest and prints
//! how many parse, give a closed outer wall (a courtyard) and a tower, and the warnings by kind.

use std::path::PathBuf;
use std::time::Instant;

use plan::eval::{DevSet, score, table};

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let data = root.join("../../../shared/data/castle_drawings_pd");
    if !data.is_dir() {
        eprintln!("skipped: {} not found", data.display());
        return;
    }
    let text = std::fs::read_to_string(root.join("tests/data/devset.json")).unwrap();
    let set = DevSet::from_json(&text).unwrap();
    let args: Vec<String> = std::env::args().collect();
    let opts = plan::Options {
        close_gaps: !args.iter().any(|a| a == "--no-close-gaps"),
        inner_ward_towers: args.iter().any(|a| a == "--inner-towers"),
        drop_marks: !args.iter().any(|a| a == "--no-drop-marks"),
        ward_ratio: arg_value("--ward-ratio").map_or(0.3, |v| v.parse().unwrap()),
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
                closed += usize::from(
                    p.faces
                        .iter()
                        .any(|f| f.label == plan::label::Label::Courtyard),
                );
                towered += usize::from(p.towers > 0);
                bars += usize::from(p.scale_bar.is_some());
                marks += p.pre.dropped_marks;
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
