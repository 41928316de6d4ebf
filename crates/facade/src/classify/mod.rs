//! Pixel classes (§3.1.2–3.1.4): user boxes per class (TRAINING.json) → per-pixel class
//! log-likelihoods ln P_kj and the initial minimum-error segmentation. Two methods
//! ([`Method`]):
//! - the text's (§3.1.3–3.1.4, [`Method::Gmm`]): 18-D features (RGB + patch PCA) → one
//!   Gaussian mixture per class (as many components as boxes, EM) → ln P_kj;
//! - the default ([`Method::Forest`], departure, [`forest`]): an ilastik-style filter bank and
//!   random forest ([`pixelclass`]) → ln p per class.

pub mod features;
pub mod forest;
pub mod gmm;
pub mod project;
mod simd;
pub mod training;

use std::collections::BTreeMap;

use image::RgbImage;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

pub use features::{FeatureParams, Features};
pub use gmm::{BLOCK, Gaussian, Gmm};
pub use training::{Class, MAX_BOXES, PixelBox, Training};

use crate::error::{FacadeError, Result};

/// Default of [`ClassifyParams::window_inner`].
pub const WINDOW_INNER: f64 = 0.0;
/// Default of [`ClassifyParams::window_ring`].
pub const WINDOW_RING: f64 = 0.1;

/// The training pixels of every box, one group per box (class, points), seeded: up to
/// `samples_per_box` pixels of each box, the boxes in class then drawing order.
///
/// Departure (§3.1.3, issue 21): the text's user draws boxes inside a class; a user who
/// outlines a whole window (`whole`, [`Training::whole_windows`]) gives a box holding frame,
/// bars, reflections and a rim
/// of wall. Such a box is sampled from its middle only (shrunk by `window_inner` on each
/// side), and the ring just outside it (`window_ring` wide, pixels of other window boxes
/// excepted) is added as a wall group — the wall next to a window is the wall a window must
/// be told from. The other boxes are sampled as drawn (the text). The rule was first keyed on
/// box size (a window box ≥ 16 px a side); a 21-px box inside a window then trained its glass
/// as wall (CMP tree window IoU 0.063), so the user says which windows are whole.
pub fn training_samples(
    boxes: &BTreeMap<Class, Vec<PixelBox>>,
    whole: &[PixelBox],
    p: &ClassifyParams,
    width: usize,
    height: usize,
    seed: u64,
) -> Vec<(Class, Vec<(usize, usize)>)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::new();
    let whole = |class: Class, b: &PixelBox| class == Class::Window && whole.contains(b);
    for (&class, bs) in boxes {
        for b in bs {
            let b = if whole(class, b) {
                shrink(b, p.window_inner)
            } else {
                *b
            };
            let bw = b[2] - b[0];
            let n = bw * (b[3] - b[1]);
            let take = n.min(p.samples_per_box);
            let points = (0..take)
                .map(|s| {
                    let k = if take == n { s } else { rng.random_range(0..n) };
                    (b[0] + k % bw, b[1] + k / bw)
                })
                .collect();
            out.push((class, points));
        }
    }
    if p.window_ring > 0.0 && boxes.contains_key(&Class::Wall) {
        let wins = boxes.get(&Class::Window).map_or(&[][..], |v| &v[..]);
        let inside = |x: usize, y: usize| {
            wins.iter()
                .any(|b| x >= b[0] && x < b[2] && y >= b[1] && y < b[3])
        };
        for b in wins.iter().filter(|b| whole(Class::Window, b)) {
            let (gx, gy) = (
                ((b[2] - b[0]) as f64 * p.window_ring).ceil() as usize,
                ((b[3] - b[1]) as f64 * p.window_ring).ceil() as usize,
            );
            let g = [
                b[0].saturating_sub(gx),
                b[1].saturating_sub(gy),
                (b[2] + gx).min(width),
                (b[3] + gy).min(height),
            ];
            let gw = g[2] - g[0];
            let n = gw * (g[3] - g[1]);
            let mut points = Vec::new();
            for _ in 0..4 * p.samples_per_box {
                if points.len() == p.samples_per_box {
                    break;
                }
                let k = rng.random_range(0..n);
                let (x, y) = (g[0] + k % gw, g[1] + k / gw);
                if !inside(x, y) {
                    points.push((x, y));
                }
            }
            if !points.is_empty() {
                out.push((Class::Wall, points));
            }
        }
    }
    out
}

