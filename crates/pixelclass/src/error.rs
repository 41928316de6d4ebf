//! What can go wrong: training that cannot define a classifier, and inputs of the wrong shape.

use thiserror::Error;

#[derive(Debug, Clone, PartialEq, Error)]
pub enum PixelClassError {
    #[error("image {width}x{height} is too small: {need}")]
    ImageTooSmall {
        width: usize,
        height: usize,
        need: String,
    },
    #[error("class {class} has no training samples (every class 0..{classes} needs at least one)")]
    EmptyClass { class: usize, classes: usize },
    #[error("{classes} class(es): a classifier needs at least two")]
    TooFewClasses { classes: usize },
    #[error("sample {index} at ({x}, {y}) is outside the {width}x{height} image")]
    SampleOutside {
        index: usize,
        x: usize,
        y: usize,
        width: usize,
        height: usize,
    },
    #[error("sample {index} has class {class}, but there are only {classes} classes")]
    UnknownClass {
        index: usize,
        class: usize,
        classes: usize,
    },
    #[error("{what}: {why}")]
    BadInput { what: String, why: String },
    #[error("the prepared features were made with another filter bank or pixel limit")]
    PreparedOtherwise,
}

pub type Result<T> = std::result::Result<T, PixelClassError>;
