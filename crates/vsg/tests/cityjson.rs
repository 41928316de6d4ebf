//! The CityJSON 2.0 writer (issue 24; Sui 2011 §7.1.3's semantic tree as city objects and
//! semantic surfaces), checked on the file it writes: counts of parts, solids, surfaces and
//! vertices, volumes and orientation from the file's own vertices, the building–part links,
//! the placement, and the official validators: cjval (the CityJSON validator, a Rust library,
//! a dev-dependency) must find no error and no warning, and cjio (PyPI, installed on first use
//! into `tools/cjio/.venv` from `tools/cjio/requirements.txt`) must load the file and count its
//! city objects. Without Python 3 and its venv module the cjio checks skip with a message,
//! unless `CI` is set.

use std::collections::BTreeMap;

use nalgebra::{Isometry3, Vector3};
use vsg::export::semantics::{Attribute, Frame, Heritage, Part, Placement};
use vsg::export::{ExportError, ExportOptions, to_cityjson};
use vsg::shape::{Primitive, ShapeType};
use vsg::tree::{Appearance, Model, NodeState};

// ---------------------------------------------------------------------------------------------
// Models built by hand, child group by child group, as the interpreter builds them.

#[path = "support/tree.rs"]
mod tree;
use tree::{Tree, at};

/// A primitive as the children's `Option`, so that shapeless nodes (`None`) sit beside them.
fn prim(kind: ShapeType, params: &[f64]) -> Option<Primitive> {
    Some(tree::prim(kind, params))
}

use NodeState::{NonTerminal, Terminal, VoidTerminal};

/// A block of masonry (4 × 3 × 2 units, standing on y = 0, 2400 kg/m³) under a roof slab
/// (4 × 1 × 2), as one part `block`.
fn block() -> Tree {
    let mut t = Tree::new("Castle");
    t.0.appearances.push(Appearance {
        density: Some(2400.0),
        ..Appearance::default()
    });
    let part = t.children(0, &[("block", NonTerminal, None, at(0.0, 0.0, 0.0), 0)]);
    t.children(
        part,
        &[
            (
                "block.masonry",
                Terminal,
                prim(ShapeType::Box, &[4.0, 3.0, 2.0]),
                at(0.0, 1.5, 0.0),
                1,
            ),
            (
                "block.roof",
                Terminal,
                prim(ShapeType::Box, &[4.0, 1.0, 2.0]),
                at(0.0, 3.5, 0.0),
                0,
            ),
        ],
    );
    t
}

