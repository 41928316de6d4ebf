//! Why integration failed (ch. 6): each error names the PROJECT.toml entry at fault.

/// Why integration failed; each names the PROJECT.toml entry at fault.
#[derive(Debug, thiserror::Error)]
pub enum IntegrateError {
    #[error("{image}: {step}: {message}")]
    Facade {
        image: String,
        step: String,
        message: String,
    },
    /// A `[[structure]]` correction that cannot apply; the message names the entry.
    #[error("{0}")]
    Correction(String),
    /// A user's Gothic element correction (`[[gothic.element]]`) that cannot be applied.
    #[error("{image}: {error}")]
    GothicCorrection {
        image: String,
        error: facade::gothic::CorrectionError,
    },
    #[error("[[correspondence]] #{index} (facade = \"{facade}\"): {message}")]
    Correspondence {
        index: usize,
        facade: String,
        message: String,
    },
}

impl IntegrateError {
    /// A chapter 3 or 4 step that failed on the photo `image`.
    pub fn facade(image: &str, step: &str, e: facade::FacadeError) -> IntegrateError {
        IntegrateError::Facade {
            image: image.to_string(),
            step: step.to_string(),
            message: e.to_string(),
        }
    }
}