/// `b` shrunk by `frac` of its width and height on each side, at least one pixel kept.
fn shrink(b: &PixelBox, frac: f64) -> PixelBox {
    let (w, h) = (b[2] - b[0], b[3] - b[1]);
    let dx = ((w as f64 * frac) as usize).min((w - 1) / 2);
    let dy = ((h as f64 * frac) as usize).min((h - 1) / 2);
    [b[0] + dx, b[1] + dy, b[2] - dx, b[3] - dy]
}

/// Which per-pixel classifier turns the boxes into class evidence.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Departure (§3.1.3–3.1.4, issue 21): the [`pixelclass`] filter bank and random forest;
    /// the log-likelihoods are ln p of the forest's class probabilities ([`forest`]).
    #[default]
    Forest,
    /// The text's method (§3.1.3–3.1.4): RGB + patch-PCA features, one Gaussian mixture per
    /// class.
    Gmm,
}

/// Classifier settings.
#[derive(Debug, Clone, PartialEq)]
pub struct ClassifyParams {
    pub method: Method,
    /// The GMM's features; `features.seed` is the seed of either method (box sampling, EM,
    /// the forest's trees).
    pub features: FeatureParams,
    /// The forest's filter bank, trees and working resolution ([`Method::Forest`]); its
    /// `forest.seed` is replaced by `features.seed`.
    pub pixel: pixelclass::Params,
    /// Pixels sampled (seeded) per training box, by either method.
    pub samples_per_box: usize,
    /// A whole window's box is sampled from its middle only: shrunk by this fraction of its
    /// width and height on each side. 0: the whole box.
    pub window_inner: f64,
    /// The ring just outside a whole window's box, this fraction of its width and height
    /// wide, trains the wall class (pixels inside any window box excepted). 0: no ring.
    pub window_ring: f64,
    /// Ridge added to every covariance diagonal (features are in [0, 1] units).
    pub ridge: f64,
    /// Plus this fraction of each feature's variance over the whole image. Departure (§3.1.3):
    /// a few small boxes under-sample the texture of a class (a 21-pixel patch changes as it
    /// nears a window's edge), so each component is widened towards the image's spread; see
    /// docs/facade.md for the measured gain. 0 is the text.
    pub ridge_rel: f64,
    pub em_iterations: usize,
}

impl Default for ClassifyParams {
    fn default() -> Self {
        ClassifyParams {
            method: Method::default(),
            features: FeatureParams::default(),
            pixel: pixelclass::Params::default(),
            samples_per_box: 400,
            window_inner: WINDOW_INNER,
            window_ring: WINDOW_RING,
            ridge: 1e-4,
            ridge_rel: 0.05,
            em_iterations: 50,
        }
    }
}

impl ClassifyParams {
    /// The defaults with this classifier and seed: what the façade command, the pipeline and
    /// the server's live map run.
    pub fn with(method: Method, seed: u64) -> ClassifyParams {
        let mut p = ClassifyParams {
            method,
            ..Default::default()
        };
        p.features.seed = seed;
        p
    }
}

/// Per-pixel class log-likelihoods ln P_kj (§3.1.4), row-major; `None` for a class without boxes.
#[derive(Debug, Clone)]
pub struct LogLikelihoods {
    pub width: usize,
    pub height: usize,
    pub maps: [Option<Vec<f32>>; 3],
}

