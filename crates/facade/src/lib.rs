//! `facade`: façade photos → rectified elevations → labelled façade trees (Sui 2011, ch. 3).
//!
//! # Brief overview
//! - [`rectify`] (§3.1.1): [`rectify::rectify`] finds the horizontal and vertical vanishing points
//!   from Prewitt/Hough edge segments by RANSAC and returns a [`rectify::Rectification`] (the
//!   homography H, output size, line families); [`rectify::rectify_with_lines`] takes user
//!   segments ([`rectify::ManualLines`], LINES.json) instead.
//! - [`classify`] (§3.1.2–3.1.4): a [`classify::Training`] (TRAINING.json boxes) trains the
//!   per-pixel classifier chosen by [`classify::Method`] — by default (departure, issue 21) the
//!   `pixelclass` filter bank and random forest, or the text's 18-D [`classify::Features`] with
//!   one [`classify::Gmm`] per [`classify::Class`]; the result is the per-pixel
//!   [`classify::LogLikelihoods`].
//! - [`model`] (§3.1.5–3.1.6): [`model::FacadeParams`] (the 18 parameters), [`model::Facade`],
//!   [`model::FacadeModel`] (FACADE.json) and its label image.
//! - [`search`] (§3.1.7): [`search::parse`] finds façade boundaries, floors and windows
//!   maximising the merit function.
//! - [`fixes`] (issue 22): the user's corrections — floor lines and column edges the search
//!   keeps, windows added or removed, floors without windows — honoured by
//!   [`search::parse_with`].
//! - [`repeat`]: windows proposed as repeats of one whole window the user drew (normalised
//!   cross-correlation, non-maximum suppression, grid columns and rows).
//! - [`parse_photo`] ([`pipeline`]): classify → repeats → search in one call, the steps the
//!   binaries share.
//! - [`draw`]: the label overlay figure (background red, wall magenta, window green).
//! - [`plausibility`]: warnings for a fitted model that looks wrong against the user's boxes
//!   (windows over most of a façade, the user's windows outside the model's).
//!
//! ```
//! use facade::classify::{classify, ClassifyParams, FeatureParams, Training};
//! use facade::search::{parse, SearchParams};
//! use image::{Rgb, RgbImage};
//!
//! // A wall with a row of three dark windows.
//! let mut img = RgbImage::from_pixel(90, 40, Rgb([190, 140, 100]));
//! for k in 0..3 {
//!     for y in 10..25 {
//!         for x in 10 + 30 * k..25 + 30 * k {
//!             img.put_pixel(x, y, Rgb([30, 40, 60]));
//!         }
//!     }
//! }
//! let training: Training = serde_json::from_str(
//!     r#"{"classes": {"window": [[12, 12, 22, 22]], "wall": [[2, 30, 88, 38]]}}"#,
//! ).unwrap();
//! let params = ClassifyParams {
//!     features: FeatureParams { pca_samples: 100, ..Default::default() },
//!     ..Default::default()
//! };
//! let ll = classify(&img, &training, &params).unwrap();
//! let model = parse(&img, &ll, &SearchParams::default()).unwrap();
//! assert_eq!(model.facades.len(), 1);
//! assert_eq!(model.facades[0].params.n_w, 3);
//! ```
//!
//! Everything is pure: images in, typed results out; randomness flows from explicit seeds.

pub mod classify;
pub mod draw;
pub mod error;
pub mod eval;
pub mod fixes;
pub mod gothic;
pub mod grow;
pub mod model;
pub mod pipeline;
pub mod plausibility;
pub mod rectify;
pub mod repeat;
pub mod search;

pub use error::{FacadeError, Result};
pub use pipeline::{classify_with_repeats, parse_photo, parse_photo_with};
