//! Parsing speed on a 3000 × 2000 synthetic scan (issue 6 target: under 2 s), and on a
//! 900 × 700 sheet, which is enlarged ×2 before parsing like the small drawings of books.

use criterion::{Criterion, criterion_group, criterion_main};
use image::DynamicImage;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("plan_parse");
    g.sample_size(10);
    let (big, _) = plan::synth::castle(1, 2.8, 3000, 2000);
    let big = DynamicImage::ImageLuma8(big);
    g.bench_function("castle_3000x2000", |b| {
        b.iter(|| plan::parse(&big, &plan::Options::default()).unwrap())
    });
    let (small, _) = plan::synth::castle(1, 1.0, 900, 700);
    let small = DynamicImage::ImageLuma8(small);
    g.bench_function("castle_900x700_enlarged", |b| {
        b.iter(|| plan::parse(&small, &plan::Options::default()).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