impl LogLikelihoods {
    pub fn get(&self, class: Class) -> Option<&[f32]> {
        self.maps[class as usize].as_deref()
    }
    /// The initial minimum-error segmentation: the most likely class of each pixel.
    pub fn initial_labels(&self) -> Vec<Class> {
        (0..self.width * self.height)
            .map(|i| {
                let mut best = (Class::Wall, f32::NEG_INFINITY);
                for c in Class::ALL {
                    if let Some(m) = self.get(c)
                        && m[i] > best.1
                    {
                        best = (c, m[i]);
                    }
                }
                best.0
            })
            .collect()
    }
}

/// The trained classifier: one mixture per class.
#[derive(Debug, Clone)]
pub struct Classifier {
    pub mixtures: BTreeMap<Class, Gmm>,
}

impl Classifier {
    /// Trains on the boxes (§3.1.3): each box seeds one component, EM refines the mixture.
    pub fn train(
        features: &Features,
        training: &Training,
        p: &ClassifyParams,
    ) -> Result<Classifier> {
        let boxes = training.boxes(features.width, features.height)?;
        let whole = training.whole_window_boxes(features.width, features.height)?;
        let groups = training_samples(
            &boxes,
            &whole,
            p,
            features.width,
            features.height,
            p.features.seed ^ 0x5eed,
        );
        let ridge = ridge_vector(features, p);
        let mut mixtures = BTreeMap::new();
        for class in boxes.keys() {
            let mut data: Vec<&[f32]> = Vec::new();
            let mut members = Vec::new();
            for (_, points) in groups.iter().filter(|g| g.0 == *class) {
                let mut g = Vec::with_capacity(points.len());
                for &(x, y) in points {
                    g.push(data.len());
                    data.push(features.at(x, y));
                }
                members.push(g);
            }
            let gmm = Gmm::fit(&data, &members, &ridge, p.em_iterations)?;
            mixtures.insert(*class, gmm);
        }
        Ok(Classifier { mixtures })
    }

    /// ln P_kj for every pixel and trained class (§3.1.4), BLOCK pixels at a time per row.
    pub fn log_likelihoods(&self, f: &Features) -> LogLikelihoods {
        let (w, n) = (f.width, f.width * f.height);
        let mixtures: Vec<(Class, &Gmm)> = self.mixtures.iter().map(|(c, g)| (*c, g)).collect();
        let nc = mixtures.len();
        let fma = gmm::fma_available();
        // Row y holds class 0's row, then class 1's, ...
        let mut rows = vec![0f32; n * nc];
        if w > 0 {
            rows.par_chunks_mut(w * nc)
                .zip(f.data.par_chunks(w * f.dim))
                .for_each(|(out, feats)| {
                    let mut x = vec![[0f32; BLOCK]; f.dim];
                    let mut diff = x.clone();
                    for x0 in (0..w).step_by(BLOCK) {
                        // Feature-major block; a short last block repeats its last pixel.
                        for lane in 0..BLOCK {
                            let px = (x0 + lane).min(w - 1);
                            for (i, xi) in x.iter_mut().enumerate() {
                                xi[lane] = feats[px * f.dim + i];
                            }
                        }
                        for (ci, (_, gmm)) in mixtures.iter().enumerate() {
                            let lp = gmm.log_pdf_block(fma, &x, &mut diff);
                            let take = BLOCK.min(w - x0);
                            for (o, v) in out[ci * w + x0..ci * w + x0 + take].iter_mut().zip(lp) {
                                *o = v.max(-1e30);
                            }
                        }
                    }
                });
        }
        let mut maps: [Option<Vec<f32>>; 3] = [None, None, None];
        for (ci, (class, _)) in mixtures.iter().enumerate() {
            let m: Vec<f32> = rows
                .chunks((w * nc).max(1))
                .flat_map(|r| &r[ci * w..(ci + 1) * w])
                .copied()
                .collect();
            maps[*class as usize] = Some(m);
        }
        LogLikelihoods {
            width: f.width,
            height: f.height,
            maps,
        }
    }
}

