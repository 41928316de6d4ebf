//! The drawing's scale, decided once for every command (§5.3's extrusion, §6.1.2's
//! integration): how plan pixels become model units.
//!
//! Naming (issue 20): a scale a user gives or a scale bar yields is always **metres per pixel**
//! (`metres_per_pixel`, PROJECT.toml's `scale`, `--scale`); the model's frame is
//! [`ModelScale`]: `units_per_pixel` and `units_per_metre`, both in the direction "model units
//! per …". With a scale the model is in metres; without one it stays in plan pixels and a
//! metre is assumed from the walls ([`ModelScale::decide`] says how, in words).

use serde::{Deserialize, Serialize};

use crate::ParsedPlan;
use crate::label::Label;
use crate::scalebar::LOOKED_FOR;

/// Plausible drawing scales in metres per pixel, the one rule for every scale a user gives
/// (`--scale`, PROJECT.toml's `scale`, a façade's `scale`): from 0.1 mm a pixel (a detail drawn
/// at 10 000 px a metre) to 100 m a pixel (a town in a thumbnail). Outside it a scale is a typo,
/// and the model it gives overflows or vanishes (issue 19: `scale = 1e300`).
pub const METRES_PER_PIXEL: std::ops::RangeInclusive<f64> = 1e-4..=100.0;
/// Plausible lengths of a drawn scale bar, in metres (1 cm to 100 km).
pub const SCALE_BAR_METRES: std::ops::RangeInclusive<f64> = 0.01..=100_000.0;

/// A typical curtain wall's thickness, taken for the outer walls' median thickness when the
/// drawing has no scale (§5.3's heights need metres).
pub const ASSUMED_OUTER_WALL_METRES: f64 = 2.5;

/// `Ok` when `value` lies in `range`; otherwise why not, for a message that names the entry.
pub fn check_range(
    value: f64,
    range: &std::ops::RangeInclusive<f64>,
    unit: &str,
) -> Result<(), String> {
    if range.contains(&value) {
        Ok(())
    } else {
        Err(format!(
            "{value} is not a plausible {unit} (castellan takes {} to {})",
            range.start(),
            range.end()
        ))
    }
}

/// The model's length unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Units {
    /// The drawing had a scale.
    #[serde(rename = "m")]
    Metres,
    /// No scale: plan pixels.
    #[serde(rename = "px")]
    Pixels,
}

impl Units {
    /// "m" or "px", as estimate.json writes it.
    pub fn symbol(self) -> &'static str {
        match self {
            Units::Metres => "m",
            Units::Pixels => "px",
        }
    }
}

/// What the user said about the drawing's scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GivenScale {
    /// Nothing: a metre is assumed from the walls.
    Unknown,
    /// Metres per pixel (`--scale`, PROJECT.toml's `scale`).
    MetresPerPixel(f64),
    /// The length in metres of the scale bar drawn on the plan (`--scale-bar`, `scale_bar`).
    ScaleBarMetres(f64),
}

impl GivenScale {
    /// From the two optional inputs of a command or a project (at most one is set).
    pub fn from_options(metres_per_pixel: Option<f64>, scale_bar_metres: Option<f64>) -> Self {
        match (metres_per_pixel, scale_bar_metres) {
            (_, Some(m)) => GivenScale::ScaleBarMetres(m),
            (Some(s), None) => GivenScale::MetresPerPixel(s),
            (None, None) => GivenScale::Unknown,
        }
    }
}

/// How plan pixels become model units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelScale {
    /// Metres with a scale, plan pixels without.
    pub units: Units,
    /// Model units per plan pixel (estimate.json's `scale`).
    #[serde(rename = "scale")]
    pub units_per_pixel: f64,
    /// Model units per metre, for the sizes only known in metres (heights, wall walks, roofs):
    /// 1 with a scale, else assumed from the plan.
    pub units_per_metre: f64,
}

/// How the scale was decided, in words, for the user to check: the bar found and what it
/// gives, or what was assumed.
#[derive(Debug, Clone, PartialEq)]
pub enum ScaleNote {
    /// The user's metres per pixel, taken as given.
    Given,
    /// The drawn bar was read.
    Bar(String),
    /// Nothing was given: an assumption, to be reported.
    Assumed(String),
    /// The user gave the bar's length (`scale_bar`, `--scale-bar`) but no bar was found in the
    /// drawing: the model stays in plan pixels with a metre assumed as without a scale
    /// (`assumed`, in words), and the caller warns (issue 22: a missing bar used to stop the
    /// run with nothing written).
    BarNotFound { metres: f64, assumed: String },
}

