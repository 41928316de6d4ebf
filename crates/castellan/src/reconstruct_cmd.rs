//! `castellan reconstruct PROJECT.toml -o OUTDIR` (issue 9, dissertation ch. 6 and §7.2.2–7.2.3):
//! plan drawing and façade photos → estimates → integrated hierarchy → VSG program → model,
//! with the overlays of every step and an HTML report (the adapter is `reconstruction.rs`, shared
//! with `demo` and `serve`; the work is `integrate::pipeline`'s).

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;

/// `castellan reconstruct` flags.
#[derive(Debug, Args)]
pub struct ReconstructArgs {
    /// The project file (PROJECT.toml contract).
    pub project: PathBuf,
    /// Output folder: model.vsg, model.glb, model.obj, model.city.json, model.ifc, stats.json,
    /// estimate.json, index.html.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also write the CityJSON model (OUTDIR/model.city.json) here.
    #[arg(long, value_name = "MODEL.city.json")]
    pub cityjson: Option<PathBuf>,
    /// Also write the IFC model (OUTDIR/model.ifc) here.
    #[arg(long, value_name = "MODEL.ifc")]
    pub ifc: Option<PathBuf>,
    /// Seed for the classifier's sampling and the program's randomness (overrides the project's).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Per-pixel classifier of the façade photos: forest (filter bank + random forest) or gmm
    /// (the dissertation's Gaussian mixtures, §3.1.3–3.1.4).
    #[arg(long, default_value = "forest", value_parser = crate::flags::classifier)]
    pub classifier: facade::classify::Method,
}

pub fn run(args: &ReconstructArgs) -> Result<()> {
    let options = integrate::pipeline::Options {
        seed: args.seed,
        classifier: args.classifier,
    };
    let s = crate::reconstruction::reconstruct(&args.project, &args.output, &options)?;
    crate::reconstruction::print_summary(&s);
    let mut copies = crate::output::Outputs::default();
    for (path, name) in [
        (&args.cityjson, "model.city.json"),
        (&args.ifc, "model.ifc"),
    ] {
        if let Some(path) = path {
            let from = args.output.join(name);
            let bytes =
                std::fs::read(&from).with_context(|| format!("cannot read {}", from.display()))?;
            copies.add(path, bytes);
        }
    }
    copies.commit()
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: ReconstructArgs,
    }

    #[test]
    fn reconstruct_needs_a_project_and_an_output_folder() {
        assert!(Cli::try_parse_from(["x", "p.toml"]).is_err());
        let c = Cli::try_parse_from(["x", "p.toml", "-o", "out", "--seed", "3"]).unwrap();
        assert_eq!(c.args.output, PathBuf::from("out"));
        assert_eq!(c.args.seed, Some(3));
        assert_eq!(c.args.classifier, facade::classify::Method::Forest);
        assert_eq!((c.args.cityjson, c.args.ifc), (None, None));
        let c = Cli::try_parse_from([
            "x",
            "p.toml",
            "-o",
            "o",
            "--cityjson",
            "c.json",
            "--ifc",
            "m.ifc",
        ])
        .unwrap();
        assert_eq!(c.args.cityjson, Some(PathBuf::from("c.json")));
        assert_eq!(c.args.ifc, Some(PathBuf::from("m.ifc")));
    }

    #[test]
    fn the_classifier_is_forest_or_gmm() {
        let c = Cli::try_parse_from(["x", "p.toml", "-o", "o", "--classifier", "gmm"]).unwrap();
        assert_eq!(c.args.classifier, facade::classify::Method::Gmm);
        let e = Cli::try_parse_from(["x", "p.toml", "-o", "o", "--classifier", "svm"])
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("'svm' is not a classifier"), "{e}");
    }
}
