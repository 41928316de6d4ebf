//! Command-line definitions (ARCHITECTURE.md contract). Each flag is defined once, with its
//! test beside it.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

#[derive(Debug, Parser)]
#[command(
    name = "castellan",
    version,
    about = "Plan drawing + façade photos of a historic building -> a labelled, volumetric 3D model"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// The Volumetric Shape Grammar (dissertation ch. 7).
    #[command(subcommand)]
    Vsg(VsgCommand),
    /// Structural corners (ch. 2, IPFIT): hyperbola fits to edge points, corners at the
    /// intersection of their asymptotes.
    Corners(CornersArgs),
    /// Modified repeatability rate (§2.2) and detections per image over image sequences with
    /// Oxford-style homographies (H1to2p ... H1to6p), for IPFIT and, optionally, peer detectors.
    CornersEval(CornersEvalArgs),
    /// Parse a castle plan drawing into labelled walls, rooms and towers (dissertation ch. 5).
    Plan(crate::plan_cmd::PlanArgs),
    /// Rectify a façade photo into an elevation view (dissertation §3.1.1).
    Rectify(crate::rectify_cmd::RectifyArgs),
    /// Parse a rectified façade into façades, floors and windows (dissertation §3.1.2-3.1.7).
    Facade(crate::facade_cmd::FacadeArgs),
    /// Plan drawing + façade photos (PROJECT.toml) → integrated estimate → VSG program → model,
    /// with every step's overlay in an HTML report (dissertation ch. 6, §7.2.2–7.2.3).
    Reconstruct(crate::reconstruct_cmd::ReconstructArgs),
    /// Reconstruct the bundled example castle and compare the estimate with its known truth.
    Demo(crate::demo_cmd::DemoArgs),
    /// The interactive workflow in the browser: a local server for one project folder.
    Serve(crate::serve::ServeArgs),
}

#[derive(Debug, Subcommand)]
pub enum VsgCommand {
    /// Run a VSG program and write the model.
    Run(VsgRunArgs),
}

#[derive(Debug, Args)]
pub struct VsgRunArgs {
    /// The VSG program.
    pub program: PathBuf,
    /// Binary glTF output (.glb); its node tree is the semantic tree.
    #[arg(short = 'o', long = "output", value_name = "MODEL.glb")]
    pub output: PathBuf,
    /// Also write Wavefront OBJ (with an .mtl beside it), one group per terminal.
    #[arg(long, value_name = "MODEL.obj")]
    pub obj: Option<PathBuf>,
    /// Write counts and exact volumes as JSON.
    #[arg(long, value_name = "STATS.json")]
    pub stats: Option<PathBuf>,
    /// Also render a quick preview picture (PNG): visible terminals in their colours, from a
    /// 3/4 view fitted to the model.
    #[arg(long, value_name = "PREVIEW.png")]
    pub preview: Option<PathBuf>,
    /// Size of the preview picture in pixels.
    #[arg(long, value_name = "WxH", default_value = "800x600", value_parser = parse_size)]
    pub preview_size: (u32, u32),
    /// Override a declared float: `--set height=12.5` (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = parse_assignment)]
    pub set: Vec<(String, f64)>,
    /// Seed of every random choice; the same program and seed give the same model.
    #[arg(long, default_value_t = vsg::DEFAULT_SEED)]
    pub seed: u64,
    /// Segments around a full circle when meshing curved shapes.
    #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u32).range(3..=4096))]
    pub segments: u32,
    /// Where `import "file.vsg"` looks after the importing file's own directory (repeatable),
    /// e.g. `--lib library` for the medieval library.
    #[arg(long = "lib", value_name = "DIR")]
    pub lib: Vec<PathBuf>,
    /// Stop with an error when production nests deeper than this.
    #[arg(long, default_value_t = vsg::Limits::default().max_depth)]
    pub max_depth: u32,
    /// Stop with an error when production creates more shapes than this.
    #[arg(long, default_value_t = vsg::Limits::default().max_shapes)]
    pub max_shapes: usize,
}

#[derive(Debug, Args)]
pub struct CornersArgs {
    /// The image (PNG, JPEG, PPM/PGM; colour, alpha and 16-bit are converted to grey).
    pub image: PathBuf,
    /// Corners as JSON (CORNERS.json contract).
    #[arg(short = 'o', long = "output", value_name = "CORNERS.json")]
    pub output: PathBuf,
    /// Also draw each corner and its two asymptote directions over the image.
    #[arg(long, value_name = "OVERLAY.png")]
    pub overlay: Option<PathBuf>,
    #[command(flatten)]
    pub detector: DetectorArgs,
}

