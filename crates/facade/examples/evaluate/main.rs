//! Accuracy on CMP base, Paris Art-deco and LabelMeFacade (oblique photos, rectified first by
//! §3.1.1 with their labels) (../shared/data, or the folder in FACADE_DATA): a
//! simulated user draws training boxes inside the ground truth; we report pixel accuracy and
//! window IoU of the per-pixel map alone and of the fitted façade tree, and the time per image.
//!
//! `cargo run --release -p facade --example evaluate [MAX_IMAGES_PER_SET]`
//!
//! Environment (experiments; defaults are the documented table):
//! - FACADE_USER=boxes|windows: three s × s boxes per class (default), or whole-window boxes
//!   (up to three ground-truth window components) with s × s boxes for wall and background.
//! - FACADE_BOX (s, default 9), FACADE_MARGIN (default 0), FACADE_RIDGE_REL, FACADE_PCS,
//!   FACADE_CLASSIFIER (gmm or forest, default forest); FACADE_INNER,
//!   FACADE_RING: how whole-window boxes are sampled (`window_inner`, `window_ring`);
//!   FACADE_SAMPLES: pixels drawn from each box (`samples_per_box`).
//! - FACADE_MAP=model|oracle: the classifier's map (default), or an experiment map made from
//!   the ground truth (log-ratio ±FACADE_ORACLE_GAP, default 2, plus smooth Gaussian noise of
//!   standard deviation FACADE_ORACLE_NOISE, default 2, and FACADE_ORACLE_FLIPS blobs of a
//!   wrong class per image, default 20) to measure the search alone.
//! - FACADE_GRAMMAR=text|columns|rows|columns-or-rows: the search's grammar
//!   (`facade::search::Grammar`; default columns-or-rows); FACADE_CLIP, FACADE_PENALTY, FACADE_MIN_WINDOW,
//!   FACADE_COLUMN_COST, FACADE_WINDOW_BIAS, FACADE_ROUNDS, FACADE_MIN_FACADE, FACADE_MERGE: `SearchParams`.
//! - FACADE_REPEAT=0|1: the repeat step of `facade::parse_photo` (proposals from whole-window
//!   boxes added to the window evidence, weight FACADE_REPEAT_WEIGHT, acceptance
//!   FACADE_REPEAT_THRESHOLD); prints the proposals' precision and recall.
//! - FACADE_GROW=0|1: small window boxes grown into whole windows on a first map
//!   (`facade::grow`), FACADE_GROW_THRESHOLD, FACADE_GROW_MAX, FACADE_GROW_MIN, FACADE_GROW_SNAP: `GrowParams`;
//!   FACADE_GROW_DIAG=1 prints how the boxes grew against their true windows.
//! - FACADE_AC=0|1, FACADE_AC_FOLDS, FACADE_AC_ROWCOL, FACADE_AC_SIGMAS, FACADE_AC_FOLD_TREES,
//!   FACADE_AC_AVERAGE:
//!   the forest's autocontext stage (`pixelclass::AutoContext`).
//! - FACADE_DIAG=1: per-set diagnostics of the map and the tree.
//! - FACADE_DUMP=dir: truth, map and tree label images per photo.
//!
//! Each set's line on stderr also says how many photos `facade::plausibility` warns of and
//! their tree window IoU against the others' (docs/facade.md, "Plausibility warnings").

use std::path::PathBuf;
use std::time::Instant;

use facade::classify::{Class, ClassifyParams, LogLikelihoods, Method, Training};
use facade::eval::{IGNORE, class_iou, pixel_accuracy, simulate_user_inside, simulate_window_user};
use facade::parse_photo;
use facade::repeat::{RepeatParams, Repeats};
use facade::search::{SearchParams, parse};

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod truth;
use truth::{artdeco_truth, cmp_truth, data, rectified_labelme};

fn env_usize(name: &str, default: usize) -> usize {
    env_f64(name, default as f64) as usize
}

fn env_f64(name: &str, default: f64) -> f64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn env_str(name: &str, default: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| default.to_string())
}

