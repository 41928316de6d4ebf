//! The wedge family of Table 7.1 (§7.1.2): tetrahedron, tetrahedronFrustum and
//! tetrahedronSector as one parametrised solid — frames, exact volumes, closed meshes and
//! R / Y / Theta splits.
//!
//! Table 7.1 only names the parameters (edge1, edge2, height, angle, topEdge1, split); the
//! geometry chosen here is this. The base is a triangle with a vertex O, edge1 (length e1) along
//! +x and edge2 (length e2) along +x turned by `angle` = A about +y (right-hand rule, so
//! towards −z), 0 < A < π. λ is the linear function on the horizontal plane with λ(O) = 0 and
//! λ = 1 on the far edge joining the ends of edge1 and edge2. With k = topEdge1/e1,
//! σ = split/e1 and c = (1 − k)/height, the solid is
//!
//! ```text
//!   { (q, y) : 0 ≤ y ≤ height, q in the wedge at O, max(0, σ − c·y) ≤ λ(q) ≤ 1 − c·y }
//!
//!   seen from above (y towards you)          seen from the side (through edge1)
//!
//!         O ────────── edge1 ──→ +x            apex (k = 0) or top edge k·e1
//!          ╲ A       .                          │╲            y
//!           ╲     .  far edge (λ = 1)           │ ╲ outer     ↑
//!      edge2 ╲ .                                │  ╲ face     └── x
//!             ↓ (cos A, 0, −sin A)              O───╲
//!                                                σ·e1 … e1: a sector keeps λ ≥ σ − c·y
//! ```
//!
//! The tetrahedron is k = σ = 0 (apex above O), the frustum 0 < k ≤ 1 with σ = 0 (k = 1 is a
//! triangular prism) and the sector 0 < σ < 1: a slab between the slanted outer face and a
//! parallel inner plane, whose section becomes the full triangle where that plane reaches O's
//! vertical line. The local origin is on the vertical line through O, at mid-height, so y runs
//! from −height/2 to height/2. Derived pieces are typed by their geometry (σ > 0: sector;
//! else k > 0: frustum; else tetrahedron).

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use super::common::{Axis, Piece, Primitive, ShapeError, ShapeType, Tessellation};
use crate::mesh::TriMesh;

/// Relative tolerance below which k or σ counts as zero, and for kinks at an end.
const TOLERANCE: f64 = 1e-12;

/// A wedge-family solid in normalised terms (see the module doc).
#[derive(Clone, Copy, Debug)]
struct Wedge {
    e1: f64,
    e2: f64,
    h: f64,
    a: f64,
    k: f64,
    s: f64,
}

impl Wedge {
    fn of(p: &Primitive) -> Wedge {
        let v = p.params();
        let k = v.get(4).map_or(0.0, |t| t / v[0]);
        let s = v.get(5).map_or(0.0, |t| t / v[0]);
        Wedge {
            e1: v[0],
            e2: v[1],
            h: v[2],
            a: v[3],
            k,
            s,
        }
    }

    /// The primitive for this geometry.
    fn primitive(&self) -> Primitive {
        let Wedge { e1, e2, h, a, .. } = *self;
        let k = self.k.clamp(0.0, 1.0);
        if self.s > TOLERANCE {
            Primitive::raw(
                ShapeType::TetrahedronSector,
                &[e1, e2, h, a, k * e1, self.s * e1],
            )
        } else if k > TOLERANCE {
            Primitive::raw(ShapeType::TetrahedronFrustum, &[e1, e2, h, a, k * e1])
        } else {
            Primitive::raw(ShapeType::Tetrahedron, &[e1, e2, h, a])
        }
    }

    /// Outer level λ = 1 − c·y at height y above the base (exactly k at the top).
    fn hi(&self, y: f64) -> f64 {
        if y >= self.h {
            self.k
        } else {
            1.0 - (1.0 - self.k) * (y / self.h)
        }
    }

    /// Inner level max(0, σ − c·y) at height y above the base.
    fn lo(&self, y: f64) -> f64 {
        (self.s - (1.0 - self.k) * (y / self.h)).max(0.0)
    }

