//! `pixelclass`: pixel classification in the manner of ilastik — a bank of Gaussian filters
//! over each channel at several scales gives every pixel a feature vector, a random forest
//! learns the classes of a few labelled pixels and returns per-class probability maps.
//!
//! # Brief overview
//! - [`channels`]: [`Channels`], planar `f32` images; colour photos become CIELAB
//!   ([`Channels::from_rgb`]), drawings one grey plane ([`Channels::from_gray`]).
//! - [`filters`]: the separable Gaussian and the central differences under the bank.
//! - [`features`]: [`FilterBank`] (scales σ × [`Family`]: smoothing, gradient magnitude, LoG,
//!   DoG, structure-tensor and Hessian eigenvalues) and [`features::compute`] → [`Features`].
//! - [`forest`]: the [`Forest`] (Gini trees on binned features, class-balanced, seeded per tree)
//!   and its [`Probabilities`].
//! - [`autocontext`]: the optional second stage ([`AutoContext`]): a forest on the bank plus
//!   the first stage's maps smoothed and averaged over rows and columns.
//! - [`resample`]: the working resolution (area shrink before, bilinear enlarge after).
//! - [`classify`] runs it all: channels + labelled [`Sample`]s → probabilities; [`prepare`]
//!   and [`classify_prepared`] split it, so that one image's features serve several trainings.
//!
//! ```
//! use image::{Rgb, RgbImage};
//! use pixelclass::{classify, Channels, Params, Sample};
//!
//! // Blue squares on a brick-red wall; two labelled pixels per class.
//! let mut img = RgbImage::from_pixel(60, 40, Rgb([170, 80, 60]));
//! for (x0, y0) in [(5, 5), (35, 20)] {
//!     for y in y0..y0 + 12 {
//!         for x in x0..x0 + 12 {
//!             img.put_pixel(x, y, Rgb([40, 60, 140]));
//!         }
//!     }
//! }
//! let samples = [
//!     Sample { x: 10, y: 10, class: 1 },
//!     Sample { x: 40, y: 25, class: 1 },
//!     Sample { x: 30, y: 5, class: 0 },
//!     Sample { x: 5, y: 35, class: 0 },
//! ];
//! let p = classify(&Channels::from_rgb(&img), &samples, 2, &Params::default()).unwrap();
//! let labels = p.argmax();
//! assert_eq!(labels[12 * 60 + 12], 1);
//! assert_eq!(labels[35 * 60 + 50], 0);
//! ```
//!
//! Pure: no files, no printing; randomness flows from [`ForestParams::seed`], and the output
//! is the same for a seed whatever the number of threads.

pub mod autocontext;
pub mod channels;
pub mod error;
pub mod features;
pub mod filters;
pub mod forest;
pub mod resample;

pub use autocontext::AutoContext;
pub use channels::Channels;
pub use error::{PixelClassError, Result};
pub use features::{Family, Features, FilterBank};
pub use forest::{Forest, ForestParams, Probabilities};

/// A labelled pixel of the input image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Sample {
    pub x: usize,
    pub y: usize,
    pub class: usize,
}

/// The whole classifier's settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    pub bank: FilterBank,
    pub forest: ForestParams,
    /// The filters and the forest run on the image shrunk (area averaging) to at most this
    /// many pixels, and the maps are enlarged back bilinearly; `usize::MAX` keeps the input
    /// resolution. The bank's σ are in pixels of the shrunk image. The default, 150 000 (about
    /// 450 x 330), was measured on the façade sets: no less accurate than the full image, and
    /// the features and the prediction cost a fraction.
    pub max_pixels: usize,
    /// A second, autocontext stage ([`autocontext`]); `None`: the single forest. The default,
    /// [`AutoContext::default`] (row and column means, maps of both stages averaged), was
    /// measured on the façade sets (docs/pixelclass.md).
    pub autocontext: Option<AutoContext>,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            bank: FilterBank::default(),
            forest: ForestParams::default(),
            max_pixels: 150_000,
            autocontext: Some(AutoContext::default()),
        }
    }
}

