//! Accuracy on CMP base and Paris Art-deco (../shared/data): a simulated user draws three
//! seeded 9-pixel boxes per class inside the ground truth; we report pixel accuracy and window
//! IoU of the GMM labels alone and of the fitted façade model, and the time per image.
//!
//! `cargo run --release -p facade --example evaluate [MAX_IMAGES_PER_SET]`

use std::path::{Path, PathBuf};
use std::time::Instant;

use facade::classify::{Class, ClassifyParams, Method, classify};
use facade::eval::{IGNORE, class_iou, pixel_accuracy, simulate_user_inside};
use facade::search::{SearchParams, parse};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data")
}

/// CMP masks are palette PNGs; the image crate expands them to RGB, so map the palette back.
fn cmp_truth(path: &Path) -> Option<Vec<u8>> {
    let img = image::open(path).ok()?.to_rgb8();
    Some(facade::eval::cmp_classes(&img))
}

/// Art-deco labels: Door 0, Shop 1, Balcony 2, Window 3, Wall 4, Sky 5, Roof 6, -1 void.
fn artdeco_truth(path: &Path) -> Option<Vec<u8>> {
    let text = std::fs::read_to_string(path).ok()?;
    Some(
        text.split_whitespace()
            .map(|v| match v.parse::<i32>() {
                Ok(3) => 2,
                Ok(0 | 1 | 2 | 4) => 1,
                Ok(5 | 6) => 0,
                _ => IGNORE,
            })
            .collect(),
    )
}

/// Overrides for experiments: FACADE_BOX (box side, default 9), FACADE_MARGIN (clearance of the
/// boxes from their class's border, default 0), FACADE_RIDGE_REL, FACADE_PCS
/// (principal components per channel), FACADE_CLASSIFIER (gmm or forest, default forest).
fn box_side() -> usize {
    env_usize("FACADE_BOX", 9)
}

fn env_usize(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
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
    p
}

#[derive(Default)]
struct Sums {
    n: usize,
    acc0: f64,
    iou0: f64,
    acc: f64,
    iou: f64,
    secs: f64,
}

fn run(name: &str, items: Vec<(PathBuf, Vec<u8>)>) {
    let mut s = Sums::default();
    for (img_path, truth) in items {
        let img = image::open(&img_path).unwrap().to_rgb8();
        let (w, h) = (img.width() as usize, img.height() as usize);
        if truth.len() != w * h {
            eprintln!("{}: label size mismatch, skipped", img_path.display());
            continue;
        }
        let Ok(training) = simulate_user_inside(
            &truth,
            w,
            h,
            3,
            box_side(),
            env_usize("FACADE_MARGIN", 0),
            1,
        ) else {
            continue;
        };
        let t = Instant::now();
        let ll = match classify(&img, &training, &classify_params()) {
            Ok(ll) => ll,
            Err(e) => {
                eprintln!("{}: {e}", img_path.display());
                continue;
            }
        };
        let model = parse(&img, &ll, &SearchParams::default()).unwrap();
        s.secs += t.elapsed().as_secs_f64();
        let gmm: Vec<u8> = ll.initial_labels().iter().map(|c| *c as u8).collect();
        let pred = model.labels();
        if let Ok(dir) = std::env::var("FACADE_DUMP") {
            let stem = img_path.file_stem().unwrap().to_string_lossy().to_string();
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
            grey(&gmm).save(format!("{dir}/{stem}_gmm.png")).unwrap();
            grey(&pred).save(format!("{dir}/{stem}_model.png")).unwrap();
            println!("{stem}: {:?}", training.classes);
        }
        s.n += 1;
        s.acc0 += pixel_accuracy(&gmm, &truth);
        s.iou0 += class_iou(&gmm, &truth, Class::Window).unwrap_or(0.0);
        s.acc += pixel_accuracy(&pred, &truth);
        s.iou += class_iou(&pred, &truth, Class::Window).unwrap_or(0.0);
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
}

fn main() {
    let max: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(usize::MAX);
    let d = data();
    if !d.is_dir() {
        eprintln!("no ../shared/data next to the repository; nothing to evaluate");
        return;
    }
    println!(
        "| set | images | GMM pixel acc. | GMM window IoU | model pixel acc. | model window IoU | s / image |"
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
}