impl ScaleNote {
    /// The assumption made, if the scale was not given or read (for estimate.json's
    /// `assumptions`).
    pub fn assumption(&self) -> Option<&str> {
        match self {
            ScaleNote::Assumed(why) | ScaleNote::BarNotFound { assumed: why, .. } => Some(why),
            ScaleNote::Given | ScaleNote::Bar(_) => None,
        }
    }
}

/// What a user reads when the bar they named is not in the drawing: what was looked for and
/// what happens instead (the caller adds where to give the scale).
pub fn no_bar_found(metres: f64) -> String {
    format!("no scale bar found for the {metres} m given ({LOOKED_FOR}); continuing in plan pixels")
}

impl ModelScale {
    /// A model in metres at `metres_per_pixel`.
    pub fn metric(metres_per_pixel: f64) -> ModelScale {
        ModelScale {
            units: Units::Metres,
            units_per_pixel: metres_per_pixel,
            units_per_metre: 1.0,
        }
    }

    /// The one rule (issue 20: `castellan plan --model` and `castellan reconstruct` used two):
    /// a given scale or the drawn bar makes the model metric; without either the model stays
    /// in plan pixels and the outer walls' median thickness is taken as
    /// [`ASSUMED_OUTER_WALL_METRES`] (without outer walls, a metre is 1/100 of the drawing's
    /// larger side). A bar asked for but not found falls back to plan pixels in the same way,
    /// with [`ScaleNote::BarNotFound`] for the caller to warn (issue 22).
    pub fn decide(plan: &ParsedPlan, given: GivenScale) -> (ModelScale, ScaleNote) {
        match given {
            GivenScale::MetresPerPixel(s) => (ModelScale::metric(s), ScaleNote::Given),
            GivenScale::ScaleBarMetres(metres) => match plan.scale_bar {
                Some(bar) => {
                    let s = bar.metres_per_pixel(metres);
                    (
                        ModelScale::metric(s),
                        ScaleNote::Bar(format!(
                            "scale bar {} = {metres} m: {s:.4} m per pixel",
                            bar.describe()
                        )),
                    )
                }
                None => {
                    let (frame, assumed) = ModelScale::assumed(plan);
                    (frame, ScaleNote::BarNotFound { metres, assumed })
                }
            },
            GivenScale::Unknown => {
                let (frame, why) = ModelScale::assumed(plan);
                (frame, ScaleNote::Assumed(why))
            }
        }
    }

    /// A model in plan pixels with a metre assumed from the walls, and the assumption in words.
    fn assumed(plan: &ParsedPlan) -> (ModelScale, String) {
        let (units_per_metre, why) = assumed_pixels_per_metre(plan);
        (
            ModelScale {
                units: Units::Pixels,
                units_per_pixel: 1.0,
                units_per_metre,
            },
            why,
        )
    }
}

/// Plan pixels per metre when the drawing has no scale, and the assumption in words.
fn assumed_pixels_per_metre(plan: &ParsedPlan) -> (f64, String) {
    let Some(median) = outer_wall_thickness(plan) else {
        let size = f64::from(plan.width.max(plan.height));
        return (
            size / 100.0,
            format!(
                "no drawing scale and no outer wall: 1 m taken as 1/100 of the drawing's {size} px"
            ),
        );
    };
    let per_metre = median / ASSUMED_OUTER_WALL_METRES;
    (
        per_metre,
        format!(
            "no drawing scale: the outer walls' median thickness ({median:.1} px) taken as {ASSUMED_OUTER_WALL_METRES} m, so 1 m = {per_metre:.2} px"
        ),
    )
}

/// The outer walls' median thickness (plan pixels), if the plan has outer walls.
pub fn outer_wall_thickness(plan: &ParsedPlan) -> Option<f64> {
    outer_wall_thickness_of(&plan.edges)
}