fn classify_params() -> ClassifyParams {
    let mut p = ClassifyParams::default();
    if std::env::var("FACADE_CLASSIFIER").as_deref() == Ok("gmm") {
        p.method = Method::Gmm;
    }
    if let Some(r) = std::env::var("FACADE_RIDGE_REL")
        .ok()
        .and_then(|v| v.parse().ok())
    {
        p.ridge_rel = r;
    }
    if let Some(k) = std::env::var("FACADE_PCS")
        .ok()
        .and_then(|v| v.parse().ok())
    {
        p.features.components = k;
    }
    p.window_inner = env_f64("FACADE_INNER", p.window_inner);
    p.window_ring = env_f64("FACADE_RING", p.window_ring);
    p.samples_per_box = env_usize("FACADE_SAMPLES", p.samples_per_box);
    // FACADE_AC=0|1 (autocontext off/on; unset: the default), FACADE_AC_FOLDS,
    // FACADE_AC_ROWCOL=0|1, FACADE_AC_SIGMAS (comma-separated), FACADE_AC_FOLD_TREES, FACADE_AC_AVERAGE=0|1.
    if let Ok(v) = std::env::var("FACADE_AC") {
        p.pixel.autocontext = (v == "1").then(|| p.pixel.autocontext.clone().unwrap_or_default());
    }
    if let Some(ac) = &mut p.pixel.autocontext {
        ac.folds = env_usize("FACADE_AC_FOLDS", ac.folds);
        ac.fold_trees = env_usize("FACADE_AC_FOLD_TREES", ac.fold_trees);
        ac.average = env_usize("FACADE_AC_AVERAGE", ac.average as usize) == 1;
        ac.row_column = env_usize("FACADE_AC_ROWCOL", ac.row_column as usize) == 1;
        if let Ok(v) = std::env::var("FACADE_AC_SIGMAS") {
            ac.sigmas = v.split(',').filter_map(|s| s.parse().ok()).collect();
        }
    }
    p
}

fn search_params() -> SearchParams {
    use facade::search::Grammar;
    let mut p = match env_str("FACADE_GRAMMAR", "columns-or-rows").as_str() {
        "text" => SearchParams::text(),
        name => {
            let grammar = match name {
                "columns" => Grammar::Columns,
                "rows" => Grammar::Rows,
                "columns-or-rows" => Grammar::ColumnsOrRows,
                other => panic!("FACADE_GRAMMAR={other}: text, columns, rows or columns-or-rows"),
            };
            SearchParams {
                grammar,
                ..SearchParams::default()
            }
        }
    };
    p.clip = env_f64("FACADE_CLIP", p.clip);
    p.facade_penalty = env_f64("FACADE_PENALTY", p.facade_penalty);
    p.min_window_frac = env_f64("FACADE_MIN_WINDOW", p.min_window_frac);
    p.column_cost = env_f64("FACADE_COLUMN_COST", p.column_cost);
    p.window_bias = env_f64("FACADE_WINDOW_BIAS", p.window_bias);
    p.rounds = env_usize("FACADE_ROUNDS", p.rounds);
    p.min_facade_frac = env_f64("FACADE_MIN_FACADE", p.min_facade_frac);
    p.merge_tolerance = env_f64("FACADE_MERGE", p.merge_tolerance);
    p
}

/// An experiment map from the ground truth: the true class gets +gap/2, the others −gap/2,
/// plus smooth noise (white noise box-blurred over 7 px, rescaled to `sigma`) per class, plus
/// `flips` discs (radius 3–20 px) where a wrong class gets +gap.
fn oracle(truth: &[u8], w: usize, h: usize, seed: u64) -> LogLikelihoods {
    let gap = env_f64("FACADE_ORACLE_GAP", 2.0) as f32;
    let sigma = env_f64("FACADE_ORACLE_NOISE", 2.0) as f32;
    let flips = env_usize("FACADE_ORACLE_FLIPS", 20);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut maps: [Option<Vec<f32>>; 3] = [None, None, None];
    for (ci, map) in maps.iter_mut().enumerate() {
        let white: Vec<f32> = (0..w * h).map(|_| rng.random_range(-1.0f32..1.0)).collect();
        let blur = box_blur(&white, w, h, 3);
        let var = blur.iter().map(|v| v * v).sum::<f32>() / blur.len().max(1) as f32;
        let k = sigma / var.sqrt().max(1e-9);
        *map = Some(
            truth
                .iter()
                .zip(&blur)
                .map(|(&t, &n)| {
                    let base = if t == IGNORE {
                        0.0
                    } else if t as usize == ci {
                        gap / 2.0
                    } else {
                        -gap / 2.0
                    };
                    base + k * n
                })
                .collect(),
        );
    }
    for _ in 0..flips {
        let (cx, cy) = (rng.random_range(0..w), rng.random_range(0..h));
        let r = rng.random_range(3..=20usize);
        let t = truth[cy * w + cx];
        if t == IGNORE {
            continue;
        }
        let wrong = (t as usize + rng.random_range(1..=2usize)) % 3;
        let m = maps[wrong].as_mut().unwrap();
        for y in cy.saturating_sub(r)..(cy + r + 1).min(h) {
            for x in cx.saturating_sub(r)..(cx + r + 1).min(w) {
                if (x.abs_diff(cx)).pow(2) + (y.abs_diff(cy)).pow(2) <= r * r {
                    m[y * w + x] += gap;
                }
            }
        }
    }
    LogLikelihoods {
        width: w,
        height: h,
        maps,
    }
}

