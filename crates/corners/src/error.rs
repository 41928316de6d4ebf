//! The library's one error type, re-exported as `corners::Error`: parameters out of range
//! (`detect`) and homographies that cannot be used (`repeat`).

/// Errors of the library.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum Error {
    #[error("bad parameter: {0}")]
    BadParam(String),
    #[error("bad homography: {0}")]
    BadHomography(String),
}
