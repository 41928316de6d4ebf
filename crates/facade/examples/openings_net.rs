//! Openings learned from synthetic engravings (issue 23): a small network trained only on
//! `facade::gothic::synth_engraving` sheets, measured on the 27 annotated public-domain images of
//! `data/gothic_devset` (none of which it sees in training).
//!
//! ```text
//! cargo run --release -p facade --example openings_net -- [--seed 1] [--sheets 60] [--steps 600] [--out FILE] [--evaluate FILE] [--maps DIR] [--with-estimator]
//! ```
//!
//! The network is the plan stage's U-Net (`plan::ink::net`, 53 k weights, about 250 px of
//! context), trained by `plan::ink::net_train` as it trains the wall ink (600 steps of six
//! 160-px crops, seeded: the same seed gives the same bytes), with the synthetic sheets'
//! opening masks as the positive class. Each annotated image's P(opening) is thresholded, its
//! 4-connected blobs (at least 30 px and 5 × 7 px) taken as element boxes, and scored as
//! `gothic_devset` scores the estimator (boxes matched one-to-one at IoU ≥ 0.5, difficult
//! elements neither missed nor false). `--out` writes the network, `--evaluate FILE` measures
//! one written before instead of training, `--maps DIR` writes each image's P(opening) as a
//! grey PNG. `--with-estimator` also runs the estimator (`castellan gothic`'s defaults without
//! the learned check, which was trained on these images) and scores it alone and together with
//! the blobs that overlap none of its elements (IoU ≤ 0.5). Needs
//! `../shared/data/castle_drawings_pd` for the measurement.

#[path = "gothic_devset.rs"]
#[allow(dead_code)]
mod devset;

use std::path::PathBuf;
use std::time::Instant;

use devset::{ImageKind, Predicted, Score, score};
use facade::gothic::synth_engraving::generate;
use plan::ink::net::WallNet;
use plan::ink::net_train::{NetParams, train_net};
use plan::ink::train::Sheet;
use raster::components::{Connectivity, components_where};

/// Thresholds of P(opening) the table reports.
const THRESHOLDS: [f32; 3] = [0.3, 0.5, 0.7];

fn fail(what: &str, why: impl std::fmt::Display) -> ! {
    eprintln!("openings_net: {what}: {why}");
    std::process::exit(2)
}