    /// Horizontal sections `(y above the base, λ inner, λ outer)` between which both levels
    /// are linear: the base, the kink where the inner plane reaches O's vertical line, the top.
    fn rings(&self) -> Vec<(f64, f64, f64)> {
        let mut rings = vec![(0.0, self.s, 1.0)];
        let fall = 1.0 - self.k; // c·h: how much both levels drop from base to top
        if self.s > 0.0 && self.s < fall * (1.0 - TOLERANCE) {
            rings.push((self.h * self.s / fall, 0.0, 1.0 - self.s));
            rings.push((self.h, 0.0, self.k));
        } else {
            rings.push((self.h, (self.s - fall).max(0.0), self.k));
        }
        rings
    }

    fn base_area(&self) -> f64 {
        0.5 * self.e1 * self.e2 * self.a.sin()
    }

    /// ∫ base_area·(hi² − lo²) dy, exact per linear stretch: ∫ f² = Δy·(f0² + f0·f1 + f1²)/3.
    fn volume(&self) -> f64 {
        let sq = |f0: f64, f1: f64| f0 * f0 + f0 * f1 + f1 * f1;
        let rings = self.rings();
        let sum: f64 = rings
            .windows(2)
            .map(|w| (w[1].0 - w[0].0) * (sq(w[0].2, w[1].2) - sq(w[0].1, w[1].1)))
            .sum();
        self.base_area() * sum / 3.0
    }

    /// Far ends of edge1 and edge2 (y = 0).
    fn ends(&self) -> ([f64; 3], [f64; 3]) {
        (
            [self.e1, 0.0, 0.0],
            [self.e2 * self.a.cos(), 0.0, -self.e2 * self.a.sin()],
        )
    }

    /// Distance from O to the far edge along the horizontal ray at angle θ from edge1.
    fn reach(&self, theta: f64) -> f64 {
        if theta <= 0.0 {
            self.e1
        } else if theta >= self.a {
            self.e2
        } else {
            let (e1, e2, a) = (self.e1, self.e2, self.a);
            e1 * e2 * a.sin() / (e2 * (a - theta).sin() + e1 * theta.sin())
        }
    }
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
    if !(v[3] > 0.0 && v[3] < std::f64::consts::PI) {
        return Err(bad(3, "must lie strictly between 0 and π"));
    }
    match p.kind {
        ShapeType::TetrahedronFrustum if !(v[4] > 0.0 && v[4] <= v[0]) => {
            Err(bad(4, "must be positive and at most edge1"))
        }
        ShapeType::TetrahedronSector if !(0.0..=v[0]).contains(&v[4]) => {
            Err(bad(4, "must lie between 0 and edge1"))
        }
        ShapeType::TetrahedronSector if !(v[5] > 0.0 && v[5] < v[0]) => {
            Err(bad(5, "must lie strictly between 0 and edge1"))
        }
        _ => Ok(()),
    }
}

pub(super) fn volume(p: &Primitive) -> f64 {
    Wedge::of(p).volume()
}

pub(super) fn size(p: &Primitive) -> [f64; 3] {
    let (lo, hi) = mesh(p, &Tessellation::default())
        .bounds()
        .unwrap_or_default();
    std::array::from_fn(|k| hi[k] - lo[k])
}

pub(super) fn extent(p: &Primitive, axis: Axis) -> f64 {
    let w = Wedge::of(p);
    match axis {
        Axis::Y => w.h,
        Axis::Theta => w.a,
        Axis::R => w.e1 - p.params().get(5).copied().unwrap_or(0.0),
        other => unreachable!("{} has no {other} extent", p.kind),
    }
}

