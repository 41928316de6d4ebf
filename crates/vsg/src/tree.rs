//! The semantic tree that production leaves behind (§7.1.3): non-terminals are kept, so the
//! model is a hierarchy of labelled shapes whose leaves are the terminal solids.

use std::borrow::Cow;
use std::collections::BTreeMap;

use nalgebra::Isometry3;
use serde::Serialize;

use crate::csg::BoolOp;
use crate::mesh::TriMesh;
use crate::shape::{Primitive, Tessellation};

/// Index of a node in [`Model::nodes`].
pub type NodeId = u32;

/// Whether a node was expanded further, and if not, whether it is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum NodeState {
    /// Replaced by its children.
    NonTerminal,
    /// A visible leaf of the model.
    Terminal,
    /// A leaf made invisible by `void()`: kept for the hierarchy and volumes, never drawn.
    VoidTerminal,
}

/// One shape of the production, terminal or not.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// Index into [`Model::symbols`].
    pub symbol: u32,
    /// 1-based line of the rule that created this node (0 for the root).
    pub rule_line: u32,
    /// The solid; `None` for a root that never got a shape, and for a unique shape (its mesh
    /// is in [`Model::unique`]; use [`Model::solid`] to get either).
    pub shape: Option<Primitive>,
    /// Frame relative to the parent's frame.
    pub local: Isometry3<f64>,
    /// Frame relative to the world.
    pub world: Isometry3<f64>,
    /// Index into [`Model::appearances`].
    pub appearance: u32,
    pub state: NodeState,
    pub parent: Option<NodeId>,
    /// Children are created together by one rule, so they are contiguous.
    pub first_child: NodeId,
    pub child_count: u32,
    /// Root has depth 0.
    pub depth: u32,
    /// Position among its siblings, from 0.
    pub index: u32,
}

impl Node {
    pub fn children(&self) -> std::ops::Range<NodeId> {
        self.first_child..self.first_child + self.child_count
    }

    pub fn is_leaf(&self) -> bool {
        self.state != NodeState::NonTerminal
    }
}

/// Surface appearance (§7.1.1 appearance function); components are 0..1.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Appearance {
    pub color: [f64; 3],
    pub transparency: f64,
    pub ambient: f64,
    pub diffuse: [f64; 3],
    pub specular: [f64; 3],
    pub emissive: [f64; 3],
    pub shine: f64,
    /// Image file name, resolved by the caller when exporting.
    pub texture: Option<String>,
    /// Line of the rule that set `texture`, for messages about the file.
    pub texture_line: u32,
    /// Density of the material in kg/m³ (`appearance("density", 2400)`): terminals with one
    /// get a mass in STATS.json.
    pub density: Option<f64>,
    /// Set by `appearance("photo", "f.png")`: the texture is stretched over this frame's box
    /// (a façade photo over its wall) and every descendant samples it where it lies in that
    /// box, instead of the box projection at real scale.
    #[serde(skip)]
    pub texture_frame: Option<TextureFrame>,
}

/// The box a photo texture covers: the frame (centre and orientation, world) and size of the
/// shape whose rule set it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureFrame {
    pub world: Isometry3<f64>,
    pub size: [f64; 3],
}

impl Default for Appearance {
    fn default() -> Self {
        Appearance {
            color: [0.8, 0.78, 0.72],
            transparency: 0.0,
            ambient: 0.2,
            diffuse: [0.8, 0.8, 0.8],
            specular: [0.0, 0.0, 0.0],
            emissive: [0.0, 0.0, 0.0],
            shine: 0.2,
            texture: None,
            texture_line: 0,
            density: None,
            texture_frame: None,
        }
    }
}

/// A unique shape (§7.1.2): the result of a Boolean, a closed mesh in its node's frame.
#[derive(Clone, Debug, PartialEq)]
pub struct UniqueShape {
    pub op: BoolOp,
    pub mesh: TriMesh,
    /// Volume of the mesh (divergence theorem).
    pub volume: f64,
}

/// The solid of a node: a primitive of Table 7.1 or a unique shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Solid<'a> {
    Primitive(Primitive),
    Unique(NodeId, &'a UniqueShape),
}

impl Solid<'_> {
    /// The shape type name (`box`, …) or the Boolean (`union`, `intersection`, `difference`).
    pub fn name(&self) -> &'static str {
        match self {
            Solid::Primitive(p) => p.kind.name(),
            Solid::Unique(_, u) => u.op.name(),
        }
    }

    /// Exact volume of a primitive, mesh volume of a unique shape.
    pub fn volume(&self) -> f64 {
        match self {
            Solid::Primitive(p) => p.volume(),
            Solid::Unique(_, u) => u.volume,
        }
    }

    /// Extent along the local axes: the primitive's size, a unique shape's bounding box.
    pub fn size(&self) -> [f64; 3] {
        match self {
            Solid::Primitive(p) => p.size(),
            Solid::Unique(_, u) => u.mesh.bounds().map_or([0.0; 3], |(lo, hi)| {
                [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]]
            }),
        }
    }

    /// The surface mesh in the node's frame.
    pub fn mesh(&self, tessellation: &Tessellation) -> Cow<'_, TriMesh> {
        match self {
            Solid::Primitive(p) => Cow::Owned(p.mesh(tessellation)),
            Solid::Unique(_, u) => Cow::Borrowed(&u.mesh),
        }
    }
}

/// The produced model: nodes in creation order (the root first), interned symbol names,
/// appearances, and the meshes of unique shapes by node.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Model {
    pub nodes: Vec<Node>,
    pub symbols: Vec<String>,
    pub appearances: Vec<Appearance>,
    /// Unique shapes (§7.1.2) by the id of the node that holds them.
    pub unique: BTreeMap<NodeId, UniqueShape>,
}

impl Model {
    pub fn root(&self) -> Option<&Node> {
        self.nodes.first()
    }

    pub fn symbol(&self, node: &Node) -> &str {
        &self.symbols[node.symbol as usize]
    }

    pub fn appearance(&self, node: &Node) -> &Appearance {
        &self.appearances[node.appearance as usize]
    }

    /// The solid of node `id`, primitive or unique.
    pub fn solid(&self, id: NodeId) -> Option<Solid<'_>> {
        match self.unique.get(&id) {
            Some(u) => Some(Solid::Unique(id, u)),
            None => self.nodes.get(id as usize)?.shape.map(Solid::Primitive),
        }
    }

    /// The leaves (visible and void terminals), in creation order.
    pub fn terminals(&self) -> impl Iterator<Item = &Node> {
        self.nodes.iter().filter(|n| n.is_leaf())
    }
}
