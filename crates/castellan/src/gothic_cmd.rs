//! `castellan gothic`: a rectified Gothic façade → GOTHIC.json (elements Θ = [x0, y0, h, w, v],
//! groups, nesting; dissertation §4.1–4.2), MASONRY.png (stones/mortar), an overlay and a
//! block-level glTF model (wall, elements, extruded stones).

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result, anyhow};
use clap::Args;
use facade::gothic::hatching::HatchParams;
use facade::gothic::masonry::{self, Masonry, MasonryParams};
use facade::gothic::{GothicEstimate, GothicParams, VsgOptions};
use image::{GrayImage, Rgb, RgbImage};

use crate::images::png;
use crate::output::Outputs;
use crate::rectify_cmd::read_rgb;

pub fn run(args: &GothicArgs) -> Result<()> {
    let file = args.image.display().to_string();
    let img = read_rgb(&args.image)?;
    let params = GothicParams {
        min_seed_radius: args.min_radius as f32,
        min_width: 2.0 * args.min_radius,
        min_height: 3.0 * args.min_radius,
        hatching: args.hatching.then(HatchParams::default),
        ..GothicParams::default()
    };
    let started = Instant::now();
    let est = facade::gothic::estimate(&img, &params).map_err(|e| anyhow!("{file}: {e}"))?;
    let masonry = (args.masonry.is_some() || args.model.is_some())
        .then(|| masonry::segment(&img, &est, &MasonryParams::default()));
    let elapsed = started.elapsed();

    let mut outputs = Outputs::default();
    let mut doc = serde_json::to_value(&est)?;
    if let Some(m) = &masonry {
        doc["stones"] = serde_json::to_value(&m.stones)?;
    }
    outputs.add(&args.output, serde_json::to_vec_pretty(&doc)?);
    if let (Some(path), Some(m)) = (&args.masonry, &masonry) {
        let g = GrayImage::from_raw(m.width, m.height, m.labels.clone())
            .ok_or_else(|| anyhow!("masonry image size"))?;
        outputs.add(path, png(&g, path)?);
    }
    if let Some(path) = &args.overlay {
        outputs.add(path, png(&overlay(&img, &est, masonry.as_ref()), path)?);
    }
    if let Some(path) = &args.model {
        let options = VsgOptions {
            px_per_unit: args.px_per_unit,
            stone_depth: args.depth,
            ..VsgOptions::default()
        };
        let src = facade::gothic::to_vsg(&est, masonry.as_ref(), &options);
        let model = vsg::run(&src, &vsg::RunOptions::default()).map_err(|e| {
            anyhow!(
                "{}: internal error in the generated façade program: {}",
                path.display(),
                e.render("gothic.vsg", &src).trim_end()
            )
        })?;
        let glb = vsg::export::to_glb(&model, &vsg::export::ExportOptions::default())
            .with_context(|| format!("cannot export {}", path.display()))?;
        outputs.add(path, glb);
    }
    outputs.commit()?;
    if est.elements.is_empty() {
        eprintln!(
            "{file}: no arched or rectangular element found; written to {}",
            args.output.display()
        );
        return Ok(());
    }
    eprintln!(
        "{file}: {} element(s) ({} nested), {} group(s){}; estimated in {:.0} ms, written to {}",
        est.elements.len(),
        est.elements.iter().filter(|e| e.parent.is_some()).count(),
        est.groups.len(),
        masonry
            .as_ref()
            .map_or(String::new(), |m| format!(", {} stone(s)", m.stones.len())),
        elapsed.as_secs_f64() * 1e3,
        args.output.display()
    );
    Ok(())
}

/// The image with mortar tinted (when segmented) and every element's contour drawn: top-level
/// elements red, nested ones blue, deeper ones green.
pub(crate) fn overlay(img: &RgbImage, est: &GothicEstimate, masonry: Option<&Masonry>) -> RgbImage {
    let mut o = img.clone();
    if let Some(m) = masonry {
        for (p, &l) in o.pixels_mut().zip(&m.labels) {
            if l == 1 {
                *p = Rgb([(p[0] as u16 / 2 + 127) as u8, p[1] / 2 + 100, p[2] / 2]);
            }
        }
    }
    let colours = [Rgb([255u8, 30, 30]), Rgb([40, 120, 255]), Rgb([0, 220, 0])];
    let (w, h) = (o.width() as i64, o.height() as i64);
    for e in &est.elements {
        let c = colours[e.depth.min(2)];
        for s in e.theta().contour_at(0.5) {
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let (x, y) = (s.x.round() as i64 + dx, s.y.round() as i64 + dy);
                if x >= 0 && y >= 0 && x < w && y < h {
                    o.put_pixel(x as u32, y as u32, c);
                }
            }
        }
    }
    o
}

