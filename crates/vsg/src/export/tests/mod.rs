//! Exporter tests on hand-built models (§7.1.2/§7.1.3: terminals carry meshes, the hierarchy is
//! kept). Meshes and volumes are injected as closures, so these tests exercise the exporters
//! and not the primitives.

use nalgebra::{Isometry3, Vector3};

use super::*;
use crate::mesh::TriMesh;
use crate::shape::ShapeType;
use crate::tree::{Appearance, Node, NodeId, NodeState};

mod glb;
mod obj;

/// An axis-aligned box centred at the origin, sized by the first three parameters.
fn box_mesh(p: &Primitive) -> TriMesh {
    let [x, y, z] = [0, 1, 2].map(|k| p.params()[k] / 2.0);
    let mut m = TriMesh::default();
    for i in 0..8 {
        let s = |bit: i32, v: f64| if i & bit == 0 { -v } else { v };
        m.push_vertex([s(1, x), s(2, y), s(4, z)]);
    }
    for quad in [
        [0, 4, 6, 2],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 2, 3, 1],
        [4, 5, 7, 6],
    ] {
        m.push_polygon(&quad);
    }
    m
}

fn box_volume(p: &Primitive) -> f64 {
    p.params().iter().product()
}

/// A 32-sided prism of radius 1 and height 2 (a coarse cylinder), whatever the primitive.
fn prism_mesh(_: &Primitive) -> TriMesh {
    let n = 32u32;
    let mut m = TriMesh::default();
    for i in 0..n {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        m.push_vertex([a.cos(), -1.0, -a.sin()]);
        m.push_vertex([a.cos(), 1.0, -a.sin()]);
    }
    for i in 0..n {
        let j = (i + 1) % n;
        m.push_polygon(&[2 * i, 2 * j, 2 * j + 1, 2 * i + 1]);
    }
    m.push_polygon(&(0..n).map(|i| 2 * i + 1).collect::<Vec<_>>());
    m.push_polygon(&(0..n).rev().map(|i| 2 * i).collect::<Vec<_>>());
    m
}

fn boxed(size: [f64; 3]) -> Primitive {
    Primitive::new(ShapeType::Box, &size).expect("a valid box")
}

/// Builds models child group by child group, like the interpreter does.
struct Tree(Model);

impl Tree {
    fn new(symbol: &str, shape: Option<Primitive>) -> Tree {
        let mut tree = Tree(Model {
            appearances: vec![Appearance::default()],
            ..Default::default()
        });
        let symbol = tree.symbol(symbol);
        tree.0.nodes.push(Node {
            symbol,
            rule_line: 0,
            shape,
            local: Isometry3::identity(),
            world: Isometry3::identity(),
            appearance: 0,
            state: NodeState::Terminal,
            parent: None,
            first_child: 0,
            child_count: 0,
            depth: 0,
            index: 0,
        });
        tree
    }

    fn symbol(&mut self, name: &str) -> u32 {
        let symbols = &mut self.0.symbols;
        let found = symbols.iter().position(|s| s == name);
        found.unwrap_or_else(|| {
            symbols.push(name.to_owned());
            symbols.len() - 1
        }) as u32
    }

    /// Adds children `(symbol, state, shape, local, appearance)` to `parent`.
    fn children(
        &mut self,
        parent: NodeId,
        kids: &[(&str, NodeState, Primitive, Isometry3<f64>, u32)],
    ) -> &mut Tree {
        let first = self.0.nodes.len() as NodeId;
        let (world, depth) = {
            let p = &mut self.0.nodes[parent as usize];
            p.state = NodeState::NonTerminal;
            p.first_child = first;
            p.child_count = kids.len() as u32;
            (p.world, p.depth + 1)
        };
        for (index, &(name, state, shape, local, appearance)) in kids.iter().enumerate() {
            let symbol = self.symbol(name);
            self.0.nodes.push(Node {
                symbol,
                rule_line: 10 + index as u32,
                shape: Some(shape),
                local,
                world: world * local,
                appearance,
                state,
                parent: Some(parent),
                first_child: 0,
                child_count: 0,
                depth,
                index: index as u32,
            });
        }
        self
    }
}

fn at(x: f64, y: f64, z: f64) -> Isometry3<f64> {
    Isometry3::translation(x, y, z)
}

