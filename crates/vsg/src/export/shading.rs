//! Vertex normals for the terminal meshes of §7.1.2: faces meeting at a crease angle larger
//! than the threshold get separate (unwelded) vertices, smaller angles get averaged normals,
//! so boxes look flat and cylinders smooth in both exporters.

use std::collections::HashMap;

use super::error::ExportError;
use crate::mesh::TriMesh;

/// A mesh ready for drawing: every vertex has a unit normal.
#[derive(Clone, Debug, Default)]
pub(crate) struct ShadedMesh {
    pub positions: Vec<[f64; 3]>,
    pub normals: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `v / |v|`, or `None` when `v` is (numerically) zero or not finite.
pub(crate) fn normalize(v: [f64; 3]) -> Option<[f64; 3]> {
    let len = dot(v, v).sqrt();
    (len > 1e-300 && len.is_finite()).then(|| v.map(|c| c / len))
}

/// Computes crease-aware normals for `mesh`. A corner's normal is the area-weighted average
/// of the faces around its vertex whose normals lie within `crease_angle_deg` of its own
/// face's normal; corners of one vertex with equal normals share an output vertex.
pub(crate) fn shade(
    kind: &'static str,
    mesh: &TriMesh,
    crease_angle_deg: f64,
) -> Result<ShadedMesh, ExportError> {
    let n = mesh.positions.len();
    let bad = |why: String| ExportError::BadMesh { kind, why };
    // Positions are stored as f32: a vertex must be finite there, not only in f64.
    if let Some(p) = mesh
        .positions
        .iter()
        .find(|p| !p.iter().all(|&c| (c as f32).is_finite()))
    {
        return Err(bad(format!("vertex {p:?} is not a finite 32-bit float")));
    }
    if let Some(t) = mesh
        .triangles
        .iter()
        .find(|t| t.iter().any(|&i| i as usize >= n))
    {
        return Err(bad(format!("triangle {t:?} refers past its {n} vertices")));
    }
    let crease_cos = crease_angle_deg.to_radians().cos();

    // Area-weighted face normals (twice the area) and their unit directions.
    let weighted: Vec<[f64; 3]> = mesh
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            cross(sub(b, a), sub(c, a))
        })
        .collect();
    let units: Vec<Option<[f64; 3]>> = weighted.iter().map(|&w| normalize(w)).collect();

    // Triangles around each vertex, as compressed rows.
    let mut start = vec![0u32; n + 1];
    for t in &mesh.triangles {
        for &i in t {
            start[i as usize + 1] += 1;
        }
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut around = vec![0u32; mesh.triangles.len() * 3];
    for (f, t) in mesh.triangles.iter().enumerate() {
        for &i in t {
            around[fill[i as usize] as usize] = f as u32;
            fill[i as usize] += 1;
        }
    }

    let mut out = ShadedMesh {
        positions: Vec::with_capacity(n),
        normals: Vec::with_capacity(n),
        triangles: Vec::with_capacity(mesh.triangles.len()),
    };
    let mut index: HashMap<(u32, [u64; 3]), u32> = HashMap::with_capacity(n * 2);
    for (f, t) in mesh.triangles.iter().enumerate() {
        let mut corners = [0u32; 3];
        for (corner, &v) in corners.iter_mut().zip(t) {
            let faces = &around[start[v as usize] as usize..start[v as usize + 1] as usize];
            let mut sum = [0.0; 3];
            for &g in faces {
                let include = match (units[f], units[g as usize]) {
                    (Some(a), Some(b)) => dot(a, b) >= crease_cos,
                    // A degenerate face takes the average of all its neighbours.
                    (None, _) => true,
                    (Some(_), None) => false,
                };
                if include {
                    let w = weighted[g as usize];
                    sum = [sum[0] + w[0], sum[1] + w[1], sum[2] + w[2]];
                }
            }
            let normal = normalize(sum).or(units[f]).unwrap_or([0.0, 1.0, 0.0]);
            *corner = *index
                .entry((v, normal.map(f64::to_bits)))
                .or_insert_with(|| {
                    out.positions.push(mesh.positions[v as usize]);
                    out.normals.push(normal);
                    (out.positions.len() - 1) as u32
                });
        }
        out.triangles.push(corners);
    }
    Ok(out)
}
