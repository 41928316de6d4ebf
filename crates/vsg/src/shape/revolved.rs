//! Solids of revolution of Table 7.1 (§7.1.2): cylinder, extrudedRing, extrudedFan,
//! cylindricalSector, cone, conicFrustum, conicRing, conicFan and conicSector, handled as one
//! family of (possibly hollow, possibly partial) conic frusta about +y.
//!
//! ```text
//!          y ^                    R  = bottom outer radius ("radius", "bottomRadius")
//!     +h/2   |-----+  Rt          Rt = top outer radius (R for cylinders, 0 for cones)
//!            |:::::|\             Ri = bottom inner radius ("innerRadius", R − thickness);
//!            |:::::| \                 the inner surface is parallel to the outer one,
//!       0  --o- - -|- \ - - ->ρ        lo(y) = max(0, Ri − c·y), hi(y) = R − c·y,
//!            |:::::|   \               c = (R − Rt)/h, y from the base; a hole that meets
//!     −h/2   |:::::+----+              the axis below the top leaves the shape solid above
//!            0     Ri   R
//!   θ ∈ [0, angle] about +y: the point (ρ, θ, y) is (ρ·cos θ, y, −ρ·sin θ). Origin on the
//!   axis at mid-height. Full shapes have angle 2π.
//! ```

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use nalgebra::{Isometry3, Vector3};

use super::common::{Axis, Piece, Primitive, ShapeError, ShapeType, Tessellation};
use crate::mesh::TriMesh;

/// Slack on angles given as 2π (or π) so rounded user input is accepted.
pub(super) const ANGLE_EPS: f64 = 1e-9;

/// The common parametrisation of the family.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Rev {
    r: f64,
    h: f64,
    rt: f64,
    ri: f64,
    angle: f64,
}

impl Rev {
    fn of(p: &Primitive) -> Rev {
        use ShapeType::*;
        let v = p.params();
        let (r, h) = (v[0], v[1]);
        let (rt, ri, angle) = match p.kind {
            Cylinder => (r, 0.0, TAU),
            ExtrudedRing => (r, v[2], TAU),
            ExtrudedFan => (r, 0.0, v[2]),
            CylindricalSector => (r, v[2], v[3]),
            Cone => (0.0, 0.0, TAU),
            ConicFrustum => (v[2], 0.0, TAU),
            ConicRing => (v[2], v[3], TAU),
            ConicFan => (0.0, 0.0, v[2]),
            ConicSector => (v[3], r - v[4], v[2]),
            other => unreachable!("{other} is not a solid of revolution"),
        };
        Rev {
            r,
            h,
            rt,
            ri,
            angle,
        }
    }

    fn slope(&self) -> f64 {
        (self.r - self.rt) / self.h
    }

    fn full(&self) -> bool {
        self.angle >= TAU - ANGLE_EPS
    }

    /// Outer radius at height `y` above the base.
    fn hi(&self, y: f64) -> f64 {
        if y >= self.h {
            self.rt
        } else {
            self.r - self.slope() * y
        }
    }

    /// Inner radius at height `y` above the base (0 where the shape is solid).
    fn lo(&self, y: f64) -> f64 {
        if self.ri > 0.0 {
            (self.ri - self.slope() * y).max(0.0)
        } else {
            0.0
        }
    }

    /// Height at which the inner surface meets the axis, when strictly below the top.
    fn closing(&self) -> Option<f64> {
        let c = self.slope();
        (self.ri > 0.0 && c > 0.0 && self.ri < c * self.h).then(|| self.ri / c)
    }

    /// (angle/2)·∫₀ʰ (hi² − lo²) dy in closed form.
    fn volume(&self) -> f64 {
        let Rev {
            r,
            h,
            rt,
            ri,
            angle,
        } = *self;
        let outer = h * (r * r + r * rt + rt * rt) / 3.0;
        let inner = if ri > 0.0 {
            let ye = self.closing().unwrap_or(h);
            let le = (ri - self.slope() * ye).max(0.0);
            ye * (ri * ri + ri * le + le * le) / 3.0
        } else {
            0.0
        };
        angle / 2.0 * (outer - inner)
    }

