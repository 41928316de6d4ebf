//! Plan shapes → structures (§6.1.3, §5.3): rooms with a circle or rectangle fit become hollow
//! cylindrical or rectangular structures (outer footprint = the fitted wall centreline plus
//! half the wall), towers found as bulges of the curtain (`plan::bulges`, no room drawn)
//! become solid cylindrical towers, and wall chains no room owns become solid wall segments.
//! Heights are the class defaults of §5.3 until a façade says otherwise.

use std::collections::BTreeMap;

use plan::ParsedPlan;
use plan::extrude::{Heights, simplify};
use plan::fit::Fit;
use plan::label::Label;
use plan::scale::{ModelScale, outer_wall_thickness};

use crate::correspond::contains;
use crate::estimate::{Element, Footprint, Kind, Provenance, Structure};

fn structure_name(l: Label) -> Option<&'static str> {
    match l {
        Label::TowerRoom => Some("tower"),
        Label::GreatHall => Some("hall"),
        Label::Chapel => Some("chapel"),
        Label::UnknownRoom => Some("room"),
        _ => None,
    }
}

/// The wall label that surrounds rooms of label `l` (for heights and names).
fn wall_of(l: Label) -> Label {
    match l {
        Label::TowerRoom => Label::TowerWall,
        Label::GreatHall => Label::GreatHallWall,
        Label::Chapel => Label::ChapelWall,
        _ => Label::UnknownWall,
    }
}

/// Children of a structure's root by kind (§6.1.3).
pub fn hierarchy(id: &str, kind: Kind) -> Vec<Element> {
    match kind {
        Kind::HollowRectangular => ["north", "south", "east", "west"]
            .iter()
            .map(|s| Element::leaf(format!("{id}Wall_{s}"), "wall"))
            .chain([Element::leaf(format!("{id}Interior"), "interior")])
            .collect(),
        Kind::HollowCylindrical => vec![
            Element::leaf(format!("{id}Wall"), "wall"),
            Element::leaf(format!("{id}Interior"), "interior"),
        ],
        Kind::SolidCylindrical => vec![
            Element::leaf(format!("{id}Wall"), "wall"),
            Element::leaf(format!("{id}Fill"), "fill"),
        ],
        Kind::Solid => vec![
            Element::leaf(format!("{id}Face_field"), "wall"),
            Element::leaf(format!("{id}Fill"), "fill"),
            Element::leaf(format!("{id}Face_ward"), "wall"),
        ],
    }
}

