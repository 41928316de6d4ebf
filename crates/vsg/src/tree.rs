//! The semantic tree that production leaves behind (§7.1.3): non-terminals are kept, so the
//! model is a hierarchy of labelled shapes whose leaves are the terminal solids.

use nalgebra::Isometry3;
use serde::Serialize;

use crate::shape::Primitive;

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
    /// The solid; `None` only for a root that never got a shape.
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
        }
    }
}

/// The produced model: nodes in creation order (the root first), interned symbol names and
/// appearances.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Model {
    pub nodes: Vec<Node>,
    pub symbols: Vec<String>,
    pub appearances: Vec<Appearance>,
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

    /// The leaves (visible and void terminals), in creation order.
    pub fn terminals(&self) -> impl Iterator<Item = &Node> {
        self.nodes.iter().filter(|n| n.is_leaf())
    }
}