/// The detector's parameters (§2.1), shared by `corners` and `corners-eval`.
#[derive(Debug, Clone, Args)]
pub struct DetectorArgs {
    /// Rectified image (§2 intro): keep corners with one horizontal and one vertical edge.
    #[arg(long)]
    pub rectified: bool,
    /// Window side W (odd, 3..=101): smoothing, fit and suppression window.
    #[arg(long, default_value_t = corners::Params::default().window, value_parser = parse_window)]
    pub window: usize,
    /// Gaussian σ of the edge image (§2.1.1).
    #[arg(long, default_value_t = corners::Params::default().sigma, value_parser = parse_positive)]
    pub sigma: f64,
    /// Upper bound on ε, the mean distance (px) of the edge points to their asymptote.
    #[arg(long, default_value_t = corners::Params::default().max_epsilon, value_parser = parse_positive)]
    pub max_epsilon: f64,
    /// Lower bound on λ, the share of inliers on the first asymptote.
    #[arg(long, default_value_t = corners::Params::default().lambda_range.0, value_parser = parse_finite)]
    pub lambda_min: f64,
    /// Upper bound on λ.
    #[arg(long, default_value_t = corners::Params::default().lambda_range.1, value_parser = parse_finite)]
    pub lambda_max: f64,
    /// Upper bound on Δ (normalised so b² − 4ac = 1, pixel units; see the corners crate docs).
    #[arg(long, default_value_t = corners::Params::default().max_delta, value_parser = parse_positive)]
    pub max_delta: f64,
    /// Lower bound on ψ, half the corner's opening angle (rad).
    #[arg(long, default_value_t = corners::Params::default().psi_range.0, value_parser = parse_finite)]
    pub psi_min: f64,
    /// Upper bound on ψ (rad).
    #[arg(long, default_value_t = corners::Params::default().psi_range.1, value_parser = parse_finite)]
    pub psi_max: f64,
    /// Skip the refit without outliers (§2.1.3's optional step).
    #[arg(long)]
    pub no_refit: bool,
    /// Keep edge points at integer pixel positions (as §2.1.1 does).
    #[arg(long)]
    pub no_subpixel: bool,
    /// Outlier distance (px) of the refit and of the inlier sets (§2.1.3).
    #[arg(long, default_value_t = corners::Params::default().refit_distance, value_parser = parse_positive)]
    pub refit_distance: f64,
    /// Skip windows whose gradient orientations agree more than this (one straight contour);
    /// 1 fits every window (speed-up, not in §2.1).
    #[arg(long, default_value_t = corners::Params::default().max_coherence, value_parser = parse_positive)]
    pub max_coherence: f64,
}

impl DetectorArgs {
    pub fn params(&self) -> corners::Params {
        corners::Params {
            window: self.window,
            sigma: self.sigma,
            max_epsilon: self.max_epsilon,
            lambda_range: (self.lambda_min, self.lambda_max),
            max_delta: self.max_delta,
            psi_range: (self.psi_min, self.psi_max),
            refit: !self.no_refit,
            subpixel: !self.no_subpixel,
            rectified: self.rectified,
            refit_distance: self.refit_distance,
            max_coherence: self.max_coherence,
            ..corners::Params::default()
        }
    }
}

#[derive(Debug, Args)]
pub struct CornersEvalArgs {
    /// Sequence folders, each with img1..imgN (.ppm/.pgm/.png/.jpg) and H1to2p..H1toNp.
    #[arg(required = true)]
    pub sequences: Vec<PathBuf>,
    /// Output folder: repeatability.csv, repeatability.md and one <sequence>.png plot each.
    #[arg(short = 'o', long = "output", value_name = "OUTDIR")]
    pub output: PathBuf,
    /// Folder of peer detections, <sequence>.json each (written by benches/corners_peers.py).
    #[arg(long, value_name = "DIR")]
    pub peers: Option<PathBuf>,
    /// Correspondence radius r0 in pixels (§2.2).
    #[arg(long, default_value_t = 5.0, value_parser = parse_positive)]
    pub r0: f64,
    /// Worker threads for the detector (0: all cores); timings are per image at this count.
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Also write <sequence>_overlay.png, the corners of img1 drawn at this scale (e.g. 0.5).
    #[arg(long, value_name = "SCALE", value_parser = parse_positive)]
    pub overlays: Option<f64>,
    #[command(flatten)]
    pub detector: DetectorArgs,
}

fn parse_window(s: &str) -> Result<usize, String> {
    let w: usize = s
        .parse()
        .map_err(|_| format!("'{s}' is not a whole number"))?;
    if w < 3 || w.is_multiple_of(2) || w > 101 {
        return Err(format!("the window must be odd, from 3 to 101 (found {w})"));
    }
    Ok(w)
}

fn parse_finite(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    if !v.is_finite() {
        return Err(format!("'{s}' is not a finite number"));
    }
    Ok(v)
}

