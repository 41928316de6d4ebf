//! Learned wall ink (issue 26): a per-pixel separation of structural wall from everything else
//! on a plan sheet, replacing the hand-tuned clean-up chain before §5.1.3 by default.
//!
//! - [`paint`]: the wall masks painted on public-domain plans, kept as recipes (ink regions
//!   kept, polygons filled or erased, walls drawn as thick polylines) and rendered to masks.
//! - [`model`]: the trained classifier ([`WallInk`]: filter bank, one or two forests), its
//!   file format, and P(wall) of every pixel of a drawing.
//! - [`train`]: training a model from drawings with wall masks.
//! - [`refine`]: the user's "wall" / "not wall" strokes refine the model for one drawing.
pub mod model;
pub mod paint;
pub mod refine;
pub mod train;

pub use model::WallInk;

use std::sync::{Arc, OnceLock};

/// Where the plan parser's wall mask comes from.
#[derive(Clone)]
pub enum Ink {
    /// The learned wall ink (the default): P(wall) > 0.5 of a model, then §5.1.2's steps
    /// (2)–(5). Departure from §5.1.2's threshold and the hand-tuned clean-up (issue 26,
    /// docs/plan.md "Learned wall ink").
    Learned(Arc<WallInk>),
    /// §5.1.2's threshold with the clean-up chain of issue 11 (`castellan plan --ink rules`).
    Rules,
}

impl Ink {
    /// The learned wall ink with the model that ships with castellan.
    pub fn shipped() -> Ink {
        static SHIPPED: OnceLock<Arc<WallInk>> = OnceLock::new();
        Ink::Learned(
            SHIPPED
                .get_or_init(|| {
                    Arc::new(WallInk::shipped().expect("the shipped model is checked by its test"))
                })
                .clone(),
        )
    }
}

impl std::fmt::Debug for Ink {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Ink::Learned(m) => write!(f, "Learned({})", m.provenance),
            Ink::Rules => write!(f, "Rules"),
        }
    }
}
