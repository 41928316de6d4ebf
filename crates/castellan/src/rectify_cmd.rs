//! `castellan rectify`: a façade photo → its elevation view (§3.1.1), with H.json and an overlay
//! of the line families and vanishing points.

use std::path::PathBuf;

use anyhow::{Result, anyhow};
use clap::Args;
use facade::rectify::{self, ManualLines, RectifyParams};

use crate::output::Outputs;

/// Reads an image as RGB, naming the file on failure.
pub fn run(args: &RectifyArgs) -> Result<()> {
    let file = args.image.display().to_string();
    let img = crate::images::read_rgb(&args.image)?;
    let params = RectifyParams {
        ransac: rectify::RansacParams {
            seed: args.seed,
            ..Default::default()
        },
        ..Default::default()
    };
    let r = match &args.lines {
        Some(lines_path) => {
            let lines: ManualLines = crate::text::read_json(lines_path, "a LINES.json")?;
            rectify::rectify_with_lines(img.width(), img.height(), &lines, &params)
                .map_err(|e| anyhow!("{}: {e}", lines_path.display()))?
        }
        None => crate::progress::with_spinner("lines and vanishing points (§3.1.1)", |_| {
            rectify::rectify(&img, &params)
        })
        .map_err(|e| anyhow!("{file}: {e}"))?,
    };
    let warped = r.warp(&img).map_err(|e| anyhow!("{file}: {e}"))?;
    let mut outputs = Outputs::default();
    outputs.add(&args.output, crate::images::png(&warped, &args.output)?);
    if let Some(hp) = &args.homography {
        let rows: Vec<[f64; 3]> = (0..3)
            .map(|i| [r.h[(i, 0)], r.h[(i, 1)], r.h[(i, 2)]])
            .collect();
        let json = serde_json::json!({ "H": rows, "width": r.width, "height": r.height,
            "horizontal_vp": r.horizontal_vp, "vertical_vp": r.vertical_vp });
        outputs.add(hp, serde_json::to_vec_pretty(&json)?);
    }
    if let Some(op) = &args.overlay {
        outputs.add(
            op,
            crate::images::png(&rectify::draw_overlay(&img, &r), op)?,
        );
    }
    outputs.commit()?;
    eprintln!(
        "{file}: {} horizontal and {} vertical segments; rectified to {}x{}, written to {}",
        r.horizontal.len(),
        r.vertical.len(),
        r.width,
        r.height,
        args.output.display()
    );
    Ok(())
}

/// `castellan rectify` flags.
#[derive(Debug, Args)]
pub struct RectifyArgs {
    /// The façade photo.
    pub image: PathBuf,
    /// The rectified image (PNG).
    #[arg(short = 'o', long = "output", value_name = "RECTIFIED.png")]
    pub output: PathBuf,
    /// Write the homography (input pixels -> output pixels) as {"H": [[..],[..],[..]]}.
    #[arg(long, value_name = "H.json")]
    pub homography: Option<PathBuf>,
    /// Use these segments instead of detected ones:
    /// {"horizontal": [[x0,y0,x1,y1], ...], "vertical": [...]}, at least two of each.
    #[arg(long, value_name = "LINES.json")]
    pub lines: Option<PathBuf>,
    /// Draw the line families and vanishing points over the photo.
    #[arg(long, value_name = "OVERLAY.png")]
    pub overlay: Option<PathBuf>,
    /// Seed of the RANSAC sampling.
    #[arg(long, default_value_t = 7)]
    pub seed: u64,
}

#[cfg(test)]
mod flag_tests {
    use std::path::PathBuf;

    use super::RectifyArgs;
    use crate::flags::testing::parse;

    fn rectify_args(extra: &[&str]) -> Result<RectifyArgs, clap::Error> {
        let mut argv = vec!["castellan", "rectify", "p.jpg", "-o", "r.png"];
        argv.extend_from_slice(extra);
        parse::<RectifyArgs>(&argv[2..])
    }

    #[test]
    fn rectify_output_is_required() {
        assert!(parse::<RectifyArgs>(&["p.jpg"]).is_err());
        assert_eq!(rectify_args(&[]).unwrap().output, PathBuf::from("r.png"));
    }

    #[test]
    fn rectify_homography_flag() {
        assert_eq!(
            rectify_args(&["--homography", "h.json"])
                .unwrap()
                .homography,
            Some(PathBuf::from("h.json"))
        );
    }

    #[test]
    fn rectify_lines_flag() {
        assert_eq!(
            rectify_args(&["--lines", "l.json"]).unwrap().lines,
            Some(PathBuf::from("l.json"))
        );
    }

    #[test]
    fn rectify_overlay_and_seed_flags() {
        let a = rectify_args(&["--overlay", "o.png", "--seed", "3"]).unwrap();
        assert_eq!((a.overlay, a.seed), (Some(PathBuf::from("o.png")), 3));
        assert_eq!(rectify_args(&[]).unwrap().seed, 7);
    }
}
