//! The hyperbola fit of §2.1.2 (eqs. 2.1–2.5) and the closed-form corner and asymptotes of
//! §2.1.3 (eqs. 2.6–2.8), with the algebraic shape parameter Δ of eq. 2.9.
//!
//! Eq. 2.5, (MᵗM − λC)α = 0 with C of eq. 2.4 (αᵗCα = b² − 4ac = 1), is a generalised eigenproblem
//! that nalgebra cannot solve directly. As Halir and Flusser do for ellipses, the linear part
//! is eliminated (α₂ = −S₃⁻¹S₂ᵗα₁ with S = MᵗM in blocks), leaving R α₁ = λ C₁ α₁ with the
//! 3 × 3 reduced scatter R = S₁ − S₂S₃⁻¹S₂ᵗ. With R = LLᵗ (Cholesky), u = Lᵗα₁ turns it into the
//! symmetric problem L⁻¹C₁L⁻ᵗ u = (1/λ) u. The cost αᵗSα equals λ under the constraint, and
//! only eigenvalues 1/λ > 0 satisfy it, so the fit is the eigenvector of the largest 1/λ.

use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// An implicit conic a x² + b xy + c y² + d x + e y + f = 0 (eq. 2.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conic {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    pub e: f64,
    pub f: f64,
}

impl Conic {
    /// Value at (x, y).
    pub fn eval(&self, x: f64, y: f64) -> f64 {
        self.a * x * x + self.b * x * y + self.c * y * y + self.d * x + self.e * y + self.f
    }

    /// The quadratic discriminant b² − 4ac (= −J(α) of §2.1.2).
    pub fn discriminant(&self) -> f64 {
        self.b * self.b - 4.0 * self.a * self.c
    }

    /// Δ(α) of eq. 2.9: the determinant of the symmetric 3 × 3 matrix of the conic. Eq. 2.9 as
    /// extracted lists the entries without the halves of the cross terms; we use the standard
    /// matrix [[a, b/2, d/2], [b/2, c, e/2], [d/2, e/2, f]] whose determinant vanishes exactly for
    /// a pair of lines, which is the property §2.1.5 relies on.
    pub fn delta(&self) -> f64 {
        let m = Matrix3::new(
            self.a,
            self.b / 2.0,
            self.d / 2.0,
            self.b / 2.0,
            self.c,
            self.e / 2.0,
            self.d / 2.0,
            self.e / 2.0,
            self.f,
        );
        m.determinant()
    }

    /// Scaled so that b² − 4ac = 1 (the hyperbolic constraint of §2.1.2 with the sign of C in
    /// eq. 2.4) and signed so that Δ ≥ 0. None unless the conic is a hyperbola.
    ///
    /// The sign of an eigenvector is arbitrary, and it decides which axis gets a′ > 0 in §2.1.3
    /// and hence which of the two supplementary angles ψ measures. With Δ ≥ 0 the constant of
    /// the standard position f″ = −4Δ ≤ 0, so the branches cross the x′ axis and ψ is half the
    /// opening of the sector that holds the fitted curve, i.e. of the corner itself.
    pub fn normalised(&self) -> Option<Conic> {
        let disc = self.discriminant();
        if !(disc > 0.0) || !disc.is_finite() {
            return None;
        }
        let mut k = 1.0 / disc.sqrt();
        if self.delta() < 0.0 {
            k = -k;
        }
        Some(Conic {
            a: self.a * k,
            b: self.b * k,
            c: self.c * k,
            d: self.d * k,
            e: self.e * k,
            f: self.f * k,
        })
    }
}

