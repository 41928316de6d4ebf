//! The training and test drawings of the learned wall ink, shared by the `train_ink` and
//! `ink_eval` examples: synthetic plans in randomised styles and the painted public-domain
//! plans (`crates/plan/data/wall_masks*.json` over `../shared/data/castle_drawings_pd`).

use std::path::PathBuf;

use image::{GrayImage, Luma};
use imageproc::distance_transform::{Norm, distance_transform};
use plan::ink::paint::{self, PaintedSet, Recipe};
use plan::ink::train::Sheet;
use plan::synth_styles::{Clutter, StyleChoice};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `../shared/data/castle_drawings_pd` beside the repository.
pub fn data_dir() -> Option<PathBuf> {
    let d =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/castle_drawings_pd");
    d.is_dir().then_some(d)
}

/// [`data_dir`], or the end of a training run that needs the painted plans and finds none.
#[allow(dead_code)] // the trainers use it, ink_eval does not
pub fn painted_data_dir() -> PathBuf {
    data_dir().unwrap_or_else(|| {
        fail(
            "../shared/data/castle_drawings_pd",
            "not found: the painted plans live there",
        )
    })
}

/// Every painted recipe (`crates/plan/data/wall_masks*.json`, in name order).
pub fn recipes() -> Vec<Recipe> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| fail(&dir.display().to_string(), e))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("wall_masks"))
        })
        .collect();
    files.sort();
    let mut all = Vec::new();
    for f in files {
        let name = f.display().to_string();
        let text = std::fs::read_to_string(&f).unwrap_or_else(|e| fail(&name, e));
        all.extend(
            PaintedSet::from_json(&text)
                .unwrap_or_else(|e| fail(&name, e))
                .masks,
        );
    }
    all
}

/// A painted drawing and its mask.
pub fn painted_sheet(data: &std::path::Path, r: &Recipe) -> Sheet {
    let path = data.join(&r.file);
    let grey = image::open(&path)
        .unwrap_or_else(|e| fail(&path.display().to_string(), e))
        .to_luma8();
    let truth = paint::render(&grey, r).unwrap_or_else(|e| fail(&r.file, e));
    Sheet { grey, truth }
}

/// How the synthetic drawings are drawn and labelled. The one home of the training recipe:
/// [`SynthOptions::default`] is the shipped model's, which `train_ink` and `ink_eval` train on
/// unless told otherwise (`train_ink --scarps --scarp-paper --far-paper PX`).
#[derive(Clone, Copy, Debug, Default)]
#[allow(dead_code)] // train_ink uses it, ink_eval does not
pub struct SynthOptions {
    /// Also draw hachured scarps and hachure bands against the walls.
    pub scarps: bool,
    /// On drawings with such scarps, ignore the paper farther than this from any ink.
    pub far_paper: Option<u8>,
    /// Mark the paper inside the scarps ([`plan::synth_styles::StyledPlan::scarps`]) as
    /// [`paint::HARD_NOT_WALL`], a pool of its own in training.
    pub scarp_paper: bool,
    /// Also draw fittings (stairs, tables, counters, doors' swings) inside the curtain.
    pub furnishing: bool,
}

/// `n` synthetic drawings of long side 300–1600 px, seeded (the shipped model's recipe).
#[allow(dead_code)] // ink_eval uses it, train_ink calls `synthetic_with`
pub fn synthetic(n: usize, seed: u64) -> Vec<Sheet> {
    synthetic_with(n, seed, SynthOptions::default())
}

/// `n` synthetic drawings of long side 300–1600 px, seeded, drawn and labelled as `o` says.
#[allow(dead_code)] // train_ink uses it, ink_eval does not
pub fn synthetic_with(n: usize, seed: u64, o: SynthOptions) -> Vec<Sheet> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5e7_0001);
    let choice = StyleChoice {
        scarps: o.scarps,
        furnishing: o.furnishing,
        ..StyleChoice::default()
    };
    (0..n)
        .map(|_| {
            let long = rng.random_range(300..1600u32);
            let short = (f64::from(long) * rng.random_range(0.6..1.0)) as u32;
            let (w, h) = if rng.random_bool(0.5) {
                (long, short)
            } else {
                (short, long)
            };
            let s = plan::synth_styles::generate_with(rng.random(), w, h, &choice);
            let mut truth = s.walls;
            if o.scarp_paper {
                for (t, z) in truth.pixels_mut().zip(s.scarps.pixels()) {
                    if z[0] == 255 && t[0] != paint::WALL {
                        t[0] = paint::HARD_NOT_WALL;
                    }
                }
            }
            let scarps = [Clutter::WallHachures, Clutter::HachureBands];
            if let Some(far) = o.far_paper
                && s.style.clutter.iter().any(|c| scarps.contains(c))
            {
                ignore_far_paper(&s.image, &mut truth, far);
            }
            Sheet {
                grey: s.image,
                truth,
            }
        })
        .collect()
}

/// Marks the paper farther than `far` pixels (chessboard) from any ink as ignored, so that the sheet's
/// "not wall" paper samples come from the gaps between hachure strokes, letters and ribs
/// rather than the open sheet (a sheet with hachured scarps; the other sheets keep the open
/// paper). Ink: darker than halfway between the drawing's 1st and 90th grey percentiles.
fn ignore_far_paper(grey: &GrayImage, truth: &mut GrayImage, far: u8) {
    let mut sorted: Vec<u8> = grey.as_raw().clone();
    sorted.sort_unstable();
    let at = |q: f64| f64::from(sorted[((sorted.len() - 1) as f64 * q) as usize]);
    let cut = (at(0.01) + at(0.9)) / 2.0;
    let ink = GrayImage::from_fn(grey.width(), grey.height(), |x, y| {
        Luma([if f64::from(grey.get_pixel(x, y)[0]) < cut {
            255
        } else {
            0
        }])
    });
    let dist = distance_transform(&ink, Norm::LInf);
    for (t, d) in truth.pixels_mut().zip(dist.pixels()) {
        if t[0] != paint::WALL && d[0] > far {
            t[0] = paint::IGNORE;
        }
    }
}

/// Adds a [`plan::ink::train::confusion`] to a running sum.
#[allow(dead_code)] // ink_eval and train_net use it, train_ink does not
pub fn add(acc: &mut [usize; 3], c: (usize, usize, usize)) {
    acc[0] += c.0;
    acc[1] += c.1;
    acc[2] += c.2;
}

/// IoU of summed confusions, as a table cell ("—" when there is nothing to score).
#[allow(dead_code)] // ink_eval and train_net use it, train_ink does not
pub fn iou(c: [usize; 3]) -> String {
    if c[0] + c[1] + c[2] == 0 {
        return "—".into();
    }
    format!("{:.3}", c[0] as f64 / (c[0] + c[1] + c[2]) as f64)
}

/// Otsu's ink as a 0/1 "probability" map: the baseline the learned ink must beat.
#[allow(dead_code)] // ink_eval and train_net use it, train_ink does not
pub fn otsu_map(grey: &GrayImage) -> Vec<f32> {
    let level = plan::binarize::threshold_level(grey);
    grey.pixels()
        .map(|p| if p[0] < level { 1.0 } else { 0.0 })
        .collect()
}

pub fn fail(what: &str, e: impl std::fmt::Display) -> ! {
    eprintln!("{what}: {e}");
    std::process::exit(1);
}
