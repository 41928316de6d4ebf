//! Where the tests find the public-domain castle drawings of `../shared`, shared by the tests
//! and the examples (`#[path]`-included there) that measure the parser on them.

use std::path::PathBuf;

/// `../shared/data/castle_drawings_pd` beside the repository, or `None` with a message on
/// standard error saying it was not found (the caller then skips).
pub fn castle_drawings() -> Option<PathBuf> {
    let data =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/castle_drawings_pd");
    if data.is_dir() {
        Some(data)
    } else {
        eprintln!(
            "skipped: {} not found (the public-domain castle drawings of ../shared)",
            data.display()
        );
        None
    }
}
