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
    Corners(crate::corners_cmd::CornersArgs),
    /// Modified repeatability rate (§2.2) and detections per image over image sequences with
    /// Oxford-style homographies (H1to2p ... H1to6p), for IPFIT and, optionally, peer detectors.
    CornersEval(crate::corners_cmd::CornersEvalArgs),
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