/// A small castle of four structures: a keep with masonry, a gable roof, two windows, a door
/// and a void room; a round tower with a conic roof and floor slabs; a curtain with a wall
/// walk and a crenel; and a ruin of void terminals only.
fn castle() -> Tree {
    let mut t = Tree::new("Castle");
    let s = t.children(
        0,
        &[
            ("keep", NonTerminal, None, at(0.0, 0.0, 0.0), 0),
            ("tower", NonTerminal, None, at(12.0, 0.0, 3.0), 0),
            ("curtain", NonTerminal, None, at(6.0, 0.0, -6.0), 0),
            ("ruin", NonTerminal, None, at(-9.0, 0.0, 0.0), 0),
        ],
    );
    let turned = |x: f64, y: f64, z: f64, a: f64| {
        Isometry3::new(Vector3::new(x, y, z), Vector3::new(0.0, a, 0.0))
    };
    let half = std::f64::consts::PI;
    t.children(
        s,
        &[
            (
                "keep.masonry",
                Terminal,
                prim(ShapeType::Box, &[8.0, 10.0, 6.0]),
                at(0.0, 5.0, 0.0),
                0,
            ),
            (
                "keep.roof",
                Terminal,
                prim(ShapeType::Ramp, &[4.0, 3.0, 6.0]),
                at(-2.0, 11.5, 0.0),
                0,
            ),
            (
                "keep.roof",
                Terminal,
                prim(ShapeType::Ramp, &[4.0, 3.0, 6.0]),
                turned(2.0, 11.5, 0.0, half),
                0,
            ),
            (
                "keep.window",
                Terminal,
                prim(ShapeType::Box, &[1.0, 1.5, 0.2]),
                at(-2.0, 6.0, 3.1),
                0,
            ),
            (
                "keep.window",
                Terminal,
                prim(ShapeType::Box, &[1.0, 1.5, 0.2]),
                at(2.0, 6.0, 3.1),
                0,
            ),
            (
                "keep.door",
                Terminal,
                prim(ShapeType::Box, &[1.4, 2.4, 0.2]),
                at(0.0, 1.2, 3.1),
                0,
            ),
            (
                "keep.room",
                VoidTerminal,
                prim(ShapeType::Box, &[6.0, 8.0, 4.0]),
                at(0.0, 5.0, 0.0),
                0,
            ),
        ],
    );
    t.children(
        s + 1,
        &[
            (
                "tower.masonry",
                Terminal,
                prim(ShapeType::ExtrudedRing, &[3.0, 12.0, 2.0]),
                at(0.0, 6.0, 0.0),
                0,
            ),
            (
                "tower.floor",
                Terminal,
                prim(ShapeType::Cylinder, &[2.0, 0.3]),
                at(0.0, 4.15, 0.0),
                0,
            ),
            (
                "tower.roof",
                Terminal,
                prim(ShapeType::Cone, &[3.4, 5.0]),
                at(0.0, 14.5, 0.0),
                0,
            ),
        ],
    );
    t.children(
        s + 2,
        &[
            (
                "wallStone",
                Terminal,
                prim(ShapeType::Box, &[10.0, 6.0, 2.0]),
                at(0.0, 3.0, 0.0),
                0,
            ),
            (
                "curtainWalk",
                Terminal,
                prim(ShapeType::Box, &[10.0, 0.2, 1.4]),
                at(0.0, 6.1, 0.3),
                0,
            ),
            (
                "wallStone",
                Terminal,
                prim(ShapeType::Box, &[10.0, 1.0, 0.6]),
                at(0.0, 6.5, -0.7),
                0,
            ),
            (
                "curtainCrenel",
                VoidTerminal,
                prim(ShapeType::Box, &[1.0, 0.8, 0.6]),
                at(0.0, 7.4, -0.7),
                0,
            ),
        ],
    );
    t.children(
        s + 3,
        &[(
            "ruin.room",
            VoidTerminal,
            prim(ShapeType::Box, &[3.0; 3]),
            at(0.0, 1.5, 0.0),
            0,
        )],
    );
    t
}

// ---------------------------------------------------------------------------------------------
// Reading the file back.

#[path = "support/cityjson_read.rs"]
mod read;
use read::{
    assert_valid, assert_vertices_unique_and_used, heritage, is_closed, signed_volume, solids,
    surface_counts, vertices, write,
};

// ---------------------------------------------------------------------------------------------
// The validators.

#[path = "support/cjio.rs"]
mod cjio;
#[path = "support/cjval.rs"]
mod cjval_check;
#[path = "support/venv.rs"]
mod venv;
use cjval_check::assert_cjval_valid;

// ---------------------------------------------------------------------------------------------
// The tests.

