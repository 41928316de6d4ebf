//! Scores the scale-bar finder (`plan::scalebar`, issue 11) on the bars read by eye in
//! `tests/data/scalebars.json`: one line per plan (outcome, bar found, bar drawn), then the
//! counts, precision and recall, for all plans and by source (Armitage's and the others).
//! Run: `cargo run --release -p plan --example scalebar_eval`.

#[path = "../tests/common/mod.rs"]
mod common;
use std::path::PathBuf;

use plan::scalebar::eval::{BarSet, Outcome, Tally, judge};
use rayon::prelude::*;

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let Some(data) = common::castle_drawings() else {
        return;
    };
    let set = BarSet::from_json(
        &std::fs::read_to_string(root.join("tests/data/scalebars.json")).unwrap(),
    )
    .unwrap();
    let judged: Vec<(Outcome, bool, String)> = set
        .plans
        .par_iter()
        .map(|p| {
            let grey = image::open(data.join(&p.file)).unwrap().to_luma8();
            let found = plan::scalebar::find(&grey);
            let o = judge(found.as_ref(), p.bar, set.tolerance_px, set.tolerance_share);
            let shown = found.map_or("-".to_string(), |b| b.describe());
            let drawn = p.bar.map_or("-".to_string(), |b| format!("{b:?}"));
            let line = format!(
                "{:<12} {:<58} found {shown:<40} drawn {drawn}",
                o.name(),
                p.file
            );
            (o, p.bar.is_some(), line)
        })
        .collect();
    for (_, _, line) in &judged {
        println!("{line}");
    }
    let tally = |armitage: Option<bool>| {
        Tally::of(
            judged
                .iter()
                .zip(&set.plans)
                .filter(|(_, p)| armitage.is_none_or(|a| p.file.contains("armitage") == a))
                .map(|((o, has, _), _)| (*o, *has)),
        )
    };
    println!("all:      {}", tally(None).summary());
    println!("Armitage: {}", tally(Some(true)).summary());
    println!("others:   {}", tally(Some(false)).summary());
}
