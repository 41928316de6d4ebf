//! Rooms of blocks in the program (issue 25): each block of a room that no circle or rectangle
//! fits is a box in the axiom, and every block takes the one `roomBlock` rule — the building's
//! mass under a flat roof (a mass, not a void: the walls around it are built as walls, at their
//! own class height, and a void room would leave its roof floating over lower walls) — so such
//! rooms add one rule each, however many blocks they have.

use std::fmt::Write;

use crate::estimate::{Footprint, Roof, Structure};

use super::common::{Part, n};

/// A room of blocks: one box per block, at the structure's height.
pub(super) fn room(s: &Structure) -> Part {
    let mut out = Part::default();
    let Footprint::Blocks { rotation, blocks } = &s.footprint else {
        return out;
    };
    let id = &s.id;
    let _ = writeln!(
        out.params,
        "float {id}H = {}; // height\nfloat {id}R = {}; // rotation about y",
        n(s.height),
        n(-rotation)
    );
    for b in blocks {
        out.axiom.push((
            format!(
                "T({}, {id}H/2, {}) R(0, {id}R, 0) I(\"box\", {{{}, {id}H, {}}})",
                n(b.center[0]),
                n(b.center[1]),
                n(b.size[0]),
                n(b.size[1])
            ),
            id.clone(),
        ));
    }
    // The user may take the flat roof off (`[[structure]] roof = "none"`, issue 22).
    let body = if s.roof == Some(Roof::None) {
        "wallStone"
    } else {
        "roomBlock"
    };
    let _ = writeln!(out.rules, "{id} :: {{{body}}};");
    out
}

/// The rule every block shares; `u` the units per metre.
pub(super) fn shared(u: f64) -> Part {
    Part {
        params: format!(
            "\n// Rooms of blocks: the flat roof's thickness.\nfloat roomRoofT = {};\n",
            n(0.4 * u)
        ),
        axiom: Vec::new(),
        rules: "\n// Rooms no circle or rectangle fits (issue 25): each block the building's mass under a flat roof.\nroomBlock :: split(\"Y\", {~1, roomRoofT}){wallStone, roof};\n".to_string(),
    }
}
