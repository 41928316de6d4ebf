//! The wall-ink model: a filter bank over the normalised grey drawing and one or two random
//! forests (the second reads the first's wall map, smoothed at several scales, as context —
//! ilastik's autocontext), serialised with postcard so that a trained model ships inside the
//! binary (`crates/plan/models/wall_ink.bin`, retrained by `cargo run --release -p plan
//! --example train_ink`; docs/plan.md).

use image::GrayImage;
use pixelclass::autocontext::{AutoContext, context};
use pixelclass::{Channels, Features, FilterBank, Forest, Probabilities};
use serde::{Deserialize, Serialize};

/// Version of the model file; a file of another version is refused.
pub const FORMAT: u32 = 2;

/// The model shipped with castellan.
pub const SHIPPED: &[u8] = include_bytes!("../../models/wall_ink.bin");

/// A trained wall-ink classifier.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WallInk {
    pub format: u32,
    /// Features of the normalised grey drawing at the working resolution.
    pub bank: FilterBank,
    /// The resolution the features are computed at.
    pub working: Working,
    /// σ (working pixels) at which the thresholded ink (Otsu's level, as §5.1.2's rule reads
    /// the drawing) is smoothed into extra features; 0 is the ink itself. The forest then
    /// learns where to depart from the threshold (hatching filled, letters dropped) rather
    /// than the whole of it.
    pub ink_sigmas: Vec<f32>,
    /// σ (working pixels) of the stage-1 wall map given to stage 2; empty: one stage.
    pub context_sigmas: Vec<f32>,
    /// Stage 1, then stage 2 if `context_sigmas` is not empty; class 1 is wall.
    pub stages: Vec<Forest>,
    /// How it was trained (seed, sources, counts), for the report.
    pub provenance: String,
}

/// Why a model file cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    #[error("wall-ink model: {0}")]
    Decode(String),
    #[error("wall-ink model has format {found}, this program reads format {FORMAT}")]
    Format { found: u32 },
    #[error("wall-ink model: {0}")]
    Invalid(String),
}

impl WallInk {
    pub fn to_bytes(&self) -> Vec<u8> {
        postcard::to_allocvec(self).expect("a model always serialises")
    }

    /// Reads and checks a model (format, stage count, every forest's structure and width).
    pub fn from_bytes(bytes: &[u8]) -> Result<WallInk, ModelError> {
        let m: WallInk =
            postcard::from_bytes(bytes).map_err(|e| ModelError::Decode(e.to_string()))?;
        if m.format != FORMAT {
            return Err(ModelError::Format { found: m.format });
        }
        let want = if m.context_sigmas.is_empty() { 1 } else { 2 };
        if m.stages.len() != want || m.working.max_side < 16 || m.bank.sigmas.is_empty() {
            return Err(ModelError::Invalid(format!(
                "{} stages for {} context scales, working side {}",
                m.stages.len(),
                m.context_sigmas.len(),
                m.working.max_side
            )));
        }
        let dim1 = m.bank.dim(1) + m.ink_sigmas.len();
        for (k, f) in m.stages.iter().enumerate() {
            f.validate()
                .map_err(|e| ModelError::Invalid(format!("stage {}: {e}", k + 1)))?;
            let dim = dim1 + k * m.context_sigmas.len();
            if f.dim != dim || f.classes != 2 {
                return Err(ModelError::Invalid(format!(
                    "stage {} reads {} features of {} classes, expected {dim} of 2",
                    k + 1,
                    f.dim,
                    f.classes
                )));
            }
        }
        Ok(m)
    }

    /// The model that ships with castellan.
    pub fn shipped() -> Result<WallInk, ModelError> {
        WallInk::from_bytes(SHIPPED)
    }

    /// The autocontext settings of stage 2.
    pub fn context(&self) -> AutoContext {
        smoothed_context(&self.context_sigmas)
    }

    /// P(wall) of every pixel of `grey`, at `out_w` × `out_h` (the drawing's size or a
    /// multiple of it).
    pub fn wall_probability(&self, grey: &GrayImage, out_w: u32, out_h: u32) -> Vec<f32> {
        let mut features = self.features(grey);
        let p = self.working_map(&mut features);
        let wall = wall_class(&p);
        pixelclass::resample::enlarge(&wall, out_w as usize, out_h as usize).data
    }