/// Weighted algebraic fit of a hyperbola to points (x, y, weight): rows of M are
/// weight · [x², xy, y², x, y, 1] (eq. 2.2). Coordinates should be small (centred on the window);
/// they are scaled by `1/scale` inside for conditioning and the result is in the input units,
/// normalised so that b² − 4ac = 1. None when the points do not determine a hyperbola (fewer
/// than five points, collinear points, degenerate scatter).
pub fn fit_hyperbola(points: &[[f64; 3]], scale: f64) -> Option<Conic> {
    if points.len() < 5 {
        return None;
    }
    let s = 1.0 / scale;
    // Scatter S = MᵗM: its entries are the 15 weighted moments Σ w² xᵃ yᵇ with a + b ≤ 4.
    let mut mo = [0.0f64; 15];
    for p in points {
        let (x, y, w2) = (p[0] * s, p[1] * s, p[2] * p[2]);
        let (x2, y2, xy) = (x * x, y * y, x * y);
        let terms = [
            1.0,
            x,
            y,
            x2,
            xy,
            y2,
            x2 * x,
            x2 * y,
            x * y2,
            y2 * y,
            x2 * x2,
            x2 * xy,
            x2 * y2,
            xy * y2,
            y2 * y2,
        ];
        for (m, t) in mo.iter_mut().zip(terms) {
            *m += w2 * t;
        }
    }
    // Moment index of xᵃ yᵇ.
    let idx = |a: usize, b: usize| {
        let d = a + b;
        d * (d + 1) / 2 + b
    };
    // Exponents of the monomials [x², xy, y², x, y, 1].
    const EXP: [(usize, usize); 6] = [(2, 0), (1, 1), (0, 2), (1, 0), (0, 1), (0, 0)];
    let m: [[f64; 6]; 6] = std::array::from_fn(|i| {
        std::array::from_fn(|j| mo[idx(EXP[i].0 + EXP[j].0, EXP[i].1 + EXP[j].1)])
    });
    let blk = |r0: usize, c0: usize| Matrix3::from_fn(|i, j| m[r0 + i][c0 + j]);
    let s1 = blk(0, 0);
    let s2 = blk(0, 3);
    let s3 = blk(3, 3);
    let s3_inv = s3.try_inverse()?;
    let t = -s3_inv * s2.transpose(); // α₂ = T α₁
    let r = s1 + s2 * t;
    // A tiny ridge keeps R positive definite when the points lie exactly on a conic (R is
    // then singular and its null vector is the answer, found as 1/λ → ∞).
    let ridge = r.trace().abs() * 1e-12 + f64::MIN_POSITIVE;
    let r = (r + r.transpose()) * 0.5 + Matrix3::identity() * ridge;
    let chol = r.cholesky()?;
    let l = chol.l();
    let l_inv = l.try_inverse()?;
    // C₁ of eq. 2.4 (its quadratic block): αᵗC α = b² − 4ac.
    let c1 = Matrix3::new(0.0, 0.0, -2.0, 0.0, 1.0, 0.0, -2.0, 0.0, 0.0);
    let k = l_inv * c1 * l_inv.transpose();
    let k = (k + k.transpose()) * 0.5;
    let (mu, u) = largest_eigen(&k)?;
    if !(mu > 0.0) {
        return None;
    }
    let a1 = l_inv.transpose() * u;
    let a2 = t * a1;
    // Back to input units: x_scaled = x / scale.
    let conic = Conic {
        a: a1[0] * s * s,
        b: a1[1] * s * s,
        c: a1[2] * s * s,
        d: a2[0] * s,
        e: a2[1] * s,
        f: a2[2],
    };
    conic.normalised()
}

/// Largest eigenvalue and its unit eigenvector of a symmetric 3 × 3 matrix, in closed form
/// (trigonometric solution of the characteristic cubic; the eigenvector is the longest cross
/// product of two rows of K − μI). Falls back to the iterative solver when the closed form is
/// ill-conditioned.
fn largest_eigen(k: &Matrix3<f64>) -> Option<(f64, Vector3<f64>)> {
    let p1 = k[(0, 1)].powi(2) + k[(0, 2)].powi(2) + k[(1, 2)].powi(2);
    let q = k.trace() / 3.0;
    let p2 = (k[(0, 0)] - q).powi(2) + (k[(1, 1)] - q).powi(2) + (k[(2, 2)] - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    if p > 0.0 && p.is_finite() {
        let b = (k - Matrix3::identity() * q) / p;
        let r = (b.determinant() / 2.0).clamp(-1.0, 1.0);
        let mu = q + 2.0 * p * (r.acos() / 3.0).cos();
        let m = k - Matrix3::identity() * mu;
        let (r0, r1, r2) = (
            m.row(0).transpose(),
            m.row(1).transpose(),
            m.row(2).transpose(),
        );
        let cands = [r0.cross(&r1), r0.cross(&r2), r1.cross(&r2)];
        let best = cands
            .iter()
            .max_by(|a, b| a.norm_squared().total_cmp(&b.norm_squared()))?;
        let n = best.norm();
        // A well separated eigenvalue gives a long cross product; otherwise iterate.
        if n > 1e-6 * p * p {
            return Some((mu, best / n));
        }
    }
    let eig = SymmetricEigen::new(*k);
    let (imax, &mu) = eig
        .eigenvalues
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))?;
    Some((mu, eig.eigenvectors.column(imax).into()))
}

