//! Departure (§3.1.3–3.1.4, issue 21): the per-pixel class evidence from an ilastik-style
//! random forest ([`pixelclass`]) instead of one Gaussian mixture per class. The boxes are the
//! same user input; the forest sees a bank of multi-scale filter responses (colour, edges,
//! blobs, ridges, texture) and, unlike a mixture fitted to a few hundred pixels, needs no
//! density model of that space. On the real façade sets it gives far better per-pixel maps
//! (docs/pixelclass.md). The search and the Gothic class map read log-likelihoods, so the
//! forest's probabilities are handed on as ln p, floored at [`P_FLOOR`].
//!
//! Which pixels of the boxes train it is decided by the caller (`classify::training_samples`);
//! this file only trains and applies the forest.

use image::RgbImage;
use pixelclass::{Channels, Prepared, Sample};

use crate::error::{FacadeError, Result};

/// Probabilities below this count as this: the search compares window and wall by their log
/// ratio, and a forest's 0 (no tree voted) would make that ratio infinite. ln 1e-3 ≈ −6.9
/// nats keeps one pixel's say bounded, about as much as the clipped GMM ratios had.
pub const P_FLOOR: f32 = 1e-3;

/// The photo's features under `params` ([`pixelclass::prepare`]), for several trainings.
pub fn prepare(img: &RgbImage, params: &pixelclass::Params) -> Result<Prepared> {
    pixelclass::prepare(&Channels::from_rgb(img), params)
        .map_err(|e| FacadeError::BadTraining(e.to_string()))
}

/// Per-pixel ln p of each of `classes` classes (indices of the samples' `class`), row-major,
/// from a forest trained on `samples`; `params.forest.seed` is replaced by `seed`. `prepared`:
/// the photo's features from [`prepare`] with the same `params`, or `None` to compute them.
pub fn log_maps(
    img: &RgbImage,
    prepared: Option<&Prepared>,
    samples: &[Sample],
    classes: usize,
    params: &pixelclass::Params,
    seed: u64,
) -> Result<Vec<Vec<f32>>> {
    let mut params = params.clone();
    params.forest.seed = seed;
    let own;
    let prepared = match prepared {
        Some(p) => p,
        None => {
            own = prepare(img, &params)?;
            &own
        }
    };
    let prob = pixelclass::classify_prepared(prepared, samples, classes, &params)
        .map_err(|e| FacadeError::BadTraining(e.to_string()))?;
    Ok((0..classes)
        .map(|index| {
            prob.class_map(index)
                .into_iter()
                .map(|v| v.max(P_FLOOR).ln())
                .collect()
        })
        .collect())
}
