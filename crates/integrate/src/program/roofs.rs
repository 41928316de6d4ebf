//! The roofs and battlements a user chose for a structure (issue 22, `[[structure]] roof` and
//! `crenellated`), built over its footprint at its height from Table 7.1's primitives: a cone;
//! a pyramid of four tetrahedra with their apex over the centre; a gable of two ramps; a hipped
//! roof, a gable between two half pyramids; a flat slab. Structures from the library then set
//! `ownRoof = 0` or `crenels = 0` (library/*.vsg) so that only the user's choice is built.

use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::fmt::Write;

use crate::estimate::{Footprint, Kind, Role, Roof, Structure};

use super::common::{Part, n};

/// The library files that build a roof of their own, and those whose parapet is crenellated.
const OWN_ROOF: [&str; 3] = ["round_tower.vsg", "solid_tower.vsg", "keep.vsg"];
const OWN_CRENELS: [&str; 2] = ["square_tower.vsg", "curtain_wall.vsg"];

/// The arguments a library structure takes for the user's choices.
pub(super) fn library_overrides(file: &str, s: &Structure) -> Vec<(&'static str, f64)> {
    let mut out = Vec::new();
    if s.roof.is_some() && OWN_ROOF.contains(&file) {
        out.push(("ownRoof", 0.0));
    }
    if s.crenellated == Some(false) && OWN_CRENELS.contains(&file) {
        out.push(("crenels", 0.0));
    }
    out
}

/// Whether the structure's own rules crenellate it (as `program::generate` builds it): square
/// towers and curtain walls of the library, and curtain runs.
pub(super) fn crenellated_by_default(s: &Structure) -> bool {
    match (&s.footprint, s.kind) {
        (Footprint::Wall { .. }, _) => s.role == Role::Curtain,
        (Footprint::Rectangle { .. }, _) if s.role == Role::Gatehouse => false,
        (Footprint::Rectangle { .. }, Kind::HollowRectangular) => {
            s.role == Role::Tower && s.facades.is_empty()
        }
        (Footprint::Rectangle { .. }, _) => true,
        _ => false,
    }
}

/// The user's roof over the structure, when one was chosen (nothing for `none`).
pub(super) fn chosen(s: &Structure, u: f64) -> Part {
    match s.roof {
        Some(kind) => roof(s, kind, u),
        None => Part::default(),
    }
}

/// A roof of this kind over the structure: the user's, or a default the program gives.
pub(super) fn roof(s: &Structure, kind: Roof, u: f64) -> Part {
    let mut out = Part::default();
    let id = &s.id;
    let sym = format!("{id}Roof");
    let h = s.height;
    let slab = 0.3 * u;
    let mut put = |inst: String| out.axiom.push((inst, sym.clone()));
    match (&s.footprint, kind) {
        (_, Roof::None) => {}
        (Footprint::Circle { center, radius }, Roof::Cone) => {
            let (r, rise) = (radius + 0.4 * u, radius * 1.4);
            put(format!(
                "T({}, {}, {}) I(\"cone\", {{{}, {}}})",
                n(center[0]),
                n(h + rise / 2.0),
                n(center[1]),
                n(r),
                n(rise)
            ));
        }
        (Footprint::Circle { center, radius }, Roof::Flat) => put(format!(
            "T({}, {}, {}) I(\"cylinder\", {{{}, {}}})",
            n(center[0]),
            n(h + slab / 2.0),
            n(center[1]),
            n(*radius),
            n(slab)
        )),
        // Over a circle, the other roofs stand on its circumscribed square.
        (Footprint::Circle { center, radius }, _) => rectangle_roof(
            &mut put,
            kind,
            *center,
            [2.0 * radius, 2.0 * radius],
            0.0,
            h,
            slab,
        ),
        (
            Footprint::Rectangle {
                center,
                size,
                rotation,
            },
            _,
        ) => rectangle_roof(&mut put, kind, *center, *size, *rotation, h, slab),
        // Blocks have their flat roof in `roomBlock` (`blocks::room` leaves it off for
        // "none"); walls take no roof (`corrections` refuses the rest).
        (Footprint::Blocks { .. } | Footprint::Wall { .. }, _) => {}
    }
    if !out.axiom.is_empty() {
        let why = if s.roof == Some(kind) {
            "[[structure]] roof in PROJECT.toml"
        } else {
            "the default"
        };
        let _ = writeln!(
            out.rules,
            "{sym} :: {{roof}}; // {} roof: {why}",
            kind.name()
        );
    }
    out
}