#[test]
fn a_block_under_a_roof_has_exact_counts_volumes_and_surfaces() {
    let mut h = heritage("Block");
    h.frame.metres_per_unit = 0.5;
    let (text, doc) = write(&block().0, &h);
    let objects = doc["CityObjects"].as_object().expect("objects");
    assert_eq!(objects.len(), 2);
    let part = &objects["Block-block"];
    assert_eq!(part["type"], "BuildingPart");
    assert_eq!(part["parents"], serde_json::json!(["Block"]));
    assert_eq!(
        objects["Block"]["children"],
        serde_json::json!(["Block-block"])
    );
    // 8 corners of the masonry and the 4 top corners of the roof: the 4 they share are one.
    assert_eq!(doc["vertices"].as_array().map(Vec::len), Some(12));
    assert_vertices_unique_and_used(&doc);
    assert_eq!(
        doc["transform"]["scale"],
        serde_json::json!([0.001, 0.001, 0.001])
    );
    // Model x ∈ [−2, 2], z ∈ [−1, 1], y ∈ [0, 4] units of 0.5 m: east, north, up.
    assert_eq!(
        doc["metadata"]["geographicalExtent"],
        serde_json::json!([-1.0, -0.5, 0.0, 1.0, 0.5, 2.0])
    );
    assert_eq!(
        doc["transform"]["translate"],
        serde_json::json!([-1.0, -0.5, 0.0])
    );
    assert_eq!(doc["metadata"]["title"], "Block");
    assert!(doc["metadata"].get("referenceSystem").is_none());

    let geometry = part["geometry"].as_array().expect("geometry");
    assert_eq!(geometry.len(), 1, "no windows: LoD 2 only");
    assert_eq!(geometry[0]["lod"], "2");
    let v = vertices(&doc);
    let solids = solids(&geometry[0]);
    assert_eq!(solids.len(), 2);
    let expected = [4.0 * 3.0 * 2.0, 4.0 * 1.0 * 2.0].map(|units| units * 0.125);
    for ((shell, _), volume) in solids.iter().zip(expected) {
        assert_eq!(shell.len(), 6, "a box's six faces, each one quad");
        assert!(shell.iter().all(|s| s.len() == 1 && s[0].len() == 4));
        assert!(is_closed(shell));
        let from_file = signed_volume(shell, &v);
        assert!(
            ((from_file - volume) / volume).abs() < 1e-6,
            "{from_file} m³ in the file, {volume} m³ from the primitive"
        );
    }
    let counts = surface_counts(&geometry[0]);
    let expected: BTreeMap<String, usize> = [
        ("WallSurface", 8),
        ("GroundSurface", 1),
        ("OuterFloorSurface", 1),
        ("RoofSurface", 1),
        ("OuterCeilingSurface", 1),
    ]
    .map(|(k, n)| (k.to_string(), n))
    .into();
    assert_eq!(counts, expected);
    let surfaces = geometry[0]["semantics"]["surfaces"]
        .as_array()
        .expect("surfaces");
    assert_eq!(surfaces.len(), 6, "one per type and terminal symbol");
    for s in surfaces {
        let class = s["castellan_class"].as_str().expect("a class");
        let symbol = s["vsg_symbol"].as_str().expect("a symbol");
        match symbol {
            "block.masonry" => assert_eq!(class, "wall"),
            "block.roof" => assert_eq!(class, "roof"),
            other => panic!("unexpected symbol {other}"),
        }
    }
    let attributes = &part["attributes"];
    assert_eq!(attributes["castellan_kind"], "block");
    assert_eq!(attributes["terminals"], 2);
    assert!((attributes["volume_m3"].as_f64().expect("volume") - 4.0).abs() < 1e-12);
    assert!((attributes["mass_kg"].as_f64().expect("mass") - 2400.0 * 3.0).abs() < 1e-9);
    assert_valid("block", &text, &doc);
}

