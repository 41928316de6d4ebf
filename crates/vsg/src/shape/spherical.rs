//! Spherical solids of Table 7.1 (§7.1.2): the sphere and the spherical sector, one family of
//! spherical-shell sectors about the sphere's centre. Departure from Table 7.1: a sector takes
//! two optional trailing parameters, innerRadius and phiStart (default 0), so that the pieces
//! of R and Phi splits are representable.
//!
//! ```text
//!               y ^  φ = 0 (pole)          sphericalSector(radius, thetaAngle, phiAngle,
//!                 |  .                                     innerRadius = 0, phiStart = 0):
//!                 | /φ0 ·  outer ρ = radius    ri ≤ ρ ≤ radius,
//!                 |/ ·   ·                     0 ≤ θ ≤ thetaAngle (about +y),
//!          -------o-------·-----> x            φ0 ≤ φ ≤ φ0 + phiAngle ≤ π (from +y);
//!                /|\  ri  ·                 point (ρ sin φ cos θ, ρ cos φ, −ρ sin φ sin θ).
//!             z /θ| φ1 ·                    sphere(radius) = sector(radius, 2π, π).
//!                 |                         Origin at the sphere centre.
//! ```

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use nalgebra::{Isometry3, Vector3};

use super::common::{Axis, Piece, Primitive, ShapeError, ShapeType, Tessellation};
use super::revolved::{ANGLE_EPS, revolve};
use crate::mesh::TriMesh;

/// The common parametrisation of the family.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Sph {
    r: f64,
    theta: f64,
    phi: f64,
    ri: f64,
    p0: f64,
}

impl Sph {
    fn of(p: &Primitive) -> Sph {
        let v = p.params();
        match p.kind {
            ShapeType::Sphere => Sph {
                r: v[0],
                theta: TAU,
                phi: PI,
                ri: 0.0,
                p0: 0.0,
            },
            ShapeType::SphericalSector => Sph {
                r: v[0],
                theta: v[1],
                phi: v[2],
                ri: v[3],
                p0: v[4],
            },
            other => unreachable!("{other} is not spherical"),
        }
    }

    /// The polar end angle.
    fn p1(&self) -> f64 {
        (self.p0 + self.phi).min(PI)
    }

    fn volume(&self) -> f64 {
        self.theta / 3.0 * (self.r.powi(3) - self.ri.powi(3)) * (self.p0.cos() - self.p1().cos())
    }

    fn primitive(&self) -> Primitive {
        let Sph {
            r,
            theta,
            phi,
            ri,
            p0,
        } = *self;
        if theta >= TAU - ANGLE_EPS && p0 == 0.0 && phi >= PI - ANGLE_EPS && ri == 0.0 {
            Primitive::raw(ShapeType::Sphere, &[r])
        } else {
            Primitive::raw(ShapeType::SphericalSector, &[r, theta, phi, ri, p0])
        }
    }
}

pub(super) fn validate(p: &Primitive) -> Result<(), ShapeError> {
    let v = p.params();
    let names = p.kind.param_names();
    let bad = |i: usize, why: &str| {
        Err(ShapeError::BadParam {
            kind: p.kind,
            name: names[i],
            value: v[i],
            why: why.into(),
        })
    };
    if v[0] <= 0.0 {
        return bad(0, "radius must be positive");
    }
    if p.kind == ShapeType::Sphere {
        return Ok(());
    }
    if !(v[1] > 0.0 && v[1] <= TAU + ANGLE_EPS) {
        return bad(1, "thetaAngle must be in (0, 2π]");
    }
    if v[2] <= 0.0 {
        return bad(2, "phiAngle must be positive");
    }
    if v[3] < 0.0 {
        return bad(3, "innerRadius must not be negative");
    }
    if v[3] >= v[0] {
        return bad(3, "innerRadius must be smaller than radius");
    }
    if v[4] < 0.0 {
        return bad(4, "phiStart must not be negative");
    }
    if v[4] + v[2] > PI + ANGLE_EPS {
        return bad(2, "phiStart + phiAngle must not exceed π");
    }
    Ok(())
}

pub(super) fn volume(p: &Primitive) -> f64 {
    Sph::of(p).volume()
}