/// A roof over a `size` rectangle turned by `rotation` (plan radians, as `Footprint`), its
/// base at height `h`. A cone over a rectangle is a pyramid (a cone has no corners).
fn rectangle_roof(
    put: &mut impl FnMut(String),
    kind: Roof,
    center: [f64; 2],
    size: [f64; 2],
    rotation: f64,
    h: f64,
    slab: f64,
) {
    // Plan (x, y) is model (x, z); the rectangle's local axes in the plane.
    let along = [rotation.cos(), rotation.sin()];
    let across = [-rotation.sin(), rotation.cos()];
    let at = |a: f64, b: f64| {
        [
            center[0] + a * along[0] + b * across[0],
            center[1] + a * along[1] + b * across[1],
        ]
    };
    let [sx, sz] = size;
    match kind {
        Roof::Flat => put(format!(
            "T({}, {}, {}) R(0, {}, 0) I(\"box\", {{{}, {}, {}}})",
            n(center[0]),
            n(h + slab / 2.0),
            n(center[1]),
            n(-rotation),
            n(sx),
            n(slab),
            n(sz)
        )),
        Roof::Cone | Roof::Pyramid => {
            let rise = 0.5 * sx.min(sz);
            let corners = [
                at(-sx / 2.0, -sz / 2.0),
                at(sx / 2.0, -sz / 2.0),
                at(sx / 2.0, sz / 2.0),
                at(-sx / 2.0, sz / 2.0),
            ];
            for k in 0..4 {
                tetrahedron(put, center, corners[k], corners[(k + 1) % 4], h, rise);
            }
        }
        Roof::Gable | Roof::Hipped => {
            // The ridge runs along the longer side.
            let (long, short, ridge_dir) = if sx >= sz {
                (sx, sz, rotation)
            } else {
                (sz, sx, rotation + FRAC_PI_2)
            };
            let d = [ridge_dir.cos(), ridge_dir.sin()];
            let side = [-d[1], d[0]];
            let rise = if kind == Roof::Gable { 0.4 } else { 0.5 } * short;
            // Hips take half the short side off each end, so that all faces slope alike.
            let ridge = if kind == Roof::Gable {
                long
            } else {
                (long - short).max(0.0)
            };
            if ridge > 1e-9 {
                gable(put, center, side, ridge, short, h, rise);
            }
            if kind == Roof::Hipped {
                for sign in [-1.0, 1.0] {
                    let apex = [
                        center[0] + sign * d[0] * ridge / 2.0,
                        center[1] + sign * d[1] * ridge / 2.0,
                    ];
                    let p = |a: f64, b: f64| {
                        [
                            apex[0] + a * d[0] + b * side[0],
                            apex[1] + a * d[1] + b * side[1],
                        ]
                    };
                    let half = short / 2.0;
                    let fan = [
                        p(0.0, -half),
                        p(sign * half, -half),
                        p(sign * half, half),
                        p(0.0, half),
                    ];
                    for k in 0..3 {
                        tetrahedron(put, apex, fan[k], fan[k + 1], h, rise);
                    }
                }
            }
        }
        Roof::None => {}
    }
}

/// Two ramps back to back, their ridge along `ridge` units through `center`, each rising
/// `rise` over half of `span` towards the ridge; `side` is the unit vector across the ridge.
fn gable(
    put: &mut impl FnMut(String),
    center: [f64; 2],
    side: [f64; 2],
    ridge: f64,
    span: f64,
    h: f64,
    rise: f64,
) {
    // A ramp rises towards its local +x; turned so that +x points from the eave to the ridge.
    let slope = side[1].atan2(side[0]);
    for (sign, turn) in [(-1.0, 0.0), (1.0, PI)] {
        put(format!(
            "T({}, {}, {}) R(0, {}, 0) I(\"ramp\", {{{}, {}, {}}})",
            n(center[0] + sign * side[0] * span / 4.0),
            n(h + rise / 2.0),
            n(center[1] + sign * side[1] * span / 4.0),
            n(-slope + turn),
            n(span / 2.0),
            n(rise),
            n(ridge)
        ));
    }
}

