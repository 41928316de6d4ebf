//! Time of each step of the parse on the 3000 × 2000 synthetic scan (what the benchmark spends
//! where): the learned wall ink alone (and the wall-ink network's), then every step of the parse after it on that mask and
//! on the rules' threshold (median of `--runs N`, default 3), then whole parses.
//! Run: `cargo run --release -p plan --example stage_times [-- --runs N] [--mask FILE]
//! [--steps-only]`; `--mask` reads the learned mask from FILE (written there first when
//! missing), `--steps-only` leaves out the whole parses (for profiling the steps alone).

use std::time::{Duration, Instant};

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

fn arg(flag: &str) -> Option<String> {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == flag)
        .and_then(|i| args.get(i + 1).cloned())
}

fn main() {
    let runs: usize = arg("--runs").map_or(3, |v| v.parse().unwrap());
    let (img, _) = plan::synth::castle(1, 2.8, 3000, 2000);
    let drawing = image::DynamicImage::ImageLuma8(img.clone());
    let t = Instant::now();
    let grey = drawing.to_luma8();
    let _ = plan::scalebar::find(&grey);
    println!("grey + scale bar {:?}", t.elapsed());
    let t = Instant::now();
    let learned = plan::ink::InkMethod::Learned;
    let opts = plan::Options {
        ink: learned,
        ..Default::default()
    };
    let cached = arg("--mask").map(std::path::PathBuf::from);
    let mask = match cached.as_ref().filter(|p| p.exists()) {
        Some(p) => Some(image::open(p).unwrap().to_luma8()),
        None => {
            let mask = plan::learned_mask_of(&img, &opts).unwrap();
            println!("learned wall ink (mask) {:?}", t.elapsed());
            if let (Some(p), Some(m)) = (&cached, &mask) {
                m.save(p).unwrap();
            }
            mask
        }
    };
    let network = plan::Options {
        ink: plan::ink::InkMethod::Network,
        ..Default::default()
    };
    let t = Instant::now();
    let _ = plan::learned_mask_of(&img, &network).unwrap();
    println!("wall-ink network (mask) {:?}", t.elapsed());
    let rules = plan::Options {
        ink: plan::ink::InkMethod::Rules,
        ..Default::default()
    };
    for (name, mask, opts) in [("learned", mask, &opts), ("rules", None, &rules)] {
        let mut steps: Vec<(&'static str, Vec<Duration>)> = Vec::new();
        let mut totals = Vec::new();
        for _ in 0..runs {
            let t = Instant::now();
            let (p, laps) = plan::parse_mask_timed(&img, mask.clone(), opts);
            totals.push(t.elapsed());
            p.unwrap();
            for (k, (step, d)) in laps.steps.into_iter().enumerate() {
                if steps.len() <= k {
                    steps.push((step, Vec::new()));
                }
                steps[k].1.push(d);
            }
        }
        println!("after the {name} ink, median of {runs} (ms):");
        for (step, ds) in steps {
            println!("  {step:32} {:8.1}", median(ds).as_secs_f64() * 1e3);
        }
        println!(
            "  {:32} {:8.1}",
            "total",
            median(totals).as_secs_f64() * 1e3
        );
    }
    if std::env::args().any(|a| a == "--steps-only") {
        return;
    }
    for ink in [plan::ink::InkMethod::Learned, plan::ink::InkMethod::Rules] {
        let t = Instant::now();
        let opts = plan::Options {
            ink,
            ..Default::default()
        };
        let p = plan::parse(&drawing, &opts).unwrap();
        println!(
            "whole parse, {ink:?} ink {:?} ({} towers)",
            t.elapsed(),
            p.towers
        );
    }
}