/// Castle(0) → Wall(1), Window(2, void), Tower(3, appearance 1), Gate(4, appearance 2 = 0);
/// Wall → Brick(5..=8), the last with appearance 2.
fn castle() -> Model {
    use NodeState::*;
    let mut t = Tree::new("Castle", Some(boxed([10.0, 4.0, 6.0])));
    let glass = Appearance {
        color: [0.9, 0.1, 0.1],
        transparency: 0.25,
        emissive: [0.0, 0.5, 0.0],
        shine: 0.7,
        texture: Some("bricks.png".into()),
        ..Appearance::default()
    };
    t.0.appearances.extend([glass, Appearance::default()]);
    let turned = Isometry3::new(Vector3::new(4.0, 0.0, 2.0), Vector3::y() * 0.785);
    t.children(
        0,
        &[
            (
                "Wall",
                Terminal,
                boxed([10.0, 4.0, 1.0]),
                at(0.0, 0.0, -2.5),
                0,
            ),
            (
                "Window",
                VoidTerminal,
                boxed([1.0, 1.0, 1.0]),
                at(2.0, 1.0, 0.0),
                0,
            ),
            ("Tower", Terminal, boxed([2.0, 4.0, 2.0]), turned, 1),
            (
                "Gate",
                Terminal,
                boxed([2.0, 4.0, 2.0]),
                at(-4.0, 0.0, 2.0),
                2,
            ),
        ],
    );
    let brick = boxed([1.0, 0.5, 1.0]);
    t.children(
        1,
        &[
            ("Brick", Terminal, brick, at(-1.0, -1.0, 0.0), 0),
            ("Brick", Terminal, brick, at(0.0, -1.0, 0.0), 0),
            ("Brick", Terminal, brick, at(1.0, -1.0, 0.0), 0),
            ("Brick", Terminal, brick, at(2.0, -1.0, 0.0), 2),
        ],
    );
    t.0
}

fn glb_with(model: &Model, mesh: &dyn Fn(&Primitive) -> TriMesh) -> Vec<u8> {
    let geometry = Geometry {
        mesh,
        volume: &box_volume,
    };
    super::gltf::write_glb(
        model,
        &ExportOptions::default(),
        &Textures::new(),
        None,
        &geometry,
    )
    .expect("export succeeds")
}

fn obj_of(model: &Model) -> (String, String) {
    let geometry = Geometry {
        mesh: &box_mesh,
        volume: &box_volume,
    };
    super::obj::write_obj(model, &ExportOptions::default(), "castle.mtl", &geometry)
        .expect("export")
}

#[test]
fn crease_angle_keeps_cylinders_smooth_and_caps_flat() {
    let shaded = shading::shade("cylinder", &prism_mesh(&boxed([1.0; 3])), 40.0).unwrap();
    // Each side ring vertex is shared by the sides (one smooth normal) and split from its cap.
    assert_eq!(shaded.positions.len(), 4 * 32);
    let radial = shaded.normals.iter().filter(|n| n[1].abs() < 1e-12).count();
    assert_eq!(radial, 2 * 32);
    let faceted = shading::shade("cylinder", &prism_mesh(&boxed([1.0; 3])), 5.0).unwrap();
    assert_eq!(faceted.positions.len(), 4 * 32 + 2 * 32);
}

#[test]
fn broken_references_are_errors() {
    let geometry = Geometry {
        mesh: &box_mesh,
        volume: &box_volume,
    };
    let options = ExportOptions::default();
    let mut model = castle();
    model.nodes[5].appearance = 9;
    let err =
        super::gltf::write_glb(&model, &options, &Textures::new(), None, &geometry).unwrap_err();
    assert!(matches!(
        err,
        ExportError::BadReference {
            node: 5,
            what: "appearance",
            ..
        }
    ));
    let mut model = castle();
    model.nodes[6].parent = Some(2);
    let err = super::obj::write_obj(&model, &options, "x.mtl", &geometry).unwrap_err();
    assert!(matches!(err, ExportError::BadTree { .. }), "{err}");
    let bad_mesh = |_: &Primitive| TriMesh {
        positions: vec![[0.0; 3]],
        triangles: vec![[0, 1, 2]],
    };
    let geometry = Geometry {
        mesh: &bad_mesh,
        volume: &box_volume,
    };
    let err =
        super::gltf::write_glb(&castle(), &options, &Textures::new(), None, &geometry).unwrap_err();
    assert!(
        matches!(err, ExportError::BadMesh { kind: "box", .. }),
        "{err}"
    );
}
