//! GLB tests: container layout, the node tree of §7.1.3, shared terminal meshes (§7.1.2),
//! materials, vertex data and speed.

use std::cell::Cell;
use std::time::Instant;

use serde_json::Value;

use super::*;

fn word(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
}

/// Checks the GLB container and returns its JSON and BIN chunk.
fn parse_glb(bytes: &[u8]) -> (Value, &[u8]) {
    assert_eq!(&bytes[0..4], b"glTF");
    assert_eq!(word(bytes, 4), 2);
    assert_eq!(word(bytes, 8) as usize, bytes.len());
    assert_eq!(bytes.len() % 4, 0);
    let json_len = word(bytes, 12) as usize;
    assert_eq!(json_len % 4, 0);
    assert_eq!(&bytes[16..20], b"JSON");
    let json = serde_json::from_slice(&bytes[20..20 + json_len]).expect("JSON chunk parses");
    let rest = &bytes[20 + json_len..];
    if rest.is_empty() {
        return (json, rest);
    }
    let bin_len = word(rest, 0) as usize;
    assert_eq!(bin_len % 4, 0);
    assert_eq!(&rest[4..8], b"BIN\0");
    assert_eq!(rest.len(), 8 + bin_len);
    (json, &rest[8..])
}

/// Reads accessor `index` as rows of f32 (or integer indices converted to f32).
fn read_accessor(json: &Value, bin: &[u8], index: u64) -> Vec<Vec<f64>> {
    let acc = &json["accessors"][index as usize];
    let view = &json["bufferViews"][acc["bufferView"].as_u64().unwrap() as usize];
    let width = match acc["type"].as_str().unwrap() {
        "VEC3" => 3,
        "VEC2" => 2,
        "SCALAR" => 1,
        other => panic!("unexpected type {other}"),
    };
    let size = match acc["componentType"].as_u64().unwrap() {
        5123 => 2,
        5125 | 5126 => 4,
        other => panic!("unexpected component type {other}"),
    };
    let stride = view["byteStride"]
        .as_u64()
        .map_or(width * size, |s| s as usize);
    let base = view["byteOffset"].as_u64().unwrap_or(0) + acc["byteOffset"].as_u64().unwrap_or(0);
    assert_eq!(base as usize % size, 0, "accessor is aligned");
    let count = acc["count"].as_u64().unwrap() as usize;
    assert!(base as usize + stride * (count - 1) + width * size <= bin.len());
    (0..count)
        .map(|i| {
            (0..width)
                .map(|k| {
                    let at = base as usize + i * stride + k * size;
                    match acc["componentType"].as_u64().unwrap() {
                        5123 => u16::from_le_bytes([bin[at], bin[at + 1]]) as f64,
                        5125 => word(bin, at) as f64,
                        _ => f32::from_le_bytes(bin[at..at + 4].try_into().unwrap()) as f64,
                    }
                })
                .collect()
        })
        .collect()
}

#[test]
fn glb_header_and_chunks_are_aligned() {
    let bytes = glb_with(&castle(), &box_mesh);
    let (json, bin) = parse_glb(&bytes);
    assert_eq!(json["asset"]["version"], "2.0");
    assert_eq!(
        json["buffers"][0]["byteLength"].as_u64().unwrap() as usize,
        bin.len()
    );
    for view in json["bufferViews"].as_array().unwrap() {
        assert_eq!(view["byteOffset"].as_u64().unwrap() % 4, 0);
    }
}

#[test]
fn glb_nodes_mirror_the_model_tree() {
    let model = castle();
    let (json, _) = parse_glb(&glb_with(&model, &box_mesh));
    let nodes = json["nodes"].as_array().unwrap();
    assert_eq!(nodes.len(), model.nodes.len());
    assert_eq!(json["scenes"][0]["nodes"], serde_json::json!([0]));
    assert_eq!(json["scene"], 0);
    assert_eq!(nodes[0]["children"], serde_json::json!([1, 2, 3, 4]));
    assert_eq!(nodes[1]["children"], serde_json::json!([5, 6, 7, 8]));
    assert!(nodes[2].get("children").is_none());
    for (node, gl) in model.nodes.iter().zip(nodes) {
        assert_eq!(gl["name"], model.symbol(node));
    }
    // Local transforms, not world ones: bricks are placed relative to the wall.
    assert_eq!(
        nodes[5]["translation"],
        serde_json::json!([-1.0, -1.0, 0.0])
    );
    let q: Vec<f64> = serde_json::from_value(nodes[3]["rotation"].clone()).unwrap();
    let half = 0.785f64 / 2.0;
    assert!(
        (q[1] - half.sin()).abs() < 1e-6 && (q[3] - half.cos()).abs() < 1e-6,
        "{q:?}"
    );
    assert!(nodes[0].get("rotation").is_none() && nodes[0].get("translation").is_none());
}