    /// The features of `grey` at the working resolution ([`working_features`]).
    pub fn features(&self, grey: &GrayImage) -> Features {
        working_features(grey, &self.working, &self.bank, &self.ink_sigmas)
    }

    /// The maps of every stage at the working resolution, given the bank's features; stage 2's
    /// context planes are added to `features` for its prediction and taken off again (no copy
    /// of the bank's planes: at 1200 × 800 they are 96 MB).
    pub fn working_map(&self, features: &mut Features) -> Probabilities {
        let mut p = predict(&self.stages[0], features);
        if let Some(stage2) = self.stages.get(1) {
            let bank = features.dim();
            add_context(features, &p, &self.context());
            p = predict(stage2, features);
            features.planes.truncate(bank);
            features.names.truncate(bank);
        }
        p
    }
}

fn predict(forest: &Forest, f: &Features) -> Probabilities {
    forest
        .predict(f)
        .expect("a validated forest matches its own bank")
}

/// Autocontext from the wall map smoothed at `sigmas` only (no row or column means): the
/// settings of stage 2 in training and use, and of the refinement by the user's strokes.
pub fn smoothed_context(sigmas: &[f32]) -> AutoContext {
    AutoContext {
        sigmas: sigmas.to_vec(),
        row_column: false,
        folds: 0,
        fold_trees: 0,
        average: false,
    }
}

/// The features of stage 2: the bank's plus the context of the stage-1 maps `p`.
pub fn with_context(mut f: Features, p: &Probabilities, ac: &AutoContext) -> Features {
    add_context(&mut f, p, ac);
    f
}

/// Adds the context of the wall class of `p` to `f`. Class 0's planes would be 1 − class 1's,
/// so they are neither computed nor given to the forest.
fn add_context(f: &mut Features, p: &Probabilities, ac: &AutoContext) {
    let (planes, names) = context(&wall_class(p), ac);
    f.planes.extend(planes);
    f.names
        .extend(names.into_iter().map(|n| n.replacen("p0", "p1", 1)));
}

/// The wall class of `p` alone. Smoothing and bilinear enlargement treat each class by
/// itself, and class 0 is 1 − class 1: the other half of the work is not needed.
pub fn wall_class(p: &Probabilities) -> Probabilities {
    Probabilities {
        width: p.width,
        height: p.height,
        classes: 1,
        data: p.class_map(1),
    }
}

/// The resolution the wall ink works at, the same in training and in use: drawings whose
/// longer side is under `enlarge_below` are enlarged (bilinear, by an integer factor of at
/// most 2, as the plan parser enlarges small drawings: [`crate::Options::upsample_below`]),
/// those over `max_side` shrunk (area averaging); the maps are resampled to the size asked
/// for. The default enlarges nothing: trained and used at ×2 below 1000 px, the model read
/// fewer points right on both development sets (120 / 97 against 123 / 113 of 169 / 159) in
/// twice the time (median 2.0 s against 0.9 s per drawing).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Working {
    pub enlarge_below: u32,
    pub max_side: u32,
}

impl Default for Working {
    fn default() -> Self {
        Working {
            enlarge_below: 0,
            max_side: 1200,
        }
    }
}

/// The working size of a `w` × `h` drawing ([`Working`]).
pub fn working_size(w: u32, h: u32, working: &Working) -> (u32, u32) {
    let long = w.max(h);
    if long < working.enlarge_below {
        let k = working.enlarge_below.div_ceil(long.max(1)).min(2);
        return (w * k, h * k);
    }
    if long <= working.max_side {
        return (w, h);
    }
    let s = f64::from(working.max_side) / f64::from(long);
    let f = |v: u32| ((f64::from(v) * s).round() as u32).max(2);
    (f(w), f(h))
}

