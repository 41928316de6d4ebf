//! `castellan corners` (ch. 2: CORNERS.json and an overlay) and `castellan corners-eval` (§2.2:
//! modified repeatability and detections per image over Oxford-style sequences, for IPFIT and
//! the peer detections written by `benches/corners_peers.py`).

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use corners::draw::{PALETTE, Series};
use corners::repeat::{Homography, Repeatability, repeatability};
use corners::{Gray, Params};
use serde::Deserialize;

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

/// Peer detections of one sequence (`benches/corners_peers.py`).
#[derive(Debug, Deserialize)]
struct PeerFile {
    /// Detector name → per image (img1, img2, ...) a list of [x, y].
    detectors: BTreeMap<String, Vec<Vec<[f64; 2]>>>,
    /// Detector name → per image milliseconds (optional).
    #[serde(default)]
    time_ms: BTreeMap<String, Vec<f64>>,
}

/// One detector's results over one sequence.
struct Run {
    name: String,
    points: Vec<Vec<[f64; 2]>>,
    time_ms: Vec<f64>,
}

struct Sequence {
    name: String,
    sizes: Vec<(usize, usize)>,
    runs: Vec<Run>,
    /// Per run, for images 2..=n: the repeatability against image 1.
    rates: Vec<Vec<Repeatability>>,
    overlay: Option<image::RgbImage>,
}

fn find_image(dir: &Path, k: usize) -> Option<PathBuf> {
    ["ppm", "pgm", "png", "jpg", "jpeg", "pnm"]
        .iter()
        .map(|ext| dir.join(format!("img{k}.{ext}")))
        .find(|p| p.is_file())
}

fn evaluate_sequence(
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
    let grays: Vec<Gray> = paths.iter().map(|p| read_gray(p)).collect::<Result<_>>()?;
    let sizes: Vec<(usize, usize)> = grays.iter().map(|g| (g.width, g.height)).collect();
    let mut ipfit = Run {
        name: "IPFIT".into(),
        points: Vec::new(),
        time_ms: Vec::new(),
    };
    let mut overlay = None;
    for (g, p) in grays.iter().zip(&paths) {
        let started = Instant::now();
        let found = pool
            .install(|| corners::detect(g, params))
            .map_err(|e| anyhow!("{}: {e}", p.display()))?;
        ipfit.time_ms.push(started.elapsed().as_secs_f64() * 1e3);
        if overlay.is_none()
            && let Some(scale) = args.overlays
        {
            overlay = Some(corners::draw::overlay(
                g,
                &found.corners,
                params.window as f64,
                scale,
            ));
        }
        ipfit
            .points
            .push(found.corners.iter().map(|c| [c.x, c.y]).collect());
    }
    let mut runs = vec![ipfit];
    if let Some(peer_dir) = &args.peers {
        let p = peer_dir.join(format!("{name}.json"));
        let peers: PeerFile = crate::text::read_json(&p, "a peer file")?;
        for (det, points) in peers.detectors {
            if points.len() != paths.len() {
                bail!(
                    "{}: {det} has {} images, the sequence {}",
                    p.display(),
                    points.len(),
                    paths.len()
                );
            }
            let time_ms = peers.time_ms.get(&det).cloned().unwrap_or_default();
            runs.push(Run {
                name: det,
                points,
                time_ms,
            });
        }
    }
    let rates = runs
        .iter()
        .map(|run| {
            homographies
                .iter()
                .enumerate()
                .map(|(i, h)| {
                    repeatability(
                        &run.points[0],
                        sizes[0],
                        &run.points[i + 1],
                        sizes[i + 1],
                        h,
                        args.r0,
                    )
                })
                .collect()
        })
        .collect();
    Ok(Sequence {
        name,
        sizes,
        runs,
        rates,
        overlay,
    })
}

fn mean(v: impl IntoIterator<Item = f64>) -> f64 {
    let (s, n) = v
        .into_iter()
        .fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    if n == 0 { f64::NAN } else { s / n as f64 }
}

fn csv(seqs: &[Sequence]) -> String {
    let mut out = String::from(
        "sequence,detector,image,width,height,detections,time_ms,n1,n2,correspondences,repeatability\n",
    );
    for s in seqs {
        for (run, rates) in s.runs.iter().zip(&s.rates) {
            for (i, pts) in run.points.iter().enumerate() {
                let t = run
                    .time_ms
                    .get(i)
                    .map(|t| format!("{t:.2}"))
                    .unwrap_or_default();
                let r = if i == 0 {
                    ",,,".to_string()
                } else {
                    let r = &rates[i - 1];
                    format!("{},{},{},{:.4}", r.n1, r.n2, r.correspondences, r.rate)
                };
                let _ = writeln!(
                    out,
                    "{},{},{},{},{},{},{t},{r}",
                    s.name,
                    run.name,
                    i + 1,
                    s.sizes[i].0,
                    s.sizes[i].1,
                    pts.len()
                );
            }
        }
    }
    out
}

