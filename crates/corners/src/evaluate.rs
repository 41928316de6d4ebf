//! The repeatability evaluation of §2.2 (figure 2.4) over Oxford-style sequences: IPFIT and the
//! peer detectors (`benches/corners_peers.py`) on every image, the modified repeatability of
//! image 1 against each other image ([`crate::repeat`]), and the tables `castellan corners-eval`
//! writes (repeatability.csv, repeatability.md). Images, homographies and peer detections come
//! in as data; the caller finds and reads the files.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::time::Instant;

use image::RgbImage;
use serde::Deserialize;

use crate::draw::{PALETTE, Series};
use crate::repeat::{Homography, Repeatability, repeatability};
use crate::{Gray, Params};

/// Peer detections of one sequence (`benches/corners_peers.py`, `<sequence>.json`).
#[derive(Debug, Clone, Default, Deserialize)]
pub struct PeerFile {
    /// Detector name → per image (img1, img2, ...) a list of [x, y].
    pub detectors: BTreeMap<String, Vec<Vec<[f64; 2]>>>,
    /// Detector name → per image milliseconds (optional).
    #[serde(default)]
    pub time_ms: BTreeMap<String, Vec<f64>>,
}

/// One sequence as loaded by the caller: img1, img2, ... and H1to2p, H1to3p, ...
#[derive(Debug, Clone)]
pub struct SequenceData {
    pub name: String,
    pub images: Vec<Gray>,
    /// `homographies[k]` maps image 1 to image k + 2.
    pub homographies: Vec<Homography>,
    pub peers: Option<PeerFile>,
}

/// One detector's results over one sequence.
#[derive(Debug, Clone)]
pub struct Run {
    pub name: String,
    pub points: Vec<Vec<[f64; 2]>>,
    pub time_ms: Vec<f64>,
}

/// Every detector's results over one sequence.
#[derive(Debug, Clone)]
pub struct Sequence {
    pub name: String,
    pub sizes: Vec<(usize, usize)>,
    /// IPFIT first, then the peers in name order.
    pub runs: Vec<Run>,
    /// Per run, for images 2..=n: the repeatability against image 1.
    pub rates: Vec<Vec<Repeatability>>,
    /// IPFIT's corners on image 1, when an overlay scale was given.
    pub overlay: Option<RgbImage>,
}

/// Why a sequence could not be evaluated.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum EvalError {
    #[error(
        "{images} images and {homographies} homographies: need two or more images and one homography for each after the first"
    )]
    Shape { images: usize, homographies: usize },
    /// The detector refused image `image` (0-based).
    #[error("image {}: {error}", image + 1)]
    Detect { image: usize, error: crate::Error },
    #[error("{detector} has {found} images, the sequence {expected}")]
    PeerImages {
        detector: String,
        found: usize,
        expected: usize,
    },
}