/// Trains a forest on the filter-bank features of `samples` (class indices `0..classes`) and
/// returns every pixel's class probabilities at the input's resolution.
pub fn classify(
    ch: &Channels,
    samples: &[Sample],
    classes: usize,
    p: &Params,
) -> Result<Probabilities> {
    classify_prepared(&prepare(ch, p)?, samples, classes, p)
}

/// An image's filter-bank features at the working resolution: what every training on that
/// image shares ([`classify_prepared`]).
#[derive(Debug, Clone)]
pub struct Prepared {
    /// The input's size.
    pub width: usize,
    pub height: usize,
    /// The features, at [`working_size`].
    pub features: Features,
    /// The bank and the pixel limit they were computed with.
    bank: FilterBank,
    max_pixels: usize,
}

/// The features of `ch` under `p.bank`, at `p.max_pixels` at most.
pub fn prepare(ch: &Channels, p: &Params) -> Result<Prepared> {
    let (w, h) = (ch.width, ch.height);
    if w < 2 || h < 2 {
        return Err(PixelClassError::ImageTooSmall {
            width: w,
            height: h,
            need: "classification needs at least 2x2 pixels".into(),
        });
    }
    let (ws, hs) = working_size(w, h, p.max_pixels);
    let features = if (ws, hs) == (w, h) {
        features::compute(ch, &p.bank)
    } else {
        features::compute(&resample::shrink(ch, ws, hs), &p.bank)
    };
    Ok(Prepared {
        width: w,
        height: h,
        features,
        bank: p.bank.clone(),
        max_pixels: p.max_pixels,
    })
}

/// [`classify`] on features made by [`prepare`]; `p.bank` and `p.max_pixels` must be the ones
/// they were made with.
pub fn classify_prepared(
    prep: &Prepared,
    samples: &[Sample],
    classes: usize,
    p: &Params,
) -> Result<Probabilities> {
    if prep.bank != p.bank || prep.max_pixels != p.max_pixels {
        return Err(PixelClassError::PreparedOtherwise);
    }
    let (w, h) = (prep.width, prep.height);
    if classes < 2 {
        return Err(PixelClassError::TooFewClasses { classes });
    }
    for (index, s) in samples.iter().enumerate() {
        if s.x >= w || s.y >= h {
            return Err(PixelClassError::SampleOutside {
                index,
                x: s.x,
                y: s.y,
                width: w,
                height: h,
            });
        }
        if s.class >= classes {
            return Err(PixelClassError::UnknownClass {
                index,
                class: s.class,
                classes,
            });
        }
    }
    let f = &prep.features;
    let (ws, hs) = (f.width, f.height);
    let dim = f.dim();
    let mut x = Vec::with_capacity(samples.len() * dim);
    let mut labels = Vec::with_capacity(samples.len());
    let mut idx = Vec::with_capacity(samples.len());
    let mut pos = Vec::with_capacity(samples.len());
    for s in samples {
        let (sx, sy) = (s.x * ws / w, s.y * hs / h);
        let i = sy * ws + sx;
        x.extend(f.planes.iter().map(|pl| pl[i]));
        labels.push(s.class);
        idx.push(i);
        pos.push((sx, sy));
    }
    let forest = Forest::train(&x, dim, &labels, classes, &p.forest)?;
    let mut prob = forest.predict(f)?;
    if let Some(ac) = &p.autocontext {
        prob = autocontext::stage_two(
            f.clone(),
            &prob,
            &idx,
            &pos,
            &labels,
            classes,
            &p.forest,
            ac,
        )?;
    }
    Ok(if (ws, hs) == (w, h) {
        prob
    } else {
        resample::enlarge(&prob, w, h)
    })
}

/// The size the classifier works at: the input scaled by one factor to at most `max_pixels`
/// pixels (and at least 2 on each side).
pub fn working_size(w: usize, h: usize, max_pixels: usize) -> (usize, usize) {
    if w * h <= max_pixels {
        return (w, h);
    }
    let s = (max_pixels as f64 / (w * h) as f64).sqrt();
    let ws = ((w as f64 * s).floor() as usize).clamp(2, w);
    let hs = ((h as f64 * s).floor() as usize).clamp(2, h);
    (ws, hs)
}

#[cfg(test)]
mod tests;
