//! Learned wall ink (issue 26): a per-pixel separation of structural wall from everything else
//! on a plan sheet, replacing the hand-tuned clean-up chain before §5.1.3 by default.
//!
//! - [`paint`]: the wall masks painted on public-domain plans, kept as recipes (ink regions
//!   kept, polygons filled or erased, walls drawn as thick polylines) and rendered to masks.
pub mod paint;
