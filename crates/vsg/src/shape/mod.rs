//! The 18 primitive solids of Table 7.1 (§7.1.2): their parameters and local frames, exact
//! (analytic) volumes, closed meshes, and the splits each one allows.
//!
//! Frames follow §7.1.1 and ARCHITECTURE.md: y is up, every shape is "centred at the origin".
//! Where the text leaves "centre" open, each family module says which point it is.

mod prism;
mod revolved;
mod spherical;
mod wedge;

use nalgebra::Isometry3;
use serde::Serialize;

use crate::diag::num;
use crate::mesh::TriMesh;

/// Relative tolerance for split lengths that must add up to a shape's extent.
pub const FIT_TOLERANCE: f64 = 1e-6;

/// Largest magnitude, in metres, of any shape size or parameter and of any shape position: the
/// one bound on a model's geometry. The exporters store 32-bit floats (glTF allows no other),
/// whose steps are already 1 m at 1e7 m and which overflow at 3.4e38, so larger values can only
/// be mistakes (`1e308`, `--set w=1e39`); the largest castle is under 1 km, and 1e7 m still
/// admits georeferenced (UTM) coordinates. With sizes and positions within it, every mesh
/// vertex lies within a few times 1e7 m of the origin, far inside f32.
pub const MAX_COORDINATE: f64 = 1e7;

/// Whether `v` is a finite number within [`MAX_COORDINATE`] of zero.
pub fn within_bounds(v: f64) -> bool {
    v.abs() <= MAX_COORDINATE
}

/// The shape types of Table 7.1 (the unique shape of §7.1.2 is not a primitive).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "camelCase")]
pub enum ShapeType {
    Box,
    Ramp,
    RampFrustum,
    Parallelepiped,
    Cylinder,
    ExtrudedRing,
    ExtrudedFan,
    CylindricalSector,
    Cone,
    ConicFrustum,
    ConicRing,
    ConicFan,
    ConicSector,
    Tetrahedron,
    TetrahedronFrustum,
    TetrahedronSector,
    Sphere,
    SphericalSector,
}

/// A split direction of Table 7.1: three Cartesian axes of the shape's frame, and radius,
/// azimuth (Theta, about +y) and polar angle (Phi, from +y) about its axis or centre.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Axis {
    X,
    Y,
    Z,
    R,
    Theta,
    Phi,
}

impl Axis {
    /// Parses `X`, `Y`, `Z`, `R`, `Theta`, `Phi` (case-insensitive).
    pub fn parse(name: &str) -> Option<Axis> {
        Some(match name.to_ascii_lowercase().as_str() {
            "x" => Axis::X,
            "y" => Axis::Y,
            "z" => Axis::Z,
            "r" => Axis::R,
            "theta" => Axis::Theta,
            "phi" => Axis::Phi,
            _ => return None,
        })
    }

    pub fn name(self) -> &'static str {
        match self {
            Axis::X => "X",
            Axis::Y => "Y",
            Axis::Z => "Z",
            Axis::R => "R",
            Axis::Theta => "Theta",
            Axis::Phi => "Phi",
        }
    }
}

impl std::fmt::Display for Axis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl ShapeType {
    pub const ALL: [ShapeType; 18] = [
        ShapeType::Box,
        ShapeType::Ramp,
        ShapeType::RampFrustum,
        ShapeType::Parallelepiped,
        ShapeType::Cylinder,
        ShapeType::ExtrudedRing,
        ShapeType::ExtrudedFan,
        ShapeType::CylindricalSector,
        ShapeType::Cone,
        ShapeType::ConicFrustum,
        ShapeType::ConicRing,
        ShapeType::ConicFan,
        ShapeType::ConicSector,
        ShapeType::Tetrahedron,
        ShapeType::TetrahedronFrustum,
        ShapeType::TetrahedronSector,
        ShapeType::Sphere,
        ShapeType::SphericalSector,
    ];

