use super::{Axis, Piece, Primitive, ShapeError, Tessellation};
use crate::mesh::TriMesh;

pub(super) fn validate(_p: &Primitive) -> Result<(), ShapeError> { unimplemented!() }
pub(super) fn volume(_p: &Primitive) -> f64 { unimplemented!() }
pub(super) fn size(_p: &Primitive) -> [f64; 3] { unimplemented!() }
pub(super) fn extent(_p: &Primitive, _axis: Axis) -> f64 { unimplemented!() }
pub(super) fn split(_p: &Primitive, _axis: Axis, _intervals: &[(f64, f64)]) -> Result<Vec<Piece>, ShapeError> { unimplemented!() }
pub(super) fn mesh(_p: &Primitive, _t: &Tessellation) -> TriMesh { unimplemented!() }
