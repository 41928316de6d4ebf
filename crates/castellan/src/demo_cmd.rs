//! `castellan demo [-o OUTDIR] [--example NAME]`: writes a bundled example project (compiled
//! into the binary) to OUTDIR/project, reconstructs it into OUTDIR, and prints how close the
//! estimate came to what is known of the building. `coucy` (the default) is a real castle from
//! two public-domain drawings (examples/coucy); `synthetic` is castellan's own drawn castle
//! with exact truth (examples/demo).

use std::path::PathBuf;

use anyhow::{Result, anyhow};
use clap::{Args, ValueEnum};
use integrate::estimate::{Footprint, Role, Structure};

use crate::output::Outputs;

/// Files of an example project: name and bytes; TRUTH.json among them.
type Files = &'static [(&'static str, &'static [u8])];

const COUCY: Files = &[
    (
        "PROJECT.toml",
        include_bytes!("../../../examples/coucy/PROJECT.toml"),
    ),
    (
        "plan.png",
        include_bytes!("../../../examples/coucy/plan.png"),
    ),
    (
        "tower_elevation.png",
        include_bytes!("../../../examples/coucy/tower_elevation.png"),
    ),
    (
        "README.md",
        include_bytes!("../../../examples/coucy/README.md"),
    ),
    (
        "TRUTH.json",
        include_bytes!("../../../examples/coucy/TRUTH.json"),
    ),
];

const SYNTHETIC: Files = &[
    (
        "PROJECT.toml",
        include_bytes!("../../../examples/demo/PROJECT.toml"),
    ),
    (
        "plan.png",
        include_bytes!("../../../examples/demo/plan.png"),
    ),
    (
        "keep_south_near.png",
        include_bytes!("../../../examples/demo/keep_south_near.png"),
    ),
    (
        "keep_south_near.training.json",
        include_bytes!("../../../examples/demo/keep_south_near.training.json"),
    ),
    (
        "keep_south_far.png",
        include_bytes!("../../../examples/demo/keep_south_far.png"),
    ),
    (
        "keep_south_far.training.json",
        include_bytes!("../../../examples/demo/keep_south_far.training.json"),
    ),
    (
        "TRUTH.json",
        include_bytes!("../../../examples/demo/TRUTH.json"),
    ),
];

/// The bundled examples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Example {
    /// Coucy castle: Viollet-le-Duc's plan and corner-tower elevation (public domain).
    Coucy,
    /// castellan's synthetic castle: a drawn plan and two photos of the keep, exact truth.
    Synthetic,
}

impl Example {
    fn files(self) -> Files {
        match self {
            Example::Coucy => COUCY,
            Example::Synthetic => SYNTHETIC,
        }
    }

    fn folder(self) -> &'static str {
        match self {
            Example::Coucy => "examples/coucy",
            Example::Synthetic => "examples/demo",
        }
    }
}

/// `castellan demo` flags.
#[derive(Debug, Args)]
pub struct DemoArgs {
    /// Output folder (the example project goes to OUTDIR/project).
    #[arg(short, long, default_value = "castellan-demo")]
    pub output: PathBuf,
    /// Which bundled example to reconstruct.
    #[arg(long, value_enum, default_value_t = Example::Coucy)]
    pub example: Example,
}

pub fn run(args: &DemoArgs) -> Result<()> {
    let project_dir = args.output.join("project");
    let files = args.example.files();
    let mut outputs = Outputs::default();
    for (name, bytes) in files {
        outputs.add(&project_dir.join(name), bytes.to_vec());
    }
    outputs.commit()?;
    let summary = crate::reconstruction::reconstruct(
        &project_dir.join("PROJECT.toml"),
        &args.output,
        &Default::default(),
    )?;
    let truth_bytes = files
        .iter()
        .find(|(n, _)| *n == "TRUTH.json")
        .map(|(_, b)| *b)
        .ok_or_else(|| anyhow!("the example has no TRUTH.json"))?;
    let truth: serde_json::Value = serde_json::from_slice(truth_bytes)?;
    eprintln!("estimate vs truth ({}/TRUTH.json):", args.example.folder());
    let lines = match args.example {
        Example::Coucy => compare_coucy(&summary.estimate.structures, &truth)?,
        Example::Synthetic => compare(&summary.estimate.structures, &truth)?,
    };
    for line in lines {
        eprintln!("{line}");
    }
    crate::reconstruction::print_summary(&summary);
    Ok(())
}

fn num(v: &serde_json::Value) -> Result<f64> {
    v.as_f64()
        .ok_or_else(|| anyhow!("TRUTH.json: {v} is not a number"))
}

fn pct(e: f64, t: f64) -> f64 {
    100.0 * (e - t) / t
}

fn circle(s: &Structure) -> Option<([f64; 2], f64)> {
    match s.footprint {
        Footprint::Circle { center, radius } => Some((center, radius)),
        Footprint::Rectangle { .. } | Footprint::Wall { .. } | Footprint::Blocks { .. } => None,
    }
}

