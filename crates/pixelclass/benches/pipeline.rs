//! The 1-Mpx pipeline (the budget: features + training + prediction well under a
//! second on 2 cores): the whole `classify` at the default working resolution, and its
//! stages. `cargo bench -p pixelclass --bench pipeline`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use pixelclass::{Channels, Forest, Params, classify, features, resample, working_size};

mod common;

fn pipeline(c: &mut Criterion) {
    let (img, samples) = common::scene();
    let p = Params::default();
    let ch = Channels::from_rgb(&img);
    let mut g = c.benchmark_group("1 Mpx");
    g.sample_size(10);
    g.bench_function("classify (default working resolution)", |b| {
        b.iter(|| classify(black_box(&ch), &samples, 3, &p).unwrap())
    });
    let (ws, hs) = working_size(ch.width, ch.height, p.max_pixels);
    let work = resample::shrink(&ch, ws, hs);
    g.bench_function("features", |b| {
        b.iter(|| features::compute(black_box(&work), &p.bank))
    });
    let f = features::compute(&work, &p.bank);
    let (x, labels): (Vec<f32>, Vec<usize>) = {
        let mut x = Vec::new();
        let mut l = Vec::new();
        for s in &samples {
            let i = (s.y * hs / ch.height) * ws + s.x * ws / ch.width;
            x.extend(f.planes.iter().map(|pl| pl[i]));
            l.push(s.class);
        }
        (x, l)
    };
    g.bench_function("train", |b| {
        b.iter(|| Forest::train(black_box(&x), f.dim(), &labels, 3, &p.forest).unwrap())
    });
    let forest = Forest::train(&x, f.dim(), &labels, 3, &p.forest).unwrap();
    g.bench_function("predict", |b| {
        b.iter(|| forest.predict(black_box(&f)).unwrap())
    });
    g.finish();
}

criterion_group!(benches, pipeline);
criterion_main!(benches);