fn markdown(seqs: &[Sequence], r0: f64, threads: usize) -> String {
    let mut md = format!(
        "# Structural corners: modified repeatability (§2.2, r0 = {r0} px)\n\n\
         Written by `castellan corners-eval`. Repeatability of image 1 against image k counts \
         1-to-1 mutual nearest neighbours over the region both images see; `det/img` is the mean \
         number of detections per image; `ms/img` the mean detection time per image \
         (IPFIT on {} thread(s); peers as timed by `benches/corners_peers.py`).\n",
        if threads == 0 {
            "all".to_string()
        } else {
            threads.to_string()
        }
    );
    let mut names: Vec<String> = Vec::new();
    for s in seqs {
        for r in &s.runs {
            if !names.contains(&r.name) {
                names.push(r.name.clone());
            }
        }
    }
    md.push_str("\n## Mean repeatability over images 2–6, per sequence\n\n| sequence |");
    for n in &names {
        let _ = write!(md, " {n} |");
    }
    md.push_str("\n| --- |");
    md.push_str(&" ---: |".repeat(names.len()));
    md.push('\n');
    for s in seqs {
        let _ = write!(md, "| {} |", s.name);
        for n in &names {
            match s.runs.iter().position(|r| &r.name == n) {
                Some(k) => {
                    let _ = write!(md, " {:.3} |", mean(s.rates[k].iter().map(|r| r.rate)));
                }
                None => md.push_str(" – |"),
            }
        }
        md.push('\n');
    }
    for s in seqs {
        let n = s.sizes.len();
        let _ = write!(md, "\n## {}\n\n| detector |", s.name);
        for k in 2..=n {
            let _ = write!(md, " 1→{k} |");
        }
        md.push_str(" det/img | ms/img |\n| --- |");
        md.push_str(&" ---: |".repeat(n + 1));
        md.push('\n');
        for (run, rates) in s.runs.iter().zip(&s.rates) {
            let _ = write!(md, "| {} |", run.name);
            for r in rates {
                let _ = write!(md, " {:.3} |", r.rate);
            }
            let det = mean(run.points.iter().map(|p| p.len() as f64));
            let t = mean(run.time_ms.iter().copied());
            let t = if t.is_nan() {
                "–".to_string()
            } else {
                format!("{t:.1}")
            };
            let _ = writeln!(md, " {det:.0} | {t} |");
        }
        let t = |name: &str| {
            s.runs
                .iter()
                .find(|r| r.name.eq_ignore_ascii_case(name))
                .map(|r| mean(r.time_ms.iter().copied()))
                .filter(|t| t.is_finite() && *t > 0.0)
        };
        if let (Some(a), Some(b)) = (t("IPFIT"), t("Harris")) {
            let _ = writeln!(md, "\nIPFIT / Harris time: {:.2}×", a / b);
        }
    }
    md
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
        let s = evaluate_sequence(dir, args, &params, &pool)?;
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
        let series: Vec<Series> = s
            .runs
            .iter()
            .zip(&s.rates)
            .enumerate()
            .map(|(i, (run, rates))| Series {
                name: run.name.clone(),
                color: PALETTE[i % PALETTE.len()],
                repeatability: rates.iter().map(|r| r.rate).collect(),
                detections: run.points.iter().map(|p| p.len() as f64).collect(),
            })
            .collect();
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
    /// Refit only windows whose first fit passes the shape thresholds loosened by this factor
    /// (corner within slack × W/2, Δ < slack² × bound, ψ range widened); 0 refits every window
    /// (speed-up, not in §2.1.3).
    #[arg(long, default_value_t = corners::Params::default().first_fit_slack, value_parser = parse_finite)]
    pub first_fit_slack: f64,
    /// Skip the refit of a window whose first-fit corner lies within this many pixels of a
    /// corner candidate already found (0: off; speed-up, not in §2.1).
    #[arg(long, default_value_t = corners::Params::default().duplicate_radius, value_parser = parse_nonnegative)]
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

fn parse_nonnegative(s: &str) -> Result<f64, String> {
    let v = parse_finite(s)?;
    if v < 0.0 {
        return Err(format!("'{s}' must not be negative"));
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

#[cfg(test)]
mod flag_tests {
    use std::path::PathBuf;

    use clap::Parser;

    use super::{CornersArgs, CornersEvalArgs};
    use crate::cli::{Cli, Command};

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
}
