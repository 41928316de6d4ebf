//! TRAINING.json from a ground-truth label file, drawn by the simulated user of `eval.rs`
//! (three seeded 9-px boxes per class, seed 1, as `examples/evaluate/` uses), for measuring
//! `castellan gothic --training` on CMP base and Paris Art-deco (docs/gothic.md).
//!
//! `cargo run --release -p facade --example gothic_training cmp|paris LABELS OUT.json`
//! (CMP: the palette PNG beside the photo; Paris: the label matrix .txt)

use std::path::Path;
use std::process::ExitCode;

use facade::eval::{IGNORE, simulate_user};

/// CMP palette → 0 background, 1 wall, 2 window (the mapping of `examples/evaluate/`).
fn cmp_truth(path: &Path) -> Result<(Vec<u8>, usize, usize), String> {
    let img = image::open(path)
        .map_err(|e| format!("{}: {e}", path.display()))?
        .to_rgb8();
    let labels = facade::eval::cmp_classes(&img);
    Ok((labels, img.width() as usize, img.height() as usize))
}

/// Art-deco labels: Door 0, Shop 1, Balcony 2, Window 3, Wall 4, Sky 5, Roof 6, -1 void
/// (the mapping of `examples/evaluate/`: windows are the window class).
fn paris_truth(path: &Path) -> Result<(Vec<u8>, usize, usize), String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let rows: Vec<&str> = text.lines().filter(|l| !l.trim().is_empty()).collect();
    let w = rows.first().map_or(0, |r| r.split_whitespace().count());
    let labels: Vec<u8> = rows
        .iter()
        .flat_map(|r| r.split_whitespace())
        .map(|v| match v.parse::<i32>() {
            Ok(3) => 2,
            Ok(0 | 1 | 2 | 4) => 1,
            Ok(5 | 6) => 0,
            _ => IGNORE,
        })
        .collect();
    Ok((labels, w, rows.len()))
}

fn run(args: &[String]) -> Result<(), String> {
    let [kind, labels, out] = args else {
        return Err("usage: gothic_training cmp|paris LABELS OUT.json".into());
    };
    let (truth, w, h) = match kind.as_str() {
        "cmp" => cmp_truth(Path::new(labels))?,
        "paris" => paris_truth(Path::new(labels))?,
        _ => return Err(format!("unknown data set '{kind}' (cmp or paris)")),
    };
    let training = simulate_user(&truth, w, h, 3, 9, 1).map_err(|e| format!("{labels}: {e}"))?;
    let json = serde_json::to_string(&training).map_err(|e| e.to_string())?;
    std::fs::write(out, json).map_err(|e| format!("{out}: {e}"))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}
