//! What the heritage and GIS formats (CityJSON, IFC, glTF structural metadata; issue 24) say of a
//! model beyond its meshes: the **parts** a building is made of (a structure of the castle: a
//! tower, the keep, a range, a curtain run, the gatehouse), the **class** of every terminal (wall,
//! roof, floor, window, door, room, opening), and the **frame** in which the files give
//! coordinates (metres, z up, north = −z of the model, optionally placed on a map).
//!
//! One home for these rules, so the three writers agree: [`Heritage`] is what a caller hands
//! them, [`class_of`] names a terminal's class from its symbol, [`Heritage::part_of`] finds the
//! part a node belongs to, [`part_totals`] sums a part's volume and mass, and
//! [`Frame::to_world`] maps a model point to the file's coordinates.

use std::collections::BTreeMap;

use nalgebra::Point3;

use crate::tree::{Model, NodeId, NodeState};

/// What a terminal is to a building model, decided from its symbol by [`class_of`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Class {
    /// Masonry: walls, wall stones, parapets, the default of a visible terminal.
    Wall,
    /// A roof: cones, pyramids, gables, roof slabs.
    Roof,
    /// A floor or walkway slab.
    Floor,
    /// A window light (glass or its frame), visible.
    Window,
    /// A door leaf or a gate, visible.
    Door,
    /// A void terminal that stands for a room or storey's interior.
    Space,
    /// Any other void terminal: an arrow slit, a crenel, a window or door opening.
    Opening,
}

impl Class {
    /// The name used in attributes and in the docs.
    pub fn name(self) -> &'static str {
        match self {
            Class::Wall => "wall",
            Class::Roof => "roof",
            Class::Floor => "floor",
            Class::Window => "window",
            Class::Door => "door",
            Class::Space => "space",
            Class::Opening => "opening",
        }
    }

    /// Whether a terminal of this class is drawn (has a surface) rather than void.
    pub fn is_solid(self) -> bool {
        !matches!(self, Class::Space | Class::Opening)
    }
}

/// The class of a terminal from its symbol and state. castellan's programs name a structure's
/// terminals `structure.part` (`tower2.roof`, `keep1.floor`, `range4.window`) and the library
/// names its own (`wallStone`, `curtainWalk`, `curtainCrenel`); the last dotted part decides,
/// by the words it contains (case-insensitive): void terminals are spaces (`room`, `storey`,
/// `interior`, `hall`) or else openings; visible ones are windows (`window`, `glass`, `light`),
/// doors (`door`, `leaf`, `portcullis`), roofs (`roof`, `cone`, `spire`), floors (`floor`,
/// `slab`, `walk`), and walls otherwise.
pub fn class_of(symbol: &str, state: NodeState) -> Class {
    let last = symbol.rsplit('.').next().unwrap_or(symbol).to_lowercase();
    let has = |words: &[&str]| words.iter().any(|w| last.contains(w));
    if state == NodeState::VoidTerminal {
        return if has(&["room", "storey", "interior", "hall"]) {
            Class::Space
        } else {
            Class::Opening
        };
    }
    if has(&["window", "glass", "light"]) {
        Class::Window
    } else if has(&["door", "leaf", "portcullis"]) {
        Class::Door
    } else if has(&["roof", "cone", "spire"]) {
        Class::Roof
    } else if has(&["floor", "slab", "walk"]) {
        Class::Floor
    } else {
        Class::Wall
    }
}

/// A value of a part's attribute, as all three formats can store it.
#[derive(Clone, Debug, PartialEq)]
pub enum Attribute {
    Text(String),
    Number(f64),
    Flag(bool),
}

/// One part of the building: a node of the model (usually a structure of the castle, a child
/// of the root) with its name and attributes (label, role, height, provenance of every
/// parameter, …). Every node under `node` and under each of `more_nodes` belongs to it.
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    pub node: NodeId,
    /// Further nodes of the same part (a curtain built as several runs, a roof built beside
    /// its tower); usually empty.
    pub more_nodes: Vec<NodeId>,
    /// Unique among the parts, e.g. `tower2`.
    pub name: String,
    /// What the part is (`tower`, `keep`, `range`, `curtain wall`, `gatehouse`, …), free text.
    pub kind: String,
    pub attributes: BTreeMap<String, Attribute>,
}