    /// The primitive type whose geometry this is.
    fn primitive(&self) -> Primitive {
        use ShapeType::*;
        let Rev {
            r,
            h,
            rt,
            ri,
            angle,
        } = *self;
        let (full, hole) = (self.full(), ri > 0.0);
        if rt == r {
            match (full, hole) {
                (true, false) => Primitive::raw(Cylinder, &[r, h]),
                (true, true) => Primitive::raw(ExtrudedRing, &[r, h, ri]),
                (false, false) => Primitive::raw(ExtrudedFan, &[r, h, angle]),
                (false, true) => Primitive::raw(CylindricalSector, &[r, h, ri, angle]),
            }
        } else {
            match (full, hole, rt == 0.0) {
                (true, false, true) => Primitive::raw(Cone, &[r, h]),
                (true, false, false) => Primitive::raw(ConicFrustum, &[r, h, rt]),
                (true, true, _) => Primitive::raw(ConicRing, &[r, h, rt, ri]),
                (false, false, true) => Primitive::raw(ConicFan, &[r, h, angle]),
                (false, _, _) => Primitive::raw(ConicSector, &[r, h, angle, rt, r - ri]),
            }
        }
    }

    /// The cross-section in the (ρ, y) half-plane, counter-clockwise, y from the base.
    fn profile(&self) -> Vec<[f64; 2]> {
        let mut pts = vec![[self.ri.max(0.0), 0.0], [self.r, 0.0], [self.rt, self.h]];
        match self.closing() {
            Some(yk) => pts.extend([[0.0, self.h], [0.0, yk]]),
            None => pts.push([self.lo(self.h), self.h]),
        }
        let tol = 1e-12 * self.r.max(self.rt).max(self.h);
        let close =
            |a: &[f64; 2], b: &[f64; 2]| (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol;
        let mut out: Vec<[f64; 2]> = Vec::with_capacity(pts.len());
        for p in pts {
            if out.last().is_none_or(|q| !close(q, &p)) {
                out.push(p);
            }
        }
        while out.len() > 1 && close(&out[0], &out[out.len() - 1]) {
            out.pop();
        }
        out
    }
}

pub(super) fn validate(p: &Primitive) -> Result<(), ShapeError> {
    use ShapeType::*;
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
    for i in [0, 1] {
        if v[i] <= 0.0 {
            return bad(i, "must be positive");
        }
    }
    let angle = match p.kind {
        ExtrudedFan | ConicFan | ConicSector => Some(2),
        CylindricalSector => Some(3),
        _ => None,
    };
    if let Some(i) = angle
        && !(v[i] > 0.0 && v[i] <= TAU + ANGLE_EPS)
    {
        return bad(i, "angle must be in (0, 2π]");
    }
    match p.kind {
        ConicFrustum if v[2] <= 0.0 => {
            return bad(
                2,
                "topRadius must be positive (a zero top radius is a cone)",
            );
        }
        ConicRing if v[2] < 0.0 => return bad(2, "topRadius must not be negative"),
        ConicSector if v[3] < 0.0 => return bad(3, "topRadius must not be negative"),
        _ => {}
    }
    let inner = match p.kind {
        ExtrudedRing | CylindricalSector => Some(2),
        ConicRing => Some(3),
        _ => None,
    };
    if let Some(i) = inner {
        if v[i] < 0.0 {
            return bad(i, "innerRadius must not be negative");
        }
        if v[i] >= v[0] {
            return bad(i, "innerRadius must be smaller than radius");
        }
    }
    if p.kind == ConicSector {
        if v[4] <= 0.0 {
            return bad(4, "thickness must be positive");
        }
        if v[4] > v[0] {
            return bad(
                4,
                "thickness must not exceed bottomRadius (equal means a solid sector)",
            );
        }
    }
    Ok(())
}

pub(super) fn volume(p: &Primitive) -> f64 {
    Rev::of(p).volume()
}

pub(super) fn size(p: &Primitive) -> [f64; 3] {
    let g = Rev::of(p);
    let rmax = g.r.max(g.rt);
    let rmin = if g.ri > 0.0 { g.ri.min(g.lo(g.h)) } else { 0.0 };
    // The xz projection is the annular sector rmin ≤ ρ ≤ rmax, 0 ≤ θ ≤ angle.
    let mut thetas = vec![0.0, g.angle.min(TAU)];
    thetas.extend(
        [FRAC_PI_2, PI, 3.0 * FRAC_PI_2]
            .into_iter()
            .filter(|&t| t <= g.angle),
    );
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for t in thetas {
        for rho in [rmin, rmax] {
            let q = [rho * t.cos(), -rho * t.sin()];
            for k in 0..2 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
    }
    [hi[0] - lo[0], g.h, hi[1] - lo[1]]
}

pub(super) fn extent(p: &Primitive, axis: Axis) -> f64 {
    let g = Rev::of(p);
    match axis {
        Axis::R => g.r - g.ri,
        Axis::Y => g.h,
        Axis::Theta => g.angle,
        other => unreachable!("axis {other} is checked before extent"),
    }
}

pub(super) fn split(
    p: &Primitive,
    axis: Axis,
    intervals: &[(f64, f64)],
) -> Result<Vec<Piece>, ShapeError> {
    let g = Rev::of(p);
    let tiny = 1e-12 * g.r.max(g.rt);
    let lift = |q: &Rev, base: f64| Piece {
        primitive: q.primitive(),
        transform: Isometry3::translation(0.0, base + q.h / 2.0 - g.h / 2.0, 0.0),
    };
    let last = intervals.len().saturating_sub(1);
    Ok(match axis {
        Axis::Y => intervals
            .iter()
            .map(|&(y0, y1)| {
                let ri = g.lo(y0);
                let q = Rev {
                    r: g.hi(y0),
                    h: y1 - y0,
                    rt: g.hi(y1),
                    ri: if ri > tiny { ri } else { 0.0 },
                    angle: g.angle,
                };
                lift(&q, y0)
            })
            .collect(),
        Axis::R => intervals
            .iter()
            .enumerate()
            .map(|(i, &(s0, s1))| {
                // Base radii of the piece's inner and outer (parallel) surfaces.
                let (a, b) = (g.ri + s0, if i == last { g.r } else { g.ri + s1 });
                let top = if i == last { g.rt } else { b - (g.r - g.rt) };
                let c = g.slope();
                let (h, rt) = if top <= tiny && c > 0.0 {
                    ((b / c).min(g.h), 0.0) // the piece closes into an apex
                } else {
                    (g.h, top)
                };
                lift(
                    &Rev {
                        r: b,
                        h,
                        rt,
                        ri: a,
                        angle: g.angle,
                    },
                    0.0,
                )
            })
            .collect(),
        Axis::Theta => intervals
            .iter()
            .map(|&(t0, t1)| Piece {
                primitive: Rev {
                    angle: t1 - t0,
                    ..g
                }
                .primitive(),
                transform: Isometry3::rotation(Vector3::y() * t0),
            })
            .collect(),
        other => unreachable!("axis {other} is checked before split"),
    })
}

pub(super) fn mesh(p: &Primitive, t: &Tessellation) -> TriMesh {
    let g = Rev::of(p);
    let profile: Vec<[f64; 2]> = g
        .profile()
        .into_iter()
        .map(|[r, y]| [r, y - g.h / 2.0])
        .collect();
    // The profile is convex (an intersection of half-planes): fan it for the side faces.
    let side: Vec<[usize; 3]> = (1..profile.len() - 1).map(|i| [0, i, i + 1]).collect();
    let mut m = revolve(&profile, &side, g.angle, t);
    m.weld(1e-9 * g.r.max(g.rt).max(g.h));
    m
}

/// Sweeps a closed profile (counter-clockwise in the (ρ, y) half-plane, ρ ≥ 0) about +y over
/// θ ∈ [0, angle]. Profile points with ρ = 0 become single axis vertices. For partial angles the
/// profile, triangulated by `side` (indices into `profile`, counter-clockwise), closes the ends
/// at θ = 0 and θ = angle. Triangles that would repeat a vertex are left out.
pub(super) fn revolve(
    profile: &[[f64; 2]],
    side: &[[usize; 3]],
    angle: f64,
    t: &Tessellation,
) -> TriMesh {
    let full = angle >= TAU - ANGLE_EPS;
    let n = t.arc_segments(if full { TAU } else { angle }) as usize;
    let cols = if full { n } else { n + 1 };
    let step = if full { TAU } else { angle } / n as f64;
    let mut m = TriMesh::default();
    let idx: Vec<Vec<u32>> = profile
        .iter()
        .map(|&[rho, y]| {
            if rho == 0.0 {
                vec![m.push_vertex([0.0, y, 0.0]); cols]
            } else {
                (0..cols)
                    .map(|j| {
                        let th = if j == n { angle } else { step * j as f64 };
                        m.push_vertex([rho * th.cos(), y, -rho * th.sin()])
                    })
                    .collect()
            }
        })
        .collect();
    let mut tri = |a: u32, b: u32, c: u32| {
        if a != b && b != c && a != c {
            m.push_triangle(a, b, c);
        }
    };
    let col = |j: usize| if full { j % n } else { j };
    for i in 0..profile.len() {
        let (p, q) = (&idx[i], &idx[(i + 1) % profile.len()]);
        for j in 0..n {
            let (a, b) = (col(j), col(j + 1));
            tri(p[a], p[b], q[b]);
            tri(p[a], q[b], q[a]);
        }
    }
    if !full {
        for &[a, b, c] in side {
            tri(idx[a][0], idx[b][0], idx[c][0]);
            tri(idx[c][n], idx[b][n], idx[a][n]);
        }
    }
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

    fn check_mesh(p: &Primitive) {
        let m = p.mesh(&Tessellation { segments: 24 });
        assert!(m.is_closed_oriented(), "{p:?} mesh not closed");
        let m = p.mesh(&Tessellation { segments: 512 });
        let rel = (m.signed_volume() - p.volume()).abs() / p.volume();
        assert!(
            rel < 2e-3,
            "{p:?}: mesh {} vs {}",
            m.signed_volume(),
            p.volume()
        );
    }

    #[test]
    fn tower_cylinder_r_split_gives_cylinder_and_ring() {
        let tower = prim(Cylinder, &[32.0, 210.0]);
        let pieces = tower.split(Axis::R, &[24.0, 8.0]).unwrap();
        assert_eq!(pieces[0].primitive, prim(Cylinder, &[24.0, 210.0]));
        assert_eq!(
            pieces[1].primitive,
            prim(ExtrudedRing, &[32.0, 210.0, 24.0])
        );
        assert!(close(
            pieces[0].primitive.volume(),
            PI * 24.0 * 24.0 * 210.0
        ));
        assert!(close(
            pieces[1].primitive.volume(),
            PI * (32.0 * 32.0 - 24.0 * 24.0) * 210.0
        ));
        assert!(pieces.iter().all(|q| q.transform == Isometry3::identity()));
    }

    #[test]
    fn cone_y_split_gives_frustum_and_cone() {
        let cone = prim(Cone, &[3.0, 6.0]);
        let pieces = cone.split(Axis::Y, &[4.0, 2.0]).unwrap();
        assert_eq!(pieces[0].primitive, prim(ConicFrustum, &[3.0, 4.0, 1.0]));
        assert_eq!(pieces[1].primitive, prim(Cone, &[1.0, 2.0]));
        assert!(close(pieces[0].primitive.volume(), 52.0 * PI / 3.0));
        assert!(close(pieces[1].primitive.volume(), 2.0 * PI / 3.0));
        assert!(close(cone.volume(), 18.0 * PI));
        assert!(close(pieces[0].transform.translation.y, -1.0));
        assert!(close(pieces[1].transform.translation.y, 2.0));
    }

    #[test]
    fn frustum_r_split_inner_piece_closes_into_a_cone() {
        // slope 1: the inner piece (base radius 1) meets the axis at y = 1 < h = 2.
        let f = prim(ConicFrustum, &[4.0, 2.0, 2.0]);
        let pieces = f.split(Axis::R, &[1.0, 3.0]).unwrap();
        assert_eq!(pieces[0].primitive, prim(Cone, &[1.0, 1.0]));
        assert!(close(pieces[0].transform.translation.y, -0.5));
        assert_eq!(pieces[1].primitive, prim(ConicRing, &[4.0, 2.0, 2.0, 1.0]));
        assert!(close(pieces[0].primitive.volume(), PI / 3.0));
        assert!(close(pieces[1].primitive.volume(), 55.0 * PI / 3.0));
        assert!(close(f.volume(), 56.0 * PI / 3.0));
        check_mesh(&pieces[1].primitive);
    }

    #[test]
    fn conic_fan_y_split_below_apex_is_a_solid_conic_sector() {
        let fan = prim(ConicFan, &[2.0, 4.0, 1.0]);
        let pieces = fan.split(Axis::Y, &[2.0, 2.0]).unwrap();
        assert_eq!(
            pieces[0].primitive,
            prim(ConicSector, &[2.0, 2.0, 1.0, 1.0, 2.0])
        );
        assert_eq!(pieces[1].primitive, prim(ConicFan, &[1.0, 2.0, 1.0]));
        let sum: f64 = pieces.iter().map(|q| q.primitive.volume()).sum();
        assert!(close(sum, fan.volume()));
    }

    #[test]
    fn ring_y_split_above_the_closing_has_no_hole() {
        let ring = prim(ConicRing, &[4.0, 2.0, 2.0, 1.0]); // hole closes at y = 1
        let pieces = ring.split(Axis::Y, &[1.5, 0.5]).unwrap();
        assert_eq!(pieces[0].primitive, prim(ConicRing, &[4.0, 1.5, 2.5, 1.0]));
        assert_eq!(pieces[1].primitive, prim(ConicFrustum, &[2.5, 0.5, 2.0]));
        let sum: f64 = pieces.iter().map(|q| q.primitive.volume()).sum();
        assert!(close(sum, ring.volume()));
    }

    #[test]
    fn theta_piece_is_rotated_to_its_start_angle() {
        let fan = prim(ExtrudedFan, &[2.0, 1.0, PI]);
        let pieces = fan.split(Axis::Theta, &[FRAC_PI_2, FRAC_PI_2]).unwrap();
        assert_eq!(
            pieces[1].primitive,
            prim(ExtrudedFan, &[2.0, 1.0, FRAC_PI_2])
        );
        let m = pieces[1].primitive.mesh(&Tessellation::default());
        assert!(
            m.positions
                .iter()
                .any(|v| (v[0] - 2.0).abs() < 1e-12 && v[2].abs() < 1e-12)
        );
        let w = pieces[1].transform * Point3::new(2.0, -0.5, 0.0);
        assert!((w - Point3::new(0.0, -0.5, -2.0)).norm() < 1e-12);
        let full = prim(Cylinder, &[1.0, 1.0])
            .split(Axis::Theta, &[1.0, TAU - 1.0])
            .unwrap();
        assert_eq!(full[1].primitive, prim(ExtrudedFan, &[1.0, 1.0, TAU - 1.0]));
    }

    #[test]
    fn meshes_are_closed_and_converge() {
        for p in [
            prim(ConicRing, &[2.0, 3.0, 0.2, 1.0]), // hole closes below the top
            prim(ConicRing, &[1.0, 2.0, 2.0, 0.5]), // inverted frustum
            prim(ConicFrustum, &[1.0, 2.0, 1.5]),   // inverted
            prim(ConicSector, &[2.0, 3.0, 4.0, 0.0, 0.5]), // pointed with a hole
            prim(ConicSector, &[2.0, 3.0, TAU, 1.0, 2.0]), // full: a frustum
            prim(CylindricalSector, &[2.0, 1.0, 0.5, 5.0]),
            prim(ExtrudedRing, &[2.0, 1.0, 0.0]),
            prim(Cone, &[1.0, 2.0]),
        ] {
            check_mesh(&p);
        }
    }

    /// Whether the local point lies inside the region (with a small outward slack `e`).
    fn contains(g: &Rev, v: Point3<f64>, e: f64) -> bool {
        let (rho, y) = ((v.x * v.x + v.z * v.z).sqrt(), v.y + g.h / 2.0);
        let th = (-v.z).atan2(v.x).rem_euclid(TAU);
        let in_angle = g.full() || th <= g.angle + e || th >= TAU - e;
        (-e..=g.h + e).contains(&y) && rho >= g.lo(y) - e && rho <= g.hi(y) + e && in_angle
    }

    #[test]
    fn r_and_y_pieces_partition_the_parent() {
        for (p, axis, lengths) in [
            (
                prim(ConicRing, &[2.0, 3.0, 0.2, 1.0]),
                Axis::R,
                &[0.3, 0.4, 0.3][..],
            ),
            (
                prim(ConicRing, &[2.0, 3.0, 0.2, 1.0]),
                Axis::Y,
                &[1.0, 1.5, 0.5],
            ),
            (
                prim(ConicSector, &[2.0, 3.0, 4.0, 0.0, 1.5]),
                Axis::R,
                &[0.5, 0.5, 0.5],
            ),
            (prim(ConicFrustum, &[1.0, 2.0, 1.5]), Axis::R, &[0.5, 0.5]),
        ] {
            let g = Rev::of(&p);
            let pieces = p.split(axis, lengths).unwrap();
            let n = 24;
            for (i, j, k) in (0..n * n * n).map(|q| (q % n, q / n % n, q / (n * n))) {
                let f = |i: usize, s: f64| (i as f64 + 0.5) / n as f64 * 2.0 * s - s;
                let v = Point3::new(f(i, 2.0), f(j, g.h / 2.0), f(k, 2.0));
                let count = pieces
                    .iter()
                    .filter(|q| contains(&Rev::of(&q.primitive), q.transform.inverse() * v, 0.0))
                    .count();
                let on_edge = pieces.iter().any(|q| {
                    let (g2, w) = (Rev::of(&q.primitive), q.transform.inverse() * v);
                    contains(&g2, w, 1e-9) != contains(&g2, w, -1e-9)
                });
                if !on_edge {
                    assert_eq!(count, contains(&g, v, 0.0) as usize, "{p:?} {axis} at {v}");
                }
            }
        }
    }

    #[test]
    fn sizes_follow_the_angle() {
        let quarter = prim(ExtrudedFan, &[2.0, 1.0, FRAC_PI_2]);
        let s = quarter.size();
        assert!(close(s[0], 2.0) && close(s[1], 1.0) && close(s[2], 2.0));
        let inverted = prim(ConicFrustum, &[1.0, 2.0, 1.5]);
        assert!(close(inverted.size()[0], 3.0));
    }

    #[test]
    fn bad_parameters_are_rejected() {
        for (kind, v) in [
            (ExtrudedRing, &[2.0, 1.0, 2.0][..]),
            (ExtrudedFan, &[2.0, 1.0, 7.0]),
            (ConicSector, &[2.0, 1.0, 1.0, 1.0, 2.5]),
            (ConicFrustum, &[2.0, 1.0, 0.0]),
            (Cone, &[2.0, 0.0]),
        ] {
            assert!(matches!(
                Primitive::new(kind, v),
                Err(ShapeError::BadParam { .. })
            ));
        }
        let e = Primitive::new(ExtrudedRing, &[2.0, 1.0, 3.0]).unwrap_err();
        assert!(
            e.to_string()
                .contains("innerRadius must be smaller than radius")
        );
    }
}