fn box_blur(v: &[f32], w: usize, h: usize, r: usize) -> Vec<f32> {
    let pass = |src: &[f32], horizontal: bool| -> Vec<f32> {
        let mut out = vec![0f32; src.len()];
        let (n, m) = if horizontal { (h, w) } else { (w, h) };
        for a in 0..n {
            let at = |b: usize| if horizontal { a * w + b } else { b * w + a };
            for b in 0..m {
                let (lo, hi) = (b.saturating_sub(r), (b + r + 1).min(m));
                out[at(b)] = (lo..hi).map(|c| src[at(c)]).sum::<f32>() / (hi - lo) as f32;
            }
        }
        out
    };
    pass(&pass(v, true), false)
}

/// The simulated user of FACADE_USER.
fn user(truth: &[u8], w: usize, h: usize) -> Option<Training> {
    let side = env_usize("FACADE_BOX", 9);
    if env_str("FACADE_USER", "boxes") == "windows" {
        return simulate_window_user(truth, w, h, 3, 3, side, 1).ok();
    }
    simulate_user_inside(truth, w, h, 3, side, env_usize("FACADE_MARGIN", 0), 1).ok()
}

/// FACADE_REPEAT=0|1 (default: the library's, on when `RepeatParams::evidence` > 0): the
/// repeat step of `facade::parse_photo`, with weight FACADE_REPEAT_WEIGHT (default the
/// library's, or 1 when that is 0) and acceptance FACADE_REPEAT_THRESHOLD.
fn repeat_params() -> RepeatParams {
    let d = RepeatParams::default();
    let on = env_str("FACADE_REPEAT", if d.evidence > 0.0 { "1" } else { "0" }) == "1";
    let weight = if d.evidence > 0.0 { d.evidence } else { 1.0 };
    RepeatParams {
        threshold: env_f64("FACADE_REPEAT_THRESHOLD", d.threshold),
        evidence: if on {
            env_f64("FACADE_REPEAT_WEIGHT", weight)
        } else {
            0.0
        },
        grow: (env_str("FACADE_GROW", if d.grow.is_some() { "1" } else { "0" }) == "1").then(
            || {
                let g = d.grow.unwrap_or_default();
                facade::grow::GrowParams {
                    threshold: env_f64("FACADE_GROW_THRESHOLD", g.threshold),
                    max_frac: env_f64("FACADE_GROW_MAX", g.max_frac),
                    min_growth: env_f64("FACADE_GROW_MIN", g.min_growth),
                    snap: env_f64("FACADE_GROW_SNAP", g.snap),
                }
            },
        ),
        ..d
    }
}

/// The repeats beyond the user's boxes, and how many match a true window (IoU > 0.5), and
/// the true windows.
fn repeat_stats(
    r: &Repeats,
    user: &Training,
    truth: &[u8],
    w: usize,
    h: usize,
) -> (usize, usize, usize) {
    let wins = user
        .classes
        .get(&Class::Window)
        .cloned()
        .unwrap_or_default();
    let comps = raster_boxes(truth, w, h);
    let new: Vec<&[f64; 4]> = r.windows.iter().filter(|b| !wins.contains(b)).collect();
    let good = new
        .iter()
        .filter(|b| comps.iter().any(|c| box_iou(b, c) > 0.5))
        .count();
    (new.len(), good, comps.len())
}

/// Bounding boxes of the true windows (8-connected components of the window class).
fn raster_boxes(truth: &[u8], w: usize, h: usize) -> Vec<[f64; 4]> {
    let c =
        raster::components::components_where(w, h, raster::components::Connectivity::Eight, |i| {
            truth[i] == 2
        });
    c.bbox[1..]
        .iter()
        .map(|b| {
            [
                b[0] as f64,
                b[1] as f64,
                b[2] as f64 + 1.0,
                b[3] as f64 + 1.0,
            ]
        })
        .collect()
}

