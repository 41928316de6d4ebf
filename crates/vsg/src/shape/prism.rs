//! The prism family of Table 7.1 (§7.1.2): box, ramp, rampFrustum and parallelepiped — their
//! parameters, local frames, exact volumes, closed meshes and X/Y/Z splits.
//!
//! Frames (y up). Box, ramp and rampFrustum are right prisms over a profile in the x-y plane,
//! extruded along z from −thickness/2 to thickness/2, with the origin at the centre of their
//! bounding box. The rampFrustum profile is a right trapezoid with its vertical side at +x:
//!
//! ```text
//!        (a/2−b, h/2) ______ (a/2, h/2)        y
//!                    /      |                  |
//!                   /       |  h               +-- x
//!                  /________|
//!   (−a/2, −h/2)       a      (a/2, −h/2)      a = length, h = height, b = topLength
//! ```
//!
//! A ramp is the `b = 0` case (a right triangle rising towards +x); `b = a` is a box. The
//! parallelepiped is spanned by e1 = (l, 0, 0), e2 = (o1, h, o2) and e3 = (o3, 0, t) (length,
//! height, thickness, offset1..3), with the origin at its centroid.
//!
//! Departure from Table 7.1: the table's generated-type lists (e.g. "Ramp X: Ramp", "Ramp
//! Frustum X: Ramp/Ramp Frustum/Parallelepiped") are not consistent with any single orientation
//! of the profile. Here the type of every piece follows its geometry: a right trapezoid with no
//! top is a ramp, one with equal parallel sides a box, otherwise a rampFrustum. An X piece left
//! of the profile corner has vertical parallel sides, so it is a ramp or rampFrustum turned by
//! the proper rotation (x', y', z') → (−y', −x', −z'); an X piece straddling the corner would be
//! a pentagonal prism, which is no primitive, and is reported as [`ShapeError::Unsupported`].

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use super::common::{Axis, Piece, Primitive, ShapeError, ShapeType, Tessellation};
use crate::mesh::TriMesh;

/// Relative tolerance for a split meeting the profile corner.
const CORNER_TOLERANCE: f64 = 1e-9;
/// Relative tolerance below which a trapezoid side counts as zero (ramp) or as equal (box).
const SHAPE_TOLERANCE: f64 = 1e-12;

/// A prism-family primitive in geometric terms.
enum Prism {
    /// Right trapezoid prism: bottom length `a`, height `h`, thickness `t`, top length `b`.
    Trapezoid { a: f64, h: f64, t: f64, b: f64 },
    /// Parallelepiped with edge vectors e1, e2, e3 (see the module doc).
    Skewed { l: f64, h: f64, t: f64, o: [f64; 3] },
}

impl Prism {
    fn of(p: &Primitive) -> Prism {
        let v = p.params();
        match p.kind {
            ShapeType::Box => Prism::Trapezoid {
                a: v[0],
                h: v[1],
                t: v[2],
                b: v[0],
            },
            ShapeType::Ramp => Prism::Trapezoid {
                a: v[0],
                h: v[1],
                t: v[2],
                b: 0.0,
            },
            ShapeType::RampFrustum => Prism::Trapezoid {
                a: v[0],
                h: v[1],
                t: v[2],
                b: v[3],
            },
            ShapeType::Parallelepiped => Prism::Skewed {
                l: v[0],
                h: v[1],
                t: v[2],
                o: [v[3], v[4], v[5]],
            },
            other => unreachable!("{other} is not a prism"),
        }
    }
}

/// The primitive for a right trapezoid prism, typed by its geometry.
fn trapezoid(a: f64, h: f64, t: f64, b: f64) -> Primitive {
    if b <= SHAPE_TOLERANCE * a {
        Primitive::raw(ShapeType::Ramp, &[a, h, t])
    } else if b >= a * (1.0 - SHAPE_TOLERANCE) {
        Primitive::raw(ShapeType::Box, &[a, h, t])
    } else {
        Primitive::raw(ShapeType::RampFrustum, &[a, h, t, b])
    }
}

fn piece(primitive: Primitive, at: [f64; 3], rotation: UnitQuaternion<f64>) -> Piece {
    Piece {
        primitive,
        transform: Isometry3::from_parts(Translation3::new(at[0], at[1], at[2]), rotation),
    }
}

