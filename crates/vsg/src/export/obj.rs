//! Wavefront OBJ + MTL export. OBJ has no hierarchy, so only the visible terminals of §7.1.2
//! are written, one group each (`symbol_nodeindex`) in world coordinates; the semantic tree of
//! §7.1.3 survives only in the group names. Each used appearance becomes one MTL material.

use std::collections::HashMap;
use std::fmt::Write;

use nalgebra::{Point3, Vector3};

use super::common::{Geometry, Palette, ShapeKey, check_model, finite_f32, solid_mesh, unit};
use super::error::ExportError;
use super::options::ExportOptions;
use super::shading::{ShadedMesh, shade};
use crate::tree::{Appearance, Model, NodeId, NodeState};

pub(super) fn write_obj(
    model: &Model,
    options: &ExportOptions,
    mtl_file_name: &str,
    geometry: &Geometry,
) -> Result<(String, String), ExportError> {
    check_model(model)?;
    let mut palette = Palette::new(model);
    let mut meshes: HashMap<ShapeKey, ShadedMesh> = HashMap::new();
    let mut obj = String::new();
    let visible = model
        .terminals()
        .filter(|n| n.state == NodeState::Terminal)
        .count();
    // Formatting into a String cannot fail, so the `write!` results are ignored below.
    let _ = writeln!(obj, "# castellan vsg export: {visible} visible terminals");
    let _ = writeln!(obj, "mtllib {mtl_file_name}");
    let mut base = 1usize; // OBJ indices are 1-based and global
    for (i, node) in model.nodes.iter().enumerate() {
        let (NodeState::Terminal, Some(p)) = (node.state, model.solid(i as NodeId)) else {
            continue;
        };
        let key = ShapeKey::of(&p);
        let mesh = match meshes.entry(key) {
            std::collections::hash_map::Entry::Occupied(e) => e.into_mut(),
            std::collections::hash_map::Entry::Vacant(e) => e.insert(shade(
                p.name(),
                &solid_mesh(&p, geometry),
                options.crease_angle_deg,
            )?),
        };
        if mesh.triangles.is_empty() {
            continue;
        }
        let slot = palette.slot(node.appearance);
        let _ = writeln!(obj, "g {}_{i}", sanitize(model.symbol(node)));
        let _ = writeln!(obj, "usemtl appearance_{}", palette.used[slot as usize]);
        for p in &mesh.positions {
            let w = node.world * Point3::from(*p);
            let [x, y, z] = finite_f32([w.x, w.y, w.z], || {
                format!("a vertex of {} (node {i})", model.symbol(node))
            })?;
            let _ = writeln!(obj, "v {x} {y} {z}");
        }
        for n in &mesh.normals {
            let w = node.world.rotation * Vector3::from(*n);
            let _ = writeln!(obj, "vn {} {} {}", w.x as f32, w.y as f32, w.z as f32);
        }
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|v| v as usize + base);
            let _ = writeln!(obj, "f {a}//{a} {b}//{b} {c}//{c}");
        }
        base += mesh.positions.len();
    }
    let mut mtl = String::from("# castellan vsg materials\n");
    for &index in &palette.used {
        write_material(&mut mtl, &model.appearances[index as usize], index);
    }
    Ok((obj, mtl))
}

/// One `newmtl` block: Ka is the ambient share of the colour, Ns maps shine 0..1 to 0..1000.
fn write_material(mtl: &mut String, a: &Appearance, index: u32) {
    let rgb = |c: [f64; 3]| c.map(|v| unit(v) as f32);
    let [r, g, b] = rgb(a.color);
    let [ar, ag, ab] = rgb(a.color.map(|c| c * unit(a.ambient)));
    let [sr, sg, sb] = rgb(a.specular);
    let [er, eg, eb] = rgb(a.emissive);
    let _ = writeln!(mtl, "\nnewmtl appearance_{index}");
    let _ = writeln!(mtl, "Ka {ar} {ag} {ab}");
    let _ = writeln!(mtl, "Kd {r} {g} {b}");
    let _ = writeln!(mtl, "Ks {sr} {sg} {sb}");
    let _ = writeln!(mtl, "Ke {er} {eg} {eb}");
    let _ = writeln!(mtl, "Ns {}", (unit(a.shine) * 1000.0) as f32);
    let _ = writeln!(mtl, "d {}", unit(1.0 - a.transparency) as f32);
    let _ = writeln!(mtl, "illum 2");
    if let Some(texture) = &a.texture {
        let _ = writeln!(mtl, "map_Kd {texture}");
    }
}

/// Group names end at whitespace in OBJ.
fn sanitize(name: &str) -> std::borrow::Cow<'_, str> {
    if name.is_empty() {
        "shape".into()
    } else if name.contains(char::is_whitespace) {
        name.replace(char::is_whitespace, "_").into()
    } else {
        name.into()
    }
}
