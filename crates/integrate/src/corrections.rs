//! The user's corrections of the structures (issue 22): `[[structure]]` entries of
//! PROJECT.toml, each given by a plan pixel so that it survives a re-parse, set a structure's
//! role ("this is the keep"), height, roof and crenellation; and `scale_line`, two clicked plan
//! points and the length between them. The plan's own corrections (`[[label]]`, `[[tower]]`,
//! `[[merge]]`) are `plan::corrections`. Every value set here has the source "user".

use serde::{Deserialize, Serialize};

use crate::correspond::structure_at;
use crate::estimate::{Footprint, Provenance, Role, Roof, Structure};
use plan::ParsedPlan;
use plan::scale::ModelScale;

/// `[[structure]]`: what the user says of the structure built on the region at `point`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StructureFix {
    /// A plan pixel inside the structure (a tower, room, or on a wall).
    pub point: [f64; 2],
    /// Height in model units (metres where the plan has a scale).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roof: Option<Roof>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crenellated: Option<bool>,
    /// `true`: this is the keep (the parser's keep, if another, becomes a tower); `false`:
    /// this is no keep (a tower).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub keep: Option<bool>,
}

/// `scale_line`: the drawing's scale from two plan points and the length between them (the
/// ends of the scale bar, or of any known length).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScaleLine {
    pub points: [[f64; 2]; 2],
    pub metres: f64,
}

impl ScaleLine {
    /// Metres per plan pixel.
    pub fn metres_per_pixel(&self) -> f64 {
        let [a, b] = self.points;
        self.metres / (b[0] - a[0]).hypot(b[1] - a[1])
    }

    /// Checks the line (the range of scales is `plan::scale`'s).
    pub fn check(&self) -> Result<(), String> {
        let [a, b] = self.points;
        if !a.iter().chain(&b).all(|v| v.is_finite()) || !self.metres.is_finite() {
            return Err("points and metres must be finite".into());
        }
        if (b[0] - a[0]).hypot(b[1] - a[1]) < 2.0 {
            return Err("the two points must be at least 2 plan pixels apart".into());
        }
        let m = self.metres_per_pixel();
        plan::scale::check_range(m, &plan::scale::METRES_PER_PIXEL, "metres per plan pixel")
            .map_err(|why| {
                format!(
                    "{} m over these points is {m} m per pixel: {why}",
                    self.metres
                )
            })
    }
}

/// The tallest a user may make a structure, metres (a cathedral spire is ~160 m).
const MAX_HEIGHT_M: f64 = 300.0;

/// The entry's name in messages and provenance.
fn entry(i: usize) -> String {
    format!("[[structure]] #{}", i + 1)
}

/// Which structure each entry is on; an entry inside none is an error naming it and what the
/// plan has there.
pub fn targets(
    structures: &[Structure],
    fixes: &[StructureFix],
    plan: &ParsedPlan,
    frame: &ModelScale,
) -> Result<Vec<usize>, String> {
    fixes
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let [x, y] = f.point;
            let inside = x.is_finite()
                && y.is_finite()
                && x >= 0.0
                && y >= 0.0
                && x < f64::from(plan.width)
                && y < f64::from(plan.height);
            if !inside {
                return Err(format!(
                    "{}: point [{x}, {y}] is outside the plan ({} × {} px)",
                    entry(i),
                    plan.width,
                    plan.height
                ));
            }
            let s = frame.units_per_pixel;
            structure_at(structures, [x * s, y * s]).ok_or_else(|| {
                format!(
                    "{}: no structure is built at [{x}, {y}] (the plan there: {})",
                    entry(i),
                    plan.label_at(x as u32, y as u32).name()
                )
            })
        })
        .collect()
}

/// "This is the keep" and "this is no keep", before heights are lent (so that a keep the user
/// names is raised over the towers as the parser's would be).
pub fn apply_roles(structures: &mut [Structure], fixes: &[StructureFix], targets: &[usize]) {
    let named_keep = fixes.iter().zip(targets).any(|(f, _)| f.keep == Some(true));
    if named_keep {
        // One keep: the parser's gives way to the user's.
        for s in structures.iter_mut().filter(|s| s.role == Role::Keep) {
            s.role = no_keep(s);
        }
    }
    for (i, (f, &t)) in fixes.iter().zip(targets).enumerate() {
        let s = &mut structures[t];
        match f.keep {
            Some(true) => s.role = Role::Keep,
            Some(false) if s.role == Role::Keep => s.role = no_keep(s),
            _ => continue,
        }
        s.provenance
            .insert("role".into(), Provenance::user(entry(i)));
    }
}

/// What a keep is when it is no keep: a round one a tower, any other a building in its ward.
fn no_keep(s: &Structure) -> Role {
    match s.footprint {
        Footprint::Circle { .. } => Role::Tower,
        _ => Role::Room,
    }
}

/// Heights, roofs and crenellation, after heights are lent (the user's height is final).
pub fn apply_values(
    structures: &mut [Structure],
    fixes: &[StructureFix],
    targets: &[usize],
    frame: &ModelScale,
) -> Result<(), String> {
    for (i, (f, &t)) in fixes.iter().zip(targets).enumerate() {
        let s = &mut structures[t];
        if let Some(h) = f.height {
            let most = MAX_HEIGHT_M * frame.units_per_metre;
            if !(h.is_finite() && h > 0.0 && h <= most) {
                return Err(format!(
                    "{}: height {h} must be above 0 and at most {most} {}",
                    entry(i),
                    frame.units.symbol()
                ));
            }
            s.height = h;
            s.provenance
                .insert("height".into(), Provenance::user(entry(i)));
        }
        if let Some(roof) = f.roof {
            if let Some(why) = roof_refused(s, roof) {
                return Err(format!("{}: roof = \"{}\": {why}", entry(i), roof.name()));
            }
            s.roof = Some(roof);
            s.provenance
                .insert("roof".into(), Provenance::user(entry(i)));
        }
        if let Some(c) = f.crenellated {
            s.crenellated = Some(c);
            s.provenance
                .insert("crenellated".into(), Provenance::user(entry(i)));
        }
    }
    Ok(())
}

/// Why a roof does not go on a structure: walls carry none, and rooms of blocks (a building's
/// mass of several blocks) keep their flat roof or none.
fn roof_refused(s: &Structure, roof: Roof) -> Option<String> {
    match (&s.footprint, roof) {
        (Footprint::Wall { .. }, _) => Some(format!(
            "{} is a wall ({}); walls take no roof (crenellated = true/false applies)",
            s.id,
            s.role.name()
        )),
        (Footprint::Blocks { .. }, Roof::Flat | Roof::None) => None,
        (Footprint::Blocks { .. }, _) => Some(format!(
            "{} is built of blocks (no circle or rectangle fits its room); it takes \"flat\" or \"none\"",
            s.id
        )),
        _ => None,
    }
}
