//! Trains the wall-ink model that ships with castellan (issue 26), reproducibly from a seed:
//! synthetic plans in randomised styles plus the wall masks painted on public-domain plans
//! (`crates/plan/data/wall_masks*.json`; needs `../shared/data/castle_drawings_pd`).
//!
//! `cargo run --release -p plan --example train_ink -- [--seed 1] [--synthetic 60] [--trees N]
//! [--depth D] [--scarps] [--scarp-paper] [--far-paper PX] [--furnishing]
//! [--out crates/plan/models/wall_ink.bin]`.
//! The shipped model's recipe is `ink_data::SynthOptions::default` with 16 trees of depth 13;
//! `--scarps` also draws hachured scarps and hachure bands against the synthetic walls,
//! `--scarp-paper` samples the paper between their strokes as a pool of its own, `--far-paper
//! PX` ignores the paper farther than PX from any ink on the drawings with scarps,
//! `--furnishing` draws fittings (stairs, tables, counters, doors' swings) inside the curtain; `--trees`
//! and `--depth` size the forests (none of these in the shipped model: docs/plan.md).

#[path = "common/ink_data.rs"]
mod ink_data;

use std::path::PathBuf;

use plan::ink::train::{TrainParams, train};

fn main() {
    let mut seed = 1u64;
    let mut synthetic = 60usize;
    let mut synth = ink_data::SynthOptions::default();
    let (mut trees, mut depth) = (None, None);
    let mut out = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("models/wall_ink.bin");
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = |name: &str| {
            args.next()
                .unwrap_or_else(|| ink_data::fail(name, "needs a value"))
        };
        match a.as_str() {
            "--seed" => {
                seed = value("--seed")
                    .parse()
                    .unwrap_or_else(|e| ink_data::fail("--seed", e))
            }
            "--synthetic" => {
                synthetic = value("--synthetic")
                    .parse()
                    .unwrap_or_else(|e| ink_data::fail("--synthetic", e))
            }
            "--trees" => {
                trees = Some(
                    value("--trees")
                        .parse()
                        .unwrap_or_else(|e| ink_data::fail("--trees", e)),
                )
            }
            "--depth" => {
                depth = Some(
                    value("--depth")
                        .parse()
                        .unwrap_or_else(|e| ink_data::fail("--depth", e)),
                )
            }
            "--scarps" => synth.scarps = true,
            "--scarp-paper" => synth.scarp_paper = true,
            "--furnishing" => synth.furnishing = true,
            "--far-paper" => {
                synth.far_paper = Some(
                    value("--far-paper")
                        .parse()
                        .unwrap_or_else(|e| ink_data::fail("--far-paper", e)),
                )
            }
            "--out" => out = PathBuf::from(value("--out")),
            _ => ink_data::fail(
                &a,
                "unknown argument (--seed, --synthetic, --trees, --depth, --scarps, --scarp-paper, --far-paper, --furnishing, --out)",
            ),
        }
    }
    let data = ink_data::painted_data_dir();
    let recipes = ink_data::recipes();
    let mut sheets = ink_data::synthetic_with(synthetic, seed, synth);
    sheets.extend(recipes.iter().map(|r| ink_data::painted_sheet(&data, r)));
    let mut params = TrainParams::default();
    params.forest.seed = seed;
    params.forest.trees = trees.unwrap_or(params.forest.trees);
    params.forest.max_depth = depth.unwrap_or(params.forest.max_depth);
    let mut recipe = match (synth.scarps, synth.far_paper) {
        (false, _) => String::new(),
        (true, None) => " with scarps".to_string(),
        (true, Some(px)) => format!(" with scarps, paper over {px} px from ink ignored"),
    };
    if synth.scarps && synth.scarp_paper {
        recipe.push_str(", the paper between their strokes sampled apart");
    }
    if synth.furnishing {
        recipe.push_str(" with fittings");
    }
    let provenance = format!(
        "seed {seed}; {synthetic} synthetic plans{recipe}; {} painted plans (crates/plan/data/wall_masks*.json)",
        recipes.len()
    );
    let t = std::time::Instant::now();
    let model =
        train(&sheets, &params, &provenance).unwrap_or_else(|e| ink_data::fail("training", e));
    let bytes = model.to_bytes();
    std::fs::write(&out, &bytes).unwrap_or_else(|e| ink_data::fail(&out.display().to_string(), e));
    println!(
        "{}: {} bytes, {} + {} nodes, trained in {:.1} s ({provenance})",
        out.display(),
        bytes.len(),
        model.stages[0].nodes(),
        model.stages.get(1).map_or(0, |f| f.nodes()),
        t.elapsed().as_secs_f64()
    );
}
