//! Plausibility checks (issue 22): a reconstruction that "worked" can still be nonsense — a
//! plan read with no walls, most of the drawing's ink left unbuilt, a façade photo that makes
//! its structure a needle, a scale that makes the castle a doll's house or a city. None of
//! this is in the dissertation (ch. 5–6 assume a plan and photos of the castle at hand); these
//! checks only warn, naming what looks wrong and the fix, and the run goes on (exit 0).
//! Pure: the plan, the estimate and the plan–model agreement in, typed warnings out.

use plan::ParsedPlan;
use plan::label::Label;
use plan::scale::{ScaleNote, Units};

use crate::agreement::Agreement;
use crate::correspond::area;
use crate::estimate::{Estimate, Footprint, Role, Source, Structure};

/// Below this share of the plan's built area in the model, most of the drawing's ink was left
/// unbuilt (`agreement`'s recall).
pub const MIN_RECALL: f64 = 0.5;
/// A structure with a mapped façade taller than this many times its footprint's larger
/// side is a needle: the photo shows another building, or a tower mapped onto a wall.
pub const MAX_HEIGHT_OVER_WIDTH: f64 = 4.0;
/// A structure a façade made taller than this many times the tallest structure around it
/// that no photo measured.
pub const MAX_OVER_SURROUNDINGS: f64 = 3.0;
/// Masses of wall (`Role::Mass`: wall-labelled pixels no fit explains, built as blocks) over
/// this share of the model's footprint are more likely hachures, slopes or shading the wall
/// ink read as wall than masonry: over the 34 shared plans they take 0–14 % but 23 % on
/// Arques, whose hachured slopes are read as wall, and 22 % on Roche-Pont-Cité-Juliana.
pub const MAX_MASS_SHARE: f64 = 0.15;
/// Castles span 10 m (a tower house) to 2 km (a town wall) across; a given scale outside is
/// more likely a typo or a bar read at the wrong length.
pub const CASTLE_METRES: std::ops::RangeInclusive<f64> = 10.0..=2000.0;

/// What looks wrong. [`std::fmt::Display`] says what and how to fix it.
#[derive(Debug, Clone, PartialEq)]
pub enum Warning {
    /// The plan parser read no wall (no edge of the wall graph).
    NoWalls { plan: String },
    /// Walls were read but no structure was built from them.
    NoStructures { plan: String },
    /// The model covers less than [`MIN_RECALL`] of the plan's built area.
    InkLeftUnbuilt { plan: String, recall: f64 },
    /// A structure with a mapped façade is taller than [`MAX_HEIGHT_OVER_WIDTH`] × its width.
    Needle {
        structure: String,
        photos: String,
        height: f64,
        width: f64,
    },
    /// A structure with a mapped façade is taller than [`MAX_OVER_SURROUNDINGS`] × the tallest
    /// structure around it that no photo measured.
    TowersOver {
        structure: String,
        photos: String,
        height: f64,
        tallest_around: f64,
    },
    /// With the scale given or read, the castle's built area spans less than 10 m or more than
    /// 2 km.
    ImplausibleSize {
        plan: String,
        metres_across: f64,
        metres_per_pixel: f64,
    },
    /// `scale_bar` was given but no bar was found: the model is in plan pixels.
    ScaleBarNotFound { plan: String, metres: f64 },
    /// Masses of wall take more than [`MAX_MASS_SHARE`] of the model's footprint.
    MassesOfWall {
        plan: String,
        share: f64,
        largest: String,
    },
    /// A façade photo's model looks wrong (`facade::plausibility`).
    Facade {
        photo: String,
        warning: facade::plausibility::FacadeWarning,
    },
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Warning::NoWalls { plan } => write!(
                f,
                "no walls were read from {plan}: is it a castle plan? Look at overlays/plan_walls.png; try ink = \"rules\" (or the other way round), clean the drawing in `castellan serve` (erase text and hatching, paint the walls), or give a cleaner drawing"
            ),
            Warning::NoStructures { plan } => write!(
                f,
                "walls were read from {plan} but no structure was built from them: look at overlays/plan_labels.png; the walls may not close a courtyard or rooms — clean the drawing in `castellan serve` (join broken walls with the wall brush) or try ink = \"rules\""
            ),
            Warning::InkLeftUnbuilt { plan, recall } => write!(
                f,
                "only {:.0} % of {plan}'s built area (walls, towers, rooms) is in the model: most of the drawing was left unbuilt (red in overlays/plan_model.png); check overlays/plan_labels.png for walls read as surroundings or courtyard, clean the drawing in `castellan serve`, or try ink = \"rules\"",
                100.0 * recall
            ),
            Warning::Needle {
                structure,
                photos,
                height,
                width,
            } => write!(
                f,
                "{structure} is {:.1} times taller than wide ({height:.1} high, {width:.1} across) with the façade of {photos}: does the photo show this structure? Check its [[correspondence]] points (plan_points on the right structure, facade_point on the façade) and the façade's bbox",
                height / width
            ),
            Warning::TowersOver {
                structure,
                photos,
                height,
                tallest_around,
            } => write!(
                f,
                "{structure} is {height:.1} high with the façade of {photos}, {:.1} times the tallest structure around it ({tallest_around:.1}): does the photo show this structure, at this scale? Check its [[correspondence]] and the photo's scale",
                height / tallest_around
            ),
            Warning::ImplausibleSize {
                plan,
                metres_across,
                metres_per_pixel,
            } => write!(
                f,
                "at {metres_per_pixel} m per pixel the castle of {plan} is {metres_across:.1} m across (castles span {} m to {} m): check scale (metres per pixel, not pixels per metre) or scale_bar (the bar's length in metres)",
                CASTLE_METRES.start(),
                CASTLE_METRES.end()
            ),
            Warning::MassesOfWall {
                plan,
                share,
                largest,
            } => write!(
                f,
                "{:.0} % of the model of {plan} are masses of wall that no fitted wall, tower or room explains (the largest {largest}): hachures, slopes or shading may have been read as wall — look at overlays/plan_walls.png and paint them \"not wall\" in `castellan serve`'s plan step",
                100.0 * share
            ),
            Warning::Facade { photo, warning } => write!(
                f,
                "façade photo {photo}: {warning} (in PROJECT.toml's [[facade]] training boxes, or in `castellan serve`'s façade step)"
            ),
            Warning::ScaleBarNotFound { plan, metres } => write!(
                f,
                "scale_bar = {metres}: {} in plan = \"{plan}\" — give scale (metres per pixel) instead, or click the bar's two ends in `castellan serve`",
                plan::scale::no_bar_found(*metres)
            ),
        }
    }
}

