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

/// [`MeshBoolean`] by `boolmesh`. The difference subtracts the union of the rest in one step
/// (as Manifold's batched Booleans do), which is faster than subtracting one by one.
#[derive(Clone, Copy, Debug, Default)]
pub struct Manifold;

impl MeshBoolean for Manifold {
    fn combine(&self, op: BoolOp, meshes: &[TriMesh]) -> Result<TriMesh, CsgError> {
        let name = op.name();
        let fail = |why: String| CsgError::Failed { op: name, why };
        let inputs = meshes
            .iter()
            .enumerate()
            .map(|(index, m)| {
                to_manifold(m).map_err(|why| CsgError::BadInput {
                    op: name,
                    index,
                    why,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let fold =
            |items: &[BmManifold], kind: fn() -> OpType| -> Result<Option<BmManifold>, CsgError> {
                let mut acc: Option<BmManifold> = None;
                for m in items {
                    acc = Some(match acc {
                        None => m.clone(),
                        Some(a) => compute_boolean(&a, m, kind()).map_err(fail)?,
                    });
                }
                Ok(acc)
            };
        let result = match op {
            BoolOp::Union => fold(&inputs, || OpType::Add)?,
            BoolOp::Intersection => fold(&inputs, || OpType::Intersect)?,
            BoolOp::Difference => match inputs.split_first() {
                None => None,
                Some((first, rest)) => match fold(rest, || OpType::Add)? {
                    None => Some(first.clone()),
                    Some(cut) => {
                        Some(compute_boolean(first, &cut, OpType::Subtract).map_err(fail)?)
                    }
                },
            },
        };
        let result = result.ok_or(CsgError::NoShapes { op: name })?;
        Ok(from_manifold(&result))
    }
}

fn to_manifold(m: &TriMesh) -> Result<BmManifold, String> {
    if !m.is_closed_oriented() {
        return Err("it has open, non-manifold or inconsistently oriented edges".into());
    }
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
mod tests {
    use super::*;
    use crate::shape::{Primitive, ShapeType, Tessellation};

    fn boxed(size: [f64; 3], at: [f64; 3]) -> TriMesh {
        let mut m = Primitive::new(ShapeType::Box, &size)
            .unwrap()
            .mesh(&Tessellation::default());
        for p in &mut m.positions {
            for k in 0..3 {
                p[k] += at[k];
            }
        }
        m
    }

    #[test]
    fn box_minus_inner_box_is_a_closed_shell() {
        let outer = boxed([4.0, 4.0, 4.0], [0.0; 3]);
        let through = boxed([2.0, 2.0, 6.0], [0.0; 3]);
        let r = Manifold
            .combine(BoolOp::Difference, &[outer, through])
            .unwrap();
        assert!(r.is_closed_oriented());
        assert!((r.signed_volume() - (64.0 - 16.0)).abs() < 1e-9);
    }

    #[test]
    fn union_and_intersection_of_overlapping_boxes() {
        let a = boxed([2.0, 2.0, 2.0], [0.0; 3]);
        let b = boxed([2.0, 2.0, 2.0], [1.0, 0.0, 0.0]);
        let u = Manifold
            .combine(BoolOp::Union, &[a.clone(), b.clone()])
            .unwrap();
        let i = Manifold.combine(BoolOp::Intersection, &[a, b]).unwrap();
        assert!(u.is_closed_oriented() && i.is_closed_oriented());
        assert!((u.signed_volume() - 12.0).abs() < 1e-9);
        assert!((i.signed_volume() - 4.0).abs() < 1e-9);
    }

    #[test]
    fn open_input_is_refused_with_its_index() {
        let a = boxed([1.0; 3], [0.0; 3]);
        let mut b = a.clone();
        b.triangles.pop();
        let e = Manifold.combine(BoolOp::Union, &[a, b]).unwrap_err();
        assert!(matches!(e, CsgError::BadInput { index: 1, .. }), "{e}");
    }
}
