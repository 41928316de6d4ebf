//! Learned wall ink (issue 26): a per-pixel separation of structural wall from everything else
//! on a plan sheet, replacing the hand-tuned clean-up chain before §5.1.3 by default.
//!
//! - [`paint`]: the wall masks painted on public-domain plans, kept as recipes (ink regions
//!   kept, polygons filled or erased, walls drawn as thick polylines) and rendered to masks.
//! - [`model`]: the trained classifier ([`WallInk`]: filter bank, one or two forests), its
//!   file format, and P(wall) of every pixel of a drawing.
//! - [`train`]: training a model from drawings with wall masks.
//! - [`net`]: the wall-ink network ([`net::WallNet`], `--ink network`): a small U-Net over the
//!   same grey, its file format, and P(wall) of every pixel; [`net_train`]: training it.
//! - [`refine`]: the user's "wall" / "not wall" strokes refine the model (or the network's
//!   map) for one drawing.
pub mod model;
pub mod net;
pub mod net_train;
pub mod paint;
pub mod refine;
pub mod train;
pub mod trim;

pub use model::WallInk;

use std::sync::{Arc, OnceLock};

/// Where the plan parser's wall mask comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum InkMethod {
    /// The learned wall ink (the default): P(wall) > 0.5 of a model, refined by the user's
    /// strokes if any, then §5.1.2's steps (2)–(5). Departure from §5.1.2's threshold and the
    /// hand-tuned clean-up (issue 26, docs/plan.md "Learned wall ink").
    #[default]
    Learned,
    /// The wall-ink network ([`net::WallNet`]): P(wall) of a small convolutional network,
    /// then as `Learned` (issue 26, docs/plan.md "The wall-ink network").
    Network,
    /// §5.1.2's threshold with the clean-up chain of issue 11 (`castellan plan --ink rules`).
    Rules,
}

/// P(wall) above which chapter 5 takes a pixel as wall. Below the even odds of 0.5 because
/// the two errors do not cost the same: a stretch of wall missed opens an enclosure (a
/// courtyard read as surroundings), a pixel too many only thickens a wall. Swept on the two
/// development sets with the model trained on every painted plan (points right of 169 /
/// of 159): 0.25 → 120 / 116, **0.3 → 123 / 113**, 0.35 → 128 / 96, 0.4 → 124 / 82, and
/// about 0.5 → 121 / 74 (docs/plan.md, "Learned wall ink").
pub const WALL_THRESHOLD: f32 = 0.3;

/// The model that ships with castellan, decoded once.
pub fn shipped() -> Arc<WallInk> {
    static SHIPPED: OnceLock<Arc<WallInk>> = OnceLock::new();
    SHIPPED
        .get_or_init(|| {
            Arc::new(WallInk::shipped().expect("the shipped model is checked by its test"))
        })
        .clone()
}

/// The network that ships with castellan, decoded once.
pub fn shipped_net() -> Arc<net::WallNet> {
    static SHIPPED: OnceLock<Arc<net::WallNet>> = OnceLock::new();
    SHIPPED
        .get_or_init(|| {
            Arc::new(net::WallNet::shipped().expect("the shipped network is checked by its test"))
        })
        .clone()
}
