//! Unique shapes (§7.1.2, figure 7.3): `union()`, `intersection()` and `difference()` over the
//! instantiations of a rule give one closed mesh, bound to a terminal successor.

use vsg::RunOptions;
use vsg::shape::{Primitive, ShapeType, Tessellation};
use vsg::stats::Stats;
use vsg::tree::{NodeState, Solid};

fn run(src: &str) -> vsg::Model {
    vsg::run(src, &RunOptions::default()).unwrap_or_else(|e| panic!("{}", e.render("t.vsg", src)))
}

fn error_of(src: &str) -> String {
    vsg::run(src, &RunOptions::default())
        .unwrap_err()
        .render("t.vsg", src)
}

/// Mesh volume of a 1.5 x 1.2 cylinder at the default tessellation, per unit height.
fn disc_area() -> f64 {
    let cyl = Primitive::new(ShapeType::Cylinder, &[1.5, 1.2]).unwrap();
    cyl.mesh(&Tessellation::default()).signed_volume() / 1.2
}

const ARCH: &str = r#"
Axiom :: I("box", {4, 6, 1}){arch};
arch :: I("box",{4,6,1}) R(1.5708,0,0) T(0,1,0) I("cylinder",{1.5,1.2}) difference(){archShape};
archShape :: {j3d.terminal};
"#;

#[test]
fn the_issue_arch_is_a_box_with_a_round_hole() {
    let m = run(ARCH);
    let terminals: Vec<u32> = (0..m.nodes.len() as u32)
        .filter(|&i| m.nodes[i as usize].state == NodeState::Terminal)
        .collect();
    assert_eq!(terminals.len(), 1);
    let Some(Solid::Unique(_, u)) = m.solid(terminals[0]) else {
        panic!("the terminal is not a unique shape");
    };
    assert!(u.mesh.is_closed_oriented());
    let expected = 24.0 - disc_area();
    assert!(
        (u.volume - expected).abs() < 1e-6,
        "{} vs {expected}",
        u.volume
    );
    let s = Stats::of(&m, &Tessellation::default());
    assert!((s.volume.total - expected).abs() < 1e-6);
    assert!((s.volume.by_symbol["archShape"] - expected).abs() < 1e-6);
    assert_eq!(s.triangles, u.mesh.triangles.len());
    // The hole goes through: 2 x 32 rim vertices plus the box's 8 corners at least.
    assert!(u.mesh.positions.len() >= 72);
}

#[test]
fn union_and_intersection_of_two_offset_boxes() {
    let src = |op: &str| {
        format!(
            "Axiom :: I(\"box\",{{2,2,2}}) T(1,0,0) I(\"box\",{{2,2,2}}) {op}(){{j3d.terminal}};"
        )
    };
    for (op, volume) in [("union", 12.0), ("intersection", 4.0), ("difference", 4.0)] {
        let m = run(&src(op));
        let s = Stats::of(&m, &Tessellation::default());
        assert_eq!(s.terminals, 1, "{op}");
        assert!(
            (s.volume.total - volume).abs() < 1e-9,
            "{op}: {}",
            s.volume.total
        );
        let Some(Solid::Unique(_, u)) = m.solid(1) else {
            panic!("{op}: no unique shape");
        };
        assert!(u.mesh.is_closed_oriented(), "{op}");
        assert_eq!(u.op.name(), op);
    }
}

#[test]
fn unique_shape_exports_to_glb_and_obj() {
    let m = run(ARCH);
    let glb = vsg::export::to_glb(&m, &Default::default()).unwrap();
    assert_eq!(&glb[..4], b"glTF");
    let (obj, _) = vsg::export::to_obj(&m, &Default::default(), "m.mtl").unwrap();
    assert!(obj.contains("g archShape_"), "{obj}");
}

#[test]
fn successor_of_a_boolean_must_be_terminal() {
    let src = "Axiom :: I(\"box\",{2,2,2}) I(\"box\",{1,1,3}) difference(){hole};\n\
               hole :: split(\"X\", {1, 1}){a, a};\n\
               a :: {j3d.terminal};";
    let e = error_of(src);
    assert!(
        e.contains("t.vsg:1:57: a unique shape is terminal (§7.1.2), but 'hole'"),
        "{e}"
    );
    let two = "Axiom :: I(\"box\",{2,2,2}) I(\"box\",{1,1,3}) union(){a, b};\na :: {j3d.terminal};\nb :: {j3d.terminal};";
    let e = error_of(two);
    assert!(
        e.contains("the rule has 1 unique shape but 2 successors"),
        "{e}"
    );
}

#[test]
fn a_boolean_needs_shapes_before_it_and_ends_the_geometry() {
    let e = error_of("Axiom :: union() I(\"box\",{1,1,1}){j3d.terminal};");
    assert!(
        e.contains("t.vsg:1:10: union() combines the shapes instantiated before it"),
        "{e}"
    );
    let e = error_of("Axiom :: I(\"box\",{1,1,1}) union() T(1,0,0){j3d.terminal};");
    assert!(
        e.contains("t.vsg:1:35: union() ends the geometry of its rule"),
        "{e}"
    );
}

#[test]
fn a_successor_rule_may_colour_the_unique_shape() {
    let src = "Axiom :: I(\"box\",{2,2,2}) T(0,1,0) I(\"sphere\",{1}) union(){top};\n\
               top :: appearance(\"color\", {1, 0, 0}){j3d.terminal};";
    let m = run(src);
    let leaf = m.terminals().next().unwrap();
    assert_eq!(m.appearance(leaf).color, [1.0, 0.0, 0.0]);
    assert_eq!(m.symbol(leaf), "top");
    let id = m.nodes.iter().position(|n| std::ptr::eq(n, leaf)).unwrap() as u32;
    let Some(Solid::Unique(_, u)) = m.solid(id) else {
        panic!("no unique shape");
    };
    assert!(u.mesh.is_closed_oriented());
    assert!(u.volume > 8.0 && u.volume < 8.0 + 4.0 / 3.0 * std::f64::consts::PI);
}
