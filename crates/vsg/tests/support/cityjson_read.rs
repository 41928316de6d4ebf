//! The CityJSON file read back for `tests/cityjson.rs` and `tests/cityjson_programs.rs`: vertices in metres, solids with their
//! surfaces' semantic types, volumes and closedness from the file's own vertices; and both
//! validators on it ([`assert_valid`]: the including test declares `mod cjio` and
//! `mod cjval_check` beside this module).

#![allow(dead_code)] // Each test file uses its own part of it.

use std::collections::{BTreeMap, HashMap, HashSet};

use serde_json::Value;
use vsg::export::semantics::Heritage;
use vsg::export::{ExportOptions, to_cityjson};
use vsg::tree::Model;

pub fn write(model: &Model, heritage: &Heritage) -> (String, Value) {
    let text = to_cityjson(model, heritage, &ExportOptions::default()).expect("export succeeds");
    let json = serde_json::from_str(&text).expect("the file is JSON");
    (text, json)
}

/// The file's vertices in metres (transform applied).
pub fn vertices(doc: &Value) -> Vec<[f64; 3]> {
    let t = &doc["transform"];
    let num = |v: &Value, k: usize| v[k].as_f64().expect("a number");
    doc["vertices"]
        .as_array()
        .expect("vertices")
        .iter()
        .map(|v| [0, 1, 2].map(|k| num(&t["translate"], k) + num(&t["scale"], k) * num(v, k)))
        .collect()
}

type Ring = Vec<usize>;
type Surface = Vec<Ring>;
pub type Shell = Vec<Surface>;

/// The solids (outer shells) of a `CompositeSolid`, with each surface's semantic type.
pub fn solids(geometry: &Value) -> Vec<(Shell, Vec<String>)> {
    assert_eq!(geometry["type"], "CompositeSolid");
    let boundaries: Vec<Vec<Shell>> =
        serde_json::from_value(geometry["boundaries"].clone()).expect("solid boundaries");
    let values: Vec<Vec<Vec<usize>>> =
        serde_json::from_value(geometry["semantics"]["values"].clone()).expect("values");
    let surfaces = geometry["semantics"]["surfaces"]
        .as_array()
        .expect("surfaces");
    boundaries
        .into_iter()
        .zip(values)
        .map(|(solid, values)| {
            assert_eq!(solid.len(), 1, "one outer shell per solid");
            let kinds = values[0]
                .iter()
                .map(|&i| surfaces[i]["type"].as_str().expect("a type").to_string())
                .collect();
            (solid.into_iter().next().expect("a shell"), kinds)
        })
        .collect()
}

/// Signed volume of a shell from its polygons (holes included): Σ p₀·A/3 over the faces,
/// with A the ring's vector area; positive when the shell faces outwards.
pub fn signed_volume(shell: &Shell, v: &[[f64; 3]]) -> f64 {
    let mut volume = 0.0;
    for surface in shell {
        let origin = v[surface[0][0]];
        for ring in surface {
            for w in 0..ring.len() {
                let a = sub(v[ring[w]], origin);
                let b = sub(v[ring[(w + 1) % ring.len()]], origin);
                // Relative to a point of the face's plane, Σ (a × b)/2 is the ring's area
                // vector; the volume's term is that point's height along it.
                let c = [
                    a[1] * b[2] - a[2] * b[1],
                    a[2] * b[0] - a[0] * b[2],
                    a[0] * b[1] - a[1] * b[0],
                ];
                volume += (origin[0] * c[0] + origin[1] * c[1] + origin[2] * c[2]) / 6.0;
            }
        }
    }
    volume
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Every directed edge of the shell's rings has its reverse exactly once: closed, and every
/// face oriented like its neighbours.
pub fn is_closed(shell: &Shell) -> bool {
    let mut edges: HashMap<(usize, usize), u32> = HashMap::new();
    for ring in shell.iter().flatten() {
        for w in 0..ring.len() {
            *edges
                .entry((ring[w], ring[(w + 1) % ring.len()]))
                .or_default() += 1;
        }
    }
    edges
        .iter()
        .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
}

/// Asserts that no two vertices are equal and that every one is used.
pub fn assert_vertices_unique_and_used(doc: &Value) {
    let vs: Vec<[i64; 3]> = serde_json::from_value(doc["vertices"].clone()).expect("integers");
    let distinct: HashSet<[i64; 3]> = vs.iter().copied().collect();
    assert_eq!(distinct.len(), vs.len(), "duplicate vertices");
    let mut used = vec![false; vs.len()];
    fn mark(v: &Value, used: &mut [bool]) {
        match v {
            Value::Array(items) => items.iter().for_each(|i| mark(i, used)),
            Value::Number(n) => used[n.as_u64().expect("an index") as usize] = true,
            _ => panic!("boundaries hold arrays and indices only"),
        }
    }
    for object in doc["CityObjects"].as_object().expect("objects").values() {
        for g in object["geometry"].as_array().into_iter().flatten() {
            mark(&g["boundaries"], &mut used);
        }
    }
    assert!(used.iter().all(|&u| u), "unused vertices");
}

/// Asserts that every solid of every geometry in the file encloses a positive volume: its
/// shell faces outwards.
pub fn assert_outward(name: &str, doc: &Value) {
    let v = vertices(doc);
    for (id, object) in doc["CityObjects"].as_object().expect("objects") {
        for g in object["geometry"].as_array().into_iter().flatten() {
            for (shell, _) in solids(g) {
                let volume = signed_volume(&shell, &v);
                assert!(
                    volume > 0.0,
                    "{name}: {id} has a shell facing inwards ({volume} m³)"
                );
            }
        }
    }
}

/// Counts of semantic surface types over all faces of a geometry object.
pub fn surface_counts(geometry: &Value) -> BTreeMap<String, usize> {
    let mut counts = BTreeMap::new();
    for (_, kinds) in solids(geometry) {
        for k in kinds {
            *counts.entry(k).or_default() += 1;
        }
    }
    counts
}

/// A heritage record with only its name.
pub fn heritage(name: &str) -> Heritage {
    Heritage {
        name: name.into(),
        ..Heritage::default()
    }
}

/// Both validators on one file.
pub fn assert_valid(name: &str, text: &str, doc: &Value) {
    super::cjval_check::assert_cjval_valid(name, text);
    let parts = doc["CityObjects"]
        .as_object()
        .expect("objects")
        .values()
        .filter(|o| o["type"] == "BuildingPart")
        .count();
    let vertices = doc["vertices"].as_array().expect("vertices").len();
    super::cjio::assert_cjio_reads(name, text, parts, vertices);
}
