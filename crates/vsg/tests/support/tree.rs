//! Models built by hand for the exporters' tests, child group by child group as the
//! interpreter builds them (children contiguous, after their parent): [`Tree`], with [`prim`]
//! and [`at`]. Shared by `gltf_validator.rs`, `cityjson.rs` and `ifc.rs` through `#[path]`.

#![allow(dead_code)] // Each test file uses its own part of it.

use nalgebra::Isometry3;
use vsg::shape::{Primitive, ShapeType};
use vsg::tree::{Appearance, Model, Node, NodeId, NodeState};

pub struct Tree(pub Model);

/// A child: symbol, state, shape (a `Primitive` or an `Option` of one), frame relative to the
/// parent, appearance.
pub type Kid<'a, S> = (&'a str, NodeState, S, Isometry3<f64>, u32);

impl Tree {
    /// A root of `symbol` without a shape, with the default appearance.
    pub fn new(symbol: &str) -> Tree {
        Tree(Model {
            nodes: vec![node(0, None, Isometry3::identity())],
            symbols: vec![symbol.to_owned()],
            appearances: vec![Appearance::default()],
            ..Default::default()
        })
    }

    /// A root of `symbol` with a shape.
    pub fn with_shape(symbol: &str, shape: Primitive) -> Tree {
        let mut t = Tree::new(symbol);
        t.0.nodes[0].shape = Some(shape);
        t
    }

    /// Gives `parent` the children `kids` (each symbol a new entry, as the tests want them)
    /// and returns the id of the first.
    pub fn children<S: Into<Option<Primitive>> + Copy>(
        &mut self,
        parent: NodeId,
        kids: &[Kid<S>],
    ) -> NodeId {
        let first = self.0.nodes.len() as NodeId;
        let p = &mut self.0.nodes[parent as usize];
        (p.state, p.first_child, p.child_count) =
            (NodeState::NonTerminal, first, kids.len() as u32);
        let (world, depth) = (p.world, p.depth + 1);
        for (index, &(name, state, shape, local, appearance)) in kids.iter().enumerate() {
            self.0.symbols.push(name.to_owned());
            let symbol = self.0.symbols.len() as u32 - 1;
            let mut n = node(symbol, shape.into(), world * local);
            n.local = local;
            n.parent = Some(parent);
            (n.state, n.appearance, n.depth, n.index) = (state, appearance, depth, index as u32);
            self.0.nodes.push(n);
        }
        first
    }
}

fn node(symbol: u32, shape: Option<Primitive>, world: Isometry3<f64>) -> Node {
    Node {
        symbol,
        rule_line: 3,
        shape,
        local: world,
        world,
        appearance: 0,
        state: NodeState::Terminal,
        parent: None,
        first_child: 0,
        child_count: 0,
        depth: 0,
        index: 0,
    }
}

/// A primitive of Table 7.1 that must be valid.
pub fn prim(kind: ShapeType, params: &[f64]) -> Primitive {
    Primitive::new(kind, params).unwrap_or_else(|e| panic!("{kind}: {e}"))
}

pub fn at(x: f64, y: f64, z: f64) -> Isometry3<f64> {
    Isometry3::translation(x, y, z)
}