fn main() {
    let (mut seed, mut sheets, mut steps) = (1u64, 60u64, 600usize);
    let (mut out, mut evaluate, mut maps): (Option<PathBuf>, Option<PathBuf>, Option<PathBuf>) =
        (None, None, None);
    let mut with_estimator = false;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "--with-estimator" {
            with_estimator = true;
            continue;
        }
        let v = args.next().unwrap_or_else(|| fail(&a, "needs a value"));
        match a.as_str() {
            "--seed" => seed = v.parse().unwrap_or_else(|e| fail(&a, e)),
            "--sheets" => sheets = v.parse().unwrap_or_else(|e| fail(&a, e)),
            "--steps" => steps = v.parse().unwrap_or_else(|e| fail(&a, e)),
            "--out" => out = Some(v.into()),
            "--evaluate" => evaluate = Some(v.into()),
            "--maps" => maps = Some(v.into()),
            _ => fail(
                &a,
                "unknown (--seed, --sheets, --steps, --out, --evaluate, --maps, --with-estimator)",
            ),
        }
    }
    let net = match &evaluate {
        Some(f) => {
            let bytes = std::fs::read(f).unwrap_or_else(|e| fail(&f.display().to_string(), e));
            WallNet::from_bytes(&bytes).unwrap_or_else(|e| fail(&f.display().to_string(), e))
        }
        None => {
            let t = Instant::now();
            let synthetic: Vec<Sheet> = (0..sheets)
                .map(|s| {
                    // Sizes 400–800 px a side, as the annotated images are.
                    let (w, h) = (400 + (s * 97 % 400) as u32, 400 + (s * 61 % 400) as u32);
                    let sheet = generate(seed.wrapping_mul(10_000).wrapping_add(s), w, h);
                    Sheet {
                        grey: sheet.image,
                        truth: sheet.openings,
                    }
                })
                .collect();
            let np = NetParams {
                seed,
                steps,
                ..NetParams::default()
            };
            let provenance = format!(
                "openings_net: {sheets} synthetic engravings (facade::gothic::synth_engraving), seed {seed}, {steps} steps"
            );
            let (net, bytes) = train_net(&[], &synthetic, &np, &provenance, &mut |s, loss| {
                if s % 100 == 0 {
                    eprintln!("step {s}: loss {loss:.3}");
                }
            })
            .unwrap_or_else(|e| fail("training", e));
            eprintln!("trained in {:.0} s", t.elapsed().as_secs_f64());
            if let Some(f) = &out {
                std::fs::write(f, &bytes).unwrap_or_else(|e| fail(&f.display().to_string(), e));
            }
            net
        }
    };
    let root = devset::images_root();
    if !root.is_dir() {
        eprintln!("skipped: {} not found", root.display());
        return;
    }
    let annotated = devset::read_annotations(&devset::annotations_path())
        .unwrap_or_else(|e| fail("annotations", e));
    // Per threshold: engravings, photos.
    let mut totals = [[Score::default(); 2]; THRESHOLDS.len()];
    // The estimator alone, and with the blobs at each threshold (engravings, photos).
    let mut estimator = [Score::default(); 2];
    let mut union = [[Score::default(); 2]; THRESHOLDS.len()];
    let params = devset::castellan_params(false, false, false);
    for a in &annotated {
        let path = root.join(&a.file);
        let grey = image::open(&path)
            .unwrap_or_else(|e| fail(&path.display().to_string(), e))
            .to_luma8();
        let (w, h) = grey.dimensions();
        let p = net.wall_probability(&grey, w, h);
        if let Some(dir) = &maps {
            let img = image::GrayImage::from_fn(w, h, |x, y| {
                image::Luma([(p[(y * w + x) as usize] * 255.0).round() as u8])
            });
            let name = a.file.replace('/', "_");
            img.save(dir.join(format!("{name}.png")))
                .unwrap_or_else(|e| fail(&name, e));
        }
        let kind = usize::from(a.kind == ImageKind::Photo);
        let found = with_estimator.then(|| {
            let rgb = image::open(&path)
                .unwrap_or_else(|e| fail(&path.display().to_string(), e))
                .to_rgb8();
            let est = facade::gothic::estimate(&rgb, &params)
                .unwrap_or_else(|e| fail(&path.display().to_string(), e));
            let found = devset::predicted(&est);
            estimator[kind].add(&score(&a.elements, &found));
            found
        });
        let mut line = format!("{:66}", a.file);
        for (k, &t) in THRESHOLDS.iter().enumerate() {
            let b = blobs(&p, w as usize, h as usize, t);
            let s = score(&a.elements, &b);
            line += &format!(" | P>{t}: {} of {}, {} boxes", s.matched, s.gt, s.pred);
            totals[k][kind].add(&s);
            if let Some(found) = &found {
                let mut both = found.clone();
                both.extend(
                    b.into_iter()
                        .filter(|x| found.iter().all(|f| devset::iou(f.bbox, x.bbox) <= 0.5)),
                );
                union[k][kind].add(&score(&a.elements, &both));
            }
        }
        println!("{line}");
    }
    println!();
    println!("| elements | images | recall | precision | boxes |");
    println!("| --- | --- | --- | --- | --- |");
    if with_estimator {
        rows("the estimator (no check)", &estimator);
    }
    for (k, t) in THRESHOLDS.iter().enumerate() {
        rows(&format!("blobs of P(opening) > {t}"), &totals[k]);
        if with_estimator {
            rows(
                &format!("the estimator and the blobs of P > {t}"),
                &union[k],
            );
        }
    }
}

/// Three table rows: engravings, photos and all.
fn rows(what: &str, by_kind: &[Score; 2]) {
    let mut all = Score::default();
    for (s, name) in by_kind.iter().zip(["engravings", "photos"]) {
        all.add(s);
        row(what, name, s);
    }
    row(what, "all", &all);
}

fn row(what: &str, images: &str, s: &Score) {
    let counted = s.pred - s.pred_on_difficult;
    println!(
        "| {what} | {images} | {} | {} | {} |",
        pct(s.recall(), s.matched, s.gt),
        pct(s.precision(), s.matched, counted),
        s.pred
    );
}

fn pct(v: Option<f64>, n: usize, of: usize) -> String {
    v.map_or("–".into(), |v| format!("{:.1} % ({n}/{of})", 100.0 * v))
}

/// The 4-connected blobs of `p > t` of at least 30 pixels and 5 × 7 px, as element boxes
/// [x0, y0, x1, y1) with no parent.
fn blobs(p: &[f32], w: usize, h: usize, t: f32) -> Vec<Predicted> {
    let c = components_where(w, h, Connectivity::Four, |i| p[i] > t);
    (1..c.sizes.len())
        .filter(|&l| {
            let b = c.bbox[l];
            c.sizes[l] >= 30 && b[2] - b[0] >= 4 && b[3] - b[1] >= 6
        })
        .map(|l| {
            let b = c.bbox[l].map(f64::from);
            Predicted {
                bbox: [b[0], b[1], b[2] + 1.0, b[3] + 1.0],
                parent: None,
            }
        })
        .collect()
}
