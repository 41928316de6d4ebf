//! The vocabulary the primitive families share (Table 7.1, §7.1.2): the shape types with their
//! parameter names, defaults and allowed split directions ([`ShapeType`], [`Axis`]), the
//! primitive itself ([`Primitive`]: its fields, parameters and unchecked constructor), the
//! pieces of a split ([`Piece`]), how finely curves are meshed ([`Tessellation`]), what can go
//! wrong ([`ShapeError`]) and the one bound on sizes and positions ([`MAX_COORDINATE`]).
//!
//! `shape/mod.rs` validates, measures, splits and meshes a primitive by handing it to its
//! family (`prism`, `revolved`, `wedge`, `spherical`); the families build on this file only,
//! so they and `mod.rs` do not import each other. Everything here is re-exported as
//! `vsg::shape::*`.

use nalgebra::Isometry3;
use serde::Serialize;

use crate::diag::num;

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
}

impl std::fmt::Display for ShapeType {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
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
    pub(super) params: [f64; 6],
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
    /// The parameters, as many as the type has.
    pub fn params(&self) -> &[f64] {
        &self.params[..self.kind.param_names().len()]
    }

    /// Builds a primitive without validation, for family modules that derive pieces from a
    /// valid parent (their parameters are valid by construction).
    pub(super) fn raw(kind: ShapeType, params: &[f64]) -> Primitive {
        let mut all = [0.0; 6];
        all[..params.len()].copy_from_slice(params);
        Primitive { kind, params: all }
    }
}