pub(super) fn split(
    p: &Primitive,
    axis: Axis,
    intervals: &[(f64, f64)],
) -> Result<Vec<Piece>, ShapeError> {
    let w = Wedge::of(p);
    let up = |y: f64| Isometry3::translation(0.0, y - w.h / 2.0, 0.0);
    let pieces: Vec<(Primitive, Isometry3<f64>)> = match axis {
        Axis::Theta => intervals
            .iter()
            .map(|&(t0, t1)| {
                let e = Wedge {
                    e1: w.reach(t0),
                    e2: w.reach(t1),
                    a: t1 - t0,
                    ..w
                };
                let turn = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), t0);
                (
                    e.primitive(),
                    Isometry3::from_parts(Translation3::identity(), turn),
                )
            })
            .collect(),
        Axis::Y => intervals
            .iter()
            .map(|&(y0, y1)| {
                let s = w.hi(y0);
                let e = Wedge {
                    e1: w.e1 * s,
                    e2: w.e2 * s,
                    h: y1 - y0,
                    k: w.hi(y1) / s,
                    s: w.lo(y0) / s,
                    ..w
                };
                (e.primitive(), up((y0 + y1) / 2.0))
            })
            .collect(),
        Axis::R => {
            let whole = extent(p, Axis::R);
            let level = |r: f64| if r >= whole { 1.0 } else { w.s + r / w.e1 };
            let fall = 1.0 - w.k;
            intervals
                .iter()
                .map(|&(r0, r1)| {
                    let (la, lb) = (level(r0), level(r1));
                    // The outer plane λ = lb − c·y reaches O's vertical line at lb/c.
                    let (h, k) = if lb < fall * (1.0 - TOLERANCE) {
                        (w.h * lb / fall, 0.0)
                    } else {
                        (w.h, ((lb - fall) / lb).max(0.0))
                    };
                    let e = Wedge {
                        e1: w.e1 * lb,
                        e2: w.e2 * lb,
                        h,
                        k,
                        s: la / lb,
                        ..w
                    };
                    (e.primitive(), up(h / 2.0))
                })
                .collect()
        }
        other => {
            return Err(ShapeError::Unsupported(format!(
                "{} cannot be split along {other}",
                p.kind
            )));
        }
    };
    Ok(pieces
        .into_iter()
        .map(|(primitive, transform)| Piece {
            primitive,
            transform,
        })
        .collect())
}