/// Where the model stands on the Earth: the model's origin at `origin` (easting, northing,
/// height, in the metres of the reference system `epsg`), its north (−z of the model) turned
/// `rotation_deg` clockwise from grid north.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    pub origin: [f64; 3],
    pub epsg: u32,
    pub rotation_deg: f64,
}

/// How model coordinates become the files' coordinates: metres, x east, y north, z up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Metres per model unit (1 when the model is in metres).
    pub metres_per_unit: f64,
    pub placement: Option<Placement>,
}

impl Default for Frame {
    fn default() -> Self {
        Frame {
            metres_per_unit: 1.0,
            placement: None,
        }
    }
}

impl Frame {
    /// The model point `p` (y up, the plan's x along x and its y along z) in the file's frame:
    /// x east, y north (the plan's up, −z of the model), z up, in metres, then turned and moved
    /// by the placement if there is one. Right-handed to right-handed: no mirror.
    pub fn to_world(&self, p: [f64; 3]) -> [f64; 3] {
        let s = self.metres_per_unit;
        let (x, y, z) = (p[0] * s, -p[2] * s, p[1] * s);
        match self.placement {
            None => [x, y, z],
            Some(pl) => {
                let (sin, cos) = pl.rotation_deg.to_radians().sin_cos();
                // Clockwise from grid north: a point on the model's north axis goes east.
                let (e, n) = (x * cos + y * sin, -x * sin + y * cos);
                [pl.origin[0] + e, pl.origin[1] + n, pl.origin[2] + z]
            }
        }
    }
}

/// What the heritage writers are given besides the model.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Heritage {
    /// The building's name (the project or program).
    pub name: String,
    /// The parts; empty, [`Heritage::parts_or_default`] takes the root's children.
    pub parts: Vec<Part>,
    pub frame: Frame,
    /// Attributes of the whole building (source drawing, castellan's version, …). The IFC
    /// header takes its time stamp from the text attribute `timestamp` (ISO 8601) when there
    /// is one, else 1970-01-01T00:00:00, so that the same model gives the same file.
    pub attributes: BTreeMap<String, Attribute>,
}

impl Heritage {
    /// The given parts, or else one per child of the root named by its symbol (with its index
    /// when a symbol repeats), or the root itself for a model of one node.
    pub fn parts_or_default(&self, model: &Model) -> Vec<Part> {
        if !self.parts.is_empty() {
            return self.parts.clone();
        }
        let Some(root) = model.root() else {
            return Vec::new();
        };
        let ids: Vec<NodeId> = if root.child_count == 0 {
            vec![0]
        } else {
            root.children().collect()
        };
        let mut seen: BTreeMap<&str, usize> = BTreeMap::new();
        for &id in &ids {
            *seen
                .entry(model.symbol(&model.nodes[id as usize]))
                .or_default() += 1;
        }
        ids.iter()
            .map(|&id| {
                let node = &model.nodes[id as usize];
                let symbol = model.symbol(node);
                let name = if seen[symbol] > 1 {
                    format!("{symbol}_{id}")
                } else {
                    symbol.to_string()
                };
                Part {
                    node: id,
                    more_nodes: Vec::new(),
                    name,
                    kind: symbol.to_string(),
                    attributes: BTreeMap::new(),
                }
            })
            .collect()
    }

    /// For every node, the index in `parts` of the part it belongs to (its nearest ancestor, or
    /// itself, that is a part's node), or `None` for nodes outside every part.
    pub fn part_of(model: &Model, parts: &[Part]) -> Vec<Option<usize>> {
        let mut of: Vec<Option<usize>> = vec![None; model.nodes.len()];
        for (i, p) in parts.iter().enumerate() {
            for id in std::iter::once(&p.node).chain(&p.more_nodes) {
                if let Some(slot) = of.get_mut(*id as usize) {
                    *slot = Some(i);
                }
            }
        }
        // Parents come before their children (creation order), so one pass inherits.
        for id in 0..model.nodes.len() {
            if of[id].is_none()
                && let Some(parent) = model.nodes[id].parent
            {
                of[id] = of[parent as usize];
            }
        }
        of
    }
}