/// The bounding box: extremes of each coordinate lie where ρ, θ and φ are at a bound or at a
/// critical angle (θ a multiple of π/2, φ = π/2) inside the ranges.
pub(super) fn size(p: &Primitive) -> [f64; 3] {
    let g = Sph::of(p);
    let quarter = [FRAC_PI_2, PI, 3.0 * FRAC_PI_2];
    let mut thetas = vec![0.0, g.theta.min(TAU)];
    thetas.extend(quarter.into_iter().filter(|&t| t <= g.theta));
    let mut phis = vec![g.p0, g.p1()];
    if g.p0 <= FRAC_PI_2 && FRAC_PI_2 <= g.p1() {
        phis.push(FRAC_PI_2);
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for &t in &thetas {
        for &f in &phis {
            for rho in [g.ri, g.r] {
                let q = [
                    rho * f.sin() * t.cos(),
                    rho * f.cos(),
                    -rho * f.sin() * t.sin(),
                ];
                for k in 0..3 {
                    lo[k] = lo[k].min(q[k]);
                    hi[k] = hi[k].max(q[k]);
                }
            }
        }
    }
    [0, 1, 2].map(|k| hi[k] - lo[k])
}

pub(super) fn extent(p: &Primitive, axis: Axis) -> f64 {
    let g = Sph::of(p);
    match axis {
        Axis::R => g.r - g.ri,
        Axis::Theta => g.theta,
        Axis::Phi => g.phi,
        other => unreachable!("axis {other} is checked before extent"),
    }
}

pub(super) fn split(
    p: &Primitive,
    axis: Axis,
    intervals: &[(f64, f64)],
) -> Result<Vec<Piece>, ShapeError> {
    let g = Sph::of(p);
    let last = intervals.len().saturating_sub(1);
    let at_centre = |q: Sph| Piece {
        primitive: q.primitive(),
        transform: Isometry3::identity(),
    };
    Ok(match axis {
        Axis::R => intervals
            .iter()
            .enumerate()
            .map(|(i, &(s0, s1))| {
                let r = if i == last { g.r } else { g.ri + s1 };
                at_centre(Sph {
                    r,
                    ri: g.ri + s0,
                    ..g
                })
            })
            .collect(),
        Axis::Theta => intervals
            .iter()
            .map(|&(t0, t1)| Piece {
                primitive: Sph {
                    theta: t1 - t0,
                    ..g
                }
                .primitive(),
                transform: Isometry3::rotation(Vector3::y() * t0),
            })
            .collect(),
        Axis::Phi => intervals
            .iter()
            .map(|&(f0, f1)| {
                at_centre(Sph {
                    p0: g.p0 + f0,
                    phi: f1 - f0,
                    ..g
                })
            })
            .collect(),
        other => unreachable!("axis {other} is checked before split"),
    })
}

pub(super) fn mesh(p: &Primitive, t: &Tessellation) -> TriMesh {
    let g = Sph::of(p);
    let n = t.arc_segments(g.phi) as usize;
    let (p0, p1) = (g.p0, g.p1());
    let point = |rho: f64, k: usize| {
        let f = if k == n {
            p1
        } else {
            p0 + (p1 - p0) * k as f64 / n as f64
        };
        let s = f.sin();
        // Poles lie exactly on the axis so they become single vertices.
        [if s.abs() < 1e-12 { 0.0 } else { rho * s }, rho * f.cos()]
    };
    // Counter-clockwise in the (ρ, y) half-plane: the outer arc upwards (φ decreasing), then
    // the inner arc downwards (φ increasing), or the centre when there is no inner surface.
    let mut profile: Vec<[f64; 2]> = (0..=n).rev().map(|k| point(g.r, k)).collect();
    let outer = |k: usize| n - k;
    let mut side = Vec::with_capacity(2 * n);
    if g.ri > 0.0 {
        profile.extend((0..=n).map(|k| point(g.ri, k)));
        let inner = |k: usize| n + 1 + k;
        for k in 0..n {
            side.push([outer(k + 1), outer(k), inner(k)]);
            side.push([outer(k + 1), inner(k), inner(k + 1)]);
        }
    } else {
        profile.push([0.0, 0.0]);
        side.extend((0..n).map(|k| [outer(k + 1), outer(k), n + 1]));
    }
    let mut m = revolve(&profile, &side, g.theta, t);
    m.weld(1e-9 * g.r);
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use ShapeType::*;
    use nalgebra::Point3;

    fn prim(kind: ShapeType, v: &[f64]) -> Primitive {
        Primitive::new(kind, v).unwrap_or_else(|e| panic!("{kind}: {e}"))
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
    }

    #[test]
    fn sphere_phi_bands_have_exact_volumes() {
        let s = prim(Sphere, &[1.0]);
        let third = PI / 3.0;
        let bands = s.split(Axis::Phi, &[third, third, third]).unwrap();
        let want = [PI / 3.0, 2.0 * PI / 3.0, PI / 3.0];
        for (b, w) in bands.iter().zip(want) {
            assert_eq!(b.primitive.kind, SphericalSector);
            assert!(close(b.primitive.volume(), w), "{:?}", b.primitive);
        }
        assert!(close(bands[1].primitive.params()[4], third));
        assert!(close(s.volume(), 4.0 * PI / 3.0));
    }

    #[test]
    fn sphere_r_split_gives_inner_sphere_and_shells() {
        let s = prim(Sphere, &[3.0]);
        let pieces = s.split(Axis::R, &[1.0, 2.0]).unwrap();
        assert_eq!(pieces[0].primitive, prim(Sphere, &[1.0]));
        assert_eq!(
            pieces[1].primitive,
            prim(SphericalSector, &[3.0, TAU, PI, 1.0, 0.0])
        );
        assert!(close(pieces[1].primitive.volume(), 4.0 * PI / 3.0 * 26.0));
    }

    #[test]
    fn quarter_sphere_size() {
        let wedge = prim(SphericalSector, &[2.0, FRAC_PI_2, PI]);
        let s = wedge.size();
        assert!(
            close(s[0], 2.0) && close(s[1], 4.0) && close(s[2], 2.0),
            "{s:?}"
        );
        let dome_half = prim(SphericalSector, &[2.0, PI, FRAC_PI_2]);
        let s = dome_half.size();
        assert!(
            close(s[0], 4.0) && close(s[1], 2.0) && close(s[2], 2.0),
            "{s:?}"
        );
        // A shell band below the equator: y runs from the outer lower corner to the inner
        // upper corner, x and z reach the outer upper edge.
        let band = prim(SphericalSector, &[2.0, TAU, 0.5, 1.0, 2.0]);
        let s = band.size();
        assert!(close(s[1], 2.0f64.cos() - 2.0 * 2.5f64.cos()), "{s:?}");
        assert!(close(s[0], 4.0 * 2.0f64.sin()));
    }

    #[test]
    fn theta_piece_is_rotated_to_its_start_angle() {
        let s = prim(Sphere, &[2.0]);
        let pieces = s.split(Axis::Theta, &[FRAC_PI_2, 3.0 * FRAC_PI_2]).unwrap();
        assert_eq!(
            pieces[1].primitive,
            prim(SphericalSector, &[2.0, 3.0 * FRAC_PI_2, PI])
        );
        let w = pieces[1].transform * Point3::new(2.0, 0.0, 0.0);
        assert!((w - Point3::new(0.0, 0.0, -2.0)).norm() < 1e-12);
    }

    #[test]
    fn sector_splits_conserve_volume() {
        let s = prim(SphericalSector, &[2.0, 2.5, 1.5, 0.5, 0.7]);
        for (axis, lengths) in [
            (Axis::R, [0.5, 1.0]),
            (Axis::Theta, [1.0, 1.5]),
            (Axis::Phi, [0.5, 1.0]),
        ] {
            let pieces = s.split(axis, &lengths).unwrap();
            let sum: f64 = pieces.iter().map(|q| q.primitive.volume()).sum();
            assert!(close(sum, s.volume()), "{axis}");
            assert!(pieces.iter().all(|q| q.primitive.kind == SphericalSector));
        }
    }

    #[test]
    fn meshes_are_closed_and_converge() {
        for p in [
            prim(Sphere, &[1.5]),
            prim(SphericalSector, &[2.0, 2.5, 1.5, 0.5, 0.7]),
            prim(SphericalSector, &[2.0, TAU, 0.8, 1.0, 1.0]),
            prim(SphericalSector, &[2.0, 1.0, PI, 0.0, 0.0]),
            prim(SphericalSector, &[2.0, 4.0, 1.0, 0.0, PI - 1.0]),
        ] {
            assert!(
                p.mesh(&Tessellation { segments: 24 }).is_closed_oriented(),
                "{p:?}"
            );
            let m = p.mesh(&Tessellation { segments: 512 });
            let rel = (m.signed_volume() - p.volume()).abs() / p.volume();
            assert!(
                rel < 2e-3,
                "{p:?}: mesh {} vs {}",
                m.signed_volume(),
                p.volume()
            );
        }
    }

    #[test]
    fn bad_parameters_are_rejected() {
        for v in [
            &[2.0, 7.0, 1.0][..],
            &[2.0, 1.0, 0.0],
            &[2.0, 1.0, 2.0, 2.0],
            &[2.0, 1.0, 2.0, 0.0, 1.5],
        ] {
            assert!(matches!(
                Primitive::new(SphericalSector, v),
                Err(ShapeError::BadParam { .. })
            ));
        }
    }
}
