//! `castellan corners` (ch. 2: CORNERS.json and an overlay) and `castellan corners-eval` (§2.2:
//! modified repeatability and detections per image over Oxford-style sequences, for IPFIT and
//! the peer detections written by `benches/corners_peers.py`). The evaluation itself is
//! `corners::evaluate`; this module finds and reads the files and writes the results.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use corners::evaluate::{self, EvalError, PeerFile, Sequence, SequenceData, csv, markdown, mean};
use corners::repeat::Homography;
use corners::{Gray, Params};

use crate::output::Outputs;

/// Reads any supported image as grey, naming the file in every error.
fn read_gray(path: &Path) -> Result<Gray> {
    Ok(Gray::from_dynamic(&crate::images::read_image(path)?))
}

use crate::images::png as png_bytes;

pub fn run(args: &CornersArgs) -> Result<()> {
    let file = args.image.display().to_string();
    let gray = read_gray(&args.image)?;
    let params = args.detector.params();
    let started = Instant::now();
    let found = crate::progress::with_spinner("structural corners (ch. 2)", |_| {
        corners::detect(&gray, &params)
    })
    .map_err(|e| anyhow!("{file}: {e}"))?;
    let took = started.elapsed();
    let mut outputs = Outputs::default();
    outputs.add(&args.output, serde_json::to_vec_pretty(&found)?);
    if let Some(path) = &args.overlay {
        let img = corners::draw::overlay(&gray, &found.corners, params.window as f64, 1.0);
        outputs.add(path, png_bytes(&img, path)?);
    }
    outputs.commit()?;
    eprintln!(
        "{file}: {} corners in {}×{} px, {:.1} ms; written to {}",
        found.corners.len(),
        found.width,
        found.height,
        took.as_secs_f64() * 1e3,
        args.output.display()
    );
    Ok(())
}

fn find_image(dir: &Path, k: usize) -> Option<PathBuf> {
    ["ppm", "pgm", "png", "jpg", "jpeg", "pnm"]
        .iter()
        .map(|ext| dir.join(format!("img{k}.{ext}")))
        .find(|p| p.is_file())
}

/// Reads one sequence folder (img1, img2, ... and H1to2p, ...; the peers' `<name>.json`) and
/// evaluates it, naming the file in every error.
fn evaluate_folder(
    dir: &Path,
    args: &CornersEvalArgs,
    params: &Params,
    pool: &rayon::ThreadPool,
) -> Result<Sequence> {
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| dir.display().to_string());
    let paths: Vec<PathBuf> = (1..).map_while(|k| find_image(dir, k)).collect();
    if paths.len() < 2 {
        bail!(
            "{}: expected img1, img2, ... (.ppm/.pgm/.png/.jpg) in the folder",
            dir.display()
        );
    }
    let mut homographies = Vec::new();
    for k in 2..=paths.len() {
        let p = dir.join(format!("H1to{k}p"));
        let text = crate::text::read_text(&p)?;
        homographies.push(Homography::parse(&text).map_err(|e| anyhow!("{}: {e}", p.display()))?);
    }
    let images: Vec<Gray> = paths.iter().map(|p| read_gray(p)).collect::<Result<_>>()?;
    let peer_path = args
        .peers
        .as_ref()
        .map(|peer_dir| peer_dir.join(format!("{name}.json")));
    let peers: Option<PeerFile> = peer_path
        .as_ref()
        .map(|p| crate::text::read_json(p, "a peer file"))
        .transpose()?;
    let data = SequenceData {
        name,
        images,
        homographies,
        peers,
    };
    evaluate::evaluate_sequence(data, params, args.r0, args.overlays, pool).map_err(|e| match e {
        EvalError::Detect { image, error } => anyhow!("{}: {error}", paths[image].display()),
        EvalError::PeerImages { .. } => match &peer_path {
            Some(p) => anyhow!("{}: {e}", p.display()),
            None => anyhow!("{e}"),
        },
        EvalError::Shape { .. } => anyhow!("{}: {e}", dir.display()),
    })
}