#[test]
fn the_castle_has_its_parts_windows_in_lod3_only_and_outward_solids() {
    let model = castle().0;
    let parts = vec![
        Part {
            more_nodes: Vec::new(),
            node: 1,
            name: "keep".into(),
            kind: "keep".into(),
            attributes: BTreeMap::from([
                ("label".to_string(), Attribute::Text("Donjon".into())),
                ("height_m".to_string(), Attribute::Number(13.0)),
                ("measured".to_string(), Attribute::Flag(true)),
            ]),
        },
        Part {
            more_nodes: Vec::new(),
            node: 2,
            name: "tower 1".into(),
            kind: "tower".into(),
            attributes: BTreeMap::new(),
        },
        Part {
            more_nodes: Vec::new(),
            node: 3,
            name: "curtain".into(),
            kind: "curtain wall".into(),
            attributes: BTreeMap::new(),
        },
        Part {
            more_nodes: Vec::new(),
            node: 4,
            name: "ruin".into(),
            kind: "ruin".into(),
            attributes: BTreeMap::new(),
        },
    ];
    let h = Heritage {
        name: "Château d'essai".into(),
        parts,
        frame: Frame::default(),
        attributes: BTreeMap::from([("source".to_string(), Attribute::Text("plan.png".into()))]),
    };
    let (text, doc) = write(&model, &h);
    let objects = doc["CityObjects"].as_object().expect("objects");
    assert_eq!(objects.len(), 5);
    let building = &objects["Ch_teau_d_essai"];
    assert_eq!(building["attributes"]["source"], "plan.png");
    let ids = [
        "Ch_teau_d_essai-keep",
        "Ch_teau_d_essai-tower_1",
        "Ch_teau_d_essai-curtain",
        "Ch_teau_d_essai-ruin",
    ];
    assert_eq!(building["children"], serde_json::json!(ids));
    for id in ids {
        assert_eq!(
            objects[id]["parents"],
            serde_json::json!(["Ch_teau_d_essai"])
        );
    }
    let keep = &objects[ids[0]];
    assert_eq!(keep["attributes"]["label"], "Donjon");
    assert_eq!(keep["attributes"]["height_m"], 13.0);
    assert_eq!(keep["attributes"]["measured"], true);
    assert_eq!(keep["attributes"]["castellan_kind"], "keep");
    assert_eq!(keep["attributes"]["terminals"], 6);
    assert_eq!(
        objects[ids[2]]["attributes"]["castellan_kind"],
        "curtain wall"
    );
    // The ruin has no drawn terminal: no geometry.
    assert!(objects[ids[3]].get("geometry").is_none());

    // The keep: LoD 2 without the windows and the door, LoD 3 with them.
    let geometry = keep["geometry"].as_array().expect("keep geometry");
    assert_eq!(geometry.len(), 2);
    assert_eq!(
        (&geometry[0]["lod"], &geometry[1]["lod"]),
        (&"2".into(), &"3".into())
    );
    let (lod2, lod3) = (surface_counts(&geometry[0]), surface_counts(&geometry[1]));
    assert_eq!(solids(&geometry[0]).len(), 3);
    assert_eq!(solids(&geometry[1]).len(), 6);
    assert!(!lod2.contains_key("Window") && !lod2.contains_key("Door"));
    assert_eq!(lod3.get("Window"), Some(&12), "two windows of six faces");
    assert_eq!(lod3.get("Door"), Some(&6));
    for kind in ["WallSurface", "RoofSurface", "GroundSurface"] {
        assert_eq!(lod2.get(kind), lod3.get(kind), "{kind}");
    }
    // The masonry's 4 sides and each ramp's 2 gable triangles and 1 back face are walls; each
    // ramp's slope is a roof; the masonry's top under the roof is a ledge, the ramps' bottoms
    // the eaves' undersides.
    assert_eq!(lod2.get("WallSurface"), Some(&(4 + 2 * 3)));
    assert_eq!(lod2.get("RoofSurface"), Some(&2));
    assert_eq!(lod2.get("GroundSurface"), Some(&1));
    assert_eq!(lod2.get("OuterFloorSurface"), Some(&1));
    assert_eq!(lod2.get("OuterCeilingSurface"), Some(&2));
    // The tower's floor slab: roofed, so an interior floor and ceiling.
    let tower = surface_counts(&objects[ids[1]]["geometry"][0]);
    assert_eq!(tower.get("FloorSurface"), Some(&1));
    assert_eq!(tower.get("CeilingSurface"), Some(&1));
    assert_eq!(tower.get("RoofSurface"), Some(&32), "the cone's 32 sides");
    // The curtain has no roof: its walk is an outer floor, the wall tops are its roofs.
    let curtain = surface_counts(&objects[ids[2]]["geometry"][0]);
    assert_eq!(curtain.get("OuterFloorSurface"), Some(&1));
    assert_eq!(curtain.get("RoofSurface"), Some(&2));

    // Every solid of every geometry: closed, outward (positive volume), the primitive's volume
    // to the grid's precision.
    let v = vertices(&doc);
    let mut count = 0;
    for id in ids {
        for g in objects[id]["geometry"].as_array().into_iter().flatten() {
            for (shell, _) in solids(g) {
                assert!(is_closed(&shell), "{id}: an open or misoriented shell");
                let volume = signed_volume(&shell, &v);
                assert!(volume > 0.0, "{id}: a shell facing inwards ({volume} m³)");
                count += 1;
            }
        }
    }
    // LoD 2: 3 keep + 3 tower + 3 curtain; LoD 3: 6 keep.
    assert_eq!(count, 15);
    assert_vertices_unique_and_used(&doc);
    assert_valid("castle", &text, &doc);
}

