//! Volumetric Booleans for unique shapes (§7.1.2, figure 7.3): `union()`, `intersection()` and
//! `difference()` combine closed meshes into one closed mesh. The Boolean engine sits behind the
//! small [`MeshBoolean`] trait; [`Manifold`] implements it with `boolmesh` (a pure-Rust port
//! of Manifold).

use boolmesh::prelude::{Manifold as BmManifold, OpType, compute_boolean};

use crate::mesh::TriMesh;

/// The three unique-shape operations of §7.1.2.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BoolOp {
    Union,
    Intersection,
    /// The first shape minus all the others.
    Difference,
}

impl BoolOp {
    pub fn name(self) -> &'static str {
        match self {
            BoolOp::Union => "union",
            BoolOp::Intersection => "intersection",
            BoolOp::Difference => "difference",
        }
    }
}

/// Why a Boolean failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CsgError {
    #[error("{op} needs at least one shape")]
    NoShapes { op: &'static str },
    #[error("shape {index} of the {op} is not a closed 2-manifold mesh: {why}")]
    BadInput {
        op: &'static str,
        index: usize,
        why: String,
    },
    #[error("the {op} failed: {why}")]
    Failed { op: &'static str, why: String },
}

/// A mesh Boolean engine: combines closed, outward-oriented meshes (all in one frame).
pub trait MeshBoolean {
    /// `Union`: all together; `Intersection`: common to all; `Difference`: the first minus the
    /// rest. The result is closed and outward-oriented (possibly empty).
    fn combine(&self, op: BoolOp, meshes: &[TriMesh]) -> Result<TriMesh, CsgError>;
}

/// [`MeshBoolean`] by `boolmesh`. Unions (and the cutters of a difference, which subtracts
/// their union in one step) are batched: shapes whose bounding boxes do not touch are disjoint,
/// so their union is their meshes side by side; overlapping groups are merged pairwise in a
/// balanced tree. A wall minus 100 separate windows is then a single Boolean.
#[derive(Clone, Copy, Debug, Default)]
pub struct Manifold;

impl MeshBoolean for Manifold {
    fn combine(&self, op: BoolOp, meshes: &[TriMesh]) -> Result<TriMesh, CsgError> {
        let name = op.name();
        let fail = |why: String| CsgError::Failed { op: name, why };
        for (index, m) in meshes.iter().enumerate() {
            if !m.is_closed_oriented() {
                return Err(CsgError::BadInput {
                    op: name,
                    index,
                    why: "it has open, non-manifold or inconsistently oriented edges".into(),
                });
            }
        }
        let manifold = |m: &TriMesh, index: usize| {
            to_manifold(m).map_err(|why| CsgError::BadInput {
                op: name,
                index,
                why,
            })
        };
        let Some((first, rest)) = meshes.split_first() else {
            return Err(CsgError::NoShapes { op: name });
        };
        let result = match op {
            BoolOp::Union => union_all(meshes, &fail)?,
            BoolOp::Intersection => {
                let mut acc = Some(manifold(first, 0)?);
                for (i, m) in rest.iter().enumerate() {
                    let Some(a) = acc else { break };
                    acc = boolean(&a, &manifold(m, i + 1)?, OpType::Intersect, &fail)?;
                }
                acc.map_or_else(TriMesh::default, |m| from_manifold(&m))
            }
            BoolOp::Difference if rest.is_empty() => first.clone(),
            BoolOp::Difference => {
                let cut = union_all(rest, &fail)?;
                let cut = to_manifold(&cut).map_err(fail)?;
                boolean(&manifold(first, 0)?, &cut, OpType::Subtract, &fail)?
                    .map_or_else(TriMesh::default, |m| from_manifold(&m))
            }
        };
        Ok(result)
    }
}

/// One `boolmesh` Boolean; `None` when the result is empty (boolmesh reports an empty result
/// as the error "empty pos matrix", as its own tests note).
fn boolean(
    a: &BmManifold,
    b: &BmManifold,
    op: OpType,
    fail: &dyn Fn(String) -> CsgError,
) -> Result<Option<BmManifold>, CsgError> {
    match compute_boolean(a, b, op) {
        Ok(m) => Ok(Some(m)),
        Err(e) if e == "empty pos matrix" => Ok(None),
        Err(e) => Err(fail(e)),
    }
}

/// The union of closed meshes: disjoint groups side by side, each group merged pairwise.
fn union_all(meshes: &[TriMesh], fail: &dyn Fn(String) -> CsgError) -> Result<TriMesh, CsgError> {
    let boxes: Vec<_> = meshes.iter().map(|m| m.bounds()).collect();
    let touch = |a: usize, b: usize| match (boxes[a], boxes[b]) {
        (Some((alo, ahi)), Some((blo, bhi))) => {
            (0..3).all(|k| alo[k] <= bhi[k] + 1e-9 && blo[k] <= ahi[k] + 1e-9)
        }
        _ => false,
    };
    // Union-find over touching bounding boxes.
    let mut parent: Vec<usize> = (0..meshes.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for a in 0..meshes.len() {
        for b in a + 1..meshes.len() {
            if touch(a, b) {
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                parent[ra.max(rb)] = ra.min(rb);
            }
        }
    }
    let mut groups: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for i in 0..meshes.len() {
        groups.entry(root(&mut parent, i)).or_default().push(i);
    }
    let mut out = TriMesh::default();
    for members in groups.values() {
        if let [only] = members.as_slice() {
            out.append(&meshes[*only]);
            continue;
        }
        let mut level = members
            .iter()
            .map(|&i| to_manifold(&meshes[i]).map_err(fail))
            .collect::<Result<Vec<_>, _>>()?;
        while level.len() > 1 {
            let mut next = Vec::with_capacity(level.len().div_ceil(2));
            let mut it = level.into_iter();
            while let Some(a) = it.next() {
                next.push(match it.next() {
                    // The union of two non-empty solids is not empty.
                    Some(b) => boolean(&a, &b, OpType::Add, fail)?.unwrap_or(a),
                    None => a,
                });
            }
            level = next;
        }
        out.append(&from_manifold(&level[0]));
    }
    Ok(out)
}

fn to_manifold(m: &TriMesh) -> Result<BmManifold, String> {
    let pos: Vec<f64> = m.positions.iter().flatten().copied().collect();
    let idx: Vec<usize> = m.triangles.iter().flatten().map(|&i| i as usize).collect();
    BmManifold::new(&pos, &idx)
}

fn from_manifold(m: &BmManifold) -> TriMesh {
    let positions = m.ps.iter().map(|p| [p.x, p.y, p.z]).collect();
    let triangles =
        m.hs.chunks_exact(3)
            .map(|h| [h[0].tail as u32, h[1].tail as u32, h[2].tail as u32])
            .collect();
    TriMesh {
        positions,
        triangles,
    }
}

#[cfg(test)]
mod tests;
