//! The training and test drawings of the learned wall ink, shared by the `train_ink` and
//! `ink_eval` examples: synthetic plans in randomised styles and the painted public-domain
//! plans (`crates/plan/data/wall_masks*.json` over `../shared/data/castle_drawings_pd`).

use std::path::PathBuf;

use plan::ink::paint::{self, PaintedSet, Recipe};
use plan::ink::train::Sheet;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `../shared/data/castle_drawings_pd` beside the repository.
pub fn data_dir() -> Option<PathBuf> {
    let d =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/castle_drawings_pd");
    d.is_dir().then_some(d)
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

/// `n` synthetic drawings of long side 300–1600 px, seeded.
pub fn synthetic(n: usize, seed: u64) -> Vec<Sheet> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5e7_0001);
    (0..n)
        .map(|_| {
            let long = rng.random_range(300..1600u32);
            let short = (f64::from(long) * rng.random_range(0.6..1.0)) as u32;
            let (w, h) = if rng.random_bool(0.5) {
                (long, short)
            } else {
                (short, long)
            };
            let s = plan::synth_styles::generate(rng.random(), w, h);
            Sheet {
                grey: s.image,
                truth: s.walls,
            }
        })
        .collect()
}

pub fn fail(what: &str, e: impl std::fmt::Display) -> ! {
    eprintln!("{what}: {e}");
    std::process::exit(1);
}