#[test]
fn identical_terminals_share_one_mesh() {
    let calls = Cell::new(0);
    let counting = |p: &Primitive| {
        calls.set(calls.get() + 1);
        box_mesh(p)
    };
    let (json, _) = parse_glb(&glb_with(&castle(), &counting));
    let nodes = json["nodes"].as_array().unwrap();
    let bricks: Vec<&Value> = (5..=8).map(|i| &nodes[i]["mesh"]).collect();
    assert!(
        bricks.iter().all(|m| *m == bricks[0] && m.is_u64()),
        "{bricks:?}"
    );
    // Bricks, tower, gate: the tower and gate share geometry but not material.
    assert_eq!(json["meshes"].as_array().unwrap().len(), 3);
    assert_ne!(nodes[3]["mesh"], nodes[4]["mesh"]);
    assert_eq!(calls.get(), 2, "each distinct primitive is meshed once");
    assert_eq!(json["accessors"].as_array().unwrap().len(), 6);
    assert_eq!(json["materials"].as_array().unwrap().len(), 2);
}

#[test]
fn void_and_non_terminals_have_no_mesh() {
    let (json, _) = parse_glb(&glb_with(&castle(), &box_mesh));
    let nodes = json["nodes"].as_array().unwrap();
    for (i, node) in nodes.iter().enumerate() {
        assert_eq!(
            node.get("mesh").is_some(),
            i >= 3,
            "node {i}: only terminals 3..=8 have one"
        );
    }
}

#[test]
fn node_extras_carry_shape_volume_rule_and_state() {
    let (json, _) = parse_glb(&glb_with(&castle(), &box_mesh));
    let nodes = &json["nodes"];
    let extras = &nodes[2]["extras"];
    assert_eq!(extras["shapeType"], "box");
    assert_eq!(extras["params"], serde_json::json!([1.0, 1.0, 1.0]));
    assert_eq!(extras["volume"], 1.0);
    assert_eq!(extras["ruleLine"], 11);
    assert_eq!(extras["state"], "void_terminal");
    assert_eq!(nodes[0]["extras"]["state"], "non_terminal");
    assert_eq!(nodes[0]["extras"]["volume"], 240.0);
    assert_eq!(nodes[5]["extras"]["state"], "terminal");
}

#[test]
fn materials_follow_appearances() {
    let (json, _) = parse_glb(&glb_with(&castle(), &box_mesh));
    let mats = json["materials"].as_array().unwrap();
    let glass = mats
        .iter()
        .find(|m| m["name"] == "appearance_1")
        .expect("tower material");
    let pbr = &glass["pbrMetallicRoughness"];
    let color: Vec<f64> = serde_json::from_value(pbr["baseColorFactor"].clone()).unwrap();
    let expected = [0.9, 0.1, 0.1, 0.75];
    assert!(
        color
            .iter()
            .zip(expected)
            .all(|(a, b)| (a - b).abs() < 1e-6),
        "{color:?}"
    );
    assert_eq!(glass["alphaMode"], "BLEND");
    assert_eq!(pbr["metallicFactor"], 0.0);
    assert!((pbr["roughnessFactor"].as_f64().unwrap() - 0.3).abs() < 1e-6);
    assert_eq!(glass["emissiveFactor"], serde_json::json!([0.0, 0.5, 0.0]));
    assert_eq!(glass["extras"]["texture"], "bricks.png");
    let plain = mats
        .iter()
        .find(|m| m["name"] == "appearance_0")
        .expect("default material");
    assert!(plain.get("alphaMode").is_none_or(|m| m == "OPAQUE"));
    assert!(plain.get("extras").is_none());
}

