//! The medieval library (`library/` at the repository root, §7.2.2): each program runs alone
//! with its defaults, gives exact terminal counts, and every terminal mesh is closed.

use std::path::{Path, PathBuf};

use vsg::RunOptions;
use vsg::shape::{Primitive, ShapeType, Tessellation};
use vsg::stats::Stats;
use vsg::tree::Solid;

#[path = "support/dir.rs"]
mod dir;
use dir::Dir;

fn library() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../library")
}

fn run(file: &str, overrides: &[(&str, f64)]) -> (vsg::Model, Stats) {
    let src = std::fs::read_to_string(library().join(file)).unwrap();
    let options = RunOptions {
        overrides: overrides.iter().map(|(n, v)| (n.to_string(), *v)).collect(),
        ..Default::default()
    };
    let model = vsg::run_with(file, &src, &options, &mut Dir(library()))
        .unwrap_or_else(|e| panic!("{}", e.render(file, &src)));
    let tess = Tessellation::default();
    for (i, n) in model.nodes.iter().enumerate() {
        if n.is_leaf() {
            let solid = model.solid(i as u32).expect("every terminal has a solid");
            assert!(
                solid.mesh(&tess).is_closed_oriented(),
                "{file}: terminal {i} ('{}') is not closed",
                model.symbol(n)
            );
        }
    }
    let stats = Stats::of(&model, &tess);
    (model, stats)
}

fn counts(s: &Stats) -> (usize, usize, usize) {
    (s.terminals, s.visible_terminals, s.void_terminals)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-6 * b.abs().max(1.0)
}

#[test]
fn round_tower() {
    // 4 storeys: 4 floors + 4 rooms inside; per storey 2 masonry bands and 8 slits between 8
    // masonry sectors in the wall; the roof.
    let (_, s) = run("round_tower.vsg", &[]);
    assert_eq!(counts(&s), (81, 45, 36));
    assert_eq!(s.by_symbol["arrowSlit"], 32);
    assert_eq!(s.by_symbol["floor"], 4);
    assert_eq!(s.by_symbol["masonry"], 40);
    let (_, s) = run("round_tower.vsg", &[("floors", 3.0), ("slits", 6.0)]);
    assert_eq!(s.by_symbol["arrowSlit"], 18);
    assert_eq!(s.by_symbol["room"], 3);
}

#[test]
fn solid_tower() {
    // A fill core inside the wall ring, and the roof: no storeys, no slits.
    let (_, s) = run("solid_tower.vsg", &[]);
    assert_eq!(counts(&s), (3, 3, 0));
    assert_eq!(s.by_symbol["fill"], 1);
    assert_eq!(s.by_symbol["masonry"], 1);
    let pi = std::f64::consts::PI;
    // The shaft is the whole cylinder π r² h: core and ring add up to it.
    let shaft = s.volume.by_symbol["fill"] + s.volume.by_symbol["masonry"];
    assert!(close(shaft, pi * 9.0 * 20.0), "{shaft}");
    assert!(close(
        s.volume.by_symbol["roof"],
        pi * 3.4 * 3.4 * 4.2 / 3.0
    ));
    let (_, s) = run("solid_tower.vsg", &[("radius", 2.0), ("wall", 0.5)]);
    assert!(close(s.volume.by_symbol["fill"], pi * 1.5 * 1.5 * 20.0));
}

#[test]
fn square_tower() {
    let (_, s) = run("square_tower.vsg", &[]);
    // Body: 2 side walls, 5 x (floor + room), 2 faces x 5 x (2 masonry + 3 window band);
    // top: 2 x (4 merlons + 4 crenels of 2) + 2 x (3 + 3 x 2) + walk + air.
    assert_eq!(counts(&s), (106, 76, 30));
    assert_eq!(s.by_symbol["window"], 10);
    assert_eq!(s.by_symbol["crenelGap"], 14);
    assert!(close(s.volume.total, 8.0 * 20.0 * 8.0));
}

