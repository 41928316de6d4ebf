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
        let (b, d, e) = (self.b / 2.0, self.d / 2.0, self.e / 2.0);
        det3(&[[self.a, b, d], [b, self.c, e], [d, e, self.f]])
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
    let mut mo = Moments::default();
    for p in points {
        mo.add(p[0] / scale, p[1] / scale, p[2] * p[2]);
    }
    fit_moments(&mo, scale)
}

/// The 15 weighted moments Σ w² xᵃ yᵇ (a + b ≤ 4) that make up the scatter S = MᵗM of eq. 2.3,
/// with the number of points. Departure from §2.1.2 in form only: the fit is computed from these
/// sums rather than from M, so a window's scatter costs 15 multiply-adds per point and no matrix.
#[derive(Debug, Clone, Copy, Default)]
pub struct Moments {
    pub n: usize,
    /// Indexed by `moment_index(a, b)`.
    pub m: [f64; 15],
}

/// Position of Σ w² xᵃ yᵇ in [`Moments::m`] (by total degree, then by b).
#[inline]
pub const fn moment_index(a: usize, b: usize) -> usize {
    let d = a + b;
    d * (d + 1) / 2 + b
}

impl Moments {
    /// Adds one point (coordinates already scaled) with squared weight `w2`.
    #[inline(always)]
    pub fn add(&mut self, x: f64, y: f64, w2: f64) {
        let (wx, wy) = (w2 * x, w2 * y);
        let (wx2, wxy, wy2) = (wx * x, wx * y, wy * y);
        let (wx3, wx2y, wxy2, wy3) = (wx2 * x, wx2 * y, wy2 * x, wy2 * y);
        let m = &mut self.m;
        m[0] += w2;
        m[1] += wx;
        m[2] += wy;
        m[3] += wx2;
        m[4] += wxy;
        m[5] += wy2;
        m[6] += wx3;
        m[7] += wx2y;
        m[8] += wxy2;
        m[9] += wy3;
        m[10] += wx3 * x;
        m[11] += wx3 * y;
        m[12] += wx2y * y;
        m[13] += wxy2 * y;
        m[14] += wy3 * y;
        self.n += 1;
    }

    /// The moments of these points without `other`'s (a subset of them).
    pub fn minus(&self, other: &Moments) -> Moments {
        Moments {
            n: self.n.saturating_sub(other.n),
            m: std::array::from_fn(|k| self.m[k] - other.m[k]),
        }
    }
}

/// The fit of [`fit_hyperbola`] from moments of points scaled by `1/scale`.
///
/// All 3 × 3 algebra is written out (adjugate inverse, Cholesky, triangular inverse) instead of
/// going through general matrix routines: the same equations, at a fraction of the cost, which
/// matters because every edge point's window is fitted (§2.1.2).
pub fn fit_moments(mo: &Moments, scale: f64) -> Option<Conic> {
    if mo.n < 5 {
        return None;
    }
    let s = 1.0 / scale;
    let (t, r) = reduced_scatter(mo)?;
    let a1 = constrained_eigvec_cubic(&r).or_else(|| constrained_eigvec_cholesky(&r))?;
    let a2: [f64; 3] = std::array::from_fn(|i| (0..3).map(|k| t[i][k] * a1[k]).sum());
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

type Mat3 = [[f64; 3]; 3];

/// T = −S₃⁻¹S₂ᵗ (α₂ = T α₁) and the reduced scatter R = S₁ + S₂T of the moments.
fn reduced_scatter(mo: &Moments) -> Option<(Mat3, Mat3)> {
    // Exponents of the monomials [x², xy, y², x, y, 1].
    const EXP: [(usize, usize); 6] = [(2, 0), (1, 1), (0, 2), (1, 0), (0, 1), (0, 0)];
    let at = |i: usize, j: usize| mo.m[moment_index(EXP[i].0 + EXP[j].0, EXP[i].1 + EXP[j].1)];
    let s1: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| at(i, j)));
    let s2: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| at(i, 3 + j)));
    let s3: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| at(3 + i, 3 + j)));
    let s3_inv = inverse3(&s3)?;
    // α₂ = T α₁ with T = −S₃⁻¹ S₂ᵗ.
    let t: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| -(0..3).map(|k| s3_inv[i][k] * s2[j][k]).sum::<f64>())
    });
    // R = S₁ + S₂ T, symmetrised.
    let mut r: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| s1[i][j] + (0..3).map(|k| s2[i][k] * t[k][j]).sum::<f64>())
    });
    for (i, j) in [(1, 0), (2, 0), (2, 1)] {
        let m = 0.5 * (r[i][j] + r[j][i]);
        r[i][j] = m;
        r[j][i] = m;
    }
    Some((t, r))
}

