//! Our forest against the Rust peers on the same data: ~50 000 labelled pixels x 60 filter
//! features of the synthetic 1-Mpx façade for training, every pixel for prediction. Timed
//! once each (the peers take seconds to minutes; criterion's repetitions would take hours).
//! `cargo bench -p pixelclass --features peers --bench peers`; figures in docs/pixelclass.md.

use std::num::NonZeroUsize;
use std::time::Instant;

use pixelclass::{Channels, Family, FilterBank, Forest, ForestParams, features};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use smartcore::ensemble::random_forest_classifier::{
    RandomForestClassifier, RandomForestClassifierParameters,
};
use smartcore::linalg::basic::matrix::DenseMatrix;

mod common;

const TREES: usize = 32;
const DEPTH: usize = 16;

fn main() {
    let (img, _) = common::scene();
    let ch = Channels::from_rgb(&img);
    let bank = FilterBank {
        sigmas: vec![1.0, 1.6, 3.5, 5.0],
        families: vec![
            Family::Smoothing,
            Family::GradientMagnitude,
            Family::LaplacianOfGaussian,
            Family::Hessian,
        ],
    };
    let f = features::compute(&ch, &bank);
    let (w, n, dim) = (f.width, f.width * f.height, f.dim());
    let truth: Vec<usize> = (0..n)
        .map(|i| common::truth((i % w) as u32, (i / w) as u32))
        .collect();
    // 50 000 training pixels; a tenth of their labels flipped so the task is not trivially
    // separable and the forests' choices differ.
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let picks: Vec<usize> = (0..50_000).map(|_| rng.random_range(0..n)).collect();
    let x: Vec<f32> = picks.iter().flat_map(|&i| f.pixel(i)).collect();
    let y: Vec<usize> = picks
        .iter()
        .map(|&i| {
            if rng.random_range(0..10) == 0 {
                rng.random_range(0..3)
            } else {
                truth[i]
            }
        })
        .collect();
    println!(
        "{} training pixels x {dim} features; prediction on {n} pixels",
        y.len()
    );
    println!("| forest | train s | predict s | accuracy | agreement with ours |");
    println!("| --- | --- | --- | --- | --- |");
    let accuracy =
        |pred: &[usize]| pred.iter().zip(&truth).filter(|(a, b)| a == b).count() as f64 / n as f64;

    let t = Instant::now();
    let p = ForestParams {
        trees: TREES,
        max_depth: DEPTH,
        max_per_class: usize::MAX,
        ..Default::default()
    };
    let ours = Forest::train(&x, dim, &y, 3, &p).unwrap();
    let train = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let ours_pred: Vec<usize> = ours
        .predict(&f)
        .unwrap()
        .argmax()
        .into_iter()
        .map(usize::from)
        .collect();
    let predict = t.elapsed().as_secs_f64();
    println!(
        "| pixelclass | {train:.2} | {predict:.2} | {:.4} | 1 |",
        accuracy(&ours_pred)
    );
    let agree = |pred: &[usize]| {
        pred.iter().zip(&ours_pred).filter(|(a, b)| a == b).count() as f64 / n as f64
    };

    // smartcore: row-major dense matrices, labels as u32.
    let t = Instant::now();
    let xm = DenseMatrix::new(y.len(), dim, x.clone(), false).unwrap();
    let ym: Vec<u32> = y.iter().map(|&c| c as u32).collect();
    let sc = RandomForestClassifier::fit(
        &xm,
        &ym,
        RandomForestClassifierParameters::default()
            .with_n_trees(TREES as u16)
            .with_max_depth(DEPTH as u16)
            .with_m((dim as f64).sqrt().ceil() as usize)
            .with_seed(0),
    )
    .unwrap();
    let train = t.elapsed().as_secs_f64();
    let all: Vec<f32> = (0..n).flat_map(|i| f.pixel(i)).collect();
    let t = Instant::now();
    let xa = DenseMatrix::new(n, dim, all, false).unwrap();
    let sc_pred: Vec<usize> = sc
        .predict(&xa)
        .unwrap()
        .into_iter()
        .map(|c| c as usize)
        .collect();
    let predict = t.elapsed().as_secs_f64();
    drop(xa);
    println!(
        "| smartcore | {train:.2} | {predict:.2} | {:.4} | {:.4} |",
        accuracy(&sc_pred),
        agree(&sc_pred)
    );

    // randomforest: f64 rows in a table; one prediction call per pixel (rows in parallel).
    let t = Instant::now();
    let mut tb = randomforest::table::TableBuilder::new();
    for (row, &c) in x.chunks(dim).zip(&y) {
        let r: Vec<f64> = row.iter().map(|&v| v as f64).collect();
        tb.add_row(&r, c as f64).unwrap();
    }
    let table = tb.build().unwrap();
    let rf = randomforest::RandomForestClassifierOptions::new()
        .seed(0)
        .trees(NonZeroUsize::new(TREES).unwrap())
        .max_features(NonZeroUsize::new((dim as f64).sqrt().ceil() as usize).unwrap())
        .fit(randomforest::criterion::Gini, table);
    let train = t.elapsed().as_secs_f64();
    let t = Instant::now();
    use rayon::prelude::*;
    let rf_pred: Vec<usize> = (0..n)
        .into_par_iter()
        .map(|i| {
            let r: Vec<f64> = f.planes.iter().map(|p| p[i] as f64).collect();
            rf.predict(&r) as usize
        })
        .collect();
    let predict = t.elapsed().as_secs_f64();
    println!(
        "| randomforest (no depth limit) | {train:.2} | {predict:.2} | {:.4} | {:.4} |",
        accuracy(&rf_pred),
        agree(&rf_pred)
    );
}
