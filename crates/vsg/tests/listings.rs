//! The dissertation's listings "VSG rules 7.1" and "VSG rules 7.3" run verbatim, with counts and
//! exact volumes worked out by hand from the rules (see the comments).

use std::f64::consts::PI;

use vsg::shape::{ShapeType, Tessellation};
use vsg::stats::Stats;
use vsg::tree::NodeState;

fn run(name: &str) -> (vsg::Model, Stats) {
    let path = format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    let src = std::fs::read_to_string(&path).unwrap();
    let model = vsg::run(&src, &vsg::RunOptions::default())
        .unwrap_or_else(|e| panic!("{}", e.render(&path, &src)));
    let stats = Stats::of(&model, &Tessellation::default());
    (model, stats)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1.0)
}

#[test]
fn rules_7_1_counts() {
    let (_, s) = run("rules_7_1.vsg");
    // 5 floors x (2 brick bands + 4 bricks and 3 windows in the window band), the three plain
    // walls, and 5 storeys of interior space + floor slab.
    assert_eq!(s.by_symbol["brickWall"], 30);
    assert_eq!(s.by_symbol["window"], 15);
    assert_eq!(s.by_symbol["interiorSpace"], 5);
    assert_eq!(s.by_symbol["floorRoof"], 5);
    assert_eq!(
        (
            s.by_symbol["wallN"],
            s.by_symbol["wallW"],
            s.by_symbol["wallE"]
        ),
        (1, 1, 1)
    );
    assert_eq!(s.terminals, 58);
    assert_eq!(s.void_terminals, 5);
    assert_eq!(s.visible_terminals, 53);
    // Axiom, building, midBuilding, walls, interior, 5 floorS, 5 midWallS.
    assert_eq!(s.nonterminals, 15);
}

#[test]
fn rules_7_1_volumes_add_up_to_the_mass_model() {
    let (_, s) = run("rules_7_1.vsg");
    assert!(
        close(s.volume.total, 5.0 * 10.0 * 3.0),
        "{}",
        s.volume.total
    );
    assert!(close(s.volume.by_symbol["window"], 15.0 * 1.0 * 1.0 * 0.1));
    assert!(close(
        s.volume.by_symbol["brickWall"],
        5.0 * 10.0 * 0.1 - 1.5
    ));
    assert!(close(
        s.volume.by_symbol["interiorSpace"],
        5.0 * 4.8 * 1.9 * 2.8
    ));
    assert!(close(s.visible_volume, 150.0 - 5.0 * 4.8 * 1.9 * 2.8));
}

#[test]
fn rules_7_1_window_band_follows_figure_7_1() {
    let (m, _) = run("rules_7_1.vsg");
    let band = m
        .nodes
        .iter()
        .position(|n| m.symbol(n) == "midWallS")
        .unwrap();
    let children: Vec<&str> = m.nodes[band]
        .children()
        .map(|c| m.symbol(&m.nodes[c as usize]))
        .collect();
    assert_eq!(
        children,
        [
            "brickWall",
            "window",
            "brickWall",
            "window",
            "brickWall",
            "window",
            "brickWall"
        ]
    );
    let xs: Vec<f64> = m.nodes[band]
        .children()
        .map(|c| m.nodes[c as usize].local.translation.x)
        .collect();
    let want = [-2.25, -1.5, -0.75, 0.0, 0.75, 1.5, 2.25];
    for (x, w) in xs.iter().zip(want) {
        assert!(close(*x, w), "{xs:?}");
    }
}

#[test]
fn rules_7_1_window_appearance_is_blue_and_half_transparent() {
    let (m, _) = run("rules_7_1.vsg");
    let w = m.nodes.iter().find(|n| m.symbol(n) == "window").unwrap();
    let a = m.appearance(w);
    assert_eq!(a.color, [0.3, 0.3, 0.7]);
    assert_eq!(a.transparency, 0.5);
    assert_eq!(w.state, NodeState::Terminal);
}

#[test]
fn rules_7_3_counts() {
    let (_, s) = run("rules_7_3.vsg");
    // Per window band: 40 of wall, then window 18 / wall 30 from the offset, the last window
    // cut to 16: 4 windows and 4 wall pieces; two bands.
    assert_eq!(s.by_symbol["window"], 8);
    assert_eq!(s.by_symbol["brickWall"], 2 * 2 + 2 * 4);
    assert_eq!(s.terminals, 29);
    // Tower interiors, windows and the keep interior are void.
    assert_eq!(s.void_terminals, 2 + 8 + 1);
    assert_eq!(s.nonterminals, 10);
}

#[test]
fn rules_7_3_volumes() {
    let (_, s) = run("rules_7_3.vsg");
    let tower = PI * 32.0 * 32.0 * 210.0;
    let keep = 104.0 * 175.0 * 200.0;
    assert!(
        close(s.volume.total, 2.0 * tower + keep),
        "{}",
        s.volume.total
    );
    assert!(close(
        s.volume.by_symbol["tower1Wall"],
        PI * (32.0 * 32.0 - 24.0 * 24.0) * 210.0
    ));
    assert!(close(
        s.volume.by_symbol["window"],
        (18.0 * 3.0 + 16.0) * 8.0 * (26.0 + 30.0)
    ));
}

#[test]
fn rules_7_3_places_the_keep_and_towers_as_table_7_2_says() {
    let (m, _) = run("rules_7_3.vsg");
    let find = |s: &str| m.nodes.iter().find(|n| m.symbol(n) == s).unwrap();
    let t = find("tower1").world.translation.vector;
    assert_eq!([t.x, t.y, t.z], [365.0, 105.0, 233.0]);
    let keep = find("keep1");
    assert_eq!(keep.shape.unwrap().kind, ShapeType::Box);
    assert!(close(keep.world.rotation.angle(), 0.05));
    let wall = find("tower1Wall").shape.unwrap();
    assert_eq!(wall.kind, ShapeType::ExtrudedRing);
    assert_eq!(wall.params(), &[32.0, 210.0, 24.0]);
}