/// The rotation taking a canonical ramp(Frustum) to an X piece left of the profile corner:
/// (x', y', z') → (−y', −x', −z'), i.e. Rz(−90°) followed by Ry(180°).
fn turned() -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::y_axis(), PI)
        * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), -FRAC_PI_2)
}

pub(super) fn validate(p: &Primitive) -> Result<(), ShapeError> {
    let v = p.params();
    let names = p.kind.param_names();
    let bad = |i: usize, why: &str| ShapeError::BadParam {
        kind: p.kind,
        name: names[i],
        value: v[i],
        why: why.into(),
    };
    if let Some(i) = (0..3).find(|&i| v[i] <= 0.0) {
        return Err(bad(i, "must be positive"));
    }
    if p.kind == ShapeType::RampFrustum && !(0.0..=v[0]).contains(&v[3]) {
        return Err(bad(3, "must lie between 0 and length"));
    }
    Ok(())
}

pub(super) fn volume(p: &Primitive) -> f64 {
    match Prism::of(p) {
        Prism::Trapezoid { a, h, t, b } => (a + b) / 2.0 * h * t,
        Prism::Skewed { l, h, t, .. } => l * h * t,
    }
}

pub(super) fn size(p: &Primitive) -> [f64; 3] {
    match Prism::of(p) {
        Prism::Trapezoid { a, h, t, .. } => [a, h, t],
        Prism::Skewed { l, h, t, o } => [l + o[0].abs() + o[2].abs(), h, t + o[1].abs()],
    }
}

pub(super) fn extent(p: &Primitive, axis: Axis) -> f64 {
    let v = p.params();
    match axis {
        Axis::X => v[0],
        Axis::Y => v[1],
        Axis::Z => v[2],
        other => unreachable!("{} has no {other} extent", p.kind),
    }
}

pub(super) fn split(
    p: &Primitive,
    axis: Axis,
    intervals: &[(f64, f64)],
) -> Result<Vec<Piece>, ShapeError> {
    let id = UnitQuaternion::identity();
    let mid = |&(s, e): &(f64, f64)| (s + e) / 2.0;
    match (Prism::of(p), axis) {
        (Prism::Trapezoid { a, h, t, b }, Axis::Z) => Ok(intervals
            .iter()
            .map(|iv| {
                piece(
                    trapezoid(a, h, iv.1 - iv.0, b),
                    [0.0, 0.0, mid(iv) - t / 2.0],
                    id,
                )
            })
            .collect()),
        (Prism::Trapezoid { a, h, t, b }, Axis::Y) => {
            // Width of the section at height y above the bottom; its right end is at x = a/2.
            let width = |y: f64| if y >= h { b } else { a - (a - b) * (y / h) };
            Ok(intervals
                .iter()
                .map(|iv| {
                    let (w0, w1) = (width(iv.0), width(iv.1));
                    let at = [(a - w0) / 2.0, mid(iv) - h / 2.0, 0.0];
                    piece(trapezoid(w0, iv.1 - iv.0, t, w1), at, id)
                })
                .collect())
        }
        (Prism::Trapezoid { a, h, t, b }, Axis::X) => {
            let corner = a - b; // from the −x end: sloped top left of it, full height right
            let tol = CORNER_TOLERANCE * a;
            intervals
                .iter()
                .map(|&(u0, u1)| {
                    let (w, x) = (u1 - u0, (u0 + u1) / 2.0 - a / 2.0);
                    if u0 >= corner - tol {
                        Ok(piece(
                            Primitive::raw(ShapeType::Box, &[w, h, t]),
                            [x, 0.0, 0.0],
                            id,
                        ))
                    } else if u1 <= corner + tol {
                        let y0 = h * u0 / corner;
                        let y1 = h * u1.min(corner) / corner;
                        let at = [x, y1 / 2.0 - h / 2.0, 0.0];
                        Ok(piece(trapezoid(y1, w, t, y0), at, turned()))
                    } else {
                        Err(ShapeError::Unsupported(format!(
                            "splitting a {} along X at {u0}..{u1} would cut across its profile \
                             corner at x = {corner} (from its start); put a split there",
                            p.kind
                        )))
                    }
                })
                .collect()
        }
        (Prism::Skewed { l, h, t, o }, axis @ (Axis::X | Axis::Y | Axis::Z)) => {
            let (e1, e2, e3) = ([l, 0.0, 0.0], [o[0], h, o[1]], [o[2], 0.0, t]);
            let (edge, whole) = match axis {
                Axis::X => (e1, l),
                Axis::Y => (e2, h),
                _ => (e3, t),
            };
            Ok(intervals
                .iter()
                .map(|iv| {
                    let f = (iv.1 - iv.0) / whole;
                    let params = match axis {
                        Axis::X => [iv.1 - iv.0, h, t, o[0], o[1], o[2]],
                        Axis::Y => [l, iv.1 - iv.0, t, o[0] * f, o[1] * f, o[2]],
                        _ => [l, h, iv.1 - iv.0, o[0], o[1], o[2] * f],
                    };
                    let shift = mid(iv) / whole - 0.5;
                    let prim = Primitive::raw(ShapeType::Parallelepiped, &params);
                    piece(prim, edge.map(|c| c * shift), id)
                })
                .collect())
        }
        (_, axis) => Err(ShapeError::Unsupported(format!(
            "{} cannot be split along {axis}",
            p.kind
        ))),
    }
}

