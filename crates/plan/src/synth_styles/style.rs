//! What a synthetic drawing holds: the drawing and its wall truth, the wall styles, the kinds
//! of clutter, and the choices a caller may force.

use image::GrayImage;

/// A drawing, its wall truth (255 = wall, 0 = not) and what was drawn.
pub struct StyledPlan {
    pub image: GrayImage,
    pub walls: GrayImage,
    /// The hachured scarps and bands against the walls (255): their strokes and the paper
    /// between them, never a wall pixel; all 0 without [`StyleChoice::scarps`].
    pub scarps: GrayImage,
    pub style: Style,
}

/// How walls are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WallStyle {
    /// Filled black.
    Solid,
    /// Two thin lines with paper between.
    Outlined,
    /// Outline with diagonal parallel lines inside.
    Hatched,
    /// Outline with two crossing sets of parallel lines inside.
    CrossHatched,
    /// Filled mid-grey, with or without a dark outline.
    GreyWash,
}

pub const WALL_STYLES: [WallStyle; 5] = [
    WallStyle::Solid,
    WallStyle::Outlined,
    WallStyle::Hatched,
    WallStyle::CrossHatched,
    WallStyle::GreyWash,
];

/// Kinds of non-wall clutter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clutter {
    Letters,
    Words,
    VaultRibs,
    /// Hachures on a ring well away from the walls.
    Hachures,
    /// Hachured scarps and moats right against the outer face of the curtain and towers
    /// (strokes perpendicular to it), sometimes closed by the ditch's outer edge as a line.
    WallHachures,
    /// Dense concentric contour-like hachure lines following the walls' outline.
    HachureBands,
    Contours,
    DashedLines,
    DimensionLines,
    ScaleBar,
    NorthArrow,
    Title,
    Frame,
    Grid,
    /// Stairs, tables, beds, counters, wells and doors with their swing, in thin line inside
    /// the curtain.
    Furnishing,
}

/// What was drawn.
#[derive(Clone, Debug)]
pub struct Style {
    /// The style of the curtain, towers, keep and inner ward.
    pub walls: WallStyle,
    /// The style of the inner buildings and partitions when it differs.
    pub second: Option<WallStyle>,
    /// Curtain wall thickness in pixels.
    pub thickness: f64,
    pub clutter: Vec<Clutter>,
    /// Whether degradations were applied.
    pub degraded: bool,
}

/// Forced choices for [`generate_with`](super::generate_with); `None` lets the seed choose.
#[derive(Clone, Debug, Default)]
pub struct StyleChoice {
    pub walls: Option<WallStyle>,
    pub thickness: Option<f64>,
    /// Skip the degradations (a clean drawing: paper 255, ink 0).
    pub clean: bool,
    /// Also draw hachured scarps and moats against the walls and contour-like hachure bands
    /// ([`Clutter::WallHachures`], [`Clutter::HachureBands`]); off by default, which draws
    /// exactly what the generator drew before they existed (the shipped model's recipe).
    pub scarps: bool,
    /// Also draw fittings inside the curtain ([`Clutter::Furnishing`]); off by default, as
    /// for `scarps`.
    pub furnishing: bool,
}