#[test]
fn vertex_data_has_bounds_unit_normals_and_valid_indices() {
    let bytes = glb_with(&castle(), &box_mesh);
    let (json, bin) = parse_glb(&bytes);
    for mesh in json["meshes"].as_array().unwrap() {
        let prim = &mesh["primitives"][0];
        let pos_id = prim["attributes"]["POSITION"].as_u64().unwrap();
        let positions = read_accessor(&json, bin, pos_id);
        let normals = read_accessor(&json, bin, prim["attributes"]["NORMAL"].as_u64().unwrap());
        let indices = read_accessor(&json, bin, prim["indices"].as_u64().unwrap());
        assert_eq!(positions.len(), 24, "flat box: 4 vertices per face");
        assert_eq!(indices.len(), 36);
        assert!(indices.iter().all(|i| (i[0] as usize) < positions.len()));
        for n in &normals {
            let len = n.iter().map(|c| c * c).sum::<f64>().sqrt();
            assert!((len - 1.0).abs() < 1e-6 && n.iter().filter(|c| c.abs() > 0.5).count() == 1);
        }
        let acc = &json["accessors"][pos_id as usize];
        for k in 0..3 {
            let lo = positions.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
            let hi = positions
                .iter()
                .map(|p| p[k])
                .fold(f64::NEG_INFINITY, f64::max);
            assert_eq!(acc["min"][k].as_f64().unwrap(), lo);
            assert_eq!(acc["max"][k].as_f64().unwrap(), hi);
        }
    }
}

#[test]
fn empty_and_void_only_models_give_valid_files() {
    let bytes = glb_with(&Model::default(), &box_mesh);
    let (json, bin) = parse_glb(&bytes);
    assert!(bin.is_empty() && json.get("buffers").is_none() && json.get("nodes").is_none());
    let mut t = Tree::new("Ruin", Some(boxed([2.0; 3])));
    let hole = boxed([1.0; 3]);
    t.children(
        0,
        &[("Hole", NodeState::VoidTerminal, hole, at(0.0, 0.0, 0.0), 0)],
    );
    let bytes = glb_with(&t.0, &box_mesh);
    let (json, bin) = parse_glb(&bytes);
    assert!(bin.is_empty() && json.get("meshes").is_none());
    assert_eq!(json["nodes"].as_array().unwrap().len(), 2);
}

#[test]
fn a_hundred_thousand_bricks_export_quickly() {
    let brick = boxed([0.2, 0.1, 0.1]);
    let mut t = Tree::new("Wall", Some(boxed([100.0, 100.0, 0.1])));
    let kids: Vec<_> = (0..100_000)
        .map(|i| {
            let local = at((i % 500) as f64 * 0.2, (i / 500) as f64 * 0.1, 0.0);
            ("Brick", NodeState::Terminal, brick, local, (i % 2) as u32)
        })
        .collect();
    t.0.appearances.push(Appearance {
        color: [0.5, 0.2, 0.1],
        ..Appearance::default()
    });
    t.children(0, &kids);
    let start = Instant::now();
    let bytes = glb_with(&t.0, &box_mesh);
    let elapsed = start.elapsed();
    let (json, _) = parse_glb(&bytes);
    assert_eq!(json["nodes"].as_array().unwrap().len(), 100_001);
    assert_eq!(json["meshes"].as_array().unwrap().len(), 2);
    if !cfg!(debug_assertions) {
        assert!(elapsed.as_secs_f64() < 1.0, "took {elapsed:?}");
    }
}

