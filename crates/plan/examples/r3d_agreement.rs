//! Wall-pixel agreement with the R3D / DeepFloorplan wall masks (research data, read from
//! `../shared/data`, never copied): for each plan, precision, recall and IoU of the pixels
//! labelled as walls against `<id>_wall.png`, and whether a courtyard (closed outer wall) was
//! found; and the IoU of the wall mask chapter 5 parsed (`ParsedPlan::walls`, the learned wall
//! ink or the rules' threshold after §5.1.2) and of Otsu's bare threshold, against the same
//! masks, and of the learned wall ink's own P(wall) > 0.5. Run: `cargo run --release -p plan --example r3d_agreement [LIMIT] [--no-close-gaps] [--no-gates] [--trim-ink] [--one-building]
//! [--rules] [--ink-model FILE] [--net] [--ink-net FILE]`; `--ink-model` reads a wall-ink model written by `train_ink --out
//! FILE` instead of the shipped one; `--net` parses with the wall-ink network (and its own
//! mask is the network's), `--ink-net` reads a network written by `train_net --out FILE`.

use std::path::PathBuf;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let ink_model = args
        .iter()
        .position(|a| a == "--ink-model")
        .and_then(|k| args.get(k + 1))
        .map(|f| {
            let bytes = std::fs::read(f).unwrap_or_else(|e| panic!("{f}: {e}"));
            std::sync::Arc::new(
                plan::ink::WallInk::from_bytes(&bytes).unwrap_or_else(|e| panic!("{f}: {e}")),
            )
        });
    let ink_net = std::sync::Arc::new(match args.iter().position(|a| a == "--ink-net") {
        Some(k) => {
            let f = args.get(k + 1).expect("--ink-net needs a file");
            let bytes = std::fs::read(f).unwrap_or_else(|e| panic!("{f}: {e}"));
            plan::ink::net::WallNet::from_bytes(&bytes).unwrap_or_else(|e| panic!("{f}: {e}"))
        }
        None => plan::ink::net::WallNet::shipped().expect("the shipped network"),
    });
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/r3d_floorplans_deepfloorplan/newyork/test");
    let opts = plan::Options {
        close_gaps: !std::env::args().any(|a| a == "--no-close-gaps"),
        close_gates: !std::env::args().any(|a| a == "--no-gates"),
        trim_ink: std::env::args().any(|a| a == "--trim-ink"),
        one_building: std::env::args().any(|a| a == "--one-building"),
        ink: if std::env::args().any(|a| a == "--rules") {
            plan::ink::InkMethod::Rules
        } else if std::env::args().any(|a| a == "--net" || a == "--ink-net") {
            plan::ink::InkMethod::Network
        } else {
            plan::ink::InkMethod::Learned
        },
        ink_model: ink_model.clone(),
        ink_net: Some(ink_net.clone()),
        ..Default::default()
    };
    let limit: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(usize::MAX);
    let Ok(entries) = std::fs::read_dir(&dir) else {
        eprintln!("skipped: {} not found", dir.display());
        return;
    };
    let mut ids: Vec<String> = entries
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter_map(|n| n.strip_suffix(".jpg").map(str::to_string))
        .collect();
    ids.sort();
    ids.truncate(limit);
    println!("id\tprecision\trecall\tiou\tcourtyard\tfaces\tms\tmask_iou\totsu_iou\tink_iou");
    let (mut sum_iou, mut closed, mut n) = (0.0, 0, 0);
    let (mut sum_mask, mut sum_otsu, mut sum_ink) = (0.0, 0.0, 0.0);
    let model = ink_model.unwrap_or_else(plan::ink::shipped);
    for id in &ids {
        let img = image::open(dir.join(format!("{id}.jpg"))).unwrap();
        let mask = image::open(dir.join(format!("{id}_wall.png")))
            .unwrap()
            .to_luma8();
        let t = std::time::Instant::now();
        let p = match plan::parse(&img, &opts) {
            Ok(p) => p,
            Err(e) => {
                println!("{id}\terror: {e}");
                n += 1;
                continue;
            }
        };
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let grey = img.to_luma8();
        let level = plan::binarize::threshold_level(&grey);
        let mask_iou = iou_of(&mask, |x, y| p.walls.get(x as i32, y as i32) != 0);
        let otsu_iou = iou_of(&mask, |x, y| grey.get_pixel(x, y)[0] < level);
        let (w, h) = grey.dimensions();
        let prob = if opts.ink == plan::ink::InkMethod::Network {
            ink_net.wall_probability(&grey, w, h)
        } else {
            model.wall_probability(&grey, w, h)
        };
        let ink_iou = iou_of(&mask, |x, y| prob[(y * w + x) as usize] > 0.5);
        sum_ink += ink_iou;
        sum_mask += mask_iou;
        sum_otsu += otsu_iou;
        let (mut tp, mut fp, mut fneg) = (0usize, 0usize, 0usize);
        for y in 0..p.height.min(mask.height()) {
            for x in 0..p.width.min(mask.width()) {
                let ours = p.label_at(x, y).is_wall();
                let theirs = mask.get_pixel(x, y)[0] >= 128;
                match (ours, theirs) {
                    (true, true) => tp += 1,
                    (true, false) => fp += 1,
                    (false, true) => fneg += 1,
                    _ => {}
                }
            }
        }
        let prec = tp as f64 / (tp + fp).max(1) as f64;
        let rec = tp as f64 / (tp + fneg).max(1) as f64;
        let iou = tp as f64 / (tp + fp + fneg).max(1) as f64;
        let court = p
            .faces
            .iter()
            .any(|f| f.label == plan::label::Label::Courtyard);
        println!(
            "{id}\t{prec:.3}\t{rec:.3}\t{iou:.3}\t{court}\t{}\t{ms:.0}\t{mask_iou:.3}\t{otsu_iou:.3}\t{ink_iou:.3}",
            p.faces.len()
        );
        sum_iou += iou;
        closed += usize::from(court);
        n += 1;
    }
    println!(
        "plans {n}, mean IoU {:.3} (labelled walls), {:.3} (wall mask), {:.3} (Otsu), {:.3} (learned ink, P > 0.5), closed outer wall {closed}",
        sum_iou / n.max(1) as f64,
        sum_mask / n.max(1) as f64,
        sum_otsu / n.max(1) as f64,
        sum_ink / n.max(1) as f64
    );
}

/// IoU of `ours(x, y)` against the R3D wall mask (≥ 128 is wall).
fn iou_of(mask: &image::GrayImage, ours: impl Fn(u32, u32) -> bool) -> f64 {
    let (mut tp, mut other) = (0usize, 0usize);
    for (x, y, m) in mask.enumerate_pixels() {
        match (ours(x, y), m[0] >= 128) {
            (true, true) => tp += 1,
            (false, false) => {}
            _ => other += 1,
        }
    }
    tp as f64 / (tp + other).max(1) as f64
}
