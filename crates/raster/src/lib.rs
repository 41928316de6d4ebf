//! Image operations shared by castellan's stages, one home for what the plan parser (ch. 5)
//! and the façade stages (ch. 3–4) would otherwise each write: one module per family, as
//! imageproc has them. Pure functions on `image` buffers; no files, no serde.
//!
//! - [`edges`]: Prewitt gradients thinned by non-maximum suppression, with the relative
//!   thresholds rectification (§3.1.1) and the Gothic likelihood (§4.2) use.
//! - [`components`]: connected components by flood fill, with sizes and bounding boxes.
//! - [`morphology`]: binary morphology built on imageproc's (openings, top-hats, distances to
//!   the background).
//! - [`text`] and [`legend`]: a 3 × 5 pixel font and the key every overlay carries (issue 22).
//!
//! The corner detector's edges (§2.1.1: Gaussian smoothing, central differences, Canny
//! thinning) are the dissertation's own algorithm and stay in `corners::edge`.

pub mod components;
pub mod edges;
pub mod legend;
#[cfg(test)]
mod literal;
pub mod morphology;
pub mod text;
