//! Time per stage of the Gothic pipeline (ch. 4) on a 1-megapixel synthetic façade: three bays
//! of 2, 4 and 3 round or pointed windows under enclosing arches on a brick wall.
//!
//! `cargo bench -p facade --bench gothic` (set `GOTHIC_BENCH_IMAGE=path.png` to also save the
//! input picture). Before timing it prints how many of the true elements were recovered.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use facade::gothic::masonry::{MasonryParams, segment};
use facade::gothic::synth::{SynthSpec, recovered, synthetic_facade};
use facade::gothic::{GothicParams, VsgOptions, detect, distance_map, organise, to_vsg};

fn bench(c: &mut Criterion) {
    let s = synthetic_facade(&SynthSpec::megapixel(), 1);
    let p = GothicParams::default();
    let dt = distance_map(&s.image, &p);
    let found = detect::detect(&dt, &p);
    let est = organise(&dt, found.clone(), &p);
    let masonry = segment(&s.image, &est, &MasonryParams::default());
    if let Ok(path) = std::env::var("GOTHIC_BENCH_IMAGE") {
        s.image
            .save(path)
            .expect("GOTHIC_BENCH_IMAGE: cannot write the picture");
    }
    let shapes: Vec<_> = est.elements.iter().map(|e| e.theta()).collect();
    let recovered = recovered(&s.elements, &shapes, 4.0);
    eprintln!(
        "1000x1000 synthetic façade: {recovered} of {} true elements within 4 px, {} detected, {} groups, {} nested, {} stones",
        s.elements.len(),
        est.elements.len(),
        est.groups.len(),
        est.elements.iter().filter(|e| e.parent.is_some()).count(),
        masonry.stones.len()
    );
    let mut g = c.benchmark_group("gothic 1000x1000");
    g.sample_size(10);
    g.bench_function("1 edges + distance transform", |b| {
        b.iter(|| distance_map(black_box(&s.image), &p))
    });
    g.bench_function("2 seeds + CG detection", |b| {
        b.iter(|| detect::detect(black_box(&dt), &p))
    });
    g.bench_function("3 grouping + enclosing arches", |b| {
        b.iter(|| organise(black_box(&dt), found.clone(), &p))
    });
    g.bench_function("4 masonry watershed + merge", |b| {
        b.iter(|| segment(black_box(&s.image), &est, &MasonryParams::default()))
    });
    g.bench_function("5 VSG program text", |b| {
        b.iter(|| to_vsg(black_box(&est), Some(&masonry), &VsgOptions::default()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