pub(super) fn mesh(p: &Primitive, _t: &Tessellation) -> TriMesh {
    let w = Wedge::of(p);
    let (end1, end2) = w.ends();
    let mut m = TriMesh::default();
    let rings = w.rings();
    // Each ring is [lo·end1, hi·end1, hi·end2, lo·end2], counter-clockwise seen from above;
    // collapsed corners (lo = 0 at O, an apex) are welded away below.
    for &(y, lo, hi) in &rings {
        for (f, end) in [(lo, end1), (hi, end1), (hi, end2), (lo, end2)] {
            m.push_vertex([f * end[0], y - w.h / 2.0, f * end[2]]);
        }
    }
    let top = 4 * (rings.len() as u32 - 1);
    m.push_polygon(&[3, 2, 1, 0]);
    m.push_polygon(&[top, top + 1, top + 2, top + 3]);
    for r in 0..rings.len() as u32 - 1 {
        let (b, t) = (4 * r, 4 * r + 4);
        for i in 0..4 {
            let j = (i + 1) % 4;
            m.push_triangle(b + i, b + j, t + j);
            m.push_triangle(b + i, t + j, t + i);
        }
    }
    m.weld(1e-9 * w.e1.max(w.e2).max(w.h));
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

    fn prim(kind: ShapeType, v: &[f64]) -> Primitive {
        Primitive::new(kind, v).unwrap()
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
    }

    /// Whether a point of the local frame lies in the solid (within a small tolerance).
    fn contains(p: &Primitive, x: [f64; 3]) -> bool {
        let w = Wedge::of(p);
        let tol = 1e-9 * w.e1.max(w.e2).max(w.h);
        let (y, b) = (x[1] + w.h / 2.0, -x[2] / w.a.sin());
        let a = x[0] - b * w.a.cos();
        let lam = a / w.e1 + b / w.e2;
        let c = (1.0 - w.k) / w.h;
        a >= -tol
            && b >= -tol
            && y >= -tol
            && y <= w.h + tol
            && lam <= 1.0 - c * y + tol
            && lam >= w.s - c * y - tol
    }

    fn check(p: &Primitive, axis: Axis, fractions: &[f64]) -> Vec<Piece> {
        crate::shape::tests::check_planar_split(p, axis, fractions, contains)
    }

    fn kinds(pieces: &[Piece]) -> Vec<ShapeType> {
        pieces.iter().map(|q| q.primitive.kind).collect()
    }

    #[test]
    fn volumes_of_hand_computed_cases() {
        let tet = prim(ShapeType::Tetrahedron, &[3.0, 2.0, 2.5, FRAC_PI_2]);
        assert!(close(tet.volume(), 2.5));
        let fru = prim(
            ShapeType::TetrahedronFrustum,
            &[3.0, 2.0, 2.5, FRAC_PI_2, 1.5],
        );
        assert!(close(fru.volume(), 3.0 * 2.5 * 1.75 / 3.0));
        let prism = prim(
            ShapeType::TetrahedronFrustum,
            &[3.0, 2.0, 2.5, FRAC_PI_2, 3.0],
        );
        assert!(close(prism.volume(), 7.5));
        // σ = 1/3, c = 0.2, kink at y = 5/3: 3·(2.5·1.75/3 − (5/3)·(1/9)/3) = 905/216.
        let sec = prim(
            ShapeType::TetrahedronSector,
            &[3.0, 2.0, 2.5, FRAC_PI_2, 1.5, 1.0],
        );
        assert!(close(sec.volume(), 905.0 / 216.0));
        // No kink: σ = 0.8 > 1 − k = 0.5; section area ∝ (1 − cy)² − (0.8 − cy)².
        let thick = prim(
            ShapeType::TetrahedronSector,
            &[3.0, 2.0, 2.5, FRAC_PI_2, 1.5, 2.4],
        );
        assert!(close(
            thick.volume(),
            3.0 * 2.5 * (1.75 - (0.64 + 0.24 + 0.09)) / 3.0
        ));
    }

    #[test]
    fn size_spans_the_base_triangle_and_height() {
        let tet = prim(ShapeType::Tetrahedron, &[3.0, 2.0, 2.5, FRAC_PI_2]);
        let s = tet.size();
        assert!(
            close(s[0], 3.0) && close(s[1], 2.5) && close(s[2], 2.0),
            "{s:?}"
        );
        let (lo, hi) = tet.mesh(&Tessellation::default()).bounds().unwrap();
        assert!(close(lo[1], -1.25) && close(hi[1], 1.25) && lo[0] == 0.0 && hi[2] == 0.0);
    }

    #[test]
    fn invalid_parameters_are_rejected() {
        let err = |k, v: &[f64]| matches!(Primitive::new(k, v), Err(ShapeError::BadParam { .. }));
        assert!(err(ShapeType::Tetrahedron, &[3.0, 2.0, 2.5, 0.0]));
        assert!(err(
            ShapeType::Tetrahedron,
            &[3.0, 2.0, 2.5, std::f64::consts::PI]
        ));
        assert!(err(
            ShapeType::TetrahedronFrustum,
            &[3.0, 2.0, 2.5, 1.0, 0.0]
        ));
        assert!(err(
            ShapeType::TetrahedronFrustum,
            &[3.0, 2.0, 2.5, 1.0, 3.5]
        ));
        assert!(err(
            ShapeType::TetrahedronSector,
            &[3.0, 2.0, 2.5, 1.0, 1.0, 3.0]
        ));
        assert!(err(
            ShapeType::TetrahedronSector,
            &[3.0, 2.0, 2.5, 1.0, 1.0, 0.0]
        ));
        assert!(
            Primitive::new(
                ShapeType::TetrahedronSector,
                &[3.0, 2.0, 2.5, 1.0, 0.0, 1.0]
            )
            .is_ok()
        );
    }

    #[test]
    fn every_wedge_splits_along_every_allowed_axis() {
        for v in [
            &[3.0, 2.0, 2.5, 1.2][..],
            &[3.0, 2.0, 2.5, 1.2, 1.5],
            &[3.0, 2.0, 2.5, 2.6, 3.0],
            &[3.0, 2.0, 2.5, 1.2, 1.5, 1.0],
            &[3.0, 2.0, 2.5, 0.7, 0.0, 1.0],
            &[3.0, 2.0, 2.5, 1.2, 1.5, 2.4],
            &[3.0, 2.0, 2.5, 1.2, 3.0, 1.0],
        ] {
            let kind = [ShapeType::Tetrahedron, ShapeType::TetrahedronFrustum][..]
                .get(v.len() - 4)
                .copied()
                .unwrap_or(ShapeType::TetrahedronSector);
            let p = prim(kind, v);
            for &axis in kind.split_axes() {
                for fractions in [&[0.2, 0.5, 0.3][..], &[0.45, 0.55], &[1.0]] {
                    assert_eq!(check(&p, axis, fractions).len(), fractions.len());
                }
            }
        }
    }

    #[test]
    fn theta_split_of_a_right_angle_meets_the_far_edge() {
        let p = prim(
            ShapeType::TetrahedronFrustum,
            &[3.0, 2.0, 2.5, FRAC_PI_2, 1.5],
        );
        let pieces = check(&p, Axis::Theta, &[0.5, 0.5]);
        // The diagonal ray x = −z = t meets x/3 + (−z)/2 = 1 at t = 6/5.
        let diag = 6.0 * 2f64.sqrt() / 5.0;
        let (a, b) = (pieces[0].primitive.params(), pieces[1].primitive.params());
        assert!(
            close(a[0], 3.0) && close(a[1], diag) && close(a[3], FRAC_PI_4),
            "{a:?}"
        );
        assert!(
            close(b[0], diag) && close(b[1], 2.0) && close(b[3], FRAC_PI_4),
            "{b:?}"
        );
        assert!(close(a[4], 1.5) && close(b[4], diag / 2.0));
        let turned = pieces[1].transform * Point3::new(1.0, 0.0, 0.0);
        assert!((turned - Point3::new(FRAC_PI_4.cos(), 0.0, -FRAC_PI_4.sin())).norm() < 1e-12);
    }

    #[test]
    fn r_split_of_a_frustum_closes_an_inner_tetrahedron() {
        // c = 0.2, so an inner piece with λ_b = 1/3 closes at y = 5/3 < 2.5.
        let p = prim(
            ShapeType::TetrahedronFrustum,
            &[3.0, 2.0, 2.5, FRAC_PI_2, 1.5],
        );
        let pieces = check(&p, Axis::R, &[1.0 / 3.0, 2.0 / 3.0]);
        let want = [ShapeType::Tetrahedron, ShapeType::TetrahedronSector];
        assert_eq!(kinds(&pieces), want);
        let t = pieces[0].primitive.params();
        assert!(
            close(t[0], 1.0) && close(t[1], 2.0 / 3.0) && close(t[2], 5.0 / 3.0),
            "{t:?}"
        );
        assert!(close(
            pieces[0].transform.translation.vector.y,
            5.0 / 6.0 - 1.25
        ));
        let s = pieces[1].primitive.params();
        assert!(
            close(s[0], 3.0) && close(s[4], 1.5) && close(s[5], 1.0),
            "{s:?}"
        );
    }

    #[test]
    fn y_split_types_follow_geometry() {
        let tet = prim(ShapeType::Tetrahedron, &[3.0, 2.0, 2.5, 1.2]);
        let pieces = check(&tet, Axis::Y, &[0.4, 0.6]);
        assert_eq!(
            kinds(&pieces),
            [ShapeType::TetrahedronFrustum, ShapeType::Tetrahedron]
        );
        assert!(close(pieces[0].primitive.params()[4], 3.0 * 0.6));
        assert!(close(pieces[1].primitive.params()[0], 3.0 * 0.6));
        assert!(close(
            pieces[1].transform.translation.vector.y,
            1.0 + 0.75 - 1.25
        ));
        // The sector's inner plane reaches O's line at y = 5/3: pieces above it are frusta.
        let sec = prim(
            ShapeType::TetrahedronSector,
            &[3.0, 2.0, 2.5, 1.2, 1.5, 1.0],
        );
        let pieces = check(&sec, Axis::Y, &[0.4, 0.4, 0.2]);
        let want = [ShapeType::TetrahedronSector, ShapeType::TetrahedronSector];
        assert_eq!(kinds(&pieces)[..2], want);
        assert_eq!(kinds(&pieces)[2], ShapeType::TetrahedronFrustum);
        let mid = pieces[1].primitive.params(); // from y = 1: scale 0.8, σ' = (1/3 − 0.2)/0.8
        assert!(
            close(mid[0], 2.4) && close(mid[5], 2.4 * (1.0 / 3.0 - 0.2) / 0.8),
            "{mid:?}"
        );
    }
}