fn box_iou(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    let iw = (a[2].min(b[2]) - a[0].max(b[0])).max(0.0);
    let ih = (a[3].min(b[3]) - a[1].max(b[1])).max(0.0);
    let area = |r: &[f64; 4]| (r[2] - r[0]) * (r[3] - r[1]);
    iw * ih / (area(a) + area(b) - iw * ih).max(1e-12)
}

#[derive(Default)]
struct Sums {
    n: usize,
    acc0: f64,
    iou0: f64,
    acc: f64,
    iou: f64,
    secs: f64,
    diag: Diag,
    proposals: usize,
    good: usize,
    true_windows: usize,
    grow: [f64; 5],
    /// Photos whose model `facade::plausibility` warns of, and their tree window IoU summed.
    warned: usize,
    warned_iou: f64,
}

/// FACADE_DIAG: where the tree loses against the map.
#[derive(Default)]
struct Diag {
    /// Truth window / wall pixels: count, with window − wall log-ratio > 0, Σ ratio clipped.
    win_px: f64,
    win_pos: f64,
    wall_px: f64,
    wall_pos: f64,
    /// Façade pixels (truth wall or window) the tree calls background, and background it calls
    /// façade, as fractions of the labelled pixels.
    lost_facade: f64,
    eaten_bg: f64,
    /// Window pixels inside the tree's façades only (the grid's own errors).
    grid_iou: f64,
    n_w: f64,
    n_l: f64,
    facades: f64,
}

fn diagnose(d: &mut Diag, ll: &LogLikelihoods, truth: &[u8], pred: &[u8]) {
    let (win, wall) = (ll.get(Class::Window).unwrap(), ll.get(Class::Wall).unwrap());
    let mut n = 0.0;
    let (mut lost, mut eaten) = (0.0, 0.0);
    let (mut inter, mut union) = (0.0, 0.0);
    for k in 0..truth.len() {
        let t = truth[k];
        if t == IGNORE {
            continue;
        }
        n += 1.0;
        let r = win[k] - wall[k];
        if t == 2 {
            d.win_px += 1.0;
            d.win_pos += (r > 0.0) as u8 as f64;
        } else if t == 1 {
            d.wall_px += 1.0;
            d.wall_pos += (r > 0.0) as u8 as f64;
        }
        lost += (t != 0 && pred[k] == 0) as u8 as f64;
        eaten += (t == 0 && pred[k] != 0) as u8 as f64;
        if pred[k] != 0 && t != 0 {
            inter += (t == 2 && pred[k] == 2) as u8 as f64;
            union += (t == 2 || pred[k] == 2) as u8 as f64;
        }
    }
    d.lost_facade += lost / n;
    d.eaten_bg += eaten / n;
    d.grid_iou += if union > 0.0 { inter / union } else { 0.0 };
}

/// FACADE_GROW_DIAG=1: how the user's window boxes grow on the first map (`facade::grow`),
/// against the bounding box of the true window component under each box's centre: boxes,
/// dropped, summed IoU, grown boxes inside / around their window's box.
fn grow_diag(
    img: &image::RgbImage,
    training: &Training,
    truth: &[u8],
    w: usize,
    h: usize,
    acc: &mut [f64; 5],
) {
    let Some(g) = repeat_params().grow else {
        return;
    };
    let Ok(ll) = facade::classify::classify(img, training, &classify_params()) else {
        return;
    };
    let Ok(mut boxes) = training.boxes(w, h) else {
        return;
    };
    let Some(wins) = boxes.remove(&Class::Window) else {
        return;
    };
    let comps =
        raster::components::components_where(w, h, raster::components::Connectivity::Eight, |i| {
            truth[i] == Class::Window as u8
        });
    let Some(grown) = facade::grow::grow_on(img, &ll, &wins, &g) else {
        return;
    };
    for (b, grown) in wins.iter().zip(grown) {
        acc[0] += 1.0;
        let (cx, cy) = ((b[0] + b[2]) / 2, (b[1] + b[3]) / 2);
        let l = comps.labels[cy * w + cx] as usize;
        let Some(gb) = grown else {
            acc[1] += 1.0;
            continue;
        };
        if l == 0 {
            continue;
        }
        let t = comps.bbox[l];
        let t = [t[0], t[1], t[2] + 1, t[3] + 1].map(|v| v as usize);
        acc[2] += box_iou(&gb.map(|v| v as f64), &t.map(|v| v as f64));
        let within = |a: &[usize; 4], b: &[usize; 4]| {
            a[0] >= b[0] && a[1] >= b[1] && a[2] <= b[2] && a[3] <= b[3]
        };
        acc[3] += within(&gb, &t) as u8 as f64;
        acc[4] += within(&t, &gb) as u8 as f64;
    }
}