/// The checks on each façade photo's model against the user's boxes
/// (`facade::plausibility::check`), in the rectified photo's frame where both live.
pub fn facade_warnings(photos: &[crate::photo::FacadeEstimate]) -> Vec<Warning> {
    photos
        .iter()
        .flat_map(|p| {
            facade::plausibility::check(&p.model, &p.training)
                .into_iter()
                .map(|warning| Warning::Facade {
                    photo: p.name.clone(),
                    warning,
                })
        })
        .collect()
}

/// The checks on the plan alone (what `castellan plan` can say too): no walls, a bar asked
/// for and not found, a castle of implausible size at the scale given or read.
pub fn plan_warnings(
    plan: &ParsedPlan,
    plan_image: &str,
    scale_note: &ScaleNote,
    units: Units,
    units_per_pixel: f64,
) -> Vec<Warning> {
    let name = || plan_image.to_string();
    let mut out = Vec::new();
    if let ScaleNote::BarNotFound { metres, .. } = scale_note {
        out.push(Warning::ScaleBarNotFound {
            plan: name(),
            metres: *metres,
        });
    }
    if plan.edges.is_empty() {
        out.push(Warning::NoWalls { plan: name() });
        return out;
    }
    if units == Units::Metres
        && let Some(pixels) = built_extent(plan)
    {
        let metres_across = pixels * units_per_pixel;
        if !CASTLE_METRES.contains(&metres_across) {
            out.push(Warning::ImplausibleSize {
                plan: name(),
                metres_across,
                metres_per_pixel: units_per_pixel,
            });
        }
    }
    out
}

