//! Leave one source out (issue 26): for each book, a wall-ink model trained without that
//! book's painted plans (synthetic plans and every other book's) is measured on that book —
//! wall IoU on its painted masks against Otsu's threshold, and labels at the annotated points
//! (`tests/data/devset.json`, `devset_more.json`) and exact tower counts against the rule
//! chain (`--ink rules`). Prints one Markdown table.
//!
//! `cargo run --release -p plan --example ink_eval -- [--seed 1] [--synthetic 60] [--only BOOK-SUBSTRING]`

#[path = "common/ink_data.rs"]
mod ink_data;

use std::collections::BTreeSet;
use std::sync::Arc;

use plan::eval::{DevPlan, DevSet, Totals, score};
use plan::ink::train::{Sheet, TrainParams, confusion, source_of, train};
use plan::ink::{InkMethod, WallInk};

fn main() {
    let mut seed = 1u64;
    let mut synthetic = 60usize;
    let mut only: Option<String> = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let v = args
            .next()
            .unwrap_or_else(|| ink_data::fail(&a, "needs a value"));
        match a.as_str() {
            "--seed" => seed = v.parse().unwrap_or_else(|e| ink_data::fail(&a, e)),
            "--synthetic" => synthetic = v.parse().unwrap_or_else(|e| ink_data::fail(&a, e)),
            "--only" => only = Some(v),
            _ => ink_data::fail(&a, "unknown argument (--seed, --synthetic, --only)"),
        }
    }
    let Some(data) = ink_data::data_dir() else {
        eprintln!("skipped: ../shared/data/castle_drawings_pd not found");
        return;
    };
    let recipes = ink_data::recipes();
    let painted: Vec<(String, Sheet)> = recipes
        .iter()
        .map(|r| (source_of(&r.book), ink_data::painted_sheet(&data, r)))
        .collect();
    let root = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut dev: Vec<(DevPlan, u32)> = Vec::new();
    for f in ["tests/data/devset.json", "tests/data/devset_more.json"] {
        let text = std::fs::read_to_string(root.join(f)).unwrap_or_else(|e| ink_data::fail(f, e));
        let set = DevSet::from_json(&text).unwrap_or_else(|e| ink_data::fail(f, e));
        dev.extend(set.plans.into_iter().map(|p| (p, set.tolerance_px)));
    }
    let sources: BTreeSet<String> = painted
        .iter()
        .map(|(s, _)| s.clone())
        .chain(dev.iter().map(|(p, _)| source_of(&p.book)))
        .filter(|s| only.as_ref().is_none_or(|o| s.contains(o.as_str())))
        .collect();
    let synth = ink_data::synthetic(synthetic, seed);
    let mut params = TrainParams::default();
    params.forest.seed = seed;
    println!(
        "| source | masks | wall IoU learned / Otsu | plans | points learned / rules | towers exact learned / rules |"
    );
    println!("| --- | ---: | --- | ---: | --- | --- |");
    let mut sum = [0usize; 12];
    for source in &sources {
        let t = std::time::Instant::now();
        let held: Vec<&Sheet> = painted
            .iter()
            .filter(|(s, _)| s == source)
            .map(|(_, sh)| sh)
            .collect();
        let mut train_set: Vec<Sheet> = synth.clone();
        train_set.extend(
            painted
                .iter()
                .filter(|(s, _)| s != source)
                .map(|(_, sh)| sh.clone()),
        );
        let model = Arc::new(
            train(&train_set, &params, "leave one out")
                .unwrap_or_else(|e| ink_data::fail("training", e)),
        );
        let (mut learned, mut otsu) = ([0usize; 3], [0usize; 3]);
        for sh in &held {
            let (w, h) = sh.grey.dimensions();
            ink_data::add(
                &mut learned,
                confusion(&model.wall_probability(&sh.grey, w, h), &sh.truth),
            );
            ink_data::add(
                &mut otsu,
                confusion(&ink_data::otsu_map(&sh.grey), &sh.truth),
            );
        }
        let plans: Vec<&(DevPlan, u32)> = dev
            .iter()
            .filter(|(p, _)| &source_of(&p.book) == source)
            .collect();
        let (l, r) = (
            points(&data, &plans, Some(model.clone())),
            points(&data, &plans, None),
        );
        println!(
            "| {} | {} | {} / {} | {} | {} / {} of {} | {} / {} | ({:.0} s)",
            source,
            held.len(),
            ink_data::iou(learned),
            ink_data::iou(otsu),
            plans.len(),
            l.right,
            r.right,
            l.points,
            l.towers_exact,
            r.towers_exact,
            t.elapsed().as_secs_f64()
        );
        for (k, v) in learned
            .iter()
            .chain(&otsu)
            .chain(&[
                l.right,
                r.right,
                l.points,
                l.towers_exact,
                r.towers_exact,
                plans.len(),
            ])
            .enumerate()
        {
            sum[k] += v;
        }
    }
    println!(
        "| all | {} | {} / {} | {} | {} / {} of {} | {} / {} |",
        painted.len(),
        ink_data::iou([sum[0], sum[1], sum[2]]),
        ink_data::iou([sum[3], sum[4], sum[5]]),
        sum[11],
        sum[6],
        sum[7],
        sum[8],
        sum[9],
        sum[10]
    );
}

/// Points and towers with the learned ink of `model`, or with the rule chain (`None`).
fn points(
    data: &std::path::Path,
    plans: &[&(DevPlan, u32)],
    model: Option<Arc<WallInk>>,
) -> Totals {
    let opts = plan::Options {
        ink: if model.is_some() {
            InkMethod::Learned
        } else {
            InkMethod::Rules
        },
        ink_model: model,
        ..Default::default()
    };
    let scores: Vec<_> = plans
        .iter()
        .map(|(p, tol)| {
            let img =
                image::open(data.join(&p.file)).unwrap_or_else(|e| ink_data::fail(&p.file, e));
            score(plan::parse(&img, &opts).ok().as_ref(), p, *tol)
        })
        .collect();
    Totals::of(&scores)
}
