//! Openings learned from synthetic engravings (issue 23): a small network trained only on
//! `facade::gothic::synth_engraving` sheets, measured on the 27 annotated public-domain images of
//! `data/gothic_devset` (none of which it sees in training).
//!
//! ```text
//! cargo run --release -p facade --example openings_net -- [--seed 1] [--sheets 60] [--steps 600] [--out FILE] [--evaluate FILE] [--maps DIR] [--with-estimator] [--check] [--fit] [--starts]
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
//! the blobs that overlap none of its elements (IoU ≤ 0.5). `--check` trains a check of the
//! blobs on more synthetic sheets (`check.rs`) and scores the blobs it keeps; `--fit` takes the
//! network's P > 0.5 as the window map of the class-driven mode
//! (`gothic::classes::estimate_from_map`) and scores the elements fitted there; `--starts` runs
//! the estimator with more first shapes, each blob's box with three heads, fitted and organised
//! with its own (`gothic::detect::detect_from_starts`, `gothic::organise`). Needs
//! `../shared/data/castle_drawings_pd` for the measurement.

mod check;
#[path = "../gothic_devset.rs"]
#[allow(dead_code)]
mod devset;

use std::path::PathBuf;
use std::time::Instant;

use devset::{ImageKind, Predicted, Score, score};
use facade::gothic::classes::{ClassMapParams, WindowMap, estimate_from_map};
use facade::gothic::synth_engraving::generate;
use facade::gothic::{Theta, detect, detect_elements, organise};
use plan::ink::net::WallNet;
use plan::ink::net_train::{NetParams, train_net};
use plan::ink::train::Sheet;

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
    let (mut with_estimator, mut with_check, mut with_fit) = (false, false, false);
    let mut with_starts = false;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let switch = match a.as_str() {
            "--with-estimator" => Some(&mut with_estimator),
            "--check" => Some(&mut with_check),
            "--fit" => Some(&mut with_fit),
            "--starts" => Some(&mut with_starts),
            _ => None,
        };
        if let Some(on) = switch {
            *on = true;
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
                "unknown (--seed, --sheets, --steps, --out, --evaluate, --maps, --with-estimator, --check, --fit, --starts)",
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
    let forest = with_check.then(|| train_check(&net, seed, sheets));
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
    // The checked blobs of P > 0.5 at each check threshold, alone and with the estimator.
    let mut checked = [[Score::default(); 2]; THRESHOLDS.len()];
    let mut checked_union = [[Score::default(); 2]; THRESHOLDS.len()];
    // Elements fitted on the network's map (the class-driven mode's estimator), alone and with
    // the estimator's.
    let (mut fitted, mut fitted_union) = ([Score::default(); 2], [Score::default(); 2]);
    // The estimator with more first shapes, one set per blob of P > 0.5.
    let mut started = [Score::default(); 2];
    let params = devset::castellan_params(false, false, false);
    for a in &annotated {
        let path = root.join(&a.file);
        let drawing = image::open(&path).unwrap_or_else(|e| fail(&path.display().to_string(), e));
        let (grey, rgb) = (drawing.to_luma8(), drawing.to_rgb8());
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
        // The estimator's detection (§4.2), made once for `--with-estimator` and `--starts`;
        // organised with the check off, it is `gothic::estimate`'s estimate.
        let detection = (with_estimator || with_starts).then(|| {
            detect_elements(&rgb, &params, &|_| {})
                .unwrap_or_else(|e| fail(&path.display().to_string(), e))
        });
        let found = detection.as_ref().filter(|_| with_estimator).map(|d| {
            let est = organise(&d.dt, d.found.clone(), &params);
            let found = devset::predicted(&est);
            estimator[kind].add(&score(&a.elements, &found));
            found
        });
        let mut line = format!("{:66}", a.file);
        let with_found = |b: Vec<Predicted>| {
            let mut both = found.clone().unwrap_or_default();
            let fresh: Vec<Predicted> = b
                .into_iter()
                .filter(|x| both.iter().all(|f| devset::iou(f.bbox, x.bbox) <= 0.5))
                .collect();
            both.extend(fresh);
            score(&a.elements, &both)
        };
        for (k, &t) in THRESHOLDS.iter().enumerate() {
            let b = boxes(&check::blobs(&p, w as usize, h as usize, t));
            let s = score(&a.elements, &b);
            line += &format!(" | P>{t}: {} of {}, {} boxes", s.matched, s.gt, s.pred);
            totals[k][kind].add(&s);
            if found.is_some() {
                union[k][kind].add(&with_found(b));
            }
        }
        if with_fit {
            let map = WindowMap {
                width: w as usize,
                height: h as usize,
                window: p.iter().map(|&v| v > 0.5).collect(),
            };
            let est = estimate_from_map(&rgb, &map, &params, &ClassMapParams::default());
            let elements = devset::predicted(&est);
            fitted[kind].add(&score(&a.elements, &elements));
            fitted_union[kind].add(&with_found(elements));
        }
        if let Some(detection) = detection.filter(|_| with_starts) {
            let starts = blob_starts(&check::blobs(&p, w as usize, h as usize, 0.5));
            let mut found = detection.found;
            found.extend(detect::detect_from_starts(&detection.dt, &starts, &params));
            let est = organise(&detection.dt, found, &params);
            started[kind].add(&score(&a.elements, &devset::predicted(&est)));
        }
        if let Some(forest) = &forest {
            let b = check::blobs(&p, w as usize, h as usize, 0.5);
            let scores: Vec<f32> = check::features(&grey, &p, &b)
                .iter()
                .map(|f| forest.predict_one(f)[1])
                .collect();
            for (k, &tau) in THRESHOLDS.iter().enumerate() {
                let kept: Vec<check::Blob> = b
                    .iter()
                    .zip(&scores)
                    .filter(|(_, s)| **s >= tau)
                    .map(|(b, _)| *b)
                    .collect();
                checked[k][kind].add(&score(&a.elements, &boxes(&kept)));
                checked_union[k][kind].add(&with_found(boxes(&kept)));
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
    if with_fit {
        rows("elements fitted on the map of P > 0.5", &fitted);
        if with_estimator {
            rows(
                "the estimator and the elements fitted on the map",
                &fitted_union,
            );
        }
    }
    if with_starts {
        rows(
            "the estimator with starts from the blobs of P > 0.5",
            &started,
        );
    }
    if forest.is_some() {
        for (k, tau) in THRESHOLDS.iter().enumerate() {
            rows(&format!("blobs of P > 0.5, check ≥ {tau}"), &checked[k]);
            if with_estimator {
                rows(
                    &format!("the estimator and the blobs of P > 0.5, check ≥ {tau}"),
                    &checked_union[k],
                );
            }
        }
    }
}

/// The check of the blobs (`check`): trained on the blobs of P > 0.5 that `net` finds on
/// `sheets` synthetic sheets of their own seeds, each labelled by whether its box meets one of
/// its sheet's elements at IoU ≥ 0.5.
fn train_check(net: &WallNet, seed: u64, sheets: u64) -> pixelclass::forest::Forest {
    let (mut rows, mut labels) = (Vec::new(), Vec::new());
    for s in 0..sheets {
        let (w, h) = (400 + (s * 89 % 400) as u32, 400 + (s * 53 % 400) as u32);
        let sheet = generate(seed.wrapping_mul(10_000).wrapping_add(5_000 + s), w, h);
        let p = net.wall_probability(&sheet.image, w, h);
        let b = check::blobs(&p, w as usize, h as usize, 0.5);
        rows.extend(check::features(&sheet.image, &p, &b));
        labels.extend(b.iter().map(|blob| {
            usize::from(
                sheet
                    .elements
                    .iter()
                    .any(|e| devset::iou(e.bbox, blob.bbox) >= devset::IOU_MIN),
            )
        }));
    }
    let right = labels.iter().sum::<usize>();
    eprintln!(
        "check: {} blobs on {sheets} sheets, {right} right",
        labels.len()
    );
    check::train(&rows, &labels, seed)
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

/// First shapes from blobs: each blob's box with a flat, a round and a pointed head (the
/// estimator's own starts are walked from seeds; `gothic::detect::starts_with`).
fn blob_starts(blobs: &[check::Blob]) -> Vec<Theta> {
    let mut out = Vec::new();
    for b in blobs {
        let [x0, top, x1, y0] = b.bbox;
        let (w, tall) = (x1 - x0, y0 - top);
        for v in [0.0, (w / 2.0).min(tall / 2.0), (0.85 * w).min(0.9 * tall)] {
            out.push(Theta {
                x0,
                y0,
                w,
                h: tall - v,
                v,
            });
        }
    }
    out
}

/// Blobs as element boxes with no parent.
fn boxes(blobs: &[check::Blob]) -> Vec<Predicted> {
    blobs
        .iter()
        .map(|b| Predicted {
            bbox: b.bbox,
            parent: None,
        })
        .collect()
}