fn parse_positive(s: &str) -> Result<f64, String> {
    let v = parse_finite(s)?;
    if v <= 0.0 {
        return Err(format!("'{s}' must be positive"));
    }
    Ok(v)
}

fn parse_assignment(s: &str) -> Result<(String, f64), String> {
    let (name, value) = s
        .split_once('=')
        .ok_or_else(|| format!("expected NAME=VALUE, found '{s}'"))?;
    let name = name.trim();
    // Imported floats are named `alias.name`.
    if name.is_empty()
        || name.starts_with('.')
        || name.ends_with('.')
        || !name
            .chars()
            .all(|c| c.is_alphanumeric() || c == '_' || c == '.')
    {
        return Err(format!("'{name}' is not a variable name"));
    }
    let v: f64 = value
        .trim()
        .parse()
        .map_err(|_| format!("'{value}' is not a number"))?;
    if !v.is_finite() {
        return Err(format!("'{value}' is not a finite number"));
    }
    Ok((name.to_string(), v))
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("expected WIDTHxHEIGHT such as 800x600 (each 16 to 8192), found '{s}'");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if !(16..=8192).contains(&w) || !(16..=8192).contains(&h) {
        return Err(bad());
    }
    Ok((w, h))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run_args(extra: &[&str]) -> Result<VsgRunArgs, clap::Error> {
        let mut argv = vec!["castellan", "vsg", "run", "p.vsg", "-o", "m.glb"];
        argv.extend_from_slice(extra);
        Cli::try_parse_from(argv).map(|c| match c.command {
            Command::Vsg(VsgCommand::Run(a)) => a,
            _ => unreachable!(),
        })
    }

    fn corners_args(extra: &[&str]) -> Result<CornersArgs, clap::Error> {
        let mut argv = vec!["castellan", "corners", "a.png", "-o", "c.json"];
        argv.extend_from_slice(extra);
        Cli::try_parse_from(argv).map(|c| match c.command {
            Command::Corners(a) => a,
            _ => unreachable!(),
        })
    }

    fn eval_args(extra: &[&str]) -> Result<CornersEvalArgs, clap::Error> {
        let mut argv = vec!["castellan", "corners-eval", "graf", "wall", "-o", "out"];
        argv.extend_from_slice(extra);
        Cli::try_parse_from(argv).map(|c| match c.command {
            Command::CornersEval(a) => a,
            _ => unreachable!(),
        })
    }

    #[test]
    fn corners_output_is_required_and_defaults_are_the_library_defaults() {
        assert!(Cli::try_parse_from(["castellan", "corners", "a.png"]).is_err());
        let a = corners_args(&[]).unwrap();
        assert_eq!(a.output, PathBuf::from("c.json"));
        assert_eq!(a.overlay, None);
        assert_eq!(a.detector.params(), corners::Params::default());
    }

    #[test]
    fn corners_overlay_flag() {
        assert_eq!(
            corners_args(&["--overlay", "o.png"]).unwrap().overlay,
            Some(PathBuf::from("o.png"))
        );
    }

    #[test]
    fn rectified_flag() {
        assert!(
            corners_args(&["--rectified"])
                .unwrap()
                .detector
                .params()
                .rectified
        );
    }

    #[test]
    fn window_flag_must_be_odd_and_bounded() {
        assert_eq!(corners_args(&["--window", "9"]).unwrap().detector.window, 9);
        for bad in ["8", "1", "103", "x"] {
            assert!(corners_args(&["--window", bad]).is_err(), "{bad}");
        }
    }

    #[test]
    fn sigma_flag_must_be_positive() {
        assert_eq!(corners_args(&["--sigma", "2"]).unwrap().detector.sigma, 2.0);
        assert!(corners_args(&["--sigma", "0"]).is_err());
        assert!(corners_args(&["--sigma", "nan"]).is_err());
    }

    #[test]
    fn threshold_flags() {
        let p = corners_args(&[
            "--max-epsilon",
            "0.7",
            "--lambda-min",
            "0.2",
            "--lambda-max",
            "0.8",
            "--max-delta",
            "1.5",
            "--psi-min",
            "0.1",
            "--psi-max",
            "1.4",
        ])
        .unwrap()
        .detector
        .params();
        assert_eq!(p.max_epsilon, 0.7);
        assert_eq!(p.lambda_range, (0.2, 0.8));
        assert_eq!(p.max_delta, 1.5);
        assert_eq!(p.psi_range, (0.1, 1.4));
        assert!(corners_args(&["--max-delta", "-1"]).is_err());
        assert!(corners_args(&["--psi-max", "inf"]).is_err());
    }

    #[test]
    fn refit_and_subpixel_switches() {
        let p = corners_args(&["--no-refit", "--no-subpixel"])
            .unwrap()
            .detector
            .params();
        assert!(!p.refit && !p.subpixel);
    }

    #[test]
    fn refit_distance_and_coherence_flags() {
        let p = corners_args(&["--refit-distance", "1.5", "--max-coherence", "1"])
            .unwrap()
            .detector
            .params();
        assert_eq!((p.refit_distance, p.max_coherence), (1.5, 1.0));
        assert!(corners_args(&["--refit-distance", "0"]).is_err());
    }

    #[test]
    fn eval_takes_sequences_and_output() {
        let a = eval_args(&[]).unwrap();
        assert_eq!(
            a.sequences,
            vec![PathBuf::from("graf"), PathBuf::from("wall")]
        );
        assert_eq!(a.output, PathBuf::from("out"));
        assert!(Cli::try_parse_from(["castellan", "corners-eval", "-o", "out"]).is_err());
    }

    #[test]
    fn eval_peers_r0_threads_overlays_flags() {
        let a = eval_args(&[
            "--peers",
            "p",
            "--r0",
            "3",
            "--threads",
            "1",
            "--overlays",
            "0.5",
        ])
        .unwrap();
        assert_eq!(a.peers, Some(PathBuf::from("p")));
        assert_eq!((a.r0, a.threads, a.overlays), (3.0, 1, Some(0.5)));
        assert_eq!(eval_args(&[]).unwrap().r0, 5.0);
        assert!(eval_args(&["--r0", "0"]).is_err());
        assert!(eval_args(&["--window", "12"]).is_err());
    }

    #[test]
    fn output_is_required() {
        assert!(Cli::try_parse_from(["castellan", "vsg", "run", "p.vsg"]).is_err());
        assert_eq!(run_args(&[]).unwrap().output, PathBuf::from("m.glb"));
    }

    #[test]
    fn obj_flag() {
        assert_eq!(
            run_args(&["--obj", "m.obj"]).unwrap().obj,
            Some(PathBuf::from("m.obj"))
        );
    }

    #[test]
    fn stats_flag() {
        assert_eq!(
            run_args(&["--stats", "s.json"]).unwrap().stats,
            Some(PathBuf::from("s.json"))
        );
    }

    #[test]
    fn set_flag_repeats_and_checks_its_value() {
        let a = run_args(&["--set", "h=2.5", "--set", "n = 3"]).unwrap();
        assert_eq!(a.set, vec![("h".to_string(), 2.5), ("n".to_string(), 3.0)]);
        assert!(run_args(&["--set", "h"]).is_err());
        assert!(run_args(&["--set", "h=tall"]).is_err());
        assert!(run_args(&["--set", "h=inf"]).is_err());
        let a = run_args(&["--set", "tower.radius=4"]).unwrap();
        assert_eq!(a.set, vec![("tower.radius".to_string(), 4.0)]);
        assert!(run_args(&["--set", "tower.=4"]).is_err());
    }

    #[test]
    fn preview_flags() {
        let a = run_args(&[]).unwrap();
        assert_eq!((a.preview, a.preview_size), (None, (800, 600)));
        let a = run_args(&["--preview", "p.png", "--preview-size", "320x200"]).unwrap();
        assert_eq!(a.preview, Some(PathBuf::from("p.png")));
        assert_eq!(a.preview_size, (320, 200));
        assert!(run_args(&["--preview-size", "320"]).is_err());
        assert!(run_args(&["--preview-size", "0x200"]).is_err());
        assert!(run_args(&["--preview-size", "99999x200"]).is_err());
    }

    #[test]
    fn lib_flag_repeats() {
        assert!(run_args(&[]).unwrap().lib.is_empty());
        let a = run_args(&["--lib", "library", "--lib", "/x"]).unwrap();
        assert_eq!(a.lib, [PathBuf::from("library"), PathBuf::from("/x")]);
    }

    #[test]
    fn seed_flag_defaults_to_the_library_default() {
        assert_eq!(run_args(&[]).unwrap().seed, vsg::DEFAULT_SEED);
        assert_eq!(run_args(&["--seed", "42"]).unwrap().seed, 42);
        assert!(run_args(&["--seed", "-1"]).is_err());
    }

    #[test]
    fn segments_flag_is_bounded() {
        assert_eq!(run_args(&[]).unwrap().segments, 32);
        assert!(run_args(&["--segments", "2"]).is_err());
        assert!(run_args(&["--segments", "100000"]).is_err());
    }

    #[test]
    fn limit_flags() {
        let a = run_args(&["--max-depth", "7", "--max-shapes", "1000"]).unwrap();
        assert_eq!((a.max_depth, a.max_shapes), (7, 1000));
    }
}