/// The shape model of §2.1.3: corner s, unit asymptote directions v₁, v₂, and the standard
/// position quantities.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Asymptotes {
    /// The corner: where the asymptotes meet.
    pub s: [f64; 2],
    /// Unit directions of the two asymptotes.
    pub v: [[f64; 2]; 2],
    /// Rotation angle θ of eq. 2.6 (chosen so that a′ > 0).
    pub theta: f64,
    /// a′ > 0 and c′ < 0 of the standard position.
    pub a1: f64,
    pub c1: f64,
    /// ψ = atan(v₂/v₁) of §2.1.4: half the angle between the asymptotes, measured across the
    /// x′ axis, in (0, π/2).
    pub psi: f64,
}

impl Asymptotes {
    /// Closed form of eqs. 2.6–2.8 for a hyperbola (b² − 4ac > 0).
    pub fn of(q: &Conic) -> Option<Self> {
        // Eq. 2.6: cot 2θ = (c − a)/b.
        let mut theta = 0.5 * q.b.atan2(q.c - q.a);
        let prime = |th: f64| {
            let (sn, cs) = th.sin_cos();
            let a1 = q.a * cs * cs - q.b * sn * cs + q.c * sn * sn;
            let c1 = q.a * sn * sn + q.b * sn * cs + q.c * cs * cs;
            (a1, c1)
        };
        let (mut a1, mut c1) = prime(theta);
        if a1 < 0.0 {
            // §2.1.3 asks for a′ > 0: a quarter turn swaps the axes.
            theta += std::f64::consts::FRAC_PI_2;
            (a1, c1) = prime(theta);
        }
        if !(a1 > 0.0 && c1 < 0.0) {
            return None;
        }
        let (sn, cs) = theta.sin_cos();
        let d1 = q.d * cs - q.e * sn;
        let e1 = q.d * sn + q.e * cs;
        // Eq. 2.7 gives the centre in the rotated frame; x = R(θ) x′ brings it back.
        let (xs, ys) = (-d1 / (2.0 * a1), -e1 / (2.0 * c1));
        let rot = |x: f64, y: f64| [cs * x + sn * y, -sn * x + cs * y];
        let s = rot(xs, ys);
        // Eq. 2.8 as extracted reads (√a′, ±√−c′); the asymptotes of a′x′² + c′y′² = 0 are
        // y′ = ±√(a′/−c′) x′, i.e. directions (√−c′, ±√a′), which is what we use.
        let (p, r) = ((-c1).sqrt(), a1.sqrt());
        let n = (p * p + r * r).sqrt();
        let v1 = rot(p / n, r / n);
        let v2 = rot(p / n, -r / n);
        let psi = (r / p).atan();
        if !(s[0].is_finite() && s[1].is_finite()) {
            return None;
        }
        Some(Self {
            s,
            v: [v1, v2],
            theta,
            a1,
            c1,
            psi,
        })
    }

    /// Euclidean distance from (x, y) to asymptote `i`.
    #[inline]
    pub fn distance(&self, i: usize, x: f64, y: f64) -> f64 {
        let v = self.v[i];
        ((x - self.s[0]) * v[1] - (y - self.s[1]) * v[0]).abs()
    }

