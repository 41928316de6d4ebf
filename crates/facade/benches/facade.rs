//! Speed on a 1-megapixel synthetic façade (issue 4: classification + search < 1 s on 2 cores),
//! and rectification of a 640 x 480 photo.
//!
//! `cargo bench -p facade --bench facade`

#[path = "../tests/common/mod.rs"]
mod common;

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use facade::classify::{ClassifyParams, classify};
use facade::eval::simulate_user;
use facade::rectify::{RectifyParams, rectify};
use facade::search::{SearchParams, parse};

fn truth(s: &common::Synth) -> Vec<u8> {
    let (w, h) = s.img.dimensions();
    (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let inside = |r: &[u32; 4]| x >= r[0] && x < r[2] && y >= r[1] && y < r[3];
            if s.windows.iter().any(inside) {
                2
            } else if inside(&s.facade) {
                1
            } else {
                0
            }
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let s = common::facade(1000, 1000, 6, 8, 1);
    let training = simulate_user(&truth(&s), 1000, 1000, 3, 15, 1).unwrap();
    let mut g = c.benchmark_group("facade");
    g.sample_size(10);
    g.bench_function("classify + parse, 1000x1000", |b| {
        b.iter(|| {
            let ll = classify(black_box(&s.img), &training, &ClassifyParams::default()).unwrap();
            parse(&s.img, &ll, &SearchParams::default()).unwrap()
        })
    });
    let ll = classify(&s.img, &training, &ClassifyParams::default()).unwrap();
    g.bench_function("parse only, 1000x1000", |b| {
        b.iter(|| parse(black_box(&s.img), &ll, &SearchParams::default()).unwrap())
    });
    let photo = common::facade(640, 480, 4, 6, 2).img;
    g.bench_function("rectify, 640x480", |b| {
        b.iter(|| rectify(black_box(&photo), &RectifyParams::default()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
