//! The structural metadata of a GLB (issue 24), decoded from the file's own bytes as a viewer
//! would: `EXT_structural_metadata`'s two property tables (parts, elements) and every drawn
//! primitive's `EXT_mesh_features` feature IDs, checked against a hand-built castle with known
//! volumes, masses and attributes. The Khronos validator passes such files
//! (`gltf_validator.rs`) but does not read these extensions, so this test is their check.

use std::collections::BTreeMap;

use nalgebra::Isometry3;
use serde_json::Value;
use vsg::export::semantics::{Attribute, Frame, Heritage, Part};
use vsg::export::{ExportOptions, Textures, to_glb, to_glb_with_metadata};
use vsg::shape::{Primitive, ShapeType};
use vsg::tree::{Appearance, Model, Node, NodeId, NodeState};

/// A model built group by group, symbols interned as the interpreter does.
struct Builder(Model);

impl Builder {
    fn new() -> Builder {
        let mut b = Builder(Model::default());
        b.0.appearances = vec![
            Appearance::default(),
            Appearance {
                density: Some(2000.0),
                ..Appearance::default()
            },
        ];
        b.push("Castle", None, NodeState::NonTerminal, 0.0, None, 0);
        b
    }

    fn symbol(&mut self, name: &str) -> u32 {
        match self.0.symbols.iter().position(|s| s == name) {
            Some(i) => i as u32,
            None => {
                self.0.symbols.push(name.into());
                self.0.symbols.len() as u32 - 1
            }
        }
    }

    /// Adds a node (children must follow their parent's other children at once).
    fn push(
        &mut self,
        name: &str,
        shape: Option<Primitive>,
        state: NodeState,
        x: f64,
        parent: Option<NodeId>,
        appearance: u32,
    ) -> NodeId {
        let symbol = self.symbol(name);
        let id = self.0.nodes.len() as NodeId;
        let local = Isometry3::translation(x, 0.0, 0.0);
        let (world, depth, index) = match parent {
            Some(p) => {
                let p = &mut self.0.nodes[p as usize];
                if p.child_count == 0 {
                    p.first_child = id;
                }
                p.child_count += 1;
                (p.world * local, p.depth + 1, p.child_count - 1)
            }
            None => (local, 0, 0),
        };
        self.0.nodes.push(Node {
            symbol,
            rule_line: 1,
            shape,
            local,
            world,
            appearance,
            state,
            parent,
            first_child: 0,
            child_count: 0,
            depth,
            index,
        });
        id
    }
}

fn cube(side: f64) -> Option<Primitive> {
    Some(Primitive::new(ShapeType::Box, &[side, side, side]).expect("a box"))
}

/// Castle → tower1 (masonry 2³, dense; roof 1³), keep1 (masonry 3³ twice, dense; window 1³;
/// a void room), and a loose terminal outside every part.
fn castle() -> (Model, Heritage) {
    use NodeState::*;
    let mut b = Builder::new();
    let tower = b.push("tower1", None, NonTerminal, 0.0, Some(0), 0);
    let keep = b.push("keep1", None, NonTerminal, 20.0, Some(0), 0);
    b.push("loose", cube(1.0), Terminal, 40.0, Some(0), 0);
    b.push("tower1.masonry", cube(2.0), Terminal, 0.0, Some(tower), 1);
    b.push("tower1.roof", cube(1.0), Terminal, 0.0, Some(tower), 0);
    for x in [0.0, 5.0] {
        b.push("keep1.masonry", cube(3.0), Terminal, x, Some(keep), 1);
    }
    b.push("keep1.window", cube(1.0), Terminal, 0.0, Some(keep), 0);
    b.push("keep1.room", cube(2.0), VoidTerminal, 0.0, Some(keep), 0);
    let part = |node: NodeId, name: &str, kind: &str, height: f64, extra: Option<bool>| {
        let mut attributes = BTreeMap::from([
            ("label".to_string(), Attribute::Text(kind.into())),
            ("height_m".to_string(), Attribute::Number(height)),
            (
                "provenance.height".to_string(),
                Attribute::Text(format!("photo {name}.jpg")),
            ),
        ]);
        if let Some(flag) = extra {
            attributes.insert("crenellated".into(), Attribute::Flag(flag));
        }
        Part {
            node,
            more_nodes: Vec::new(),
            name: name.into(),
            kind: kind.into(),
            attributes,
        }
    };
    let heritage = Heritage {
        name: "Test castle".into(),
        parts: vec![
            part(tower, "tower1", "tower", 12.5, Some(true)),
            part(keep, "keep1", "keep", 30.0, None),
        ],
        frame: Frame {
            metres_per_unit: 0.5,
            placement: None,
        },
        attributes: BTreeMap::new(),
    };
    (b.0, heritage)
}

