//! Rooms of blocks in the program (issue 25): each block of a room that no circle or rectangle
//! fits is a box in the axiom, and every block takes the one `roomBlock` rule — the building's
//! mass under a flat roof (a mass, not a void: the walls around it are built as walls, at their
//! own class height, and a void room would leave its roof floating over lower walls) — so such
//! rooms add one rule each, however many blocks they have.

use std::fmt::Write;

use crate::estimate::{Footprint, Role, Roof, Structure};

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
    // A mass of wall (`Role::Mass`) is stone to the top, unless the
    // user gave it a roof.
    let unroofed = s.roof.unwrap_or(if s.role == Role::Mass {
        Roof::None
    } else {
        Roof::Flat
    }) == Roof::None;
    let body = if unroofed { "wallStone" } else { "roomBlock" };
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimate::{Block, Kind};
    use plan::label::Label;

    fn of(role: Role, roof: Option<Roof>) -> Structure {
        Structure {
            id: "b1".into(),
            label: Label::UnknownWall,
            role,
            kind: Kind::Solid,
            footprint: Footprint::Blocks {
                rotation: 0.0,
                blocks: vec![Block {
                    center: [1.0, 2.0],
                    size: [3.0, 4.0],
                }],
            },
            height: 6.0,
            wall_thickness: 1.0,
            facades: vec![],
            roof,
            crenellated: None,
            children: vec![],
            provenance: Default::default(),
        }
    }

    #[test]
    fn a_range_of_blocks_is_roofed_and_a_mass_of_wall_is_stone_unless_the_user_roofs_it() {
        assert_eq!(room(&of(Role::Range, None)).rules, "b1 :: {roomBlock};\n");
        assert_eq!(
            room(&of(Role::Range, Some(Roof::None))).rules,
            "b1 :: {wallStone};\n"
        );
        assert_eq!(room(&of(Role::Mass, None)).rules, "b1 :: {wallStone};\n");
        assert_eq!(
            room(&of(Role::Mass, Some(Roof::Flat))).rules,
            "b1 :: {roomBlock};\n"
        );
        let axiom = &room(&of(Role::Mass, None)).axiom;
        assert_eq!(axiom.len(), 1);
        assert!(
            axiom[0].0.contains("I(\"box\", {3, b1H, 4})"),
            "{}",
            axiom[0].0
        );
    }
}