/// The normalised drawing ([`normalise`]) at the working size, and its features: the bank's,
/// then the thresholded ink at each of `ink_sigmas` ([`WallInk::ink_sigmas`]).
pub fn working_features(
    grey: &GrayImage,
    working: &Working,
    bank: &FilterBank,
    ink_sigmas: &[f32],
) -> Features {
    let (w, h) = grey.dimensions();
    let norm = normalise(grey);
    let (ws, hs) = working_size(w, h, working);
    let ch = if ws > w {
        let big = image::imageops::resize(&norm, ws, hs, image::imageops::FilterType::Triangle);
        Channels::from_gray(&big)
    } else if ws < w {
        pixelclass::resample::shrink(&Channels::from_gray(&norm), ws as usize, hs as usize)
    } else {
        Channels::from_gray(&norm)
    };
    let mut f = pixelclass::features::compute(&ch, bank);
    if ink_sigmas.is_empty() {
        return f; // the default: no thresholded-ink planes, so no threshold to take
    }
    let level = f32::from(crate::binarize::threshold_level(&norm)) / 255.0;
    let ink: Vec<f32> = ch.planes[0]
        .iter()
        .map(|&v| f32::from(u8::from(v < level)))
        .collect();
    for &sigma in ink_sigmas {
        let plane = if sigma > 0.0 {
            pixelclass::filters::smooth(&ink, ch.width, ch.height, sigma)
        } else {
            ink.clone()
        };
        f.planes.push(plane);
        f.names.push(format!("ink σ{sigma}"));
    }
    f
}

/// The grey stretched so that its 1st percentile is 0 and its 90th is 255.
pub fn normalise(grey: &GrayImage) -> GrayImage {
    let mut hist = [0usize; 256];
    grey.pixels().for_each(|p| hist[p[0] as usize] += 1);
    let n = grey.len();
    let at = |q: f64| {
        let want = (q * n as f64) as usize;
        let mut seen = 0;
        (0..256)
            .find(|&v| {
                seen += hist[v];
                seen > want
            })
            .unwrap_or(255) as f32
    };
    let (lo, hi) = (at(0.01), at(0.90));
    if hi - lo < 16.0 {
        return grey.clone(); // a blank or flat sheet: nothing to stretch
    }
    let k = 255.0 / (hi - lo);
    GrayImage::from_fn(grey.width(), grey.height(), |x, y| {
        let v = (f32::from(grey.get_pixel(x, y)[0]) - lo) * k;
        image::Luma([v.clamp(0.0, 255.0) as u8])
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Luma;

    #[test]
    fn normalise_stretches_ink_and_paper_to_the_ends() {
        // 95 % paper at 200, 5 % ink at 100.
        let g = GrayImage::from_fn(20, 20, |x, y| {
            Luma([if (y * 20 + x) % 20 == 0 { 100 } else { 200 }])
        });
        let n = normalise(&g);
        assert_eq!(n.get_pixel(0, 0)[0], 0);
        assert_eq!(n.get_pixel(1, 0)[0], 255);
        let flat = GrayImage::from_pixel(5, 5, Luma([240]));
        assert_eq!(normalise(&flat), flat);
    }

    #[test]
    fn working_size_enlarges_small_drawings_and_shrinks_large_ones() {
        let wk = Working {
            enlarge_below: 1000,
            max_side: 1200,
        };
        assert_eq!(working_size(600, 400, &wk), (1200, 800));
        assert_eq!(working_size(300, 200, &wk), (600, 400));
        assert_eq!(working_size(1100, 400, &wk), (1100, 400));
        assert_eq!(working_size(3000, 2000, &wk), (1200, 800));
        assert_eq!(working_size(600, 400, &Working::default()), (600, 400));
    }

    #[test]
    fn the_shipped_model_reads_and_a_damaged_one_is_refused() {
        let m = WallInk::shipped().unwrap();
        assert_eq!(WallInk::from_bytes(&m.to_bytes()).unwrap(), m);
        assert!(matches!(
            WallInk::from_bytes(&SHIPPED[..SHIPPED.len() / 2]),
            Err(ModelError::Decode(_))
        ));
        let mut other = m.clone();
        other.format = FORMAT + 1;
        assert_eq!(
            WallInk::from_bytes(&other.to_bytes()),
            Err(ModelError::Format { found: FORMAT + 1 })
        );
        let mut short = m;
        short.stages.truncate(0);
        assert!(matches!(
            WallInk::from_bytes(&short.to_bytes()),
            Err(ModelError::Invalid(_))
        ));
    }
}
