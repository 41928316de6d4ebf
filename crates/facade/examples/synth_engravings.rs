//! Writes synthetic engravings and their opening masks for viewing (issue 23;
//! `facade::gothic::synth_engraving`).
//!
//! `cargo run --release -p facade --example synth_engravings -- OUT_DIR [N] [SEED]`
//! writes N sheets (default 8) of 600 × 600 px from seeds SEED, SEED + 1, … (default 0) as
//! `NNN.png` and `NNN_openings.png`.

use std::path::PathBuf;
use std::process::ExitCode;

use facade::gothic::synth_engraving::generate;

fn run(args: &[String]) -> Result<(), String> {
    let usage = "usage: synth_engravings OUT_DIR [N] [SEED]";
    let out = PathBuf::from(args.first().ok_or(usage)?);
    let parse = |i: usize, default: u64| -> Result<u64, String> {
        args.get(i).map_or(Ok(default), |s| {
            s.parse()
                .map_err(|_| format!("{s}: not a number ({usage})"))
        })
    };
    let (n, seed) = (parse(1, 8)?, parse(2, 0)?);
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    for i in 0..n {
        let sheet = generate(seed + i, 600, 600);
        let (image, mask) = (
            out.join(format!("{i:03}.png")),
            out.join(format!("{i:03}_openings.png")),
        );
        sheet
            .image
            .save(&image)
            .map_err(|e| format!("{}: {e}", image.display()))?;
        sheet
            .openings
            .save(&mask)
            .map_err(|e| format!("{}: {e}", mask.display()))?;
        let open = sheet.elements.iter().filter(|e| !e.enclosing).count();
        println!(
            "{}: seed {}, {} openings, {} enclosing arches",
            image.display(),
            seed + i,
            open,
            sheet.elements.len() - open
        );
    }
    Ok(())
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
