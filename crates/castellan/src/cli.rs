//! The command tree (ARCHITECTURE.md contract). Each command's flags are defined once, beside
//! the command in its `*_cmd.rs` module, with their tests.

use clap::{Parser, Subcommand};

#[derive(Debug, Parser)]
#[command(
    name = "castellan",
    version,
    about = "Plan drawing + façade photos of a historic building -> a labelled, volumetric 3D model"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// The Volumetric Shape Grammar (dissertation ch. 7).
    #[command(subcommand)]
    Vsg(VsgCommand),
    /// Structural corners (ch. 2, IPFIT): hyperbola fits to edge points, corners at the
    /// intersection of their asymptotes.
    Corners(crate::corners_cmd::CornersArgs),
    /// Modified repeatability rate (§2.2) and detections per image over image sequences with
    /// Oxford-style homographies (H1to2p ... H1to6p), for IPFIT and, optionally, peer detectors.
    CornersEval(crate::corners_cmd::CornersEvalArgs),
    /// Parse a castle plan drawing into labelled walls, rooms and towers (dissertation ch. 5).
    Plan(crate::plan_cmd::PlanArgs),
    /// Rectify a façade photo into an elevation view (dissertation §3.1.1).
    Rectify(crate::rectify_cmd::RectifyArgs),
    /// Parse a rectified façade into façades, floors and windows (dissertation §3.1.2-3.1.7).
    Facade(crate::facade_cmd::FacadeArgs),
    /// Gothic façade: arches and rectangles, groups, nesting, masonry (dissertation ch. 4).
    Gothic(crate::gothic_cmd::GothicArgs),
    /// Plan drawing + façade photos (PROJECT.toml) → integrated estimate → VSG program → model,
    /// with every step's overlay in an HTML report (dissertation ch. 6, §7.2.2–7.2.3).
    Reconstruct(crate::reconstruct_cmd::ReconstructArgs),
    /// Reconstruct the bundled example castle and compare the estimate with its known truth.
    Demo(crate::demo_cmd::DemoArgs),
    /// The interactive workflow in the browser: a local server for one project folder.
    Serve(crate::serve::ServeArgs),
}

#[derive(Debug, Subcommand)]
pub enum VsgCommand {
    /// Run a VSG program and write the model.
    Run(crate::vsg_cmd::VsgRunArgs),
}