/// α₁ of R α₁ = λ C₁ α₁ for the smallest positive λ, from the characteristic cubic
/// det(R − λC₁) = 0 in closed form (as Halir and Flusser solve their 3 × 3 reduced problem).
/// R is positive semi-definite and C₁ has two positive eigenvalues and one negative, so the
/// cubic has two roots ≥ 0 and one negative (Sylvester's law of inertia): the answer is its
/// middle root, and α₁ the longest cross product of two rows of R − λC₁. None when the roots
/// are too close for that (then [`constrained_eigvec_cholesky`] decides).
///
/// Departure in form from eq. 2.5's generalised 6 × 6 eigenproblem: the same α, from the
/// Halir–Flusser reduction and a cubic, which costs a fraction of a symmetric eigensolver.
fn constrained_eigvec_cubic(r: &[[f64; 3]; 3]) -> Option<[f64; 3]> {
    let (r00, r01, r02, r11, r12, r22) = (r[0][0], r[0][1], r[0][2], r[1][1], r[1][2], r[2][2]);
    // det(R − λC₁) = 4λ³ + 4(r02 − r11)λ² + (r02² − 4 r11 r02 + 4 r01 r12 − r00 r22)λ + det R,
    // made monic: λ³ + bλ² + cλ + d.
    let b = r02 - r11;
    let c = 0.25 * (r02 * r02 - 4.0 * r11 * r02 + 4.0 * r01 * r12 - r00 * r22);
    let d = 0.25 * det3(r);
    let poly = |l: f64| ((l + b) * l + c) * l + d;
    let slope = |l: f64| (3.0 * l + 2.0 * b) * l + c;
    // The middle root lies between the cubic's local maximum and minimum, where it falls; from
    // the inflection point λ = −b/3 Newton's method approaches it monotonically (p is concave
    // on the left of that point, convex on the right), without trigonometry. Three real roots
    // need a negative slope there.
    let mut lambda = -b / 3.0;
    if !(slope(lambda) < 0.0) {
        return None;
    }
    for _ in 0..60 {
        let step = poly(lambda) / slope(lambda);
        if !step.is_finite() {
            return None;
        }
        lambda -= step;
        if step.abs() <= 1e-15 * (lambda.abs() + b.abs() + 1e-300) {
            break;
        }
    }
    let rows = [
        [r00, r01, r02 + 2.0 * lambda],
        [r01, r11 - lambda, r12],
        [r02 + 2.0 * lambda, r12, r22],
    ];
    let cross = |u: &[f64; 3], v: &[f64; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let norm2 = |v: &[f64; 3]| v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    let cands = [
        cross(&rows[0], &rows[1]),
        cross(&rows[0], &rows[2]),
        cross(&rows[1], &rows[2]),
    ];
    let best = cands
        .into_iter()
        .max_by(|u, v| norm2(u).total_cmp(&norm2(v)))?;
    // A simple root leaves R − λC₁ of rank 2 and a cross product of the size of its squared
    // entries; a double root (or none) leaves it near zero.
    let scale = rows.iter().map(norm2).fold(0.0, f64::max);
    if !(norm2(&best) > 1e-16 * scale * scale) {
        return None;
    }
    Some(best)
}

/// The same α₁ by the symmetric route: with R = LLᵗ (Cholesky) and u = Lᵗα₁, the eigenvector
/// of the largest 1/λ of L⁻¹C₁L⁻ᵗ. Slower, but it handles double roots.
fn constrained_eigvec_cholesky(r: &[[f64; 3]; 3]) -> Option<[f64; 3]> {
    let mut r = *r;
    // A tiny ridge keeps R positive definite when the points lie exactly on a conic (R is
    // then singular and its null vector is the answer, found as 1/λ → ∞).
    let ridge = (r[0][0] + r[1][1] + r[2][2]).abs() * 1e-12 + f64::MIN_POSITIVE;
    for (i, row) in r.iter_mut().enumerate() {
        row[i] += ridge;
    }
    let l = cholesky3(&r)?;
    let li = lower_inverse3(&l)?;
    // K = L⁻¹ C₁ L⁻ᵗ with C₁ of eq. 2.4 (its quadratic block, αᵗC α = b² − 4ac):
    // C₁ = [[0, 0, −2], [0, 1, 0], [−2, 0, 0]].
    let k = Matrix3::from_fn(|i, j| {
        -2.0 * (li[i][0] * li[j][2] + li[i][2] * li[j][0]) + li[i][1] * li[j][1]
    });
    let (mu, u) = largest_eigen(&k)?;
    if !(mu > 0.0) {
        return None;
    }
    // α₁ = L⁻ᵗ u.
    Some(std::array::from_fn(|i| {
        (0..3).map(|k| li[k][i] * u[k]).sum()
    }))
}

fn det3(m: &[[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// Inverse by the adjugate; None when singular or not finite.
fn inverse3(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let det = det3(m);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv = 1.0 / det;
    let c = |i: usize, j: usize| {
        let (i1, i2, j1, j2) = ((i + 1) % 3, (i + 2) % 3, (j + 1) % 3, (j + 2) % 3);
        m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]
    };
    Some(std::array::from_fn(|i| {
        std::array::from_fn(|j| c(j, i) * inv)
    }))
}

/// Lower Cholesky factor of a symmetric positive definite 3 × 3 matrix.
fn cholesky3(a: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let mut l = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..=i {
            let s = a[i][j] - (0..j).map(|k| l[i][k] * l[j][k]).sum::<f64>();
            if i == j {
                if !(s > 0.0) {
                    return None;
                }
                l[i][i] = s.sqrt();
            } else {
                l[i][j] = s / l[j][j];
            }
        }
    }
    Some(l)
}

/// Inverse of a lower-triangular 3 × 3 matrix with a positive diagonal.
fn lower_inverse3(l: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let (d0, d1, d2) = (1.0 / l[0][0], 1.0 / l[1][1], 1.0 / l[2][2]);
    if !(d0.is_finite() && d1.is_finite() && d2.is_finite()) {
        return None;
    }
    let m10 = -l[1][0] * d0 * d1;
    let m21 = -l[2][1] * d1 * d2;
    let m20 = -(l[2][0] * d0 + l[2][1] * m10) * d2;
    Some([[d0, 0.0, 0.0], [m10, d1, 0.0], [m20, m21, d2]])
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
    /// (cos θ, sin θ) of the rotation of eq. 2.6 (θ chosen so that a′ > 0).
    pub rotation: [f64; 2],
    /// a′ > 0 and c′ < 0 of the standard position.
    pub a1: f64,
    pub c1: f64,
    /// ψ = atan(v₂/v₁) of §2.1.4: half the angle between the asymptotes, measured across the
    /// x′ axis, in (0, π/2).
    pub psi: f64,
}

impl Asymptotes {
    /// Closed form of eqs. 2.6–2.8 for a hyperbola (b² − 4ac > 0).
    ///
    /// Eq. 2.6 gives θ through cot 2θ; we take cos θ and sin θ from cos 2θ and sin 2θ by the
    /// half-angle formulas instead of calling atan2 and sin/cos, which is the same rotation
    /// (θ = ½ atan2(b, c − a), then a quarter turn when a′ < 0) without trigonometry.
    pub fn of(q: &Conic) -> Option<Self> {
        let rho = (q.b * q.b + (q.c - q.a) * (q.c - q.a)).sqrt();
        let (c2, s2) = if rho > 0.0 {
            ((q.c - q.a) / rho, q.b / rho)
        } else {
            (1.0, 0.0)
        };
        let (mut cs, mut sn) = if c2 >= 0.0 {
            let cs = (0.5 * (1.0 + c2)).sqrt();
            (cs, s2 / (2.0 * cs))
        } else {
            let sn = (0.5 * (1.0 - c2)).sqrt().copysign(s2);
            (s2 / (2.0 * sn), sn)
        };
        let prime = |cs: f64, sn: f64| {
            let a1 = q.a * cs * cs - q.b * sn * cs + q.c * sn * sn;
            let c1 = q.a * sn * sn + q.b * sn * cs + q.c * cs * cs;
            (a1, c1)
        };
        let (mut a1, mut c1) = prime(cs, sn);
        if a1 < 0.0 {
            // §2.1.3 asks for a′ > 0: a quarter turn swaps the axes.
            (cs, sn) = (-sn, cs);
            (a1, c1) = prime(cs, sn);
        }
        if !(a1 > 0.0 && c1 < 0.0) {
            return None;
        }
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
            rotation: [cs, sn],
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
    fn written_out_3x3_algebra_matches_nalgebra() {
        let a = [[4.0, 1.2, -0.7], [1.2, 3.0, 0.4], [-0.7, 0.4, 2.5]];
        let m = Matrix3::from_fn(|i, j| a[i][j]);
        let inv = inverse3(&a).unwrap();
        let want = m.try_inverse().unwrap();
        let l = cholesky3(&a).unwrap();
        let want_l = m.cholesky().unwrap().l();
        let li = lower_inverse3(&l).unwrap();
        let want_li = want_l.try_inverse().unwrap();
        for i in 0..3 {
            for j in 0..3 {
                assert!((inv[i][j] - want[(i, j)]).abs() < 1e-12);
                assert!((l[i][j] - want_l[(i, j)]).abs() < 1e-12);
                assert!((li[i][j] - want_li[(i, j)]).abs() < 1e-12);
            }
        }
        assert!((det3(&a) - m.determinant()).abs() < 1e-12);
        assert!(inverse3(&[[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 1.0, 1.0]]).is_none());
        assert!(cholesky3(&[[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).is_none());
    }

    #[test]
    fn cubic_and_cholesky_routes_give_the_same_fit() {
        // Reduced scatters of noisy corners at many angles, offsets and weights: both solvers
        // of R α₁ = λ C₁ α₁ return the same direction.
        let mut checked = 0;
        for k in 0..200 {
            let t1 = k as f64 * 0.37;
            let t2 = t1 + 0.5 + (k % 7) as f64 * 0.3;
            let c = [
                ((k * 13) % 7) as f64 * 0.3 - 1.0,
                ((k * 5) % 9) as f64 * 0.2 - 0.8,
            ];
            let mut pts = line_pair_points(c, t1, t2, 6);
            for (i, p) in pts.iter_mut().enumerate() {
                p[0] += 0.05 * ((i * 7 + k) as f64).sin();
                p[1] += 0.05 * ((i * 3 + k) as f64).cos();
                p[2] = 1.0 + (i % 4) as f64;
            }
            let mut mo = Moments::default();
            for p in &pts {
                mo.add(p[0] / 6.0, p[1] / 6.0, p[2] * p[2]);
            }
            let r = reduced_scatter(&mo).unwrap().1;
            let (Some(u), Some(v)) = (
                constrained_eigvec_cubic(&r),
                constrained_eigvec_cholesky(&r),
            ) else {
                continue;
            };
            let n = |a: &[f64; 3]| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            let cos = (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) / (n(&u) * n(&v));
            assert!(cos.abs() > 1.0 - 1e-9, "case {k}: |cos| = {}", cos.abs());
            checked += 1;
        }
        assert!(checked > 190, "{checked} cases solved by both");
    }

    #[test]
    fn half_angle_rotation_is_eq_2_6() {
        // For conics at every orientation, (cos θ, sin θ) is the rotation with cot 2θ =
        // (c − a)/b (up to the quarter turn that makes a′ > 0) and it diagonalises the
        // quadratic part.
        for k in 0..72 {
            let phi = k as f64 * 5f64.to_radians();
            let (sn, cs) = phi.sin_cos();
            // x′²/4 − y′² = 1 with x′ along phi, centred at (0.3, −0.2).
            let (a, c) = (0.25, -1.0);
            let q = Conic {
                a: a * cs * cs + c * sn * sn,
                b: 2.0 * (a - c) * sn * cs,
                c: a * sn * sn + c * cs * cs,
                d: 0.0,
                e: 0.0,
                f: -1.0,
            };
            let (x0, y0) = (0.3, -0.2);
            let q = Conic {
                d: -2.0 * q.a * x0 - q.b * y0,
                e: -2.0 * q.c * y0 - q.b * x0,
                f: q.a * x0 * x0 + q.b * x0 * y0 + q.c * y0 * y0 - 1.0,
                ..q
            };
            let h = Asymptotes::of(&q).unwrap();
            let [cs, sn] = h.rotation;
            assert!((cs * cs + sn * sn - 1.0).abs() < 1e-12);
            let theta = sn.atan2(cs);
            let want = 0.5 * q.b.atan2(q.c - q.a);
            let turns = (theta - want) / std::f64::consts::FRAC_PI_2;
            assert!((turns - turns.round()).abs() < 1e-9, "θ {theta} vs {want}");
            let cross = 2.0 * (q.a - q.c) * sn * cs + q.b * (cs * cs - sn * sn);
            assert!(cross.abs() < 1e-9, "{k}: off-diagonal {cross}");
            assert!((h.s[0] - x0).abs() < 1e-9 && (h.s[1] - y0).abs() < 1e-9);
            assert!((h.psi - 0.5f64.atan()).abs() < 1e-9);
        }
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
