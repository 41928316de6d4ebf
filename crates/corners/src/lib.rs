//! The structural corner detector of Sui (2011), chapter 2 ("IPFIT"): corners as the
//! intersection of two straight contours, found by fitting a hyperbola to the edge points in a
//! small window and taking its asymptotes; and the modified repeatability rate of §2.2 that
//! evaluates it.
//!
//! # Brief overview
//! - [`Gray`] holds an image as `f32` luma (build it with [`Gray::from_luma8`] or
//!   [`Gray::from_dynamic`], which accepts colour, alpha and 16-bit images).
//! - [`detect`] runs §2.1 with a [`Params`] and returns [`Corners`]: each [`Corner`] has its
//!   position, the two asymptote directions and the features Φ = (ε, λ, Δ, ψ). The steps are
//!   public: [`edge::edge_map`] (§2.1.1), [`fit::fit_hyperbola`] and [`fit::Asymptotes`]
//!   (§2.1.2–2.1.3), [`detect::candidates`] and [`detect::suppress`] (§2.1.4–2.1.5).
//! - [`repeat`] holds [`repeat::Homography`] (with the Oxford `H1to2p` text format) and
//!   [`repeat::repeatability`], the 1-to-1 mutual-nearest-neighbour rate of §2.2.
//! - [`draw`] renders an overlay of the corners and their asymptotes, and the repeatability /
//!   detection-count plot of figure 2.4.
//! - [`evaluate`] runs §2.2's evaluation over Oxford-style sequences (IPFIT and peer
//!   detections) and writes its CSV and Markdown tables.
//!
//! ```
//! use corners::{Gray, Params, detect};
//! // A bright square on a dark background: four right-angled corners.
//! let (w, x0, x1) = (64usize, 20usize, 44usize);
//! let data = (0..w * w)
//!     .map(|i| if (x0..x1).contains(&(i % w)) && (x0..x1).contains(&(i / w)) { 200.0 } else { 40.0 })
//!     .collect();
//! let found = detect(&Gray::new(w, w, data), &Params::default()).unwrap();
//! assert_eq!(found.corners.len(), 4);
//! let c = &found.corners[0];
//! assert!((c.x - 19.5).abs() < 1.0 && (c.y - 19.5).abs() < 1.0);
//! ```
//!
//! # The Δ normalisation
//! §2.1.5 thresholds |Δ| < 10⁻⁶ and relies on ‖α‖ = 1. With ‖α‖ = 1, Δ changes with the
//! coordinate origin and scale (a corner far from the origin has large d, e, f, which shrink
//! a, b, c), so the threshold means nothing without the text's unstated coordinates. We scale
//! α instead by the fit's own constraint, b² − 4ac = 1, in pixel units. Then Δ is a Euclidean
//! invariant: in standard position 4a′c′ = −1, so Δ = a′c′f″ = −f″/4, and the hyperbola's
//! vertex lies g = 2√(2Δ / tan ψ) pixels from the corner. The threshold on Δ thus bounds how
//! far the fitted curve rounds the corner off (default 0.25: g ≈ 1.4 px at 90°).

// Thresholds are written `!(x < bound)` on purpose: a NaN feature must fail every test.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod detect;
pub mod draw;
pub mod edge;
mod error;
pub mod evaluate;
pub mod fit;
pub mod repeat;
mod sat;

pub use detect::{Corner, Corners, Params, detect};
pub use edge::Gray;
pub use error::Error;