/// The GLB's JSON and binary chunks.
fn chunks(glb: &[u8]) -> (Value, Vec<u8>) {
    let word = |at: usize| u32::from_le_bytes(glb[at..at + 4].try_into().unwrap()) as usize;
    let json_len = word(12);
    let json = serde_json::from_slice(&glb[20..20 + json_len]).expect("JSON chunk");
    let bin_at = 20 + json_len;
    let bin = glb[bin_at + 8..bin_at + 8 + word(bin_at)].to_vec();
    (json, bin)
}

fn view<'a>(json: &Value, bin: &'a [u8], index: &Value) -> &'a [u8] {
    let v = &json["bufferViews"][index.as_u64().expect("a view index") as usize];
    let start = v["byteOffset"].as_u64().unwrap_or(0) as usize;
    assert_eq!(start % 8, 0, "property table views are 8-byte aligned");
    &bin[start..start + v["byteLength"].as_u64().expect("a length") as usize]
}

/// Decodes column `property` of property table `table`, by its class's type.
fn column(json: &Value, bin: &[u8], table: usize, property: &str) -> Vec<Value> {
    let metadata = &json["extensions"]["EXT_structural_metadata"];
    let t = &metadata["propertyTables"][table];
    let class = &metadata["schema"]["classes"][t["class"].as_str().unwrap()];
    let definition = &class["properties"][property];
    let stored = &t["properties"][property];
    let count = t["count"].as_u64().unwrap() as usize;
    let values = view(json, bin, &stored["values"]);
    let words = |size: usize| values.chunks_exact(size).take(count);
    match (
        definition["type"].as_str(),
        definition["componentType"].as_str(),
    ) {
        (Some("STRING"), _) => {
            let offsets: Vec<usize> = view(json, bin, &stored["stringOffsets"])
                .chunks_exact(4)
                .map(|w| u32::from_le_bytes(w.try_into().unwrap()) as usize)
                .collect();
            assert_eq!(offsets.len(), count + 1);
            (0..count)
                .map(|i| String::from_utf8(values[offsets[i]..offsets[i + 1]].to_vec()).unwrap())
                .map(Value::from)
                .collect()
        }
        (Some("SCALAR"), Some("FLOAT64")) => words(8)
            .map(|w| Value::from(f64::from_le_bytes(w.try_into().unwrap())))
            .collect(),
        (Some("SCALAR"), Some("UINT32")) => words(4)
            .map(|w| Value::from(u32::from_le_bytes(w.try_into().unwrap())))
            .collect(),
        (Some("BOOLEAN"), _) => (0..count)
            .map(|i| Value::from(values[i / 8] >> (i % 8) & 1 == 1))
            .collect(),
        other => panic!("unexpected type {other:?} of {property}"),
    }
}

fn glb() -> (Value, Vec<u8>) {
    let (model, heritage) = castle();
    let options = ExportOptions::default();
    let glb = to_glb_with_metadata(&model, &options, &Textures::new(), &heritage).expect("export");
    chunks(&glb)
}