/// Volume and mass of a part's drawn terminals, in model units³ and kg (mass from the
/// appearances' densities, which are per m³: meaningful when the model is in metres).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Totals {
    pub volume: f64,
    pub mass: f64,
    pub terminals: usize,
}

/// Totals per part (indexed like `parts`) of the visible terminals, from `part_of`.
pub fn part_totals(model: &Model, parts: &[Part], part_of: &[Option<usize>]) -> Vec<Totals> {
    let mut totals = vec![Totals::default(); parts.len()];
    for (id, node) in model.nodes.iter().enumerate() {
        if node.state != NodeState::Terminal {
            continue;
        }
        let (Some(Some(p)), Some(solid)) = (part_of.get(id), model.solid(id as NodeId)) else {
            continue;
        };
        let volume = solid.volume();
        let t = &mut totals[*p];
        t.volume += volume;
        t.mass += model.appearance(node).density.unwrap_or(0.0) * volume;
        t.terminals += 1;
    }
    totals
}

/// A mesh in world (model) coordinates: points and their triangles.
pub type WorldMesh = (Vec<[f64; 3]>, Vec<[u32; 3]>);

/// A terminal's mesh in world (model) coordinates: what the writers turn into surfaces.
pub fn world_mesh(
    model: &Model,
    id: NodeId,
    tessellation: &crate::shape::Tessellation,
) -> Option<WorldMesh> {
    let node = model.nodes.get(id as usize)?;
    let solid = model.solid(id)?;
    let mesh = solid.mesh(tessellation);
    let points = mesh
        .positions
        .iter()
        .map(|p| {
            let w = node.world * Point3::from(*p);
            [w.x, w.y, w.z]
        })
        .collect();
    Some((points, mesh.triangles.clone()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn castellan_symbols_get_their_classes() {
        let t = NodeState::Terminal;
        let v = NodeState::VoidTerminal;
        assert_eq!(class_of("keep1.masonry", t), Class::Wall);
        assert_eq!(class_of("wallStone", t), Class::Wall);
        assert_eq!(class_of("tower2.roof", t), Class::Roof);
        assert_eq!(class_of("roof", t), Class::Roof);
        assert_eq!(class_of("keep1.floor", t), Class::Floor);
        assert_eq!(class_of("curtainWalk", t), Class::Floor);
        assert_eq!(class_of("range4.window", t), Class::Window);
        assert_eq!(class_of("gate.door", t), Class::Door);
        assert_eq!(class_of("keep1.room", v), Class::Space);
        assert_eq!(class_of("keep1.arrowSlit", v), Class::Opening);
        assert_eq!(class_of("curtainCrenel", v), Class::Opening);
        assert_eq!(class_of("opening", v), Class::Opening);
        // The structure's name before the dot does not decide: a window of the gatehouse.
        assert_eq!(class_of("gatehouse1.window", t), Class::Window);
        assert_eq!(class_of("roofHall.masonry", t), Class::Wall);
    }

    #[test]
    fn the_frame_is_metres_z_up_north_up_and_right_handed() {
        let f = Frame {
            metres_per_unit: 2.0,
            placement: None,
        };
        assert_eq!(f.to_world([1.0, 0.0, 0.0]), [2.0, 0.0, 0.0]);
        assert_eq!(f.to_world([0.0, 1.0, 0.0]), [0.0, 0.0, 2.0]);
        // The plan's y grows down the page: +z of the model is south.
        assert_eq!(f.to_world([0.0, 0.0, 1.0]), [0.0, -2.0, 0.0]);
        // x × y = z in both frames: east × north = up.
        let placed = Frame {
            metres_per_unit: 1.0,
            placement: Some(Placement {
                origin: [500_000.0, 4_000_000.0, 100.0],
                epsg: 32631,
                rotation_deg: 90.0,
            }),
        };
        let north = placed.to_world([0.0, 0.0, -1.0]);
        // Turned 90° clockwise, the model's north points east.
        assert!((north[0] - 500_001.0).abs() < 1e-9 && (north[1] - 4_000_000.0).abs() < 1e-9);
        assert_eq!(placed.to_world([0.0, 3.0, 0.0])[2], 103.0);
    }
}
