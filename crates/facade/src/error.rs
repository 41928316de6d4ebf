//! The one error type of the crate: every bad input is reported as a value, never a panic.

use thiserror::Error;

/// What can go wrong while rectifying, classifying or parsing a façade image.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FacadeError {
    /// The image has no pixels, or is too small for the operation.
    #[error("the image is too small ({width}x{height}); {need}")]
    ImageTooSmall {
        width: u32,
        height: u32,
        need: String,
    },
    /// Rectification found no two families of converging lines (§3.1.1).
    #[error("cannot rectify: {0}")]
    NoVanishingPoints(String),
    /// Manual line segments (LINES.json) are unusable.
    #[error("bad line segments: {0}")]
    BadLines(String),
    /// Training boxes (TRAINING.json) are unusable (§3.1.2).
    #[error("bad training data: {0}")]
    BadTraining(String),
    /// The user's corrections of the façade estimate cannot be used (issue 22).
    #[error("bad façade corrections: {0}")]
    BadFixes(crate::fixes::FixError),
    /// A numerical step failed (a singular matrix, a degenerate homography).
    #[error("numerical failure: {0}")]
    Numerical(String),
}

/// Result with [`FacadeError`].
pub type Result<T> = std::result::Result<T, FacadeError>;