/// Per-dimension ridge: `ridge` + `ridge_rel` × the feature's variance over (a sample of) the image.
fn ridge_vector(f: &Features, p: &ClassifyParams) -> Vec<f64> {
    let n = f.width * f.height;
    let step = (n / 20_000).max(1);
    let (mut s1, mut s2, mut cnt) = (vec![0f64; f.dim], vec![0f64; f.dim], 0.0);
    for x in f.data.chunks(f.dim).step_by(step) {
        for i in 0..f.dim {
            s1[i] += x[i] as f64;
            s2[i] += (x[i] as f64).powi(2);
        }
        cnt += 1.0;
    }
    (0..f.dim)
        .map(|i| {
            let var = (s2[i] / cnt - (s1[i] / cnt).powi(2)).max(0.0);
            p.ridge + p.ridge_rel * var
        })
        .collect()
}

/// Features, training and per-pixel log-likelihoods in one call, by `p.method`. A single-colour image is an
/// error: no boxes can tell classes apart in it.
pub fn classify(img: &RgbImage, training: &Training, p: &ClassifyParams) -> Result<LogLikelihoods> {
    classify_prepared(img, None, training, p)
}

/// A photo the classifier can read: at least 2 × 2 pixels and more than one colour.
fn check_image(img: &RgbImage) -> Result<()> {
    let (w, h) = img.dimensions();
    if w < 2 || h < 2 {
        return Err(FacadeError::ImageTooSmall {
            width: w,
            height: h,
            need: "classification needs at least 2x2 pixels".into(),
        });
    }
    let first = *img.get_pixel(0, 0);
    if img.pixels().all(|q| *q == first) {
        return Err(FacadeError::BadTraining(
            "the image has a single colour; no classes can be told apart".into(),
        ));
    }
    Ok(())
}

/// The photo's forest features ([`forest::prepare`]), made once for several trainings on it
/// ([`classify_prepared`]); `None` for the text's mixtures, which have none to share.
pub fn prepare(img: &RgbImage, p: &ClassifyParams) -> Result<Option<pixelclass::Prepared>> {
    match p.method {
        Method::Forest => {
            check_image(img)?;
            forest::prepare(img, &p.pixel).map(Some)
        }
        Method::Gmm => Ok(None),
    }
}