/// `castellan gothic` flags.
#[derive(Debug, Args)]
pub struct GothicArgs {
    /// The rectified Gothic façade (PNG, JPEG or PNM).
    pub image: PathBuf,
    /// Elements (Θ = [x0, y0, h, w, v] in pixels), groups and nesting as JSON.
    #[arg(short = 'o', long = "output", value_name = "GOTHIC.json")]
    pub output: PathBuf,
    /// 8-bit masonry image: 0 not wall (elements), 1 mortar, 2 stone.
    #[arg(long, value_name = "MASONRY.png")]
    pub masonry: Option<PathBuf>,
    /// Draw the element contours (and the mortar, with --masonry or --model) over the image.
    #[arg(long, value_name = "OVERLAY.png")]
    pub overlay: Option<PathBuf>,
    /// Block-level glTF model: the wall, each element cut from it, each stone extruded.
    #[arg(long, value_name = "MODEL.glb")]
    pub model: Option<PathBuf>,
    /// How far each stone block stands out of the wall, in model units.
    #[arg(long, default_value_t = 0.05, value_parser = parse_positive)]
    pub depth: f64,
    /// Image pixels per model unit (e.g. pixels per metre).
    #[arg(long, default_value_t = 100.0, value_parser = parse_positive)]
    pub px_per_unit: f64,
    /// Smallest element half-width in pixels: seeds need an empty disc this large, and
    /// elements are at least twice as wide and three times as tall.
    #[arg(long, default_value_t = 8.0, value_parser = parse_positive)]
    pub min_radius: f64,
    /// Engravings: replace parallel hatching and coursing strokes by their tone before the
    /// edges, so hatched openings show their outline (off for photographs).
    #[arg(long)]
    pub hatching: bool,
}

fn parse_positive(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    if !v.is_finite() || v <= 0.0 {
        return Err(format!("'{s}' must be a positive number"));
    }
    Ok(v)
}

#[cfg(test)]
mod flag_tests {
    use std::path::PathBuf;

    use clap::Parser;

    use super::GothicArgs;
    use crate::cli::{Cli, Command};

    fn gothic_args(extra: &[&str]) -> Result<GothicArgs, clap::Error> {
        let mut argv = vec!["castellan", "gothic", "g.png", "-o", "g.json"];
        argv.extend_from_slice(extra);
        Cli::try_parse_from(argv).map(|c| match c.command {
            Command::Gothic(a) => a,
            _ => unreachable!("parsed a gothic command line"),
        })
    }

    #[test]
    fn gothic_output_is_required() {
        assert!(Cli::try_parse_from(["castellan", "gothic", "g.png"]).is_err());
        let a = gothic_args(&[]).unwrap();
        assert_eq!(
            (a.image, a.output),
            (PathBuf::from("g.png"), PathBuf::from("g.json"))
        );
        assert_eq!((a.masonry, a.overlay, a.model), (None, None, None));
        assert!(!a.hatching);
        assert!(gothic_args(&["--hatching"]).unwrap().hatching);
    }

    #[test]
    fn gothic_masonry_overlay_model_flags() {
        let a = gothic_args(&[
            "--masonry",
            "m.png",
            "--overlay",
            "o.png",
            "--model",
            "x.glb",
        ])
        .unwrap();
        assert_eq!(a.masonry, Some(PathBuf::from("m.png")));
        assert_eq!(a.overlay, Some(PathBuf::from("o.png")));
        assert_eq!(a.model, Some(PathBuf::from("x.glb")));
    }

    #[test]
    fn gothic_numeric_flags_are_positive() {
        let a = gothic_args(&[]).unwrap();
        assert_eq!((a.depth, a.px_per_unit, a.min_radius), (0.05, 100.0, 8.0));
        let a =
            gothic_args(&["--depth", "0.1", "--px-per-unit", "50", "--min-radius", "5"]).unwrap();
        assert_eq!((a.depth, a.px_per_unit, a.min_radius), (0.1, 50.0, 5.0));
        for bad in [
            ["--depth", "0"],
            ["--px-per-unit", "-3"],
            ["--min-radius", "nan"],
        ] {
            assert!(gothic_args(&bad).is_err(), "{bad:?}");
        }
    }
}
