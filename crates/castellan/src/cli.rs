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
    /// Rectify a façade photo into an elevation view (dissertation §3.1.1).
    Rectify(RectifyArgs),
    /// Parse a rectified façade into façades, floors and windows (dissertation §3.1.2-3.1.7).
    Facade(FacadeArgs),
}

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

#[derive(Debug, Args)]
pub struct FacadeArgs {
    /// The (rectified) façade image.
    pub image: PathBuf,
    /// User-drawn training boxes: {"classes": {"window": [[x0,y0,x1,y1], ...], "wall": [...], "background": [...]}}.
    #[arg(long, value_name = "TRAINING.json")]
    pub training: PathBuf,
    /// The façade trees with the 18 parameters of §3.1.6.
    #[arg(short = 'o', long = "output", value_name = "FACADE.json")]
    pub output: PathBuf,
    /// 8-bit label image: 0 background, 1 wall, 2 window.
    #[arg(long, value_name = "LABELS.png")]
    pub labels: Option<PathBuf>,
    /// Draw the façades, floors and windows over the image.
    #[arg(long, value_name = "OVERLAY.png")]
    pub overlay: Option<PathBuf>,
    /// Seed of the sampling of training and PCA pixels.
    #[arg(long, default_value_t = 7)]
    pub seed: u64,
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
    /// Override a declared float: `--set height=12.5` (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = parse_assignment)]
    pub set: Vec<(String, f64)>,
    /// Seed of every random choice; the same program and seed give the same model.
    #[arg(long, default_value_t = vsg::DEFAULT_SEED)]
    pub seed: u64,
    /// Segments around a full circle when meshing curved shapes.
    #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u32).range(3..=4096))]
    pub segments: u32,
    /// Stop with an error when production nests deeper than this.
    #[arg(long, default_value_t = vsg::Limits::default().max_depth)]
    pub max_depth: u32,
    /// Stop with an error when production creates more shapes than this.
    #[arg(long, default_value_t = vsg::Limits::default().max_shapes)]
    pub max_shapes: usize,
}

fn parse_assignment(s: &str) -> Result<(String, f64), String> {
    let (name, value) = s
        .split_once('=')
        .ok_or_else(|| format!("expected NAME=VALUE, found '{s}'"))?;
    let name = name.trim();
    if name.is_empty() || !name.chars().all(|c| c.is_alphanumeric() || c == '_') {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn run_args(extra: &[&str]) -> Result<VsgRunArgs, clap::Error> {
        let mut argv = vec!["castellan", "vsg", "run", "p.vsg", "-o", "m.glb"];
        argv.extend_from_slice(extra);
        Cli::try_parse_from(argv).map(|c| match c.command {
            Command::Vsg(VsgCommand::Run(a)) => a,
            _ => unreachable!("parsed a vsg run command line"),
        })
    }

    fn rectify_args(extra: &[&str]) -> Result<RectifyArgs, clap::Error> {
        let mut argv = vec!["castellan", "rectify", "p.jpg", "-o", "r.png"];
        argv.extend_from_slice(extra);
        Cli::try_parse_from(argv).map(|c| match c.command {
            Command::Rectify(a) => a,
            _ => unreachable!("parsed a rectify command line"),
        })
    }

    fn facade_args(extra: &[&str]) -> Result<FacadeArgs, clap::Error> {
        let mut argv = vec![
            "castellan",
            "facade",
            "f.png",
            "--training",
            "t.json",
            "-o",
            "f.json",
        ];
        argv.extend_from_slice(extra);
        Cli::try_parse_from(argv).map(|c| match c.command {
            Command::Facade(a) => a,
            _ => unreachable!("parsed a facade command line"),
        })
    }

    #[test]
    fn rectify_output_is_required() {
        assert!(Cli::try_parse_from(["castellan", "rectify", "p.jpg"]).is_err());
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

    #[test]
    fn facade_training_and_output_are_required() {
        assert!(Cli::try_parse_from(["castellan", "facade", "f.png", "-o", "f.json"]).is_err());
        assert!(
            Cli::try_parse_from(["castellan", "facade", "f.png", "--training", "t.json"]).is_err()
        );
        let a = facade_args(&[]).unwrap();
        assert_eq!(
            (a.training, a.output),
            (PathBuf::from("t.json"), PathBuf::from("f.json"))
        );
    }

    #[test]
    fn facade_labels_overlay_and_seed_flags() {
        let a = facade_args(&["--labels", "l.png", "--overlay", "o.png", "--seed", "9"]).unwrap();
        assert_eq!(a.labels, Some(PathBuf::from("l.png")));
        assert_eq!(a.overlay, Some(PathBuf::from("o.png")));
        assert_eq!(a.seed, 9);
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
