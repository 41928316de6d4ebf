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
    /// Parse a castle plan drawing into labelled walls, rooms and towers (dissertation ch. 5).
    Plan(PlanArgs),
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

#[derive(Debug, Args)]
pub struct PlanArgs {
    /// The plan drawing (PNG, JPEG or PNM).
    pub image: PathBuf,
    /// The parsed plan: vertices, labelled edges with fits, labelled faces with shapes.
    #[arg(short = 'o', long = "output", value_name = "PLAN.json")]
    pub output: PathBuf,
    /// 8-bit image of label indices (the legend of PLAN.json).
    #[arg(long, value_name = "LABELS.png")]
    pub labels: Option<PathBuf>,
    /// The vectorised walls with their fitted lines and arcs.
    #[arg(long, value_name = "PLAN.svg")]
    pub svg: Option<PathBuf>,
    /// The §5.3 extruded model as binary glTF.
    #[arg(long, value_name = "MODEL.glb")]
    pub model: Option<PathBuf>,
    /// The drawing coloured by label.
    #[arg(long, value_name = "OVERLAY.png")]
    pub overlay: Option<PathBuf>,
    /// Drawing scale in metres per pixel; the model comes out in metres.
    #[arg(long, value_parser = parse_scale)]
    pub scale: Option<f64>,
}

fn parse_scale(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    if !(v.is_finite() && v > 0.0) {
        return Err(format!("the scale must be a positive number, found '{s}'"));
    }
    Ok(v)
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
            Command::Plan(_) => unreachable!("vsg run parsed as plan"),
        })
    }

    fn plan_args(extra: &[&str]) -> Result<PlanArgs, clap::Error> {
        let mut argv = vec!["castellan", "plan", "p.png", "-o", "plan.json"];
        argv.extend_from_slice(extra);
        Cli::try_parse_from(argv).map(|c| match c.command {
            Command::Plan(a) => a,
            Command::Vsg(_) => unreachable!("plan parsed as vsg"),
        })
    }

    #[test]
    fn plan_output_is_required() {
        assert!(Cli::try_parse_from(["castellan", "plan", "p.png"]).is_err());
        let a = plan_args(&[]).unwrap();
        assert_eq!(a.output, PathBuf::from("plan.json"));
        assert_eq!(a.image, PathBuf::from("p.png"));
    }

    #[test]
    fn plan_labels_flag() {
        assert_eq!(
            plan_args(&["--labels", "l.png"]).unwrap().labels,
            Some(PathBuf::from("l.png"))
        );
    }

    #[test]
    fn plan_svg_flag() {
        assert_eq!(
            plan_args(&["--svg", "p.svg"]).unwrap().svg,
            Some(PathBuf::from("p.svg"))
        );
    }

    #[test]
    fn plan_model_flag() {
        assert_eq!(
            plan_args(&["--model", "m.glb"]).unwrap().model,
            Some(PathBuf::from("m.glb"))
        );
    }

    #[test]
    fn plan_overlay_flag() {
        assert_eq!(
            plan_args(&["--overlay", "o.png"]).unwrap().overlay,
            Some(PathBuf::from("o.png"))
        );
    }

    #[test]
    fn plan_scale_flag_is_positive() {
        assert_eq!(plan_args(&[]).unwrap().scale, None);
        assert_eq!(plan_args(&["--scale", "0.05"]).unwrap().scale, Some(0.05));
        assert!(plan_args(&["--scale", "0"]).is_err());
        assert!(plan_args(&["--scale", "-1"]).is_err());
        assert!(plan_args(&["--scale", "nan"]).is_err());
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
