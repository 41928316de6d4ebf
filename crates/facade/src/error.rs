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
    BadFixes(FixError),
    /// A numerical step failed (a singular matrix, a degenerate homography).
    #[error("numerical failure: {0}")]
    Numerical(String),
}

/// Result with [`FacadeError`].
pub type Result<T> = std::result::Result<T, FacadeError>;

/// Why the user's façade corrections (`crate::fixes::FacadeFixes`) cannot be used on an image; the message names the value at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FixError {
    #[error("floor line {0} is not a number")]
    FloorLineNotFinite(f64),
    #[error("floor line {y} is above the façade (rectified image top is 0)")]
    FloorLineAbove { y: f64 },
    #[error("floor line {y} is below the façade (rectified height {height})")]
    FloorLineBelow { y: f64, height: u32 },
    #[error("floor lines must go from top to bottom, each below the last: {0} after {1}")]
    FloorLinesUnsorted(f64, f64),
    #[error("{0} floor lines make more than {1} floors")]
    TooManyFloorLines(usize, u32),
    #[error(
        "column {index} [{left}, {right}] must have left < right, both inside 0..{width} (the rectified width)"
    )]
    BadColumn {
        index: usize,
        left: f64,
        right: f64,
        width: u32,
    },
    #[error("columns must go left to right without overlapping: column {0} starts before column {prev} ends", prev = .0 - 1)]
    ColumnsOverlap(usize),
    #[error("{0} columns: at most {1}")]
    TooManyColumns(usize, u32),
    #[error(
        "add_windows #{index} {b:?} must be [x0, y0, x1, y1] with x1 > x0 and y1 > y0, inside the {width}x{height} rectified image"
    )]
    BadWindow {
        index: usize,
        b: [f64; 4],
        width: u32,
        height: u32,
    },
    #[error(
        "remove_windows #{index} {p:?} is not a point inside the {width}x{height} rectified image"
    )]
    BadPoint {
        index: usize,
        p: [f64; 2],
        width: u32,
        height: u32,
    },
    #[error("{0} windows added or removed: at most {1} each")]
    TooManyWindows(usize, usize),
    #[error("blind floor {0}: floors are counted from 1 (the ground floor) to {1}")]
    BlindFloorOutOfRange(u32, u32),
    #[error("blind floor {floor}: the floor lines make only {floors} floors")]
    BlindFloorAboveTop { floor: u32, floors: usize },
    #[error("blind floor {0} is listed twice")]
    BlindFloorTwice(u32),
}
