//! Time of classification + search on a 1000 x 1000 synthetic façade (issue 4: target < 1 s on
//! 2 cores), split by stage. `cargo run --release -p facade --example megapixel`
//! (the criterion version is `cargo bench -p facade --bench facade`).

#[path = "../tests/common/mod.rs"]
mod common;

use std::time::Instant;

use facade::classify::{Classifier, ClassifyParams, features};
use facade::eval::simulate_user;
use facade::search::{SearchParams, parse};

fn main() {
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
        let mut best = [f64::INFINITY; 4];
        for _ in 0..3 {
            let t0 = Instant::now();
            let f = features::compute(&s.img, &p.features);
            let t1 = Instant::now();
            let c = Classifier::train(&f, &training, &p).unwrap();
            let ll = c.log_likelihoods(&f);
            let t2 = Instant::now();
            let m = parse(&s.img, &ll, &SearchParams::default()).unwrap();
            let t3 = Instant::now();
            assert_eq!(m.facades.len(), 1);
            let d = [
                (t1 - t0).as_secs_f64(),
                (t2 - t1).as_secs_f64(),
                (t3 - t2).as_secs_f64(),
                (t3 - t0).as_secs_f64(),
            ];
            for (b, v) in best.iter_mut().zip(d) {
                *b = b.min(v);
            }
        }
        println!(
            "| {} | {:.3} | {:.3} | {:.3} | {:.3} |",
            3 + 3 * components,
            best[0],
            best[1],
            best[2],
            best[3]
        );
    }
}