    /// The name used in `I("name", {...})`.
    pub fn name(self) -> &'static str {
        match self {
            ShapeType::Box => "box",
            ShapeType::Ramp => "ramp",
            ShapeType::RampFrustum => "rampFrustum",
            ShapeType::Parallelepiped => "parallelepiped",
            ShapeType::Cylinder => "cylinder",
            ShapeType::ExtrudedRing => "extrudedRing",
            ShapeType::ExtrudedFan => "extrudedFan",
            ShapeType::CylindricalSector => "cylindricalSector",
            ShapeType::Cone => "cone",
            ShapeType::ConicFrustum => "conicFrustum",
            ShapeType::ConicRing => "conicRing",
            ShapeType::ConicFan => "conicFan",
            ShapeType::ConicSector => "conicSector",
            ShapeType::Tetrahedron => "tetrahedron",
            ShapeType::TetrahedronFrustum => "tetrahedronFrustum",
            ShapeType::TetrahedronSector => "tetrahedronSector",
            ShapeType::Sphere => "sphere",
            ShapeType::SphericalSector => "sphericalSector",
        }
    }

    /// Looks a type up by name, ignoring case, spaces, `_` and `-` ("Conic Frustum",
    /// "conic_frustum" and "conicFrustum" are one type); "coneFrustum" is accepted as Table 7.1
    /// spells it once.
    pub fn parse(name: &str) -> Option<ShapeType> {
        let key: String = name
            .chars()
            .filter(|c| c.is_ascii_alphanumeric())
            .map(|c| c.to_ascii_lowercase())
            .collect();
        if key == "conefrustum" {
            return Some(ShapeType::ConicFrustum);
        }
        ShapeType::ALL
            .into_iter()
            .find(|t| t.name().to_ascii_lowercase() == key)
    }

    /// Parameter names in order (Table 7.1); the first [`ShapeType::required_params`] are
    /// required, the rest optional with the defaults of [`ShapeType::default_params`].
    pub fn param_names(self) -> &'static [&'static str] {
        match self {
            ShapeType::Box | ShapeType::Ramp => &["length", "height", "thickness"],
            ShapeType::RampFrustum => &["length", "height", "thickness", "topLength"],
            ShapeType::Parallelepiped => &[
                "length",
                "height",
                "thickness",
                "offset1",
                "offset2",
                "offset3",
            ],
            ShapeType::Cylinder | ShapeType::Cone => &["radius", "height"],
            ShapeType::ExtrudedRing => &["radius", "height", "innerRadius"],
            ShapeType::ExtrudedFan | ShapeType::ConicFan => &["radius", "height", "angle"],
            ShapeType::CylindricalSector => &["radius", "height", "innerRadius", "angle"],
            ShapeType::ConicFrustum => &["radius", "height", "topRadius"],
            ShapeType::ConicRing => &["radius", "height", "topRadius", "innerRadius"],
            ShapeType::ConicSector => {
                &["bottomRadius", "height", "angle", "topRadius", "thickness"]
            }
            ShapeType::Tetrahedron => &["edge1", "edge2", "height", "angle"],
            ShapeType::TetrahedronFrustum => &["edge1", "edge2", "height", "angle", "topEdge1"],
            ShapeType::TetrahedronSector => {
                &["edge1", "edge2", "height", "angle", "topEdge1", "split"]
            }
            ShapeType::Sphere => &["radius"],
            ShapeType::SphericalSector => &[
                "radius",
                "thetaAngle",
                "phiAngle",
                "innerRadius",
                "phiStart",
            ],
        }
    }

    /// How many leading parameters must be given.
    pub fn required_params(self) -> usize {
        match self {
            ShapeType::SphericalSector => 3,
            other => other.param_names().len(),
        }
    }

    /// Defaults of the optional trailing parameters (a departure from Table 7.1, which gives a
    /// spherical sector no inner radius or polar start: without them an R or Phi split of a
    /// sector could not be represented).
    pub fn default_params(self) -> &'static [f64] {
        match self {
            ShapeType::SphericalSector => &[0.0, 0.0],
            _ => &[],
        }
    }

    /// The split directions Table 7.1 allows for this type.
    pub fn split_axes(self) -> &'static [Axis] {
        use Axis::*;
        match self {
            ShapeType::Box
            | ShapeType::Ramp
            | ShapeType::RampFrustum
            | ShapeType::Parallelepiped => &[X, Y, Z],
            ShapeType::Cylinder
            | ShapeType::ExtrudedRing
            | ShapeType::ExtrudedFan
            | ShapeType::CylindricalSector
            | ShapeType::ConicFrustum
            | ShapeType::ConicRing
            | ShapeType::ConicSector
            | ShapeType::TetrahedronFrustum
            | ShapeType::TetrahedronSector => &[R, Y, Theta],
            ShapeType::Cone | ShapeType::ConicFan | ShapeType::Tetrahedron => &[Y, Theta],
            ShapeType::Sphere | ShapeType::SphericalSector => &[R, Theta, Phi],
        }
    }

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

