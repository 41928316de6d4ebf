//! Time of classification + search on a 1000 x 1000 synthetic façade (issue 4: target < 1 s on
//! 2 cores), split by stage. `cargo run --release -p facade --example megapixel`
//! (the criterion version is `cargo bench -p facade --bench facade`).

#[path = "../tests/common/mod.rs"]
mod common;

use std::time::Instant;

/// This process's user + system CPU seconds (Linux; 0 elsewhere): on a shared, loaded machine
/// wall time mostly measures the other jobs.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<f64> = after
        .split_whitespace()
        .map(|v| v.parse().unwrap_or(0.0))
        .collect();
    // Fields 14 and 15 (utime, stime) in clock ticks of 1/100 s.
    (f.get(11).copied().unwrap_or(0.0) + f.get(12).copied().unwrap_or(0.0)) / 100.0
}

use facade::classify::{Classifier, ClassifyParams, features};
use facade::eval::simulate_user;
use facade::search::{SearchParams, parse};

fn main() {
    println!("wall / CPU seconds, best of 3");
    println!("| feature dims | features | GMM training (EM) | log-likelihoods | search | total |");
    println!("| --- | --- | --- | --- | --- | --- |");
    let s = common::facade(1000, 1000, 6, 8, 1);
    let truth: Vec<u8> = (0..1000u32 * 1000)
        .map(|i| {
            let (x, y) = (i % 1000, i / 1000);
            let inside = |r: &[u32; 4]| x >= r[0] && x < r[2] && y >= r[1] && y < r[3];
            if s.windows.iter().any(inside) {
                2
            } else if inside(&s.facade) {
                1
            } else {
                0
            }
        })
        .collect();
    let training = simulate_user(&truth, 1000, 1000, 3, 15, 1).unwrap();
    for components in [5, 0] {
        let p = ClassifyParams {
            features: facade::classify::FeatureParams {
                components,
                ..Default::default()
            },
            ..Default::default()
        };
        // Per stage: best wall time, and best CPU time (user + system, all threads).
        let mut wall = [f64::INFINITY; 5];
        let mut cpu = [f64::INFINITY; 5];
        for _ in 0..3 {
            let mut marks = vec![(Instant::now(), cpu_seconds())];
            let f = features::compute(&s.img, &p.features);
            marks.push((Instant::now(), cpu_seconds()));
            let c = Classifier::train(&f, &training, &p).unwrap();
            marks.push((Instant::now(), cpu_seconds()));
            let ll = c.log_likelihoods(&f);
            marks.push((Instant::now(), cpu_seconds()));
            let m = parse(&s.img, &ll, &SearchParams::default()).unwrap();
            marks.push((Instant::now(), cpu_seconds()));
            assert_eq!(m.facades.len(), 1);
            for i in 0..4 {
                wall[i] = wall[i].min((marks[i + 1].0 - marks[i].0).as_secs_f64());
                cpu[i] = cpu[i].min(marks[i + 1].1 - marks[i].1);
            }
            wall[4] = wall[4].min((marks[4].0 - marks[0].0).as_secs_f64());
            cpu[4] = cpu[4].min(marks[4].1 - marks[0].1);
        }
        let cell = |i: usize| format!("{:.2} / {:.2}", wall[i], cpu[i]);
        println!(
            "| {} | {} | {} | {} | {} | {} |",
            3 + 3 * components,
            cell(0),
            cell(1),
            cell(2),
            cell(3),
            cell(4)
        );
    }
    // The default pipeline every command runs (`facade::parse_photo`: forest, the window boxes
    // grown into whole windows and classified again, their repeats, the search), and the same
    // with the boxes as drawn, best of 3 each.
    let grown = facade::repeat::RepeatParams::default();
    for (name, rp) in [
        ("boxes grown (default)", grown),
        (
            "boxes as drawn",
            facade::repeat::RepeatParams {
                grow: None,
                ..grown
            },
        ),
        (
            "boxes grown, no repeats",
            facade::repeat::RepeatParams {
                evidence: 0.0,
                ..grown
            },
        ),
    ] {
        let (mut wall, mut cpu) = (f64::INFINITY, f64::INFINITY);
        for _ in 0..3 {
            let (t, c) = (Instant::now(), cpu_seconds());
            let (_, m, _) = facade::parse_photo(
                &s.img,
                &training,
                &ClassifyParams::default(),
                &SearchParams::default(),
                &rp,
            )
            .unwrap();
            assert_eq!(m.facades.len(), 1);
            wall = wall.min(t.elapsed().as_secs_f64());
            cpu = cpu.min(cpu_seconds() - c);
        }
        println!("parse_photo, forest, {name}: {wall:.2} s wall / {cpu:.2} s CPU");
    }
}
