//! The CityJSON writer (issue 24) on programs a user runs: a castle written as the Coucy demo
//! writes its `model.vsg`, the repository's example castle and the library's programs, each
//! read back (unique vertices, outward solids) and passed through both validators (cjval and
//! cjio; see `tests/cityjson.rs` for when cjio skips).

use std::path::Path;
use std::time::Instant;

use serde_json::Value;
use vsg::export::semantics::Placement;
use vsg::export::{ExportOptions, to_cityjson};
use vsg::tree::Model;

#[path = "support/cityjson_read.rs"]
mod read;
use read::{
    assert_outward, assert_valid, assert_vertices_unique_and_used, heritage, surface_counts, write,
};

#[path = "support/cjio.rs"]
mod cjio;
#[path = "support/cjval.rs"]
mod cjval_check;
#[path = "support/venv.rs"]
mod venv;

#[path = "support/dir.rs"]
mod dir;
use dir::Dir;

fn run(name: &str, src: &str) -> Model {
    let library = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../library");
    vsg::run_with(name, src, &vsg::RunOptions::default(), &mut Dir(library))
        .unwrap_or_else(|e| panic!("{}", e.render(name, src)))
}

/// A castle like the Coucy demo's `model.vsg` (`castellan demo`): the library's round towers,
/// keeps with windows and gatehouse imported once per structure with their own parameters,
/// and curtain runs and room blocks as the demo writes them, each a child of the axiom.
const COUCY_LIKE: &str = r#"
import "round_tower.vsg" as tower1 (radius = 11.5, height = 35.7, wall = 4.9, floors = 9, floorT = 0.3, slits = 8, slitH = 1.4, roofH = 16.1, overhang = 0.4);
import "round_tower.vsg" as tower2 (radius = 11.5, height = 35.7, wall = 4.7, floors = 9, floorT = 0.3, slits = 8, slitH = 1.4, roofH = 16.1, overhang = 0.4);
import "round_tower.vsg" as keep1 (radius = 16.2, height = 53.5, wall = 6.8, floors = 13, floorT = 0.3, slits = 8, slitH = 1.4, roofH = 22.6, overhang = 0.4);
import "keep.vsg" as chapel1 (width = 30.1, depth = 21.5, height = 8, wall = 4.3, floorH = 4, floorT = 0.4, windows = 4, windowW = 1.2, windowH = 1.6, sill = 0.8, roofH = 7.5);
import "keep.vsg" as range4 (width = 11.8, depth = 11.2, height = 6, wall = 3.4, floorH = 3, floorT = 0.4, windows = 1, windowW = 1.2, windowH = 1.2, sill = 0.6, roofH = 3.9);
import "gatehouse.vsg" as gate1 ();
float curtainH = 14;
float curtainT = 3;
float curtainParapetH = 1.8;
float curtainMerlon = 1.4;
float curtainWalkT = 0.2;
float roomRoofT = 0.5;
Axiom ::
    T(0, 0, 0) I("box", {1, 1, 1})
    T(60, 0, 0) I("box", {1, 1, 1})
    T(30, 0, 60) I("box", {1, 1, 1})
    T(30, 0, 25) I("box", {1, 1, 1})
    T(85, 0, 40) R(0, 0.4, 0) I("box", {1, 1, 1})
    T(30, 0, -12) I("box", {1, 1, 1})
    T(30, curtainH/2, 0) I("box", {37, curtainH, curtainT})
    T(5, curtainH/2, 30) R(0, 1.2, 0) I("box", {40, curtainH, curtainT})
    T(70, 3, 70) R(0, -0.3, 0) I("box", {12, 6, 9})
    {tower1Site, tower2Site, keep1Site, chapel1Site, range4Site, gate1Site, curtain1, curtain2, range5};