/// Every structure of the plan, without façades: rooms, then the bulge towers (named `tower{n}`
/// after the tower rooms' `tower1 … tower{k}`), then the walls.
pub fn from_plan(plan: &ParsedPlan, image: &str, frame: &ModelScale) -> Vec<Structure> {
    let heights = Heights::scaled(frame.units_per_metre);
    let s = frame.units_per_pixel;
    let mut counters: BTreeMap<&str, usize> = BTreeMap::new();
    let mut next_id = |base: &'static str| {
        let n = counters.entry(base).or_insert(0);
        *n += 1;
        format!("{base}{n}")
    };
    let mut owned = vec![false; plan.edges.len()];
    let mut out = Vec::new();
    for (fi, face) in plan.faces.iter().enumerate() {
        let Some(base) = structure_name(face.label) else {
            continue;
        };
        let thickness: Vec<f64> = face
            .edges
            .iter()
            .map(|&e| plan.edges[e].thickness)
            .collect();
        let t_px = if thickness.is_empty() {
            2.0
        } else {
            thickness.iter().sum::<f64>() / thickness.len() as f64
        };
        let (footprint, kind, fit, error) = match &face.shape {
            Some(Fit::Circle {
                center,
                radius,
                error,
            }) if *radius > 0.5 => (
                Footprint::Circle {
                    center: [center[0] * s, center[1] * s],
                    radius: (radius + t_px / 2.0) * s,
                },
                Kind::HollowCylindrical,
                "circle",
                *error,
            ),
            Some(Fit::Rectangle {
                center,
                size,
                angle,
                error,
            }) if size[0] > 0.5 && size[1] > 0.5 => (
                Footprint::Rectangle {
                    center: [center[0] * s, center[1] * s],
                    size: [(size[0] + t_px) * s, (size[1] + t_px) * s],
                    rotation: *angle,
                },
                Kind::HollowRectangular,
                "rectangle",
                *error,
            ),
            _ => continue,
        };
        for &e in &face.edges {
            owned[e] = true;
        }
        let id = next_id(base);
        let wall_label = wall_of(face.label);
        let mut provenance = BTreeMap::new();
        provenance.insert(
            "footprint".to_string(),
            Provenance::new(
                image,
                format!(
                    "§5.1.5 {fit} fit of plan face {fi} ({}), plus half the wall",
                    face.label.name()
                ),
                Some(error),
            ),
        );
        provenance.insert(
            "wall_thickness".to_string(),
            Provenance::new(
                image,
                format!(
                    "§5.1.4 mean thickness of the {} walls around plan face {fi}",
                    face.edges.len()
                ),
                None,
            ),
        );
        provenance.insert(
            "height".to_string(),
            Provenance::new(
                "default",
                format!("§5.3 class height of {}", wall_label.name()),
                None,
            ),
        );
        out.push(Structure {
            children: hierarchy(&id, kind),
            id,
            label: face.label,
            kind,
            footprint,
            height: heights.of(wall_label),
            wall_thickness: t_px * s,
            facades: Vec::new(),
            provenance,
        });
    }
    let rooms = out.len();
    let curtain_px = outer_wall_thickness(plan);
    for (bi, b) in plan.bulge_towers.iter().enumerate() {
        let center = [b.center[0] * s, b.center[1] * s];
        // A bulge on a tower whose room the plan found is that tower: it is built once.
        let built = out[..rooms]
            .iter()
            .any(|t| t.label == Label::TowerRoom && contains(&t.footprint, center));
        if built || b.radius <= 0.5 {
            continue;
        }
        let id = next_id("tower");
        let wall_px = curtain_px.unwrap_or(b.radius / 3.0).min(b.radius / 2.0);
        let mut provenance = BTreeMap::new();
        provenance.insert(
            "footprint".to_string(),
            Provenance::new(
                image,
                format!(
                    "§5.1.6 bulge tower {bi} of the castle's outline (plan::bulges, no room drawn): circle fitted to the bulge, solid"
                ),
                None,
            ),
        );
        provenance.insert(
            "wall_thickness".to_string(),
            Provenance::new(
                image,
                match curtain_px {
                    Some(_) => "§5.1.4 median thickness of the outer walls (the curtain the tower studs), at most half the radius; inside it, fill",
                    None => "no outer wall: a third of the radius; inside it, fill",
                },
                None,
            ),
        );
        provenance.insert(
            "height".to_string(),
            Provenance::new(
                "default",
                format!("§5.3 class height of {}", Label::TowerWall.name()),
                None,
            ),
        );
        out.push(Structure {
            children: hierarchy(&id, Kind::SolidCylindrical),
            id,
            label: Label::TowerWall,
            kind: Kind::SolidCylindrical,
            footprint: Footprint::Circle {
                center,
                radius: b.radius * s,
            },
            height: heights.of(Label::TowerWall),
            wall_thickness: wall_px * s,
            facades: Vec::new(),
            provenance,
        });
    }
    for (ei, edge) in plan.edges.iter().enumerate() {
        let height = heights.of(edge.label);
        if owned[ei] || !edge.label.is_wall() || height <= 0.0 {
            continue;
        }
        let pts: Vec<[f64; 2]> = edge
            .points
            .iter()
            .map(|&(x, y)| [f64::from(x), f64::from(y)])
            .collect();
        let t_px = edge.thickness.max(1.0);
        for seg in simplify(&pts, 1.5).windows(2) {
            let (dx, dy) = (seg[1][0] - seg[0][0], seg[1][1] - seg[0][1]);
            let len = dx.hypot(dy);
            if len < 1.0 {
                continue;
            }
            let id = next_id("wall");
            let mut provenance = BTreeMap::new();
            provenance.insert(
                "footprint".to_string(),
                Provenance::new(
                    image,
                    format!(
                        "§5.1.4 skeleton chain of plan edge {ei} ({}), a segment of its Douglas–Peucker simplification (within 1.5 px)",
                        edge.label.name()
                    ),
                    None,
                ),
            );
            provenance.insert(
                "height".to_string(),
                Provenance::new(
                    "default",
                    format!("§5.3 class height of {}", edge.label.name()),
                    None,
                ),
            );
            out.push(Structure {
                children: hierarchy(&id, Kind::Solid),
                id,
                label: edge.label,
                kind: Kind::Solid,
                footprint: Footprint::Rectangle {
                    center: [
                        (seg[0][0] + seg[1][0]) / 2.0 * s,
                        (seg[0][1] + seg[1][1]) / 2.0 * s,
                    ],
                    // Overlap by the wall's thickness so that segments meet at corners.
                    size: [(len + t_px) * s, t_px * s],
                    rotation: dy.atan2(dx),
                },
                height,
                wall_thickness: t_px * s,
                facades: Vec::new(),
                provenance,
            });
        }
    }
    out
}