#[test]
fn the_part_table_holds_each_part_with_its_totals_and_attributes() {
    let (json, bin) = glb();
    let used: Vec<&str> = json["extensionsUsed"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        .collect();
    assert_eq!(used, ["EXT_mesh_features", "EXT_structural_metadata"]);
    let col = |p: &str| column(&json, &bin, 0, p);
    assert_eq!(col("name"), ["tower1", "keep1"]);
    assert_eq!(col("kind"), ["tower", "keep"]);
    // Half a metre per unit: volumes × 1/8. Drawn terminals only (the room is void).
    let m3 = 0.125;
    assert_eq!(
        col("volume_m3"),
        [(8.0 + 1.0) * m3, (27.0 * 2.0 + 1.0) * m3]
    );
    assert_eq!(col("mass_kg"), [2000.0 * 8.0 * m3, 2000.0 * 54.0 * m3]);
    assert_eq!(col("terminals"), [2, 3]);
    assert_eq!(col("height_m"), [12.5, 30.0]);
    assert_eq!(col("label"), ["tower", "keep"]);
    assert_eq!(
        col("provenance_height"),
        ["photo tower1.jpg", "photo keep1.jpg"]
    );
    // Only the tower says whether it is crenellated: text, with the no-data value elsewhere.
    assert_eq!(col("crenellated"), ["true", ""]);
}

#[test]
fn the_element_table_holds_each_part_and_symbol() {
    let (json, bin) = glb();
    let col = |p: &str| column(&json, &bin, 1, p);
    assert_eq!(col("part"), ["tower1", "tower1", "keep1", "keep1"]);
    assert_eq!(
        col("symbol"),
        [
            "tower1.masonry",
            "tower1.roof",
            "keep1.masonry",
            "keep1.window"
        ]
    );
    assert_eq!(col("class"), ["wall", "roof", "wall", "window"]);
    assert_eq!(col("volume_m3"), [1.0, 0.125, 6.75, 0.125]);
    assert_eq!(col("terminals"), [1, 1, 2, 1]);
}

/// Every drawn primitive in a part points at its part's and element's rows; terminals outside
/// every part get none; equal boxes of one element still share a mesh.
#[test]
fn every_primitive_points_at_its_rows() {
    let (json, bin) = glb();
    let accessor_values = |index: u64| -> Vec<f32> {
        let a = &json["accessors"][index as usize];
        assert_eq!(a["componentType"], 5126);
        let v = &json["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
        let start = v["byteOffset"].as_u64().unwrap_or(0) as usize;
        let count = a["count"].as_u64().unwrap() as usize;
        bin[start..start + 4 * count]
            .chunks_exact(4)
            .map(|w| f32::from_le_bytes(w.try_into().unwrap()))
            .collect()
    };
    let expected = BTreeMap::from([
        ("tower1.masonry", Some([0.0, 0.0])),
        ("tower1.roof", Some([0.0, 1.0])),
        ("keep1.masonry", Some([1.0, 2.0])),
        ("keep1.window", Some([1.0, 3.0])),
        ("loose", None),
    ]);
    let mut keep_meshes = Vec::new();
    for node in json["nodes"].as_array().unwrap() {
        let Some(mesh) = node["mesh"].as_u64() else {
            continue;
        };
        let name = node["name"].as_str().unwrap();
        let primitive = &json["meshes"][mesh as usize]["primitives"][0];
        let ids = ["_FEATURE_ID_0", "_FEATURE_ID_1"].map(|a| {
            primitive["attributes"][a].as_u64().map(|i| {
                let values = accessor_values(i);
                assert!(values.windows(2).all(|w| w[0] == w[1]), "constant");
                values[0]
            })
        });
        match expected[name] {
            Some(rows) => {
                assert_eq!(ids, rows.map(Some), "{name}");
                let features = &primitive["extensions"]["EXT_mesh_features"]["featureIds"];
                assert_eq!(features[0]["propertyTable"], 0);
                assert_eq!(features[1]["attribute"], 1);
            }
            None => assert_eq!(ids, [None, None], "{name}"),
        }
        if name == "keep1.masonry" {
            keep_meshes.push(mesh);
        }
    }
    assert_eq!(keep_meshes.len(), 2);
    assert_eq!(keep_meshes[0], keep_meshes[1]);
}

/// Without metadata nothing changes: the same file as before issue 24.
#[test]
fn without_metadata_the_file_has_no_extension() {
    let (model, _) = castle();
    let (json, _) = chunks(&to_glb(&model, &ExportOptions::default()).expect("export"));
    assert!(json.get("extensionsUsed").is_none());
    assert!(json.get("extensions").is_none());
}

/// With no part given, the root's children are the parts.
#[test]
fn default_parts_are_the_roots_children() {
    let (model, _) = castle();
    let heritage = Heritage::default();
    let glb = to_glb_with_metadata(
        &model,
        &ExportOptions::default(),
        &Textures::new(),
        &heritage,
    )
    .expect("export");
    let (json, bin) = chunks(&glb);
    assert_eq!(column(&json, &bin, 0, "name"), ["tower1", "keep1", "loose"]);
    assert_eq!(column(&json, &bin, 0, "volume_m3"), [9.0, 55.0, 1.0]);
}
