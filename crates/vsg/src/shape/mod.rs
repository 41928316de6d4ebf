//! The 18 primitive solids of Table 7.1 (§7.1.2): their parameters and local frames, exact
//! (analytic) volumes, closed meshes, and the splits each one allows.
//!
//! Frames follow §7.1.1 and ARCHITECTURE.md: y is up, every shape is "centred at the origin".
//! Where the text leaves "centre" open, each family module says which point it is.

mod common;
mod prism;
mod revolved;
mod spherical;
mod wedge;

// The types the families share, in a file of their own (the families import it, not this file).
pub use common::{
    Axis, MAX_COORDINATE, Piece, Primitive, ShapeError, ShapeType, Tessellation, within_bounds,
};

use crate::mesh::TriMesh;

/// Relative tolerance for split lengths that must add up to a shape's extent.
pub const FIT_TOLERANCE: f64 = 1e-6;

impl ShapeType {
    /// The family module that validates, measures, splits and meshes this type.
    fn family(self) -> Family {
        match self {
            ShapeType::Box
            | ShapeType::Ramp
            | ShapeType::RampFrustum
            | ShapeType::Parallelepiped => Family::Prism,
            ShapeType::Tetrahedron
            | ShapeType::TetrahedronFrustum
            | ShapeType::TetrahedronSector => Family::Wedge,
            ShapeType::Sphere | ShapeType::SphericalSector => Family::Spherical,
            _ => Family::Revolved,
        }
    }
}

enum Family {
    Prism,
    Revolved,
    Wedge,
    Spherical,
}

impl Primitive {
    /// Validates the parameters (count, finite, in range) and fills optional defaults.
    pub fn new(kind: ShapeType, params: &[f64]) -> Result<Primitive, ShapeError> {
        let names = kind.param_names();
        let required = kind.required_params();
        if params.len() < required || params.len() > names.len() {
            let expected = if required == names.len() {
                required.to_string()
            } else {
                format!("{required} to {}", names.len())
            };
            return Err(ShapeError::ParamCount {
                kind,
                expected,
                names: names.join(", "),
                found: params.len(),
            });
        }
        let mut all = [0.0; 6];
        all[..params.len()].copy_from_slice(params);
        let defaults = kind.default_params();
        all[params.len()..names.len()]
            .copy_from_slice(&defaults[params.len() - required..names.len() - required]);
        for (i, &v) in all[..names.len()].iter().enumerate() {
            if !v.is_finite() {
                return Err(ShapeError::BadParam {
                    kind,
                    name: names[i],
                    value: v,
                    why: "not a finite number".into(),
                });
            }
            if !within_bounds(v) {
                return Err(ShapeError::ParamTooLarge {
                    kind,
                    name: names[i],
                    value: v,
                });
            }
        }
        let p = Primitive { kind, params: all };
        match kind.family() {
            Family::Prism => prism::validate(&p)?,
            Family::Revolved => revolved::validate(&p)?,
            Family::Wedge => wedge::validate(&p)?,
            Family::Spherical => spherical::validate(&p)?,
        }
        // Parameters within bounds can still add up (a parallelepiped's offsets).
        for (axis, size) in [Axis::X, Axis::Y, Axis::Z].into_iter().zip(p.size()) {
            if !within_bounds(size) {
                return Err(ShapeError::TooLarge { kind, axis, size });
            }
        }
        Ok(p)
    }

    /// Exact (analytic) volume.
    pub fn volume(&self) -> f64 {
        match self.kind.family() {
            Family::Prism => prism::volume(self),
            Family::Revolved => revolved::volume(self),
            Family::Wedge => wedge::volume(self),
            Family::Spherical => spherical::volume(self),
        }
    }

    /// Size of the local axis-aligned bounding box along x, y, z.
    pub fn size(&self) -> [f64; 3] {
        match self.kind.family() {
            Family::Prism => prism::size(self),
            Family::Revolved => revolved::size(self),
            Family::Wedge => wedge::size(self),
            Family::Spherical => spherical::size(self),
        }
    }

    /// How long the shape is along a split direction (radians for Theta and Phi); the lengths
    /// of a split must add up to this.
    pub fn extent(&self, axis: Axis) -> Result<f64, ShapeError> {
        self.check_axis(axis)?;
        Ok(match self.kind.family() {
            Family::Prism => prism::extent(self, axis),
            Family::Revolved => revolved::extent(self, axis),
            Family::Wedge => wedge::extent(self, axis),
            Family::Spherical => spherical::extent(self, axis),
        })
    }

    /// Splits the shape along `axis` into pieces of the given lengths, in order from the
    /// axis' start (−x, −y, −z side; the inner boundary for R; angle 0 for Theta and Phi).
    /// Lengths must be positive and add up to [`Primitive::extent`] within [`FIT_TOLERANCE`].
    pub fn split(&self, axis: Axis, lengths: &[f64]) -> Result<Vec<Piece>, ShapeError> {
        let extent = self.extent(axis)?;
        let intervals = fit_intervals(self.kind, axis, extent, lengths)?;
        match self.kind.family() {
            Family::Prism => prism::split(self, axis, &intervals),
            Family::Revolved => revolved::split(self, axis, &intervals),
            Family::Wedge => wedge::split(self, axis, &intervals),
            Family::Spherical => spherical::split(self, axis, &intervals),
        }
    }

    /// A closed, outward-oriented triangle mesh of the solid in its local frame.
    pub fn mesh(&self, tessellation: &Tessellation) -> TriMesh {
        match self.kind.family() {
            Family::Prism => prism::mesh(self, tessellation),
            Family::Revolved => revolved::mesh(self, tessellation),
            Family::Wedge => wedge::mesh(self, tessellation),
            Family::Spherical => spherical::mesh(self, tessellation),
        }
    }

    fn check_axis(&self, axis: Axis) -> Result<(), ShapeError> {
        let allowed = self.kind.split_axes();
        if allowed.contains(&axis) {
            Ok(())
        } else {
            Err(ShapeError::AxisNotAllowed {
                kind: self.kind,
                axis,
                allowed: allowed
                    .iter()
                    .map(|a| a.name())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
        }
    }
}

/// Turns lengths into `(start, end)` intervals over `[0, extent]`, checking they fit; the last
/// end is snapped to `extent` so pieces tile the shape exactly.
fn fit_intervals(
    kind: ShapeType,
    axis: Axis,
    extent: f64,
    lengths: &[f64],
) -> Result<Vec<(f64, f64)>, ShapeError> {
    for (index, &value) in lengths.iter().enumerate() {
        if !(value.is_finite() && value > 0.0) {
            return Err(ShapeError::BadLength { index, value });
        }
    }
    let sum: f64 = lengths.iter().sum();
    if lengths.is_empty() || (sum - extent).abs() > FIT_TOLERANCE * extent.max(1e-12) {
        return Err(ShapeError::LengthsDontFit {
            kind,
            axis,
            sum,
            extent,
        });
    }
    let mut start = 0.0;
    let mut out = Vec::with_capacity(lengths.len());
    for (i, &l) in lengths.iter().enumerate() {
        let end = if i + 1 == lengths.len() {
            extent
        } else {
            start + l
        };
        out.push((start, end));
        start = end;
    }
    Ok(out)
}

#[cfg(test)]
mod tests;
