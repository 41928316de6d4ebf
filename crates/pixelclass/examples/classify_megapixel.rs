//! The 1-Mpx pipeline stage by stage on a synthetic façade (for timing and peak memory:
//! `/usr/bin/time -v cargo run --release -p pixelclass --example classify_megapixel [MAX_PIXELS]`).

use std::time::Instant;

use pixelclass::{
    AutoContext, Channels, Forest, Params, classify, features, resample, working_size,
};

#[path = "../benches/common/mod.rs"]
mod common;

fn main() {
    let mut p = Params::default();
    if let Some(m) = std::env::args().nth(1).and_then(|a| a.parse().ok()) {
        p.max_pixels = m;
    }
    let (img, samples) = common::scene();
    let t = Instant::now();
    let ch = Channels::from_rgb(&img);
    let t_lab = t.elapsed().as_secs_f64();
    let (ws, hs) = working_size(ch.width, ch.height, p.max_pixels);
    let t = Instant::now();
    let work = resample::shrink(&ch, ws, hs);
    let t_shrink = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let f = features::compute(&work, &p.bank);
    let t_feat = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let dim = f.dim();
    let mut x = Vec::new();
    let mut labels = Vec::new();
    for s in &samples {
        let i = (s.y * hs / ch.height) * ws + s.x * ws / ch.width;
        x.extend(f.planes.iter().map(|pl| pl[i]));
        labels.push(s.class);
    }
    let forest = Forest::train(&x, dim, &labels, 3, &p.forest).unwrap();
    let t_train = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let prob = forest.predict(&f).unwrap();
    let t_pred = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let prob = resample::enlarge(&prob, ch.width, ch.height);
    let t_big = t.elapsed().as_secs_f64();
    println!(
        "{}x{} at {ws}x{hs}, {dim} features, {} nodes: lab {t_lab:.3} s, shrink {t_shrink:.3} s, \
         features {t_feat:.3} s, train {t_train:.3} s, predict {t_pred:.3} s, enlarge {t_big:.3} s, \
         total {:.3} s",
        ch.width,
        ch.height,
        forest.nodes(),
        t_lab + t_shrink + t_feat + t_train + t_pred + t_big
    );
    let labels = prob.argmax();
    let windows = labels.iter().filter(|&&l| l == 2).count();
    println!("window pixels: {windows}");
    // The whole `classify`, single stage and with autocontext (in-sample and 2-fold context).
    for (name, ac) in [
        ("single stage", None),
        (
            "autocontext σ 1…16 + row/column",
            Some(AutoContext::smoothed()),
        ),
        (
            "autocontext row/column, averaged (default)",
            Some(AutoContext::default()),
        ),
        (
            "autocontext, 2 folds",
            Some(AutoContext {
                folds: 2,
                ..AutoContext::smoothed()
            }),
        ),
    ] {
        let q = Params {
            autocontext: ac,
            ..p.clone()
        };
        let t = Instant::now();
        let prob = classify(&Channels::from_rgb(&img), &samples, 3, &q).unwrap();
        let s = t.elapsed().as_secs_f64();
        let windows = prob.argmax().iter().filter(|&&l| l == 2).count();
        println!("classify, {name}: {s:.3} s, window pixels {windows}");
    }
}