/// Coucy: the mapped corner tower's height and diameter, the donjon's (the keep's) diameter and
/// height, and the round towers and keep found, against published figures.
fn compare_coucy(structures: &[Structure], truth: &serde_json::Value) -> Result<Vec<String>> {
    let mut lines = Vec::new();
    let tower = structures
        .iter()
        .find(|s| !s.facades.is_empty())
        .ok_or_else(|| anyhow!("no structure received the elevation"))?;
    let (lo, hi) = (
        num(&truth["corner_tower_height_m"][0])?,
        num(&truth["corner_tower_height_m"][1])?,
    );
    lines.push(format!(
        "  corner tower height   {:7.2} m   published {lo:.0}–{hi:.0} m   (from the elevation's scale bar)",
        tower.height
    ));
    if let Some((_, r)) = circle(tower) {
        let t = num(&truth["corner_tower_diameter_m"])?;
        lines.push(format!(
            "  corner tower diameter {:7.2} m   published {t:6.2} m   ({:+.1} %, from the plan's scale bar)",
            2.0 * r,
            pct(2.0 * r, t)
        ));
    }
    // Issue 25: the donjon is the keep the plan's shapes name; its height a default over the
    // measured towers'.
    let keep = structures
        .iter()
        .find(|s| s.role == Role::Keep)
        .and_then(|s| circle(s).map(|(_, r)| (r, s.height)));
    match keep {
        Some((r, h)) => {
            let t = num(&truth["donjon_diameter_m"])?;
            lines.push(format!(
                "  donjon diameter       {:7.2} m   published {t:6.2} m   ({:+.1} %, the keep)",
                2.0 * r,
                pct(2.0 * r, t)
            ));
            let t = num(&truth["donjon_height_m"])?;
            lines.push(format!(
                "  donjon height         {h:7.2} m   published {t:6.2} m   ({:+.1} %, 1.5 × the measured tower: a default)",
                pct(h, t)
            ));
        }
        None => lines.push("  donjon                not found as the keep".to_string()),
    }
    let round = structures
        .iter()
        .filter(|s| matches!(s.role, Role::Tower | Role::Keep) && circle(s).is_some())
        .count();
    lines.push(format!(
        "  round towers and keep {round:7}     drawn {:6}",
        truth["round_towers_on_plan"]
    ));
    Ok(lines)
}

/// Estimate vs truth, one line per figure.
fn compare(structures: &[Structure], truth: &serde_json::Value) -> Result<Vec<String>> {
    let mut lines = Vec::new();
    let keep = structures
        .iter()
        .find(|s| !s.facades.is_empty())
        .ok_or_else(|| anyhow!("no structure received a façade"))?;
    let k = &truth["keep"];
    let (h, th) = (keep.height, num(&k["height_m"])?);
    lines.push(format!(
        "  keep height        {h:7.2} m   truth {th:6.2} m   ({:+.1} %)",
        pct(h, th)
    ));
    let f = &keep.facades[0];
    lines.push(format!(
        "  keep width         {:7.2} m   truth {:6.2} m   ({:+.1} %)",
        f.width,
        num(&k["width_m"])?,
        pct(f.width, num(&k["width_m"])?)
    ));
    lines.push(format!(
        "  keep floors        {:7}     truth {:6}",
        f.floors.len(),
        k["floors"]
    ));
    let per_floor: Vec<u32> = f.floors.iter().map(|fl| fl.windows).collect();
    lines.push(format!(
        "  windows per floor  {per_floor:?}   truth {}",
        k["windows_per_floor"]
    ));
    lines.push(format!(
        "  window width       {:7.2} m   truth {:6.2} m",
        f.windows.width,
        num(&k["window_width_m"])?
    ));
    let towers: Vec<&Structure> = structures
        .iter()
        .filter(|s| s.label == plan::label::Label::TowerRoom)
        .collect();
    let truth_towers = truth["towers"].as_array().cloned().unwrap_or_default();
    lines.push(format!(
        "  towers             {:7}     truth {:6}",
        towers.len(),
        truth_towers.len()
    ));
    for t in &truth_towers {
        let c = [num(&t["center_m"][0])?, num(&t["center_m"][1])?];
        let r = num(&t["outer_radius_m"])?;
        let found = towers.iter().find_map(|s| match s.footprint {
            Footprint::Circle { center, radius }
                if (center[0] - c[0]).hypot(center[1] - c[1]) < r =>
            {
                Some((center, radius))
            }
            _ => None,
        });
        match found {
            Some((centre, radius)) => lines.push(format!(
                "  tower at ({:.1}, {:.1}): radius {radius:.2} m (truth {r:.2} m), centre off by {:.2} m",
                c[0],
                c[1],
                (centre[0] - c[0]).hypot(centre[1] - c[1])
            )),
            None => lines.push(format!("  tower at ({:.1}, {:.1}): not found", c[0], c[1])),
        }
    }
    Ok(lines)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: DemoArgs,
    }

    #[test]
    fn demo_output_defaults_to_castellan_demo() {
        assert_eq!(
            Cli::try_parse_from(["x"]).unwrap().args.output,
            PathBuf::from("castellan-demo")
        );
        assert_eq!(
            Cli::try_parse_from(["x", "-o", "d"]).unwrap().args.output,
            PathBuf::from("d")
        );
    }

    #[test]
    fn demo_example_defaults_to_coucy() {
        assert_eq!(
            Cli::try_parse_from(["x"]).unwrap().args.example,
            Example::Coucy
        );
        assert_eq!(
            Cli::try_parse_from(["x", "--example", "synthetic"])
                .unwrap()
                .args
                .example,
            Example::Synthetic
        );
        assert!(Cli::try_parse_from(["x", "--example", "atlantis"]).is_err());
    }

    #[test]
    fn the_bundled_projects_parse_and_bundle_their_files() {
        for example in [Example::Coucy, Example::Synthetic] {
            let files = example.files();
            let text = std::str::from_utf8(files[0].1).unwrap();
            let p = integrate::project::Project::from_toml(text).unwrap();
            let bundled = |name: &str| files.iter().any(|(n, _)| *n == name);
            assert!(bundled(&p.plan) && bundled("TRUTH.json"), "{example:?}");
            for f in &p.facades {
                assert!(bundled(&f.image), "{} is bundled", f.image);
            }
        }
    }
}
