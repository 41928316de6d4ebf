//! Writes synthetic castle plan drawings in randomised draughting styles and their wall truth
//! masks as PNG, to look at: `cargo run --release -p plan --example synth_styles -- OUTDIR 12`
//! (OUTDIR/NNN.png the drawing, OUTDIR/NNN_walls.png the truth; optional third and fourth
//! arguments: width and height, default 1200 × 900; `FURNISHING=1` also draws the fittings of
//! `StyleChoice::furnishing`).

use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let dir = PathBuf::from(
        args.first()
            .ok_or("usage: synth_styles OUTDIR [N] [W] [H]")?,
    );
    let arg = |k: usize, d: u32| args.get(k).map_or(Ok(d), |s| s.parse::<u32>());
    let (n, w, h) = (arg(1, 12)?, arg(2, 1200)?, arg(3, 900)?);
    std::fs::create_dir_all(&dir)?;
    let choice = plan::synth_styles::StyleChoice {
        furnishing: std::env::var("FURNISHING").is_ok_and(|v| v == "1"),
        ..Default::default()
    };
    for seed in 0..n as u64 {
        let p = plan::synth_styles::generate_with(seed, w, h, &choice);
        p.image.save(dir.join(format!("{seed:03}.png")))?;
        p.walls.save(dir.join(format!("{seed:03}_walls.png")))?;
        let s = &p.style;
        println!(
            "{seed:03}: {:?}{} t={:.1} clutter {:?}",
            s.walls,
            s.second.map_or(String::new(), |w| format!("+{w:?}")),
            s.thickness,
            s.clutter
        );
    }
    Ok(())
}