#[test]
fn a_placed_model_has_its_reference_system_and_map_coordinates() {
    let mut h = heritage("Placed");
    h.frame = Frame {
        metres_per_unit: 1.0,
        placement: Some(Placement {
            origin: [700_000.0, 6_600_000.0, 80.0],
            epsg: 2154,
            rotation_deg: 90.0,
        }),
    };
    let (text, doc) = write(&block().0, &h);
    assert_eq!(
        doc["metadata"]["referenceSystem"],
        "https://www.opengis.net/def/crs/EPSG/0/2154"
    );
    // Turned 90° clockwise: the model's x (±2) runs south, its −z (±1) east.
    let extent: Vec<f64> =
        serde_json::from_value(doc["metadata"]["geographicalExtent"].clone()).expect("extent");
    let expected = [699_999.0, 6_599_998.0, 80.0, 700_001.0, 6_600_002.0, 84.0];
    for (a, b) in extent.iter().zip(expected) {
        assert!((a - b).abs() < 1e-6, "{extent:?} vs {expected:?}");
    }
    let translate: Vec<f64> =
        serde_json::from_value(doc["transform"]["translate"].clone()).expect("translate");
    assert!((translate[0] - 699_999.0).abs() < 1e-6 && (translate[2] - 80.0).abs() < 1e-9);
    // Every vertex is a corner of the boxes where the frame puts it, to the millimetre.
    let corners: Vec<[f64; 3]> = [(0.0, 3.0), (3.0, 4.0)]
        .iter()
        .flat_map(|&(y0, y1)| {
            [-2.0, 2.0].into_iter().flat_map(move |x| {
                [y0, y1]
                    .into_iter()
                    .flat_map(move |y| [-1.0, 1.0].map(|z| h.frame.to_world([x, y, z])))
            })
        })
        .collect();
    for p in vertices(&doc) {
        assert!(
            corners
                .iter()
                .any(|c| (0..3).all(|k| (c[k] - p[k]).abs() <= 0.0005 + 1e-9)),
            "{p:?} is no corner"
        );
    }
    // A rotation keeps the shells outward.
    let v = vertices(&doc);
    for (shell, _) in solids(&doc["CityObjects"]["Placed-block"]["geometry"][0]) {
        assert!(signed_volume(&shell, &v) > 0.0);
    }
    assert_valid("placed", &text, &doc);
}