pub fn eval(args: &CornersEvalArgs) -> Result<()> {
    let params = args.detector.params();
    params.validate().map_err(|e| anyhow!("{e}"))?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()
        .context("cannot start worker threads")?;
    let mut seqs = Vec::new();
    for dir in &args.sequences {
        let s = evaluate_folder(dir, args, &params, &pool)?;
        eprintln!(
            "{}: IPFIT {:.0} detections/image, mean repeatability {:.3}",
            s.name,
            mean(s.runs[0].points.iter().map(|p| p.len() as f64)),
            mean(s.rates[0].iter().map(|r| r.rate))
        );
        seqs.push(s);
    }
    let mut outputs = Outputs::default();
    outputs.add(
        &args.output.join("repeatability.csv"),
        csv(&seqs).into_bytes(),
    );
    outputs.add(
        &args.output.join("repeatability.md"),
        markdown(&seqs, args.r0, args.threads).into_bytes(),
    );
    for s in &seqs {
        let series = s.series();
        let path = args.output.join(format!("{}.png", s.name));
        outputs.add(
            &path,
            png_bytes(&corners::draw::plot(&s.name, &series), &path)?,
        );
        if let Some(img) = &s.overlay {
            let path = args.output.join(format!("{}_overlay.png", s.name));
            outputs.add(&path, png_bytes(img, &path)?);
        }
    }
    outputs.commit()?;
    eprintln!("written to {}", args.output.display());
    Ok(())
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
    #[arg(long, default_value_t = corners::Params::default().window, value_parser = crate::flags::odd_window)]
    pub window: usize,
    /// Gaussian σ of the edge image (§2.1.1).
    #[arg(long, default_value_t = corners::Params::default().sigma, value_parser = crate::flags::positive)]
    pub sigma: f64,
    /// Upper bound on ε, the mean distance (px) of the edge points to their asymptote.
    #[arg(long, default_value_t = corners::Params::default().max_epsilon, value_parser = crate::flags::positive)]
    pub max_epsilon: f64,
    /// Lower bound on λ, the share of inliers on the first asymptote.
    #[arg(long, default_value_t = corners::Params::default().lambda_range.0, value_parser = crate::flags::finite)]
    pub lambda_min: f64,
    /// Upper bound on λ.
    #[arg(long, default_value_t = corners::Params::default().lambda_range.1, value_parser = crate::flags::finite)]
    pub lambda_max: f64,
    /// Upper bound on Δ (normalised so b² − 4ac = 1, pixel units; see the corners crate docs).
    #[arg(long, default_value_t = corners::Params::default().max_delta, value_parser = crate::flags::positive)]
    pub max_delta: f64,
    /// Lower bound on ψ, half the corner's opening angle (rad).
    #[arg(long, default_value_t = corners::Params::default().psi_range.0, value_parser = crate::flags::finite)]
    pub psi_min: f64,
    /// Upper bound on ψ (rad).
    #[arg(long, default_value_t = corners::Params::default().psi_range.1, value_parser = crate::flags::finite)]
    pub psi_max: f64,
    /// Skip the refit without outliers (§2.1.3's optional step).
    #[arg(long)]
    pub no_refit: bool,
    /// Keep edge points at integer pixel positions (as §2.1.1 does).
    #[arg(long)]
    pub no_subpixel: bool,
    /// Outlier distance (px) of the refit and of the inlier sets (§2.1.3).
    #[arg(long, default_value_t = corners::Params::default().refit_distance, value_parser = crate::flags::positive)]
    pub refit_distance: f64,
    /// Skip windows whose gradient orientations agree more than this (one straight contour);
    /// 1 fits every window (speed-up, not in §2.1).
    #[arg(long, default_value_t = corners::Params::default().max_coherence, value_parser = crate::flags::positive)]
    pub max_coherence: f64,
    /// Refit only windows whose first fit passes the shape thresholds loosened by this factor
    /// (corner within slack × W/2, Δ < slack² × bound, ψ range widened); 0 refits every window
    /// (speed-up, not in §2.1.3).
    #[arg(long, default_value_t = corners::Params::default().first_fit_slack, value_parser = crate::flags::finite)]
    pub first_fit_slack: f64,
    /// Skip the refit of a window whose first-fit corner lies within this many pixels of a
    /// corner candidate already found (0: off; speed-up, not in §2.1).
    #[arg(long, default_value_t = corners::Params::default().duplicate_radius, value_parser = crate::flags::nonnegative)]
    pub duplicate_radius: f64,
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
            first_fit_slack: self.first_fit_slack,
            duplicate_radius: self.duplicate_radius,
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
    #[arg(long, default_value_t = 5.0, value_parser = crate::flags::positive)]
    pub r0: f64,
    /// Worker threads for the detector (0: all cores); timings are per image at this count.
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Also write <sequence>_overlay.png, the corners of img1 drawn at this scale (e.g. 0.5).
    #[arg(long, value_name = "SCALE", value_parser = crate::flags::positive)]
    pub overlays: Option<f64>,
    #[command(flatten)]
    pub detector: DetectorArgs,
}

#[cfg(test)]
mod flag_tests {
    use std::path::PathBuf;

    use super::{CornersArgs, CornersEvalArgs};
    use crate::flags::testing::parse;

    fn corners_args(extra: &[&str]) -> Result<CornersArgs, clap::Error> {
        let mut argv = vec!["castellan", "corners", "a.png", "-o", "c.json"];
        argv.extend_from_slice(extra);
        parse::<CornersArgs>(&argv[2..])
    }

    fn eval_args(extra: &[&str]) -> Result<CornersEvalArgs, clap::Error> {
        let mut argv = vec!["castellan", "corners-eval", "graf", "wall", "-o", "out"];
        argv.extend_from_slice(extra);
        parse::<CornersEvalArgs>(&argv[2..])
    }

    #[test]
    fn corners_output_is_required_and_defaults_are_the_library_defaults() {
        assert!(parse::<CornersArgs>(&["a.png"]).is_err());
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
        let p = corners_args(&["--first-fit-slack", "2"])
            .unwrap()
            .detector
            .params();
        assert_eq!(p.first_fit_slack, 2.0);
        assert!(corners_args(&["--refit-distance", "0"]).is_err());
        let p = corners_args(&["--duplicate-radius", "1.5"])
            .unwrap()
            .detector
            .params();
        assert_eq!(p.duplicate_radius, 1.5);
        assert!(corners_args(&["--duplicate-radius", "-1"]).is_err());
    }

    #[test]
    fn eval_takes_sequences_and_output() {
        let a = eval_args(&[]).unwrap();
        assert_eq!(
            a.sequences,
            vec![PathBuf::from("graf"), PathBuf::from("wall")]
        );
        assert_eq!(a.output, PathBuf::from("out"));
        assert!(parse::<CornersEvalArgs>(&["-o", "out"]).is_err());
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
}
