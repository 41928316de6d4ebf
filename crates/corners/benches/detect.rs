//! Speed of the §2.1 detector on one core, per stage: the edge image (§2.1.1), the window fits
//! and thresholds (§2.1.2–2.1.5) and the whole of `detect`. On img1 of each Oxford affine
//! sequence when `../shared/data/oxford_affine` exists, otherwise on a synthetic 800 × 640
//! image of rectangles. The ratio to OpenCV Harris is measured by `benches/corners_peers.py`.
//!
//! `RAYON_NUM_THREADS=1 cargo bench -p corners --bench detect`

use std::hint::black_box;
use std::path::PathBuf;

use corners::detect::{candidates, suppress};
use corners::edge::edge_map;
use corners::{Gray, Params, detect};
use criterion::{Criterion, criterion_group, criterion_main};

const SEQUENCES: [&str; 8] = [
    "bark", "bikes", "boat", "graf", "leuven", "trees", "ubc", "wall",
];

fn oxford() -> Vec<(String, Gray)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/oxford_affine");
    if !dir.is_dir() {
        eprintln!(
            "{} not found: benchmarking a synthetic image instead",
            dir.display()
        );
        return Vec::new();
    }
    SEQUENCES
        .iter()
        .filter_map(|s| {
            let ext = if *s == "boat" { "pgm" } else { "ppm" };
            let img = image::open(dir.join(s).join(format!("img1.{ext}"))).ok()?;
            Some((s.to_string(), Gray::from_dynamic(&img)))
        })
        .collect()
}

/// Axis-aligned and slanted bright rectangles on a dark ground, lightly textured so the edge
/// image is not trivially sparse.
fn synthetic() -> Gray {
    let (w, h) = (800usize, 640usize);
    let data = (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as f64, (i / w) as f64);
            let (cx, cy) = (x % 80.0, y % 64.0);
            let slant = (x + 0.4 * y) % 100.0;
            let mut v = 40.0;
            if (15.0..55.0).contains(&cx) && (12.0..44.0).contains(&cy) {
                v = 190.0;
            } else if slant < 20.0 {
                v = 120.0;
            }
            v + ((x * 12.9898 + y * 78.233).sin() * 43758.5453)
                .fract()
                .abs()
                * 6.0
        })
        .map(|v| v as f32)
        .collect();
    Gray::new(w, h, data)
}

fn bench(c: &mut Criterion) {
    let mut images = oxford();
    if images.is_empty() {
        images.push(("synthetic".into(), synthetic()));
    }
    let p = Params::default();
    let mut g = c.benchmark_group("corners");
    g.sample_size(10);
    for (name, img) in &images {
        let edges = edge_map(img, p.window, p.sigma, p.subpixel);
        g.bench_function(format!("{name}/edge image"), |b| {
            b.iter(|| edge_map(black_box(img), p.window, p.sigma, p.subpixel))
        });
        g.bench_function(format!("{name}/fits + thresholds"), |b| {
            b.iter(|| candidates(black_box(&edges), &p))
        });
        let cands = candidates(&edges, &p);
        g.bench_function(format!("{name}/suppression"), |b| {
            b.iter(|| suppress(black_box(cands.clone()), p.window))
        });
        g.bench_function(format!("{name}/detect"), |b| {
            b.iter(|| detect(black_box(img), &p).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