fn run(name: &str, items: Vec<(PathBuf, Vec<u8>)>) {
    let mut s = Sums::default();
    let use_oracle = env_str("FACADE_MAP", "model") == "oracle";
    for (i, (img_path, truth)) in items.into_iter().enumerate() {
        let img = image::open(&img_path).unwrap().to_rgb8();
        let (w, h) = (img.width() as usize, img.height() as usize);
        if truth.len() != w * h {
            eprintln!("{}: label size mismatch, skipped", img_path.display());
            continue;
        }
        let Some(training) = user(&truth, w, h) else {
            continue;
        };
        if env_str("FACADE_GROW_DIAG", "0") == "1" {
            grow_diag(&img, &training, &truth, w, h, &mut s.grow);
        }
        let t = Instant::now();
        let (ll, model) = if use_oracle {
            let ll = oracle(&truth, w, h, i as u64 + 1);
            let model = parse(&img, &ll, &search_params()).unwrap();
            (ll, model)
        } else {
            match parse_photo(
                &img,
                &training,
                &classify_params(),
                &search_params(),
                &repeat_params(),
            ) {
                Ok((ll, model, repeats)) => {
                    if let Some(r) = repeats {
                        let (n, good, truth_n) = repeat_stats(&r, &training, &truth, w, h);
                        s.proposals += n;
                        s.good += good;
                        s.true_windows += truth_n;
                    }
                    (ll, model)
                }
                Err(e) => {
                    eprintln!("{}: {e}", img_path.display());
                    continue;
                }
            }
        };
        s.secs += t.elapsed().as_secs_f64();
        let map: Vec<u8> = ll.initial_labels().iter().map(|c| *c as u8).collect();
        let pred = model.labels();
        let stem = img_path.file_stem().unwrap().to_string_lossy().to_string();
        if let Ok(dir) = std::env::var("FACADE_DUMP") {
            let grey = |v: &[u8]| {
                image::GrayImage::from_raw(
                    w as u32,
                    h as u32,
                    v.iter().map(|l| l.saturating_mul(100)).collect(),
                )
                .unwrap()
            };
            grey(&truth)
                .save(format!("{dir}/{stem}_truth.png"))
                .unwrap();
            grey(&map).save(format!("{dir}/{stem}_map.png")).unwrap();
            grey(&pred).save(format!("{dir}/{stem}_model.png")).unwrap();
        }
        s.n += 1;
        let (a0, i0) = (
            pixel_accuracy(&map, &truth),
            class_iou(&map, &truth, Class::Window).unwrap_or(0.0),
        );
        let (a1, i1) = (
            pixel_accuracy(&pred, &truth),
            class_iou(&pred, &truth, Class::Window).unwrap_or(0.0),
        );
        s.acc0 += a0;
        s.iou0 += i0;
        s.acc += a1;
        s.iou += i1;
        if !facade::plausibility::check(&model, &training).is_empty() {
            s.warned += 1;
            s.warned_iou += i1;
        }
        if std::env::var("FACADE_DIAG").is_ok() {
            diagnose(&mut s.diag, &ll, &truth, &pred);
            for f in &model.facades {
                s.diag.n_w += f.params.n_w as f64;
                s.diag.n_l += f.params.n_l as f64;
            }
            s.diag.facades += model.facades.len() as f64;
            let fs: Vec<String> = model
                .facades
                .iter()
                .map(|f| {
                    let p = &f.params;
                    format!(
                        "[{:.0},{:.0},{:.0},{:.0}] n_l {} n_w {} w_w {:.0} gap {:.0}",
                        p.x_fl, p.y_ft, p.x_fr, p.y_fb, p.n_l, p.n_w, p.w_w, p.w_gap
                    )
                })
                .collect();
            eprintln!(
                "{stem} {w}x{h}: map {a0:.3}/{i0:.3} tree {a1:.3}/{i1:.3} {}",
                fs.join("; ")
            );
        }
    }
    let n = s.n.max(1) as f64;
    println!(
        "| {name} | {} | {:.3} | {:.3} | {:.3} | {:.3} | {:.2} |",
        s.n,
        s.acc0 / n,
        s.iou0 / n,
        s.acc / n,
        s.iou / n,
        s.secs / n
    );
    // Which photos `castellan facade` would warn of (`facade::plausibility`), and whether
    // they are the bad ones: their tree window IoU against the others'.
    let others = (s.n - s.warned).max(1) as f64;
    eprintln!(
        "{name}: {} of {} warned, tree window IoU {:.3} against {:.3}",
        s.warned,
        s.n,
        s.warned_iou / s.warned.max(1) as f64,
        (s.iou - s.warned_iou) / others
    );
    if s.proposals > 0 || repeat_params().evidence > 0.0 {
        eprintln!(
            "{name}: repeats proposed {} (beyond the user's), {} match a true window (IoU > 0.5): precision {:.3}, recall {:.3} of {} true windows",
            s.proposals,
            s.good,
            s.good as f64 / s.proposals.max(1) as f64,
            s.good as f64 / s.true_windows.max(1) as f64,
            s.true_windows
        );
    }
    if s.grow[0] > 0.0 {
        let g = &s.grow;
        eprintln!(
            "{name}: window boxes grown {} of {}; mean IoU with their window's box {:.3}; inside it {}, around it {}",
            g[0] - g[1],
            g[0],
            g[2] / (g[0] - g[1]).max(1.0),
            g[3],
            g[4]
        );
    }
    if std::env::var("FACADE_DIAG").is_ok() {
        let d = &s.diag;
        eprintln!(
            "{name}: window px with ratio > 0: {:.3}; wall px with ratio > 0: {:.3}; façade lost to background {:.3}, background eaten {:.3}; window IoU inside both façades {:.3}; façades/image {:.2}, mean n_l {:.2}, n_w {:.2}",
            d.win_pos / d.win_px.max(1.0),
            d.wall_pos / d.wall_px.max(1.0),
            d.lost_facade / n,
            d.eaten_bg / n,
            d.grid_iou / n,
            d.facades / n,
            d.n_l / d.facades.max(1.0),
            d.n_w / d.facades.max(1.0),
        );
    }
}