#[test]
fn curtain_wall() {
    let (_, s) = run("curtain_wall.vsg", &[]);
    // Body, 8 merlons + 8 crenels of 2, walk + air.
    assert_eq!(counts(&s), (27, 18, 9));
    assert_eq!(s.by_symbol["crenelGap"], 8);
    assert!(close(s.volume.total, 20.0 * 10.0 * 2.5));
    let (_, s) = run("curtain_wall.vsg", &[("length", 40.0)]);
    assert_eq!(s.by_symbol["crenelGap"], 17);
}

#[test]
fn keep() {
    let (_, s) = run("keep.vsg", &[]);
    // 2 side walls, 3 x (floor + room), 2 façades x 3 floors x (2 + 4 windows x 3), 2 roofs.
    assert_eq!(counts(&s), (94, 91, 3));
    assert_eq!(s.by_symbol["window"], 24);
    let ramp = Primitive::new(ShapeType::Ramp, &[10.0, 7.0, 16.0])
        .unwrap()
        .volume();
    assert!(close(s.volume.total, 20.0 * 24.0 * 16.0 + 2.0 * ramp));
    let (_, s) = run("keep.vsg", &[("windows", 6.0)]);
    assert_eq!(s.by_symbol["window"], 36);
}

#[test]
fn gothic_window() {
    let (model, s) = run("gothic_window.vsg", &[]);
    // 2 masonry rows, jambs (2 masonry + glass), arch zone (2 masonry, 2 spandrels, arch glass).
    assert_eq!(counts(&s), (10, 10, 0));
    assert_eq!(s.by_symbol["spandrel"], 2);
    assert_eq!(s.by_symbol["archGlass"], 1);
    // Spandrels and the pointed light between them fill the arch zone exactly, so the panel's
    // volume is conserved by the Booleans.
    assert!(close(s.volume.total, 4.0 * 7.0 * 0.8));
    let uniques = (0..model.nodes.len() as u32)
        .filter(|&i| matches!(model.solid(i), Some(Solid::Unique(..))))
        .count();
    assert_eq!(uniques, 3);
    // v < w/2 is not a pointed arch: refused.
    let src = std::fs::read_to_string(library().join("gothic_window.vsg")).unwrap();
    let options = RunOptions {
        overrides: vec![("v".into(), 0.5)],
        ..Default::default()
    };
    let e = vsg::run(&src, &options).unwrap_err().render("g.vsg", &src);
    assert!(e.contains("no rule for 'archBay' applies"), "{e}");
}

#[test]
fn gatehouse() {
    let (_, s) = run("gatehouse.vsg", &[]);
    // Gate masonry (one unique shape); top: 2 parapets x (6 merlons + 6 crenels of 2), walk,
    // air; two imported towers of 3 storeys: 6 inside + 3 x (2 + 16) in the wall + roof.
    assert_eq!(counts(&s), (161, 94, 67));
    assert_eq!(s.by_symbol["gateMasonry"], 1);
    assert_eq!(s.by_symbol["tower.arrowSlit"], 48);
    assert_eq!(s.by_symbol["tower.roof"], 2);
    // The block minus a 4 x 3 passage and the half disc of its arch, 8 deep.
    let cylinder = Primitive::new(ShapeType::Cylinder, &[2.0, 1.0])
        .unwrap()
        .mesh(&Tessellation::default())
        .signed_volume();
    let passage = (4.0 * 3.0 + cylinder / 2.0) * 8.0;
    let gate = s.volume.by_symbol["gateMasonry"];
    assert!(close(gate, 12.0 * 9.4 * 8.0 - passage), "{gate}");
    // The towers' floats are reachable from outside.
    let (_, s) = run("gatehouse.vsg", &[("tower.slits", 4.0)]);
    assert_eq!(s.by_symbol["tower.arrowSlit"], 24);
}