#[test]
fn every_primitive_type_is_a_closed_outward_solid() {
    use ShapeType::*;
    let samples = [
        (Box, vec![4.0, 3.0, 2.0]),
        (Ramp, vec![4.0, 3.0, 2.0]),
        (RampFrustum, vec![4.0, 3.0, 2.0, 1.5]),
        (Parallelepiped, vec![4.0, 3.0, 2.0, 0.5, 0.3, -0.4]),
        (Cylinder, vec![2.0, 3.0]),
        (ExtrudedRing, vec![2.0, 3.0, 1.2]),
        (ExtrudedFan, vec![2.0, 3.0, 2.0]),
        (CylindricalSector, vec![2.0, 3.0, 1.2, 2.0]),
        (Cone, vec![2.0, 3.0]),
        (ConicFrustum, vec![2.0, 3.0, 1.0]),
        (ConicRing, vec![2.0, 3.0, 1.0, 1.5]),
        (ConicFan, vec![2.0, 3.0, 2.0]),
        (ConicSector, vec![2.0, 3.0, 2.0, 1.0, 0.8]),
        (Tetrahedron, vec![3.0, 2.0, 2.5, 1.2]),
        (TetrahedronFrustum, vec![3.0, 2.0, 2.5, 1.2, 1.5]),
        (TetrahedronSector, vec![3.0, 2.0, 2.5, 1.2, 1.5, 1.0]),
        (Sphere, vec![2.0]),
        (SphericalSector, vec![2.0, 2.0, 1.2]),
    ];
    let mut t = Tree::new("Zoo");
    let kids: Vec<_> = samples
        .iter()
        .enumerate()
        .map(|(i, (kind, params))| {
            let turn = Isometry3::new(
                Vector3::new(i as f64 * 5.0, 2.0, 0.0),
                Vector3::new(0.3, 0.2 * i as f64, 0.1),
            );
            (kind.name(), Terminal, prim(*kind, params), turn, 0)
        })
        .collect();
    t.children(0, &kids);
    let (text, doc) = write(&t.0, &heritage("Zoo"));
    let objects = doc["CityObjects"].as_object().expect("objects");
    assert_eq!(objects.len(), 1 + samples.len());
    let v = vertices(&doc);
    for (id, object) in objects {
        if object["type"] == "Building" {
            continue;
        }
        let solids = solids(&object["geometry"][0]);
        assert_eq!(solids.len(), 1, "{id}");
        let (shell, _) = &solids[0];
        assert!(is_closed(shell), "{id}");
        let volume = signed_volume(shell, &v);
        let expected = object["attributes"]["volume_m3"].as_f64().expect("volume");
        // Meshes approximate curved primitives, and the grid moves vertices by ≤ 0.5 mm.
        assert!(
            volume > 0.0 && ((volume - expected) / expected).abs() < 0.05,
            "{id}: {volume} m³ in the file, {expected} m³ exact"
        );
    }
    assert_vertices_unique_and_used(&doc);
    assert_valid("all-primitives", &text, &doc);
}

#[test]
fn non_finite_coordinates_are_an_error() {
    let mut model = block().0;
    model.nodes[2].world.translation.vector.x = f64::NAN;
    let err = to_cityjson(&model, &heritage("Bad"), &ExportOptions::default());
    assert!(matches!(err, Err(ExportError::NotFinite { .. })), "{err:?}");
    let mut h = heritage("Bad");
    h.frame.metres_per_unit = f64::INFINITY;
    let err = to_cityjson(&block().0, &h, &ExportOptions::default());
    assert!(matches!(err, Err(ExportError::NotFinite { .. })), "{err:?}");
    // Finite but too far apart for integer millimetres in a double.
    let mut model = block().0;
    model.nodes[2].world.translation.vector.x = 1e14;
    let err = to_cityjson(&model, &heritage("Far"), &ExportOptions::default());
    assert!(matches!(err, Err(ExportError::NotFinite { .. })), "{err:?}");
}

#[test]
fn an_empty_model_is_a_valid_building_without_parts() {
    let (text, doc) = write(&Model::default(), &heritage(""));
    let objects = doc["CityObjects"].as_object().expect("objects");
    assert_eq!(objects.len(), 1);
    assert_eq!(objects["building"]["type"], "Building");
    assert_eq!(doc["vertices"], serde_json::json!([]));
    assert_cjval_valid("empty", &text);
}