tower1Site :: {tower1.Axiom};
tower2Site :: {tower2.Axiom};
keep1Site :: {keep1.Axiom};
chapel1Site :: {chapel1.Axiom};
range4Site :: {range4.Axiom};
gate1Site :: {gate1.Axiom};
curtain1 :: {curtain};
curtain2 :: {curtain};
range5 :: {roomBlock};
curtain :: split("Y", {~1, curtainParapetH}){wallStone, curtainTop};
curtainTop :: split("Z", {~1, ~4}){curtainParapet, curtainWalkZone};
curtainParapet :: repeat("X", {~curtainMerlon, ~curtainMerlon}){wallStone, curtainCrenel};
curtainCrenel :: split("Y", {~4, ~5}){wallStone, opening};
curtainWalkZone :: split("Y", {curtainWalkT, ~1}){curtainWalk, opening};
curtainWalk :: appearance("color", {0.5, 0.47, 0.42}){j3d.terminal};
roomBlock :: split("Y", {~1, roomRoofT}){wallStone, roof};
opening :: void(){j3d.terminal};
roof :: appearance("color", {0.55, 0.2, 0.15}){j3d.terminal};
wallStone :: appearance("color", {0.76, 0.72, 0.64}, "density", 2200){j3d.terminal};
"#;

#[test]
fn a_coucy_like_castle_is_valid() {
    let model = run("coucy_like.vsg", COUCY_LIKE);
    let mut h = heritage("Coucy-like castle");
    h.frame.placement = Some(Placement {
        origin: [717_000.0, 6_935_000.0, 150.0],
        epsg: 2154,
        rotation_deg: 12.0,
    });
    let start = Instant::now();
    let text = to_cityjson(&model, &h, &ExportOptions::default()).expect("export succeeds");
    let elapsed = start.elapsed();
    let doc: Value = serde_json::from_str(&text).expect("JSON");
    eprintln!(
        "coucy-like: {} bytes, {} vertices, written in {:.3} s (debug build)",
        text.len(),
        doc["vertices"].as_array().map_or(0, Vec::len),
        elapsed.as_secs_f64()
    );
    let objects = doc["CityObjects"].as_object().expect("objects");
    assert_eq!(objects.len(), 1 + 9);
    let part = |name: &str| &objects[&format!("Coucy-like_castle-{name}")];
    // The keeps of the library have windows: LoD 2 and 3; the towers and curtains LoD 2 only.
    for (name, lods) in [
        ("chapel1Site", 2),
        ("range4Site", 2),
        ("tower1Site", 1),
        ("keep1Site", 1),
        ("curtain1", 1),
        ("range5", 1),
    ] {
        assert_eq!(
            part(name)["geometry"].as_array().map(Vec::len),
            Some(lods),
            "{name}"
        );
    }
    let lod3 = surface_counts(&part("chapel1Site")["geometry"][1]);
    assert!(lod3.get("Window").is_some_and(|&n| n > 0), "{lod3:?}");
    let tower = surface_counts(&part("tower1Site")["geometry"][0]);
    for kind in [
        "RoofSurface",
        "WallSurface",
        "GroundSurface",
        "FloorSurface",
    ] {
        assert!(tower.contains_key(kind), "{kind} in {tower:?}");
    }
    let curtain = surface_counts(&part("curtain1")["geometry"][0]);
    assert!(curtain.contains_key("OuterFloorSurface"), "{curtain:?}");
    // Masses from the densities: the curtains' and the room block's stone.
    let mass = part("curtain1")["attributes"]["mass_kg"]
        .as_f64()
        .expect("mass");
    let volume = part("curtain1")["attributes"]["volume_m3"]
        .as_f64()
        .expect("volume");
    assert!(mass > 0.0 && (mass / volume - 2200.0).abs() < 2200.0 * 0.5);
    assert_vertices_unique_and_used(&doc);
    assert_outward("coucy-like", &doc);
    assert_valid("coucy-like", &text, &doc);
}

/// The repository's example castle and the library's programs, run as a user would.
#[test]
fn example_and_library_programs_are_valid() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    for path in [
        "examples/castle.vsg",
        "library/keep.vsg",
        "library/round_tower.vsg",
        "library/gatehouse.vsg",
        "library/curtain_wall.vsg",
    ] {
        let src = std::fs::read_to_string(root.join(path)).expect("the program exists");
        let model = run(path, &src);
        let (text, doc) = write(&model, &heritage(path));
        assert_vertices_unique_and_used(&doc);
        assert_outward(path, &doc);
        assert_valid(path, &text, &doc);
    }
}
