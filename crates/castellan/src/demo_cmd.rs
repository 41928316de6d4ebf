//! `castellan demo [-o OUTDIR]`: writes the bundled example project (examples/demo, compiled
//! into the binary) to OUTDIR/project, reconstructs it into OUTDIR, and prints how close the
//! estimate came to the castle's known truth.

use std::path::PathBuf;

use anyhow::{Result, anyhow};
use clap::Args;
use integrate::estimate::{Footprint, Structure};

use crate::output::Outputs;

/// The example project: file name and bytes.
const PROJECT: [(&str, &[u8]); 7] = [
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

/// `castellan demo` flags.
#[derive(Debug, Args)]
pub struct DemoArgs {
    /// Output folder (the example project goes to OUTDIR/project).
    #[arg(short, long, default_value = "castellan-demo")]
    pub output: PathBuf,
}

pub fn run(args: &DemoArgs) -> Result<()> {
    let project_dir = args.output.join("project");
    let mut outputs = Outputs::default();
    for (name, bytes) in PROJECT {
        outputs.add(&project_dir.join(name), bytes.to_vec());
    }
    outputs.commit()?;
    let summary =
        crate::reconstruct_cmd::reconstruct(&project_dir.join("PROJECT.toml"), &args.output, None)?;
    let truth: serde_json::Value = serde_json::from_slice(PROJECT[6].1)?;
    for line in compare(&summary.estimate.structures, &truth)? {
        eprintln!("{line}");
    }
    crate::reconstruct_cmd::print_summary(&summary);
    Ok(())
}

/// Estimate vs truth, one line per figure.
fn compare(structures: &[Structure], truth: &serde_json::Value) -> Result<Vec<String>> {
    let num = |v: &serde_json::Value| {
        v.as_f64()
            .ok_or_else(|| anyhow!("TRUTH.json: not a number"))
    };
    let mut lines = vec!["estimate vs truth (examples/demo/TRUTH.json):".to_string()];
    let keep = structures
        .iter()
        .find(|s| !s.facades.is_empty())
        .ok_or_else(|| anyhow!("no structure received a façade"))?;
    let k = &truth["keep"];
    let pct = |e: f64, t: f64| 100.0 * (e - t) / t;
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
        .filter(|s| s.label == "tower_room")
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
    fn the_bundled_project_parses() {
        let text = std::str::from_utf8(PROJECT[0].1).unwrap();
        let p = integrate::project::Project::from_toml(text).unwrap();
        for f in &p.facades {
            assert!(
                PROJECT.iter().any(|(n, _)| *n == f.image),
                "{} is bundled",
                f.image
            );
        }
    }
}