#[test]
fn large_meshes_switch_to_u32_indices() {
    let row = |p: &Primitive| {
        let mut m = TriMesh::default();
        for i in 0..3000 {
            let mut b = box_mesh(p);
            b.positions.iter_mut().for_each(|v| v[0] += 2.0 * i as f64);
            m.append(&b);
        }
        m
    };
    let bytes = glb_with(&Tree::new("Row", Some(boxed([1.0; 3]))).0, &row);
    let (json, bin) = parse_glb(&bytes);
    let prim = &json["meshes"][0]["primitives"][0];
    let indices_id = prim["indices"].as_u64().unwrap();
    assert_eq!(
        json["accessors"][indices_id as usize]["componentType"],
        5125
    );
    let positions = read_accessor(&json, bin, prim["attributes"]["POSITION"].as_u64().unwrap());
    assert_eq!(positions.len(), 3000 * 24);
    let indices = read_accessor(&json, bin, indices_id);
    assert!(indices.iter().all(|i| (i[0] as usize) < positions.len()));
    assert_eq!(
        indices.iter().map(|i| i[0] as usize).max(),
        Some(positions.len() - 1)
    );
}

#[test]
fn textures_are_embedded_with_real_scale_uvs() {
    let model = castle();
    let png = b"\x89PNG\r\n\x1a\nnot really, but bytes".to_vec();
    let mut textures = Textures::new();
    textures.insert(
        "bricks.png".into(),
        TextureImage {
            bytes: png.clone(),
            mime_type: "image/png".into(),
            size: None,
        },
    );
    let options = ExportOptions {
        texture_scale: 2.0,
        ..ExportOptions::default()
    };
    let geometry = Geometry {
        mesh: &box_mesh,
        volume: &box_volume,
    };
    let glb = super::gltf::write_glb(&model, &options, &textures, None, &geometry).unwrap();
    let (json, bin) = parse_glb(&glb);
    assert_eq!(json["images"].as_array().unwrap().len(), 1);
    assert_eq!(json["textures"].as_array().unwrap().len(), 1);
    assert_eq!(json["samplers"].as_array().unwrap().len(), 1);
    assert_eq!(json["samplers"][0]["wrapS"], 10497);
    assert_eq!(json["samplers"][0]["wrapT"], 10497);
    // Trilinear: mipmapped minification (LINEAR_MIPMAP_LINEAR), linear magnification.
    assert_eq!(json["samplers"][0]["minFilter"], 9987);
    assert_eq!(json["samplers"][0]["magFilter"], 9729);
    let image = &json["images"][0];
    assert_eq!(image["mimeType"], "image/png");
    let view = &json["bufferViews"][image["bufferView"].as_u64().unwrap() as usize];
    let start = view["byteOffset"].as_u64().unwrap_or(0) as usize;
    assert_eq!(start % 4, 0);
    let len = view["byteLength"].as_u64().unwrap() as usize;
    assert_eq!(&bin[start..start + len], &png[..], "image bytes round-trip");

    // The textured material (appearance 0, tinted by its colour) draws a mesh.
    let materials = json["materials"].as_array().unwrap();
    let textured: Vec<usize> = (0..materials.len())
        .filter(|&m| materials[m]["pbrMetallicRoughness"]["baseColorTexture"]["index"] == 0)
        .collect();
    assert_eq!(textured.len(), 1);
    let tint = &materials[textured[0]]["pbrMetallicRoughness"]["baseColorFactor"];
    assert!(
        (tint[0].as_f64().unwrap() - 0.9).abs() < 1e-6,
        "tinted by the colour"
    );
    let primitive = json["meshes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| &m["primitives"][0])
        .find(|p| p["material"].as_u64() == Some(textured[0] as u64))
        .expect("a mesh drawn with the textured material");
    let attributes = &primitive["attributes"];
    let uvs = read_accessor(&json, bin, attributes["TEXCOORD_0"].as_u64().unwrap());
    let positions = read_accessor(&json, bin, attributes["POSITION"].as_u64().unwrap());
    let normals = read_accessor(&json, bin, attributes["NORMAL"].as_u64().unwrap());
    assert_eq!(uvs.len(), positions.len());
    for ((uv, p), n) in uvs.iter().zip(&positions).zip(&normals) {
        let p = [p[0], p[1], p[2]];
        let expected = super::gltf::box_uv(p, [n[0], n[1], n[2]], [2.0; 2]);
        assert!((uv[0] - expected[0]).abs() < 1e-6 && (uv[1] - expected[1]).abs() < 1e-6);
        // Real scale: along a face, the UV distance is the model distance over the scale.
        if n[2].abs() > 0.9 {
            assert!((uv[0].abs() - p[0].abs() / 2.0).abs() < 1e-6);
            assert!((uv[1].abs() - p[1].abs() / 2.0).abs() < 1e-6);
        }
    }

    // Without texture images the export is unchanged.
    let plain =
        super::gltf::write_glb(&model, &options, &Textures::new(), None, &geometry).unwrap();
    let (plain_json, _) = parse_glb(&plain);
    assert!(plain_json.get("images").is_none());
    assert!(
        plain_json["meshes"][0]["primitives"][0]["attributes"]
            .get("TEXCOORD_0")
            .is_none()
    );
    assert_eq!(plain, glb_with(&model, &box_mesh));
}

#[test]
fn box_uv_projects_on_the_dominant_axis() {
    use super::gltf::box_uv;
    assert_eq!(
        box_uv([1.0, 2.0, 3.0], [0.0, 0.0, 1.0], [1.0; 2]),
        [1.0, -2.0]
    );
    assert_eq!(
        box_uv([1.0, 2.0, 3.0], [0.0, 0.0, -1.0], [2.0; 2]),
        [-0.5, -1.0]
    );
    assert_eq!(
        box_uv([1.0, 2.0, 3.0], [1.0, 0.0, 0.0], [1.0; 2]),
        [-3.0, -2.0]
    );
    assert_eq!(
        box_uv([1.0, 2.0, 3.0], [0.0, 1.0, 0.0], [1.0; 2]),
        [1.0, 3.0]
    );
    // Across and up the texture at their own sizes.
    assert_eq!(
        box_uv([1.0, 2.0, 3.0], [0.0, 0.0, 1.0], [4.0, 0.5]),
        [0.25, -4.0]
    );
    // A degenerate size falls back to 1.
    assert_eq!(
        box_uv([1.0, 2.0, 3.0], [0.0, 0.0, 1.0], [0.0; 2]),
        [1.0, -2.0]
    );
}

#[test]
fn photo_uv_covers_each_face_once_seen_from_outside() {
    use super::gltf::photo_uv;
    let size = [6.0, 2.0, 1.0];
    // Front (+z): left edge u = 0, right edge u = 1, top v = 0, bottom v = 1.
    assert_eq!(
        photo_uv([-3.0, 1.0, 0.5], [0.0, 0.0, 1.0], size),
        [0.0, 0.0]
    );
    assert_eq!(
        photo_uv([3.0, -1.0, 0.5], [0.0, 0.0, 1.0], size),
        [1.0, 1.0]
    );
    // Back (−z) seen from behind: its left is +x.
    assert_eq!(
        photo_uv([3.0, 1.0, -0.5], [0.0, 0.0, -1.0], size),
        [0.0, 0.0]
    );
    // +x side seen from outside: its left is +z.
    assert_eq!(photo_uv([3.0, 1.0, 0.5], [1.0, 0.0, 0.0], size), [0.0, 0.0]);
}

#[test]
fn a_photo_spans_the_wall_it_is_set_on_across_the_pieces_split_from_it() {
    let src = r#"Axiom :: I("box", {6, 2, 1}){wall};
wall :: appearance("photo", "p.png") split("X", {~1, ~1, ~1}){piece, piece, piece};
piece :: {j3d.terminal};"#;
    let model = crate::run(src, &crate::RunOptions::default()).unwrap();
    let mut textures = Textures::new();
    textures.insert(
        "p.png".into(),
        TextureImage {
            bytes: b"\x89PNG\r\n\x1a\nbytes".to_vec(),
            mime_type: "image/png".into(),
            size: None,
        },
    );
    let glb = to_glb_with_textures(&model, &ExportOptions::default(), &textures).unwrap();
    let (json, bin) = parse_glb(&glb);
    let meshes = json["meshes"].as_array().unwrap();
    assert_eq!(
        meshes.len(),
        3,
        "each piece under the photo has its own mesh"
    );
    let mut spans: Vec<(f64, f64)> = meshes
        .iter()
        .map(|m| {
            let a = &m["primitives"][0]["attributes"];
            let uvs = read_accessor(&json, bin, a["TEXCOORD_0"].as_u64().unwrap());
            let normals = read_accessor(&json, bin, a["NORMAL"].as_u64().unwrap());
            let front: Vec<&Vec<f64>> = uvs
                .iter()
                .zip(&normals)
                .filter(|(_, n)| n[2] > 0.9)
                .map(|(uv, _)| uv)
                .collect();
            assert!(
                front
                    .iter()
                    .all(|uv| uv[1].abs() < 1e-6 || (uv[1] - 1.0).abs() < 1e-6)
            );
            let lo = front.iter().map(|uv| uv[0]).fold(f64::INFINITY, f64::min);
            let hi = front
                .iter()
                .map(|uv| uv[0])
                .fold(f64::NEG_INFINITY, f64::max);
            (lo, hi)
        })
        .collect();
    spans.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (k, (lo, hi)) in spans.iter().enumerate() {
        assert!(
            (lo - k as f64 / 3.0).abs() < 1e-5 && (hi - (k + 1) as f64 / 3.0).abs() < 1e-5,
            "{spans:?}"
        );
    }
}

#[test]
fn each_texture_repeats_at_its_own_real_size() {
    // Two walls of the same box, one textured with a sample 4 × 2 units large, the other with
    // a texture of no known size (the global texture scale, 0.5): the same primitive gets two
    // sets of texture coordinates.
    let src = r#"Axiom :: I("box", {8, 4, 1}) T(0, 0, 3) I("box", {8, 4, 1}){a, b};
a :: appearance("texture", "stone.png"){j3d.terminal};
b :: appearance("texture", "plain.png"){j3d.terminal};"#;
    let model = crate::run(src, &crate::RunOptions::default()).unwrap();
    let image = |size| TextureImage {
        bytes: b"\x89PNG\r\n\x1a\nbytes".to_vec(),
        mime_type: "image/png".into(),
        size,
    };
    let mut textures = Textures::new();
    textures.insert("stone.png".into(), image(Some([4.0, 2.0])));
    textures.insert("plain.png".into(), image(None));
    let options = ExportOptions {
        texture_scale: 0.5,
        ..ExportOptions::default()
    };
    let glb = to_glb_with_textures(&model, &options, &textures).unwrap();
    let (json, bin) = parse_glb(&glb);
    let materials = json["materials"].as_array().unwrap();
    let texture_of = |material: u64| {
        let t = materials[material as usize]["pbrMetallicRoughness"]["baseColorTexture"]["index"]
            .as_u64()
            .unwrap();
        json["textures"][t as usize]["name"]
            .as_str()
            .unwrap()
            .to_owned()
    };
    let mut seen = Vec::new();
    for m in json["meshes"].as_array().unwrap() {
        let p = &m["primitives"][0];
        let size = match texture_of(p["material"].as_u64().unwrap()).as_str() {
            "stone.png" => [4.0, 2.0],
            _ => [0.5, 0.5],
        };
        let a = &p["attributes"];
        let uvs = read_accessor(&json, bin, a["TEXCOORD_0"].as_u64().unwrap());
        let positions = read_accessor(&json, bin, a["POSITION"].as_u64().unwrap());
        let normals = read_accessor(&json, bin, a["NORMAL"].as_u64().unwrap());
        for ((uv, q), n) in uvs.iter().zip(&positions).zip(&normals) {
            let e = super::gltf::box_uv([q[0], q[1], q[2]], [n[0], n[1], n[2]], size);
            assert!((uv[0] - e[0]).abs() < 1e-6 && (uv[1] - e[1]).abs() < 1e-6);
        }
        // The 8-unit-wide front face spans two repeats of the sample, sixteen of the other.
        let front: Vec<f64> = uvs
            .iter()
            .zip(&normals)
            .filter(|(_, n)| n[2] > 0.9)
            .map(|(uv, _)| uv[0])
            .collect();
        let span = front.iter().cloned().fold(f64::MIN, f64::max)
            - front.iter().cloned().fold(f64::MAX, f64::min);
        seen.push((size[0], span));
    }
    seen.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert_eq!(seen.len(), 2, "{seen:?}");
    assert!(
        (seen[0].1 - 16.0).abs() < 1e-5 && (seen[1].1 - 2.0).abs() < 1e-5,
        "{seen:?}"
    );
}