impl std::fmt::Display for ShapeType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

enum Family {
    Prism,
    Revolved,
    Wedge,
    Spherical,
}

/// What can be wrong with a shape or a split of it.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ShapeError {
    #[error("{kind} takes {expected} parameters ({names}), found {found}")]
    ParamCount {
        kind: ShapeType,
        expected: String,
        names: String,
        found: usize,
    },
    #[error("{kind} parameter {name} = {} is invalid: {why}", num(*.value))]
    BadParam {
        kind: ShapeType,
        name: &'static str,
        value: f64,
        why: String,
    },
    #[error("{kind} cannot be split along {axis}; Table 7.1 allows {allowed}")]
    AxisNotAllowed {
        kind: ShapeType,
        axis: Axis,
        allowed: String,
    },
    #[error("split length #{index} is {}; lengths must be finite and positive", num(*.value))]
    BadLength { index: usize, value: f64 },
    #[error(
        "split lengths along {axis} add up to {}, but the {kind} measures {} along {axis}",
        num(*.sum),
        num(*.extent)
    )]
    LengthsDontFit {
        kind: ShapeType,
        axis: Axis,
        sum: f64,
        extent: f64,
    },
    #[error(
        "{kind} parameter {name} = {value:e} is larger than the {max:e} m a model may span (shapes are stored as 32-bit floats)",
        max = MAX_COORDINATE
    )]
    ParamTooLarge {
        kind: ShapeType,
        name: &'static str,
        value: f64,
    },
    #[error(
        "{kind} would measure {size:e} m along {axis}, more than the {max:e} m a model may span (shapes are stored as 32-bit floats)",
        max = MAX_COORDINATE
    )]
    TooLarge {
        kind: ShapeType,
        axis: Axis,
        size: f64,
    },
    #[error("{0}")]
    Unsupported(String),
}

/// A primitive solid: its type and parameters (unused trailing slots are zero).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Primitive {
    pub kind: ShapeType,
    params: [f64; 6],
}

/// One piece of a split: a primitive and where its frame sits in the frame of the split shape.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    pub primitive: Primitive,
    pub transform: Isometry3<f64>,
}

/// How finely curved surfaces are meshed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tessellation {
    /// Segments around a full circle (partial arcs get their share, at least one).
    pub segments: u32,
}

impl Default for Tessellation {
    fn default() -> Self {
        Tessellation { segments: 32 }
    }
}

impl Tessellation {
    /// Most segments around a full circle (the binary's `--segments` bound): a library caller's
    /// `u32::MAX` would otherwise ask for meshes of billions of triangles.
    pub const MAX_SEGMENTS: u32 = 4096;

    /// Segments for an arc of `angle` radians.
    pub fn arc_segments(&self, angle: f64) -> u32 {
        let full = self.segments.clamp(3, Self::MAX_SEGMENTS) as f64;
        ((full * angle / std::f64::consts::TAU).ceil() as u32).max(1)
    }
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

    /// The parameters, as many as the type has.
    pub fn params(&self) -> &[f64] {
        &self.params[..self.kind.param_names().len()]
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

    /// Builds a primitive without validation, for family modules that derive pieces from a
    /// valid parent (their parameters are valid by construction).
    fn raw(kind: ShapeType, params: &[f64]) -> Primitive {
        let mut all = [0.0; 6];
        all[..params.len()].copy_from_slice(params);
        Primitive { kind, params: all }
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
