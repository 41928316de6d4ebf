//! Gatehouses in the program (issue 25, after §7.2.2's `gatehouse.vsg`, whose flanking towers
//! are here the plan's own): a block from one tower's centre to the other's, its body pierced
//! by the passage through its depth, crenellated on top.

use std::fmt::Write;

use crate::estimate::{Footprint, Structure};

use super::common::{Part, n};

/// One gatehouse: its block in the axiom and its rules (the passage's width and height are
/// its own); `u` the units per metre.
pub(super) fn block(s: &Structure, u: f64) -> Part {
    let mut out = Part::default();
    let Footprint::Rectangle {
        center,
        size,
        rotation,
    } = s.footprint
    else {
        return out;
    };
    let (id, h) = (&s.id, s.height);
    let parapet = (1.6 * u).min(0.2 * h);
    let _ = writeln!(
        out.params,
        "float[] {id}H = {{{}, {}, {}, {}}}; // height, passage width, passage height, parapet",
        n(h),
        n((4.0 * u).min(size[0] / 3.0)),
        n((5.0 * u).min(0.5 * (h - parapet))),
        n(parapet)
    );
    out.axiom.push((
        format!(
            "T({}, {id}H[0]/2, {}) R(0, {}, 0) I(\"box\", {{{}, {id}H[0], {}}})",
            n(center[0]),
            n(center[1]),
            n(-rotation),
            n(size[0]),
            n(size[1])
        ),
        id.clone(),
    ));
    let _ = writeln!(
        out.rules,
        "{id} :: split(\"Y\", {{~1, {id}H[3]}}){{{id}Body, gateTop}};\n{id}Body :: split(\"X\", {{~1, {id}H[1], ~1}}){{wallStone, {id}Passage, wallStone}};\n{id}Passage :: split(\"Y\", {{{id}H[2], ~1}}){{opening, wallStone}};"
    );
    out
}

/// The crenellated top every gatehouse shares; `u` the units per metre.
pub(super) fn shared(u: f64) -> Part {
    Part {
        params: format!(
            "\n// Gatehouses' merlons.\nfloat gateMerlon = {};\n",
            n(1.0 * u)
        ),
        axiom: Vec::new(),
        rules: "\n// Gatehouses (issue 25): merlons across the block's top.\ngateTop :: repeat(\"X\", {~gateMerlon, ~gateMerlon}){wallStone, opening};\n".to_string(),
    }
}
