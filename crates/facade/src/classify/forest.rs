//! Departure (§3.1.3–3.1.4, issue 21): the per-pixel class evidence from an ilastik-style
//! random forest ([`pixelclass`]) instead of one Gaussian mixture per class. The boxes are the
//! same user input; the forest sees a bank of multi-scale filter responses (colour, edges,
//! blobs, ridges, texture) and, unlike a mixture fitted to a few hundred pixels, needs no
//! density model of that space. On the real façade sets it gives far better per-pixel maps
//! (docs/pixelclass.md). The search and the Gothic class map read log-likelihoods, so the
//! forest's probabilities are handed on as ln p, floored at [`P_FLOOR`].

use image::RgbImage;
use pixelclass::{Channels, Params, Sample};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::error::{FacadeError, Result};

/// Probabilities below this count as this: the search compares window and wall by their log
/// ratio, and a forest's 0 (no tree voted) would make that ratio infinite. ln 1e-3 ≈ −6.9
/// nats keeps one pixel's say bounded, about as much as the clipped GMM ratios had.
pub const P_FLOOR: f32 = 1e-3;

/// Per-pixel ln p (row-major) of each class given by its boxes (`[x0, y0, x1, y1]`, exclusive
/// ends, inside the image), in the order given, from a forest trained on up to
/// `samples_per_box` pixels of every box, drawn with `seed` (which also seeds the trees).
pub fn log_probabilities(
    img: &RgbImage,
    classes: &[&[[usize; 4]]],
    samples_per_box: usize,
    seed: u64,
    params: &Params,
) -> Result<Vec<Vec<f32>>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0xf0_7e57);
    let mut samples = Vec::new();
    for (index, boxes) in classes.iter().enumerate() {
        for b in *boxes {
            let bw = b[2] - b[0];
            let n = bw * (b[3] - b[1]);
            let take = n.min(samples_per_box);
            for s in 0..take {
                let k = if take == n { s } else { rng.random_range(0..n) };
                samples.push(Sample {
                    x: b[0] + k % bw,
                    y: b[1] + k / bw,
                    class: index,
                });
            }
        }
    }
    let mut params = params.clone();
    params.forest.seed = seed;
    let prob = pixelclass::classify(&Channels::from_rgb(img), &samples, classes.len(), &params)
        .map_err(|e| FacadeError::BadTraining(e.to_string()))?;
    Ok((0..classes.len())
        .map(|c| {
            prob.class_map(c)
                .into_iter()
                .map(|v| v.max(P_FLOOR).ln())
                .collect()
        })
        .collect())
}