/// A tetrahedron with its apex `rise` over `apex` and its base triangle (apex, a, b) at height
/// `h` (vsg's wedge frame: edge1 along local +x, edge2 turned by `angle` about +y).
fn tetrahedron(
    put: &mut impl FnMut(String),
    apex: [f64; 2],
    a: [f64; 2],
    b: [f64; 2],
    h: f64,
    rise: f64,
) {
    // R(0, θ, 0) takes +x to (cos θ, −sin θ) in (x, z): the heading of a plan direction.
    let heading = |p: [f64; 2]| (-(p[1] - apex[1])).atan2(p[0] - apex[0]);
    let (mut first, mut second) = (a, b);
    let mut angle = (heading(b) - heading(a)).rem_euclid(TAU);
    if angle > PI {
        (first, second) = (b, a);
        angle = TAU - angle;
    }
    let len = |p: [f64; 2]| (p[0] - apex[0]).hypot(p[1] - apex[1]);
    if angle < 1e-6 || len(first) < 1e-9 || len(second) < 1e-9 {
        return;
    }
    put(format!(
        "T({}, {}, {}) R(0, {}, 0) I(\"tetrahedron\", {{{}, {}, {}, {}}})",
        n(apex[0]),
        n(h + rise / 2.0),
        n(apex[1]),
        n(heading(first)),
        n(len(first)),
        n(len(second)),
        n(rise),
        n(angle)
    ));
}

/// Battlements the user asked for on a structure whose rules have none: a crenellated ring on
/// a round top, four crenellated parapets round a rectangle, merlons a metre wide.
pub(super) fn battlements(s: &Structure, u: f64) -> Part {
    let mut out = Part::default();
    if s.crenellated != Some(true) || crenellated_by_default(s) {
        return out;
    }
    let id = &s.id;
    let sym = format!("{id}Battlement");
    let (ph, merlon) = (1.6 * u, 1.0 * u);
    let t = s.wall_thickness.clamp(0.3 * u, 0.8 * u);
    let y = s.height + ph / 2.0;
    match &s.footprint {
        Footprint::Circle { center, radius } => {
            let count = ((TAU * radius) / (2.0 * merlon)).round().max(3.0);
            out.axiom.push((
                format!(
                    "T({}, {}, {}) I(\"cylinder\", {{{}, {}}})",
                    n(center[0]),
                    n(y),
                    n(center[1]),
                    n(*radius),
                    n(ph)
                ),
                sym.clone(),
            ));
            let _ = writeln!(
                out.rules,
                "{sym} :: split(\"R\", {{~1, {}}}){{opening, {sym}Ring}};\n{sym}Ring :: repeat(\"Theta\", {{~PI/{}, ~PI/{}}}){{wallStone, {sym}Crenel}};\n{sym}Crenel :: split(\"Y\", {{~1, ~1}}){{wallStone, opening}};",
                n(t),
                n(count),
                n(count)
            );
        }
        Footprint::Rectangle {
            center,
            size,
            rotation,
        } => {
            let along = [rotation.cos(), rotation.sin()];
            let across = [-rotation.sin(), rotation.cos()];
            let [sx, sz] = *size;
            // Two parapets along the rectangle's length, two across it between them.
            for (offset, dir, len, turn) in [
                (sz / 2.0 - t / 2.0, across, sx, 0.0),
                (-(sz / 2.0 - t / 2.0), across, sx, 0.0),
                (sx / 2.0 - t / 2.0, along, sz - 2.0 * t, FRAC_PI_2),
                (-(sx / 2.0 - t / 2.0), along, sz - 2.0 * t, FRAC_PI_2),
            ] {
                if len <= 0.0 {
                    continue;
                }
                out.axiom.push((
                    format!(
                        "T({}, {}, {}) R(0, {}, 0) I(\"box\", {{{}, {}, {}}})",
                        n(center[0] + offset * dir[0]),
                        n(y),
                        n(center[1] + offset * dir[1]),
                        n(-(rotation + turn)),
                        n(len),
                        n(ph),
                        n(t)
                    ),
                    sym.clone(),
                ));
            }
            let _ = writeln!(
                out.rules,
                "{sym} :: repeat(\"X\", {{~{}, ~{}}}){{wallStone, {sym}Crenel}};\n{sym}Crenel :: split(\"Y\", {{~1, ~1}}){{wallStone, opening}};",
                n(merlon),
                n(merlon)
            );
        }
        Footprint::Blocks { .. } | Footprint::Wall { .. } => {}
    }
    out
}
