//! Renders the painted wall masks (`crates/plan/data/wall_masks.json`, [`plan::ink::paint`])
//! over their drawings, so that a recipe can be checked by eye while it is written: for each
//! recipe, `NAME.mask.png` (255 wall, 0 not, 128 left out) and `NAME.overlay.png` (the drawing
//! in grey, walls red, left-out pixels yellow, a grid every 50 px in blue).
//!
//! `cargo run -p plan --example paint_masks -- [RECIPES.json] OUTDIR [NAME-SUBSTRING]`

use std::path::PathBuf;

use image::{Rgb, RgbImage};
use plan::ink::paint::{self, IGNORE, PaintedSet, WALL};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let here = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let (recipes, out, only) = match args.as_slice() {
        [out] => (here.join("data/wall_masks.json"), PathBuf::from(out), None),
        [r, out] => (PathBuf::from(r), PathBuf::from(out), None),
        [r, out, only] => (PathBuf::from(r), PathBuf::from(out), Some(only.clone())),
        _ => {
            eprintln!("usage: paint_masks [RECIPES.json] OUTDIR [NAME-SUBSTRING]");
            std::process::exit(2);
        }
    };
    let data = here.join("../../../shared/data/castle_drawings_pd");
    let text = std::fs::read_to_string(&recipes).unwrap_or_else(|e| fail(&recipes, e));
    let set = PaintedSet::from_json(&text).unwrap_or_else(|e| fail(&recipes, e));
    std::fs::create_dir_all(&out).unwrap_or_else(|e| fail(&out, e));
    for r in &set.masks {
        if only.as_ref().is_some_and(|o| !r.file.contains(o.as_str())) {
            continue;
        }
        let path = data.join(&r.file);
        let grey = image::open(&path)
            .unwrap_or_else(|e| fail(&path, e))
            .to_luma8();
        let mask = match paint::render(&grey, r) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("{}: {e}", r.file);
                continue;
            }
        };
        let stem = std::path::Path::new(&r.file)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .to_string();
        let overlay = RgbImage::from_fn(grey.width(), grey.height(), |x, y| {
            let g = grey.get_pixel(x, y)[0];
            let m = mask.get_pixel(x, y)[0];
            if m == WALL {
                Rgb([255, g / 3, g / 3])
            } else if m == IGNORE {
                Rgb([255, 230, g / 3])
            } else if x % 50 == 0 || y % 50 == 0 {
                Rgb([g / 2, g / 2, 255])
            } else {
                Rgb([g, g, g])
            }
        });
        let wall = mask.pixels().filter(|p| p[0] == WALL).count();
        println!(
            "{}: {:.1} % wall",
            r.file,
            100.0 * wall as f64 / mask.len() as f64
        );
        mask.save(out.join(format!("{stem}.mask.png")))
            .unwrap_or_else(|e| fail(&out, e));
        overlay
            .save(out.join(format!("{stem}.overlay.png")))
            .unwrap_or_else(|e| fail(&out, e));
    }
}

fn fail(path: &std::path::Path, e: impl std::fmt::Display) -> ! {
    eprintln!("{}: {e}", path.display());
    std::process::exit(1);
}