fn main() {
    let max: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(usize::MAX);
    let d = data();
    if !d.is_dir() {
        eprintln!(
            "no data folder at {} (set FACADE_DATA); nothing to evaluate",
            d.display()
        );
        return;
    }
    println!(
        "| set | images | map pixel acc. | map window IoU | tree pixel acc. | tree window IoU | s / image |"
    );
    println!("| --- | --- | --- | --- | --- | --- | --- |");
    let mut cmp: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let mut names: Vec<PathBuf> = std::fs::read_dir(d.join("cmp_facade_base/base"))
        .map(|r| r.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    names.sort();
    for p in names
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "jpg"))
        .take(max)
    {
        if let Some(t) = cmp_truth(&p.with_extension("png")) {
            cmp.push((p.clone(), t));
        }
    }
    run("CMP base", cmp);
    let mut art = Vec::new();
    for n in (1..=77).step_by(4).take(max) {
        let img = d.join(format!("paris_artdeco_facades/images/facade_{n}.png"));
        if let Some(t) =
            artdeco_truth(&d.join(format!("paris_artdeco_facades/labels/facade_{n}.txt")))
        {
            art.push((img, t));
        }
    }
    run("Paris Art-deco", art);
    let lm = d.join("labelmefacade");
    let dir = std::env::temp_dir().join(format!("castellan-labelme-{}", std::process::id()));
    let mut photos: Vec<PathBuf> = std::fs::read_dir(lm.join("images"))
        .map(|r| r.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    photos.sort();
    if !photos.is_empty() && std::fs::create_dir_all(&dir).is_ok() {
        let mut items = Vec::new();
        for p in photos.iter().take(max) {
            let labels = lm
                .join("labels")
                .join(p.file_name().unwrap_or_default())
                .with_extension("png");
            match rectified_labelme(p, &labels, &dir) {
                Ok(item) => items.push(item),
                Err(e) => eprintln!("{}: not rectified ({e}), left out", p.display()),
            }
        }
        run("LabelMeFacade (rectified)", items);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