    /// Angle between the two asymptotes as lines, in [0, π/2].
    pub fn line_angle(&self) -> f64 {
        let dot = (self.v[0][0] * self.v[1][0] + self.v[0][1] * self.v[1][1]).abs();
        dot.min(1.0).acos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line_pair_points(c: [f64; 2], t1: f64, t2: f64, n: usize) -> Vec<[f64; 3]> {
        let mut pts = Vec::new();
        for k in 1..=n {
            let r = k as f64 * 0.7;
            pts.push([c[0] + r * t1.cos(), c[1] + r * t1.sin(), 1.0]);
            pts.push([c[0] + r * t2.cos(), c[1] + r * t2.sin(), 1.0]);
        }
        pts
    }

    #[test]
    fn exact_l_corner_is_recovered() {
        let c = [0.8, -1.3];
        let (t1, t2) = (0.3f64, 0.3 + 1.2);
        let q = fit_hyperbola(&line_pair_points(c, t1, t2, 8), 6.0).unwrap();
        assert!((q.discriminant() - 1.0).abs() < 1e-9);
        assert!(q.delta().abs() < 1e-6, "Δ = {}", q.delta());
        let h = Asymptotes::of(&q).unwrap();
        assert!(
            (h.s[0] - c[0]).abs() < 1e-6 && (h.s[1] - c[1]).abs() < 1e-6,
            "{:?}",
            h.s
        );
        assert!((h.line_angle() - 1.2).abs() < 1e-6);
        let dirs: Vec<f64> =
            h.v.iter()
                .map(|v| v[1].atan2(v[0]).rem_euclid(std::f64::consts::PI))
                .collect();
        for t in [t1, t2] {
            assert!(dirs.iter().any(|d| (d - t).abs() < 1e-6), "{dirs:?} vs {t}");
        }
    }

    #[test]
    fn known_hyperbola_gives_its_centre_and_psi() {
        // x²/4 − y² = 1 rotated by 30° and moved to (1, 2): asymptotes at ±atan(1/2) about the
        // x′ axis, so ψ = atan(1/2).
        let (sn, cs) = (30f64.to_radians()).sin_cos();
        let mut pts = Vec::new();
        for k in -10..=10 {
            let t = k as f64 * 0.25;
            for sgn in [-1.0, 1.0] {
                let (xp, yp) = (sgn * 2.0 * t.cosh(), t.sinh());
                pts.push([1.0 + cs * xp - sn * yp, 2.0 + sn * xp + cs * yp, 1.0]);
            }
        }
        let q = fit_hyperbola(&pts, 6.0).unwrap();
        let h = Asymptotes::of(&q).unwrap();
        assert!((h.s[0] - 1.0).abs() < 1e-6 && (h.s[1] - 2.0).abs() < 1e-6);
        assert!((h.psi - 0.5f64.atan()).abs() < 1e-6, "ψ = {}", h.psi);
        // Δ = a′c′f″ with 4a′c′ = −1: here the conic is x′²/4 − y′² − 1, Δ = 1/4.
        assert!((q.delta() - 0.25).abs() < 1e-6, "Δ = {}", q.delta());
    }

    #[test]
    fn closed_form_eigen_matches_the_iterative_one() {
        let k = Matrix3::new(2.0, -0.5, 0.3, -0.5, -1.0, 0.7, 0.3, 0.7, 0.5);
        let (mu, v) = largest_eigen(&k).unwrap();
        let eig = SymmetricEigen::new(k);
        let top = eig.eigenvalues.max();
        assert!((mu - top).abs() < 1e-9);
        assert!(((k * v) - v * mu).norm() < 1e-9);
        // A multiple of the identity has no preferred vector but still an answer.
        let (mu, v) = largest_eigen(&(Matrix3::identity() * 3.0)).unwrap();
        assert!((mu - 3.0).abs() < 1e-12 && (v.norm() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn collinear_points_do_not_fit() {
        let pts: Vec<[f64; 3]> = (0..20).map(|i| [i as f64, 2.0 * i as f64, 1.0]).collect();
        let fitted = fit_hyperbola(&pts, 6.0);
        // Either no fit or a degenerate one; never a panic. A fit must satisfy the constraint.
        if let Some(q) = fitted {
            assert!((q.discriminant() - 1.0).abs() < 1e-6);
        }
        assert!(fit_hyperbola(&pts[..4], 6.0).is_none());
    }
}
