//! `facade`: façade photos → rectified elevations → labelled façade trees (Sui 2011, ch. 3).
//!
//! # Brief overview
//! - [`rectify`] (§3.1.1): [`rectify::rectify`] finds the horizontal and vertical vanishing points
//!   and returns a [`rectify::Rectification`] (the homography H, output size, line families).
//!
//! Everything is pure: images in, typed results out; randomness flows from explicit seeds.

pub mod error;
pub mod classify;
pub mod rectify;

pub use error::{FacadeError, Result};