/// [`classify`] with the forest's features from [`prepare`] (same `img` and `p`), when given;
/// the photo was then checked when they were made.
pub fn classify_prepared(
    img: &RgbImage,
    prepared: Option<&pixelclass::Prepared>,
    training: &Training,
    p: &ClassifyParams,
) -> Result<LogLikelihoods> {
    if prepared.is_none() {
        check_image(img)?;
    }
    let (w, h) = img.dimensions();
    let boxes = training.boxes(w as usize, h as usize)?;
    if p.method == Method::Forest {
        let whole = training.whole_window_boxes(w as usize, h as usize)?;
        let present: Vec<Class> = boxes.keys().copied().collect();
        let seed = p.features.seed ^ 0xf0_7e57;
        let samples: Vec<pixelclass::Sample> =
            training_samples(&boxes, &whole, p, w as usize, h as usize, seed)
                .into_iter()
                .flat_map(|(class, points)| {
                    let index = present.iter().position(|c| *c == class).expect("present");
                    points
                        .into_iter()
                        .map(move |(x, y)| pixelclass::Sample { x, y, class: index })
                })
                .collect();
        let logs = forest::log_maps(
            img,
            prepared,
            &samples,
            present.len(),
            &p.pixel,
            p.features.seed,
        )?;
        let mut maps: [Option<Vec<f32>>; 3] = [None, None, None];
        for (class, map) in present.iter().zip(logs) {
            maps[*class as usize] = Some(map);
        }
        return Ok(LogLikelihoods {
            width: w as usize,
            height: h as usize,
            maps,
        });
    }
    let f = features::compute(img, &p.features);
    let c = Classifier::train(&f, training, p)?;
    Ok(c.log_likelihoods(&f))
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Rgb;

    fn training(pairs: &[(&str, Vec<[f64; 4]>)]) -> Training {
        Training {
            classes: pairs
                .iter()
                .map(|(k, v)| {
                    let class = Class::ALL.into_iter().find(|c| c.name() == *k).unwrap();
                    (class, v.clone())
                })
                .collect(),
            ..Default::default()
        }
    }

    #[test]
    fn whole_windows_are_window_boxes_checked_and_named() {
        let mut t = training(&[("wall", vec![[0.0, 0.0, 5.0, 5.0]])]);
        t.whole_windows = vec![[2.0, 2.0, 8.0, 9.0]];
        // A whole window is a window box: the set is complete.
        assert_eq!(t.boxes(10, 10).unwrap()[&Class::Window], vec![[2, 2, 8, 9]]);
        assert_eq!(t.whole_window_boxes(10, 10).unwrap(), vec![[2, 2, 8, 9]]);
        t.whole_windows.push([9.0, 9.0, 3.0, 3.0]);
        let e = t.validate(10, 10).unwrap_err().to_string();
        assert!(
            e.contains("whole window box 1") && e.contains("inverted"),
            "{e}"
        );
        // Optional in TRAINING.json, and left out when empty.
        let parsed: Training = serde_json::from_str(r#"{"classes": {}}"#).unwrap();
        assert!(parsed.whole_windows.is_empty());
        assert!(
            !serde_json::to_string(&parsed)
                .unwrap()
                .contains("whole_windows")
        );
    }

    #[test]
    fn boxes_are_checked() {
        let t = training(&[("window", vec![[0.0, 0.0, 5.0, 5.0]])]);
        assert!(
            t.boxes(10, 10)
                .unwrap_err()
                .to_string()
                .contains("no wall boxes")
        );
        let t = training(&[
            ("window", vec![[20.0, 20.0, 30.0, 30.0]]),
            ("wall", vec![[0.0, 0.0, 5.0, 5.0]]),
        ]);
        assert!(
            t.boxes(10, 10)
                .unwrap_err()
                .to_string()
                .contains("no pixels inside")
        );
        let e = serde_json::from_str::<Training>(r#"{"classes": {"door": [[0, 0, 5, 5]]}}"#)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("unknown variant `door`") && e.contains("line 1 column"),
            "{e}"
        );
        let t = training(&[
            ("window", vec![[2.0, 2.0, 2.0, 8.0]]),
            ("wall", vec![[0.0, 0.0, 5.0, 5.0]]),
        ]);
        assert!(t.boxes(10, 10).is_err(), "an empty box");
    }

    fn refusal(b: [f64; 4]) -> String {
        training(&[
            ("wall", vec![[0.0, 0.0, 5.0, 5.0], b]),
            ("window", vec![[1.0, 1.0, 4.0, 4.0]]),
        ])
        .boxes(10, 10)
        .unwrap_err()
        .to_string()
    }

    #[test]
    fn an_inverted_training_box_is_refused() {
        let e = refusal([8.0, 1.0, 2.0, 9.0]);
        assert!(e.contains("wall box 1") && e.contains("inverted"), "{e}");
        let e = refusal([1.0, 8.0, 9.0, 2.0]);
        assert!(e.contains("wall box 1") && e.contains("inverted"), "{e}");
    }

    #[test]
    fn a_zero_area_or_non_finite_training_box_is_refused() {
        let e = refusal([3.0, 1.0, 3.0, 9.0]);
        assert!(e.contains("wall box 1") && e.contains("zero area"), "{e}");
        let e = refusal([1.0, 1.0, f64::INFINITY, 9.0]);
        assert!(
            e.contains("wall box 1") && e.contains("not a finite"),
            "{e}"
        );
    }

    #[test]
    fn a_training_box_outside_the_image_is_refused() {
        let e = refusal([11.0, 11.0, 20.0, 20.0]);
        assert!(
            e.contains("wall box 1") && e.contains("no pixels inside"),
            "{e}"
        );
        let e = refusal([-9.0, 2.0, -1.0, 5.0]);
        assert!(e.contains("no pixels inside"), "{e}");
        // Overlapping an edge is clipped to it.
        let t = training(&[
            ("wall", vec![[-3.0, 0.0, 5.0, 12.0]]),
            ("window", vec![[1.0, 1.0, 4.0, 4.0]]),
        ]);
        assert_eq!(t.boxes(10, 10).unwrap()[&Class::Wall], vec![[0, 0, 5, 10]]);
    }

    #[test]
    fn more_training_boxes_than_the_limit_are_refused() {
        let mut t = training(&[
            ("wall", vec![[0.0, 0.0, 5.0, 5.0]; MAX_BOXES - 1]),
            ("window", vec![[1.0, 1.0, 4.0, 4.0]]),
        ]);
        assert!(t.boxes(10, 10).is_ok());
        t.classes
            .get_mut(&Class::Window)
            .unwrap()
            .push([1.0, 1.0, 4.0, 4.0]);
        let e = t.validate(10, 10).unwrap_err().to_string();
        assert!(
            e.contains("1001 boxes") && e.contains("limit of 1000"),
            "{e}"
        );
    }

    #[test]
    fn a_set_being_drawn_validates_without_window_and_wall() {
        let t = training(&[("wall", vec![[0.0, 0.0, 5.0, 5.0]])]);
        assert!(t.validate(10, 10).is_ok());
        assert!(t.boxes(10, 10).is_err());
    }

    #[test]
    fn two_colours_are_told_apart() {
        let mut img = RgbImage::from_pixel(40, 30, Rgb([200, 150, 100]));
        for y in 10..20 {
            for x in 10..20 {
                img.put_pixel(x, y, Rgb([30, 40, 60]));
            }
        }
        let t = training(&[
            ("window", vec![[12.0, 12.0, 18.0, 18.0]]),
            ("wall", vec![[25.0, 2.0, 38.0, 8.0], [2.0, 22.0, 8.0, 28.0]]),
        ]);
        let p = ClassifyParams {
            features: FeatureParams {
                pca_samples: 80,
                ..Default::default()
            },
            ..Default::default()
        };
        let ll = classify(&img, &t, &p).unwrap();
        let labels = ll.initial_labels();
        assert_eq!(labels[15 * 40 + 15], Class::Window);
        assert_eq!(labels[2 * 40 + 2], Class::Wall);
        assert!(ll.get(Class::Background).is_none());
    }

    #[test]
    fn whole_window_boxes_train_wall_on_their_ring() {
        let mut boxes = BTreeMap::new();
        boxes.insert(Class::Window, vec![[20, 20, 40, 50], [60, 5, 66, 11]]);
        boxes.insert(Class::Wall, vec![[0, 0, 9, 9]]);
        let p = ClassifyParams::default();
        let whole = [[20, 20, 40, 50]];
        let g = training_samples(&boxes, &whole, &p, 100, 80, 1);
        // Three drawn boxes, one ring (the other window box is a patch of glass, no ring).
        assert_eq!(g.len(), 4);
        let (class, ring) = &g[3];
        assert_eq!(*class, Class::Wall);
        assert_eq!(ring.len(), p.samples_per_box);
        for &(x, y) in ring {
            assert!((18..42).contains(&x) && (17..53).contains(&y), "{x} {y}");
            assert!(!((20..40).contains(&x) && (20..50).contains(&y)), "{x} {y}");
        }
        // Without the ring the drawn boxes alone, sampled as drawn.
        let off = ClassifyParams {
            window_ring: 0.0,
            ..p.clone()
        };
        assert_eq!(training_samples(&boxes, &whole, &off, 100, 80, 1).len(), 3);
        // A window box the user did not outline whole is sampled as drawn, whatever its size.
        assert_eq!(training_samples(&boxes, &[], &p, 100, 80, 1).len(), 3);
    }

    #[test]
    fn single_colour_image_is_an_error() {
        let img = RgbImage::from_pixel(20, 20, Rgb([9, 9, 9]));
        let t = training(&[
            ("window", vec![[0.0, 0.0, 5.0, 5.0]]),
            ("wall", vec![[6.0, 6.0, 9.0, 9.0]]),
        ]);
        let e = classify(&img, &t, &ClassifyParams::default()).unwrap_err();
        assert!(e.to_string().contains("single colour"), "{e}");
    }
}