pub(super) fn mesh(p: &Primitive, _t: &Tessellation) -> TriMesh {
    match Prism::of(p) {
        Prism::Trapezoid { a, h, t, b } => {
            let mut profile = vec![
                [-a / 2.0, -h / 2.0],
                [a / 2.0, -h / 2.0],
                [a / 2.0, h / 2.0],
            ];
            if b > SHAPE_TOLERANCE * a {
                profile.push([a / 2.0 - b, h / 2.0]);
            }
            extrude(&profile, t)
        }
        Prism::Skewed { l, h, t, o } => {
            let (e1, e2, e3) = ([l, 0.0, 0.0], [o[0], h, o[1]], [o[2], 0.0, t]);
            let mut m = TriMesh::default();
            for n in 0..8 {
                let f = [n & 1, (n >> 1) & 1, (n >> 2) & 1].map(|b| b as f64 - 0.5);
                m.push_vertex(std::array::from_fn(|c| {
                    f[0] * e1[c] + f[1] * e2[c] + f[2] * e3[c]
                }));
            }
            // Corner n = i + 2j + 4k; faces counter-clockwise seen from outside (det > 0).
            for face in [
                [0, 4, 6, 2],
                [1, 3, 7, 5],
                [0, 1, 5, 4],
                [2, 6, 7, 3],
                [0, 2, 3, 1],
                [4, 5, 7, 6],
            ] {
                m.push_polygon(&face);
            }
            m
        }
    }
}