/// The checks on the reconstruction: no structure, most of the ink unbuilt, façades that make
/// needles or giants. Call after [`plan_warnings`] (a plan without walls is not checked again).
pub fn model_warnings(
    plan: &ParsedPlan,
    estimate: &Estimate,
    agreement: &Agreement,
) -> Vec<Warning> {
    let name = || estimate.plan.image.clone();
    let mut out = Vec::new();
    if plan.edges.is_empty() {
        return out;
    }
    if estimate.structures.is_empty() {
        out.push(Warning::NoStructures { plan: name() });
        return out;
    }
    if agreement.plan_pixels > 0 && agreement.recall < MIN_RECALL {
        out.push(Warning::InkLeftUnbuilt {
            plan: name(),
            recall: agreement.recall,
        });
    }
    let footprint: f64 = estimate.structures.iter().map(|s| area(&s.footprint)).sum();
    let masses: Vec<(&Structure, f64)> = estimate
        .structures
        .iter()
        .filter(|s| s.role == Role::Mass)
        .map(|s| (s, area(&s.footprint)))
        .collect();
    let in_masses: f64 = masses.iter().map(|(_, a)| a).sum();
    if footprint > 0.0
        && in_masses > MAX_MASS_SHARE * footprint
        && let Some((largest, _)) = masses.iter().max_by(|a, b| a.1.total_cmp(&b.1))
    {
        out.push(Warning::MassesOfWall {
            plan: name(),
            share: in_masses / footprint,
            largest: largest.id.clone(),
        });
    }
    let any_measured_tower = estimate
        .structures
        .iter()
        .any(|s| height_source(s) == Source::Measured);
    for (i, s) in estimate.structures.iter().enumerate() {
        if s.facades.is_empty() {
            continue;
        }
        let photos = s
            .facades
            .iter()
            .map(|f| f.image.as_str())
            .collect::<Vec<_>>()
            .join(", ");
        if let Some(width) = footprint_width(&s.footprint)
            && width > 0.0
            && s.height > MAX_HEIGHT_OVER_WIDTH * width
        {
            out.push(Warning::Needle {
                structure: s.id.clone(),
                photos: photos.clone(),
                height: s.height,
                width,
            });
        }
        // The structures around it that no photo measured: user heights and class defaults,
        // but not a default keep raised over measured towers (heights::propagate), whose
        // height is the photo's.
        let tallest_around = estimate
            .structures
            .iter()
            .enumerate()
            .filter(|&(k, o)| k != i && o.facades.is_empty())
            .filter(|(_, o)| match height_source(o) {
                Source::User => true,
                Source::Default => !(o.role == Role::Keep && any_measured_tower),
                Source::Measured | Source::Lent => false,
            })
            .map(|(_, o)| o.height)
            .fold(0.0_f64, f64::max);
        if tallest_around > 0.0 && s.height > MAX_OVER_SURROUNDINGS * tallest_around {
            out.push(Warning::TowersOver {
                structure: s.id.clone(),
                photos,
                height: s.height,
                tallest_around,
            });
        }
    }
    out
}

fn height_source(s: &Structure) -> Source {
    s.provenance
        .get("height")
        .map_or(Source::Default, |p| p.source())
}

/// The larger horizontal side of a footprint (model units); none for walls, whose height is
/// not a façade's.
fn footprint_width(f: &Footprint) -> Option<f64> {
    match f {
        Footprint::Circle { radius, .. } => Some(2.0 * radius),
        Footprint::Rectangle { size, .. } => Some(size[0].max(size[1])),
        Footprint::Blocks { blocks, rotation } => {
            // The blocks' extent in their own turned frame.
            let (c, s) = (rotation.cos(), rotation.sin());
            let mut lo = [f64::INFINITY; 2];
            let mut hi = [f64::NEG_INFINITY; 2];
            for b in blocks {
                let u = b.center[0] * c + b.center[1] * s;
                let v = -b.center[0] * s + b.center[1] * c;
                lo = [
                    lo[0].min(u - b.size[0] / 2.0),
                    lo[1].min(v - b.size[1] / 2.0),
                ];
                hi = [
                    hi[0].max(u + b.size[0] / 2.0),
                    hi[1].max(v + b.size[1] / 2.0),
                ];
            }
            (!blocks.is_empty()).then(|| (hi[0] - lo[0]).max(hi[1] - lo[1]))
        }
        Footprint::Wall { .. } => None,
    }
}

/// The larger side, in plan pixels, of the box round every pixel the plan builds on or
/// encloses (every label but castle_surroundings); none when there is none.
fn built_extent(plan: &ParsedPlan) -> Option<f64> {
    let outside = Label::CastleSurroundings as u8;
    let w = plan.width as usize;
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for (i, &l) in plan.labels.iter().enumerate() {
        if l != outside {
            let (x, y) = (i % w, i / w);
            x0 = x0.min(x);
            y0 = y0.min(y);
            x1 = x1.max(x);
            y1 = y1.max(y);
        }
    }
    (x0 != usize::MAX).then(|| ((x1 - x0 + 1).max(y1 - y0 + 1)) as f64)
}

#[cfg(test)]
mod tests;
