//! Curtain and inner walls in the program (issue 25, after §7.2.2's `curtain_wall.vsg`): each
//! straight piece of a wall run is a box in the axiom, and every curtain piece takes the one
//! `curtain` rule — a wall body, then on top a parapet crenellated on the field side and the wall
//! walk behind it — so a castle's curtain is one rule however many pieces it has. Inner walls
//! are plain masonry.

use std::fmt::Write;

use crate::estimate::{Footprint, Role, Structure};

use super::common::{Part, n};

/// A wall run: one box per straight piece, lengthened by the wall's thickness so that pieces
/// meet at their corners. Local −z of every piece is the field side (the centreline keeps the
/// field on its left, `Footprint::Wall`), where the `curtain` rule puts the parapet.
/// `textures`: the wall samples' list, when there are any (one of them per shape, tinted by the
/// stone colour, as the library's structures take them).
pub(super) fn run(s: &Structure, textures: Option<&str>) -> Part {
    let mut out = Part::default();
    let Footprint::Wall {
        thickness,
        ref widths,
        ..
    } = s.footprint
    else {
        return out;
    };
    let id = &s.id;
    let _ = writeln!(
        out.params,
        "float[] {id}H = {{{}, {}}}; // height, thickness",
        n(s.height),
        n(thickness)
    );
    // Each piece's own thickness as drawn (issue 25), when the plan measured it.
    if !widths.is_empty() {
        let list: Vec<String> = widths.iter().map(|w| n(*w)).collect();
        let _ = writeln!(
            out.params,
            "float[] {id}W = {{{}}}; // each piece's thickness as drawn",
            list.join(", ")
        );
    }
    for (k, ([a, b], width)) in s.footprint.pieces_with_widths().into_iter().enumerate() {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        if len < 1e-9 {
            continue;
        }
        let depth = if widths.is_empty() {
            format!("{id}H[1]")
        } else {
            format!("{id}W[{k}]")
        };
        out.axiom.push((
            format!(
                "T({}, {id}H[0]/2, {}) R(0, {}, 0) I(\"box\", {{{}, {id}H[0], {depth}}})",
                n((a[0] + b[0]) / 2.0),
                n((a[1] + b[1]) / 2.0),
                n(-dy.atan2(dx)),
                n(len + width)
            ),
            id.clone(),
        ));
    }
    // The curtain is crenellated and inner walls are not, unless the user said otherwise
    // (`[[structure]] crenellated`, issue 22).
    let body = match (s.role == Role::Curtain, s.crenellated) {
        (_, Some(true)) | (true, None) => "curtain",
        (true, Some(false)) => "curtainPlain",
        (false, _) => "innerWall",
    };
    let appearance = textures
        .map(|list| format!("appearance(\"texture\", {list})"))
        .unwrap_or_default();
    let _ = writeln!(out.rules, "{id} :: {appearance}{{{body}}};");
    out
}

/// The parameters and rules every curtain piece and inner wall shares; `lowest` is the lowest
/// curtain (model units), so that the parapet always fits, `u` the units per metre.
pub(super) fn shared(lowest: f64, u: f64) -> Part {
    let parapet = (1.8 * u).min(0.3 * lowest);
    Part {
        params: format!(
            "\n// The curtain's parapet (§7.2.2's curtain_wall.vsg): height, merlon width, wall-walk paving.\nfloat curtainParapetH = {};\nfloat curtainMerlon = {};\nfloat curtainWalkT = {};\n",
            n(parapet),
            n(1.2 * u),
            n((0.2 * u).min(parapet * 0.3))
        ),
        axiom: Vec::new(),
        rules: "\n// Curtain walls (curtain_wall.vsg as one rule for every piece): the body, then a parapet\n// on the field side (local −z, a fifth of the wall) crenellated once, and the wall walk behind it.\ncurtain :: split(\"Y\", {~1, curtainParapetH}){wallStone, curtainTop};\ncurtainTop :: split(\"Z\", {~1, ~4}){curtainParapet, curtainWalkZone};\ncurtainParapet :: repeat(\"X\", {~curtainMerlon, ~curtainMerlon}){wallStone, curtainCrenel};\ncurtainCrenel :: split(\"Y\", {~4, ~5}){wallStone, opening};\ncurtainWalkZone :: split(\"Y\", {curtainWalkT, ~1}){curtainWalk, opening};\ncurtainWalk :: appearance(\"color\", {0.5, 0.47, 0.42}){j3d.terminal};\n// A curtain the user wants without crenels: the parapet whole.\ncurtainPlain :: split(\"Y\", {~1, curtainParapetH}){wallStone, curtainPlainTop};\ncurtainPlainTop :: split(\"Z\", {~1, ~4}){wallStone, curtainWalkZone};\ninnerWall :: {wallStone};\n".to_string(),
    }
}