/// A right prism over a convex counter-clockwise profile in the x-y plane, z in [−t/2, t/2].
fn extrude(profile: &[[f64; 2]], t: f64) -> TriMesh {
    let mut m = TriMesh::default();
    for z in [-t / 2.0, t / 2.0] {
        for &[x, y] in profile {
            m.push_vertex([x, y, z]);
        }
    }
    let n = profile.len() as u32;
    m.push_polygon(&(0..n).rev().collect::<Vec<_>>());
    m.push_polygon(&(n..2 * n).collect::<Vec<_>>());
    for i in 0..n {
        let j = (i + 1) % n;
        m.push_polygon(&[i, j, n + j, n + i]);
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;

    fn prim(kind: ShapeType, v: &[f64]) -> Primitive {
        Primitive::new(kind, v).unwrap()
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
    }

    /// Piece vertices in the parent frame.
    fn placed(q: &Piece) -> Vec<[f64; 3]> {
        let m = q.primitive.mesh(&Tessellation::default());
        let p = |v: &[f64; 3]| q.transform * Point3::new(v[0], v[1], v[2]);
        m.positions.iter().map(|v| p(v).coords.into()).collect()
    }

    fn same_points(mut got: Vec<[f64; 3]>, mut want: Vec<[f64; 3]>) {
        let key = |v: &[f64; 3]| v.map(|c| (c * 1e6).round() as i64);
        got.sort_by_key(key);
        want.sort_by_key(key);
        assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
        for (g, w) in got.iter().zip(&want) {
            assert!((0..3).all(|k| close(g[k], w[k])), "{got:?} vs {want:?}");
        }
    }

    /// Whether a point of the local frame lies in the solid (within a small tolerance).
    fn contains(p: &Primitive, x: [f64; 3]) -> bool {
        let inside = |f: [f64; 3]| f.iter().all(|c| c.abs() <= 0.5 + 1e-9);
        match Prism::of(p) {
            Prism::Trapezoid { a, h, t, b } => {
                let y = x[1] / h + 0.5; // 0 at the bottom, 1 at the top
                let left = -a / 2.0 + (a - b) * y - 1e-9 * a;
                inside([x[0] / a, x[1] / h, x[2] / t]) && x[0] >= left
            }
            Prism::Skewed { l, h, t, o } => {
                let j = x[1] / h;
                let k = (x[2] - j * o[1]) / t;
                inside([(x[0] - j * o[0] - k * o[2]) / l, j, k])
            }
        }
    }

    fn check(p: &Primitive, axis: Axis, fractions: &[f64]) -> Vec<Piece> {
        crate::shape::tests::check_planar_split(p, axis, fractions, contains)
    }

    fn kinds(pieces: &[Piece]) -> Vec<ShapeType> {
        pieces.iter().map(|q| q.primitive.kind).collect()
    }

    #[test]
    fn volumes_of_hand_computed_cases() {
        assert_eq!(prim(ShapeType::Box, &[4.0, 3.0, 2.0]).volume(), 24.0);
        assert_eq!(prim(ShapeType::Ramp, &[4.0, 3.0, 2.0]).volume(), 12.0);
        assert_eq!(
            prim(ShapeType::RampFrustum, &[4.0, 3.0, 2.0, 1.5]).volume(),
            16.5
        );
        let pp = prim(ShapeType::Parallelepiped, &[4.0, 3.0, 2.0, 0.5, 0.3, -0.4]);
        assert_eq!(pp.volume(), 24.0);
        let s = pp.size();
        assert!(
            close(s[0], 4.9) && close(s[1], 3.0) && close(s[2], 2.3),
            "{s:?}"
        );
    }

    #[test]
    fn invalid_parameters_are_rejected() {
        let err = |k, v: &[f64]| matches!(Primitive::new(k, v), Err(ShapeError::BadParam { .. }));
        assert!(err(ShapeType::Box, &[0.0, 1.0, 1.0]));
        assert!(err(ShapeType::Ramp, &[1.0, -1.0, 1.0]));
        assert!(err(ShapeType::RampFrustum, &[1.0, 1.0, 1.0, 1.5]));
        assert!(err(ShapeType::RampFrustum, &[1.0, 1.0, 1.0, -0.1]));
        assert!(Primitive::new(ShapeType::RampFrustum, &[1.0, 1.0, 1.0, 1.0]).is_ok());
        assert!(
            Primitive::new(ShapeType::Parallelepiped, &[1.0, 1.0, 1.0, -3.0, 2.0, 5.0]).is_ok()
        );
    }

    #[test]
    fn all_prisms_split_along_every_axis() {
        for (kind, v) in [
            (ShapeType::Box, &[4.0, 3.0, 2.0][..]),
            (ShapeType::Ramp, &[4.0, 3.0, 2.0]),
            (ShapeType::RampFrustum, &[4.0, 3.0, 2.0, 1.2]),
            (ShapeType::RampFrustum, &[4.0, 3.0, 2.0, 4.0]),
            (ShapeType::RampFrustum, &[4.0, 3.0, 2.0, 0.0]),
            (ShapeType::Parallelepiped, &[4.0, 3.0, 2.0, 0.5, 0.3, -0.4]),
        ] {
            let p = prim(kind, v);
            for axis in [Axis::X, Axis::Y, Axis::Z] {
                assert_eq!(check(&p, axis, &[0.25, 0.45, 0.3]).len(), 3);
                assert_eq!(check(&p, axis, &[0.7, 0.3]).len(), 2);
            }
        }
    }

    #[test]
    fn ramp_x_split_pieces_are_rotated_ramps_and_frusta() {
        let p = prim(ShapeType::Ramp, &[4.0, 3.0, 2.0]);
        let pieces = check(&p, Axis::X, &[0.25, 0.75]);
        assert_eq!(kinds(&pieces), [ShapeType::Ramp, ShapeType::RampFrustum]);
        assert_eq!(pieces[0].primitive.params(), &[0.75, 1.0, 2.0]);
        assert_eq!(pieces[1].primitive.params(), &[3.0, 3.0, 2.0, 0.75]);
        let both = |pts: &[[f64; 2]]| {
            let z = |z: f64| pts.iter().map(move |&[x, y]| [x, y, z]);
            z(-1.0).chain(z(1.0)).collect::<Vec<_>>()
        };
        same_points(
            placed(&pieces[0]),
            both(&[[-2.0, -1.5], [-1.0, -1.5], [-1.0, -0.75]]),
        );
        same_points(
            placed(&pieces[1]),
            both(&[[-1.0, -1.5], [2.0, -1.5], [2.0, 1.5], [-1.0, -0.75]]),
        );
        // The rotation maps the canonical frame as (x', y', z') -> (-y', -x', -z').
        let r = pieces[1].transform.rotation * Vector3::new(1.0, 2.0, 3.0);
        assert!((r - Vector3::new(-2.0, -1.0, -3.0)).norm() < 1e-12);
    }

    #[test]
    fn ramp_frustum_x_split_at_the_corner_gives_ramp_frustum_and_box() {
        let p = prim(ShapeType::RampFrustum, &[4.0, 3.0, 2.0, 1.5]);
        let pieces = check(&p, Axis::X, &[1.0 / 4.0, 1.5 / 4.0, 1.5 / 4.0]);
        let want = [ShapeType::Ramp, ShapeType::RampFrustum, ShapeType::Box];
        assert_eq!(kinds(&pieces), want);
        assert_eq!(pieces[1].primitive.params(), &[3.0, 1.5, 2.0, 1.2]);
        assert!(close(pieces[2].transform.translation.vector.x, 1.25));
    }

    #[test]
    fn ramp_frustum_x_split_across_the_corner_is_unsupported() {
        let p = prim(ShapeType::RampFrustum, &[4.0, 3.0, 2.0, 1.5]);
        match p.split(Axis::X, &[1.0, 1.8, 1.2]) {
            Err(ShapeError::Unsupported(msg)) => {
                assert!(
                    msg.contains("at 1..2.8") && msg.contains("x = 2.5"),
                    "{msg}"
                );
            }
            other => panic!("expected Unsupported, got {other:?}"),
        }
    }

    #[test]
    fn y_split_types_and_centres_follow_geometry() {
        let p = prim(ShapeType::Ramp, &[4.0, 3.0, 2.0]);
        let pieces = check(&p, Axis::Y, &[1.0 / 3.0, 2.0 / 3.0]);
        assert_eq!(kinds(&pieces), [ShapeType::RampFrustum, ShapeType::Ramp]);
        assert!(close(pieces[0].primitive.params()[3], 4.0 * 2.0 / 3.0));
        assert!(close(pieces[1].primitive.params()[0], 4.0 * 2.0 / 3.0));
        let c = pieces[1].transform.translation.vector;
        assert!(
            close(c.x, 2.0 - 4.0 / 3.0) && close(c.y, 0.5) && c.z == 0.0,
            "{c}"
        );
        let boxy = prim(ShapeType::RampFrustum, &[4.0, 3.0, 2.0, 4.0]);
        assert!(
            kinds(&check(&boxy, Axis::Y, &[0.5, 0.5]))
                .iter()
                .all(|&k| k == ShapeType::Box)
        );
    }

    #[test]
    fn parallelepiped_y_split_scales_its_offsets() {
        let p = prim(ShapeType::Parallelepiped, &[4.0, 3.0, 2.0, 0.6, 0.3, -0.4]);
        let pieces = check(&p, Axis::Y, &[1.0 / 3.0, 2.0 / 3.0]);
        let q = pieces[1].primitive.params();
        assert!(close(q[1], 2.0) && close(q[3], 0.4) && close(q[4], 0.2) && q[5] == -0.4);
        let c = pieces[1].transform.translation.vector;
        assert!((c - Vector3::new(0.1, 0.5, 0.05)).norm() < 1e-12, "{c}");
    }
}