/// Runs IPFIT on every image (in `pool`, timed from the caller's thread), takes the peers'
/// points, and measures each detector's repeatability of image 1 against every other image at
/// radius `r0`. With `overlay_scale`, image 1's corners are drawn at that scale.
pub fn evaluate_sequence(
    data: SequenceData,
    params: &Params,
    r0: f64,
    overlay_scale: Option<f64>,
    pool: &rayon::ThreadPool,
) -> Result<Sequence, EvalError> {
    let SequenceData {
        name,
        images: grays,
        homographies,
        peers,
    } = data;
    if grays.len() < 2 || homographies.len() + 1 != grays.len() {
        return Err(EvalError::Shape {
            images: grays.len(),
            homographies: homographies.len(),
        });
    }
    let sizes: Vec<(usize, usize)> = grays.iter().map(|g| (g.width, g.height)).collect();
    let mut ipfit = Run {
        name: "IPFIT".into(),
        points: Vec::new(),
        time_ms: Vec::new(),
    };
    let mut overlay = None;
    for (image, g) in grays.iter().enumerate() {
        let started = Instant::now();
        let found = pool
            .install(|| crate::detect(g, params))
            .map_err(|error| EvalError::Detect { image, error })?;
        ipfit.time_ms.push(started.elapsed().as_secs_f64() * 1e3);
        if overlay.is_none()
            && let Some(scale) = overlay_scale
        {
            overlay = Some(crate::draw::overlay(
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
    if let Some(peers) = peers {
        for (det, points) in peers.detectors {
            if points.len() != grays.len() {
                return Err(EvalError::PeerImages {
                    detector: det,
                    found: points.len(),
                    expected: grays.len(),
                });
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
                        r0,
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

impl Sequence {
    /// The series of the figure 2.4 plot ([`crate::draw::plot`]), one per detector.
    pub fn series(&self) -> Vec<Series> {
        self.runs
            .iter()
            .zip(&self.rates)
            .enumerate()
            .map(|(i, (run, rates))| Series {
                name: run.name.clone(),
                color: PALETTE[i % PALETTE.len()],
                repeatability: rates.iter().map(|r| r.rate).collect(),
                detections: run.points.iter().map(|p| p.len() as f64).collect(),
            })
            .collect()
    }
}

/// The mean, NaN when empty.
pub fn mean(v: impl IntoIterator<Item = f64>) -> f64 {
    let (s, n) = v
        .into_iter()
        .fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    if n == 0 { f64::NAN } else { s / n as f64 }
}

/// repeatability.csv: one row per sequence, detector and image.
pub fn csv(seqs: &[Sequence]) -> String {
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

/// repeatability.md: the mean repeatability per sequence and detector, then each sequence's
/// table; `threads` is the IPFIT thread count the timings were taken at (0: all cores).
pub fn markdown(seqs: &[Sequence], r0: f64, threads: usize) -> String {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A bright square of side 24 at (x0, y0) on a dark 64 × 48 image.
    fn square(x0: usize, y0: usize) -> Gray {
        let (w, h) = (64, 48);
        let data = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                if (x0..x0 + 24).contains(&x) && (y0..y0 + 24).contains(&y) {
                    200.0
                } else {
                    40.0
                }
            })
            .collect();
        Gray::new(w, h, data)
    }

    fn shift(dx: f64, dy: f64) -> Homography {
        Homography([[1.0, 0.0, dx], [0.0, 1.0, dy], [0.0, 0.0, 1.0]])
    }

    fn pool() -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
    }

    /// img_k is img1 moved by (2(k - 1), k - 1); a peer finds three of the four corners and one
    /// stray point per image.
    fn shifted(peers: Option<PeerFile>) -> SequenceData {
        SequenceData {
            name: "shift".into(),
            images: vec![square(10, 10), square(12, 11), square(14, 12)],
            homographies: vec![shift(2.0, 1.0), shift(4.0, 2.0)],
            peers,
        }
    }

    fn peer() -> PeerFile {
        let points = (0..3)
            .map(|k| {
                let (x, y) = (9.5 + 2.0 * k as f64, 9.5 + k as f64);
                vec![
                    [x, y],
                    [x + 24.0, y],
                    [x, y + 24.0],
                    [5.0 + 20.0 * k as f64, 45.0],
                ]
            })
            .collect();
        PeerFile {
            detectors: BTreeMap::from([("Fake".to_string(), points)]),
            time_ms: BTreeMap::from([("Fake".to_string(), vec![1.0, 2.0, 3.0])]),
        }
    }

    #[test]
    fn ipfit_and_a_peer_over_a_shifted_sequence() {
        let s = evaluate_sequence(
            shifted(Some(peer())),
            &Params::default(),
            5.0,
            Some(0.5),
            &pool(),
        )
        .unwrap();
        assert_eq!(s.sizes, vec![(64, 48); 3]);
        let names: Vec<&str> = s.runs.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["IPFIT", "Fake"]);
        assert!(s.runs[0].points.iter().all(|p| p.len() == 4));
        assert_eq!(s.runs[0].time_ms.len(), 3);
        assert!(s.rates[0].iter().all(|r| r.rate == 1.0), "{:?}", s.rates[0]);
        assert!(
            s.rates[1].iter().all(|r| r.rate == 0.75),
            "{:?}",
            s.rates[1]
        );
        assert_eq!(s.overlay.as_ref().map(|o| o.dimensions()), Some((32, 24)));
        let series = s.series();
        assert_eq!(series.len(), 2);
        assert_eq!(series[1].repeatability, vec![0.75, 0.75]);
        assert_eq!(series[0].detections, vec![4.0; 3]);
    }

    #[test]
    fn peers_with_another_image_count_and_missing_homographies_are_refused() {
        let mut p = peer();
        p.detectors.get_mut("Fake").unwrap().pop();
        let e = evaluate_sequence(shifted(Some(p)), &Params::default(), 5.0, None, &pool())
            .unwrap_err();
        assert_eq!(e.to_string(), "Fake has 2 images, the sequence 3");
        let mut d = shifted(None);
        d.homographies.pop();
        let e = evaluate_sequence(d, &Params::default(), 5.0, None, &pool()).unwrap_err();
        assert!(
            matches!(
                e,
                EvalError::Shape {
                    images: 3,
                    homographies: 1
                }
            ),
            "{e}"
        );
        let bad = Params {
            window: 4,
            ..Params::default()
        };
        let e = evaluate_sequence(shifted(None), &bad, 5.0, None, &pool()).unwrap_err();
        assert!(matches!(e, EvalError::Detect { image: 0, .. }), "{e}");
        assert!(e.to_string().starts_with("image 1: bad parameter"), "{e}");
    }

    /// A sequence of three images with hand-made results: IPFIT timed, a peer without times.
    fn hand_made() -> Sequence {
        let rate = |correspondences, rate| Repeatability {
            correspondences,
            n1: 4,
            n2: 4,
            rate,
        };
        Sequence {
            name: "graf".into(),
            sizes: vec![(10, 8); 3],
            runs: vec![
                Run {
                    name: "IPFIT".into(),
                    points: vec![vec![[1.0, 1.0]; 4]; 3],
                    time_ms: vec![2.0, 4.0, 6.0],
                },
                Run {
                    name: "Harris".into(),
                    points: vec![vec![[1.0, 1.0]; 2], vec![], vec![[2.0, 2.0]]],
                    time_ms: vec![],
                },
            ],
            rates: vec![
                vec![rate(4, 1.0), rate(3, 0.75)],
                vec![rate(1, 0.5), rate(0, 0.0)],
            ],
            overlay: None,
        }
    }

    #[test]
    fn csv_has_one_row_per_detector_and_image() {
        assert_eq!(
            csv(&[hand_made()]),
            "sequence,detector,image,width,height,detections,time_ms,n1,n2,correspondences,repeatability\n\
             graf,IPFIT,1,10,8,4,2.00,,,,\n\
             graf,IPFIT,2,10,8,4,4.00,4,4,4,1.0000\n\
             graf,IPFIT,3,10,8,4,6.00,4,4,3,0.7500\n\
             graf,Harris,1,10,8,2,,,,,\n\
             graf,Harris,2,10,8,0,,4,4,1,0.5000\n\
             graf,Harris,3,10,8,1,,4,4,0,0.0000\n"
        );
    }

    #[test]
    fn markdown_has_the_means_and_each_sequence_table() {
        let md = markdown(&[hand_made()], 5.0, 1);
        assert!(md.starts_with("# Structural corners: modified repeatability (§2.2, r0 = 5 px)\n"));
        assert!(md.contains("(IPFIT on 1 thread(s);"), "{md}");
        assert!(
            md.contains(
                "| sequence | IPFIT | Harris |\n| --- | ---: | ---: |\n| graf | 0.875 | 0.250 |\n"
            ),
            "{md}"
        );
        assert!(
            md.contains(
                "## graf\n\n| detector | 1→2 | 1→3 | det/img | ms/img |\n\
                 | --- | ---: | ---: | ---: | ---: |\n\
                 | IPFIT | 1.000 | 0.750 | 4 | 4.0 |\n\
                 | Harris | 0.500 | 0.000 | 1 | – |\n"
            ),
            "{md}"
        );
        // No Harris timing, so no time ratio.
        assert!(!md.contains("IPFIT / Harris time"), "{md}");
        assert!(markdown(&[], 3.0, 0).contains("(IPFIT on all thread(s);"));
    }

    #[test]
    fn the_mean_of_nothing_is_nan() {
        assert!(mean([]).is_nan());
        assert_eq!(mean([1.0, 2.0, 6.0]), 3.0);
    }
}
