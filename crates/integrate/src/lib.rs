//! `integrate`: a parsed plan drawing and façade estimates → one semantic 3D hierarchy → a VSG
//! program (Sui 2011, chapter 6 and §7.2.2–7.2.3).
//!
//! # Brief overview
//! - [`project::Project`] is PROJECT.toml: the plan, the façade photos with their training boxes,
//!   the correspondences (§6.1.1).
//! - [`photo::estimate_facade`] runs chapter 3 on one photo ([`photo::FacadeEstimate`]).
//! - [`integrate`] maps each façade onto its plan structure ([`correspond`]), scales it
//!   (s = w_p / w_f), re-estimates façades that share a structure jointly (§6.1.2), and builds
//!   the [`estimate::Estimate`] (estimate.json) with the hierarchy of §6.1.3 and the provenance
//!   of every parameter.
//! - [`program::generate`] writes the VSG program (§7.2.2) that [`vsg::run_with`] turns into the
//!   model; [`library::Library`] resolves the medieval library it imports.
//! - [`pipeline::reconstruct`] runs all of it on a [`project::Project`], reading the files it
//!   names through the caller's [`pipeline::Files`]: the commands are adapters over it.
//! - [`agreement::measure`] compares the model seen from above with the plan's built area
//!   (issue 25): IoU, precision, recall, rooms and towers present; stats.json carries it.
//! - [`plausibility`] warns of nonsense that ran without error (issue 22): no walls, most of
//!   the drawing unbuilt, a façade making a needle, a castle 2 m or 20 km across.
//! - [`synth`] draws a synthetic project (plan and perspective façade photos with known answers).
//!
//! ```
//! use integrate::{Inputs, integrate, program, synth};
//! let truth = synth::Castle::default();
//! let plan = plan::parse(&image::DynamicImage::ImageLuma8(truth.plan()), &plan::Options::default()).unwrap();
//! let estimate = integrate(&Inputs {
//!     plan: &plan,
//!     plan_image: "plan.png",
//!     scale: plan::scale::GivenScale::MetresPerPixel(truth.metres_per_pixel),
//!     facades: &[],
//!     gothics: &[],
//!     correspondences: &[],
//!     structure_fixes: &[],
//! })
//! .unwrap()
//! .estimate;
//! assert_eq!(estimate.scale.units, plan::scale::Units::Metres);
//! assert!(estimate.structures.iter().filter(|s| s.label == plan::label::Label::TowerRoom).count() >= 2);
//! let src = program::generate(&estimate, &program::Options::default());
//! let model = vsg::run_with("model.vsg", &src, &vsg::RunOptions::default(), &mut integrate::library::Library::default()).unwrap();
//! assert!(model.terminals().count() > 0);
//! ```

pub mod agreement;
pub mod corrections;
pub mod correspond;
pub mod error;
pub mod estimate;
pub mod gothic;
pub mod heights;
pub mod heritage;
mod integration;
pub mod library;
pub mod photo;
pub mod pipeline;
pub mod plausibility;
pub mod program;
pub mod project;
pub mod structures;
pub mod summary;
pub mod synth;
pub mod textures;

pub use error::IntegrateError;
pub use integration::{Inputs, Integrated, integrate};