/// [`outer_wall_thickness`] of a plan's edges: the drawing's scale, the model's walls and
/// towers' rings, and the rooms of the plan's thick towers ([`crate::thick_towers::rooms`])
/// all read the curtain so.
pub fn outer_wall_thickness_of(edges: &[crate::PlanEdge]) -> Option<f64> {
    let mut t: Vec<f64> = edges
        .iter()
        .filter(|e| e.label == Label::CastleOuterWall && e.thickness > 0.0)
        .map(|e| e.thickness)
        .collect();
    t.sort_by(f64::total_cmp);
    t.get(t.len() / 2).copied()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalebar::ScaleBar;

    fn plan_with_outer_walls(thicknesses: &[f64]) -> ParsedPlan {
        let mut p = ParsedPlan::empty(400, 300);
        for &t in thicknesses {
            p.edges.push(crate::PlanEdge {
                from: 0,
                to: 0,
                label: Label::CastleOuterWall,
                points: vec![],
                fit: None,
                thickness: t,
            });
        }
        p
    }

    #[test]
    fn a_given_scale_makes_a_metric_model() {
        let p = plan_with_outer_walls(&[5.0]);
        let (s, note) = ModelScale::decide(&p, GivenScale::MetresPerPixel(0.25));
        assert_eq!(s, ModelScale::metric(0.25));
        assert_eq!(s.units, Units::Metres);
        assert_eq!(note, ScaleNote::Given);
    }

    #[test]
    fn without_a_scale_the_median_outer_wall_is_two_and_a_half_metres() {
        let p = plan_with_outer_walls(&[4.0, 5.0, 100.0]);
        let (s, note) = ModelScale::decide(&p, GivenScale::Unknown);
        assert_eq!(s.units, Units::Pixels);
        assert_eq!(s.units_per_pixel, 1.0);
        assert_eq!(s.units_per_metre, 2.0); // 5 px / 2.5 m
        assert!(matches!(note, ScaleNote::Assumed(w) if w.contains("5.0 px")));
    }

    #[test]
    fn without_a_scale_or_outer_walls_a_metre_is_a_hundredth_of_the_drawing() {
        let p = plan_with_outer_walls(&[]);
        let (s, _) = ModelScale::decide(&p, GivenScale::Unknown);
        assert_eq!(s.units_per_metre, 4.0);
    }

    #[test]
    fn a_scale_bar_not_in_the_drawing_falls_back_to_pixels_and_with_one_gives_metres() {
        let mut p = plan_with_outer_walls(&[5.0]);
        // Issue 22: no bar is a warning, not an error: plan pixels with the walls' metre.
        let (s, note) = ModelScale::decide(&p, GivenScale::ScaleBarMetres(30.0));
        assert_eq!(s, ModelScale::decide(&p, GivenScale::Unknown).0);
        assert_eq!((s.units, s.units_per_metre), (Units::Pixels, 2.0));
        let ScaleNote::BarNotFound { metres, assumed } = &note else {
            panic!("{note:?}")
        };
        assert_eq!(*metres, 30.0);
        assert!(assumed.contains("5.0 px"), "{assumed}");
        assert_eq!(note.assumption(), Some(assumed.as_str()));
        assert!(no_bar_found(30.0).starts_with("no scale bar found for the 30 m given ("));
        p.scale_bar = Some(ScaleBar {
            x0: 10,
            y0: 20,
            x1: 110,
            y1: 20,
            length_px: 100,
        });
        let (s, note) = ModelScale::decide(&p, GivenScale::ScaleBarMetres(30.0));
        assert_eq!(s, ModelScale::metric(0.3));
        assert_eq!(note.assumption(), None);
        assert!(matches!(note, ScaleNote::Bar(w) if w.contains("100 px = 30 m")));
    }

    #[test]
    fn given_scales_prefer_the_bar_when_both_are_set() {
        assert_eq!(
            GivenScale::from_options(Some(0.1), Some(30.0)),
            GivenScale::ScaleBarMetres(30.0)
        );
        assert_eq!(
            GivenScale::from_options(Some(0.1), None),
            GivenScale::MetresPerPixel(0.1)
        );
        assert_eq!(GivenScale::from_options(None, None), GivenScale::Unknown);
    }

    #[test]
    fn units_serialise_as_the_symbols_of_estimate_json() {
        assert_eq!(serde_json::to_string(&Units::Metres).unwrap(), "\"m\"");
        assert_eq!(serde_json::to_string(&Units::Pixels).unwrap(), "\"px\"");
        let s = serde_json::to_value(ModelScale::metric(0.5)).unwrap();
        assert_eq!(
            s,
            serde_json::json!({"units": "m", "scale": 0.5, "units_per_metre": 1.0})
        );
    }
}
