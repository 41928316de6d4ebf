//! Gaussian mixtures fitted by Expectation Maximisation (§3.1.3): one mixture per semantic class,
//! one component per user box, full covariances with a small ridge so flat boxes stay regular.

use nalgebra::{DMatrix, DVector};

pub use super::simd::fma_available;
use super::simd::{exp_nonpositive, madd};

use crate::error::{FacadeError, Result};

/// Largest feature dimension handled (the text's features have 18).
pub const MAX_DIM: usize = 64;

/// One multivariate normal, stored for fast log densities: the inverse Cholesky factor.
#[derive(Debug, Clone)]
pub struct Gaussian {
    pub mean: DVector<f64>,
    /// L⁻¹ with Σ = L Lᵀ, lower triangle packed column by column (column j holds rows j..d), so
    /// z = L⁻¹ (x − μ) is a run of contiguous, vectorisable updates.
    l_inv: Vec<f64>,
    /// −½ (d ln 2π + ln |Σ|).
    log_norm: f64,
    /// f32 copies for [`Gmm::log_pdf_block`]: the mean, and L⁻¹'s lower triangle row by row.
    mean32: Vec<f32>,
    l_inv_rows: Vec<f32>,
}

impl Gaussian {
    /// From a mean and covariance; `ridge[i]` is added to diagonal entry i.
    pub fn new(mean: DVector<f64>, mut cov: DMatrix<f64>, ridge: &[f64]) -> Result<Gaussian> {
        let d = mean.len();
        if d > MAX_DIM || ridge.len() < d || cov.shape() != (d, d) {
            return Err(FacadeError::Numerical(format!(
                "Gaussians of 1 to {MAX_DIM} dimensions with a matching covariance and ridge (got {d})"
            )));
        }
        for i in 0..d {
            cov[(i, i)] += ridge[i];
        }
        let chol = cov
            .cholesky()
            .ok_or_else(|| FacadeError::Numerical("covariance not positive definite".into()))?;
        let l = chol.l();
        let log_det: f64 = 2.0 * l.diagonal().iter().map(|v| v.ln()).sum::<f64>();
        let l_inv = l
            .solve_lower_triangular(&DMatrix::identity(d, d))
            .ok_or_else(|| FacadeError::Numerical("singular covariance".into()))?;
        let l_inv_rows = (0..d)
            .flat_map(|i| (0..=i).map(move |j| (i, j)))
            .map(|(i, j)| l_inv[(i, j)] as f32)
            .collect();
        let l_inv_cols = (0..d)
            .flat_map(|j| (j..d).map(move |i| (i, j)))
            .map(|(i, j)| l_inv[(i, j)])
            .collect();
        Ok(Gaussian {
            mean32: mean.iter().map(|&v| v as f32).collect(),
            mean,
            l_inv: l_inv_cols,
            log_norm: -0.5 * (d as f64 * (2.0 * std::f64::consts::PI).ln() + log_det),
            l_inv_rows,
        })
    }

    /// ln N(x | μ, Σ).
    pub fn log_pdf(&self, x: &[f32]) -> f64 {
        let d = self.mean.len();
        let mut z = [0f64; MAX_DIM];
        let mut at = 0;
        for j in 0..d {
            let diff = x[j] as f64 - self.mean[j];
            let col = &self.l_inv[at..at + d - j];
            at += d - j;
            for (zi, l) in z[j..d].iter_mut().zip(col) {
                *zi += l * diff;
            }
        }
        let m: f64 = z[..d].iter().map(|v| v * v).sum();
        self.log_norm - 0.5 * m
    }

    /// ln N(x | μ, Σ) for BLOCK points at once, given feature-major (`x[i][lane]`), in f32;
    /// `diff` is scratch of at least d rows. The lanes share every L⁻¹ entry, so the triangular
    /// solve vectorises across points.
    #[inline(always)]
    fn log_pdf_block_with<const FMA: bool>(
        &self,
        x: &[[f32; BLOCK]],
        diff: &mut [[f32; BLOCK]],
    ) -> [f32; BLOCK] {
        let d = self.mean32.len();
        let mut maha = [0f32; BLOCK];
        let mut at = 0;
        for i in 0..d {
            for (a, b) in diff[i].iter_mut().zip(&x[i]) {
                *a = b - self.mean32[i];
            }
            let row = &self.l_inv_rows[at..at + i + 1];
            at += i + 1;
            // Two partial sums (even and odd j) halve the chain of dependent additions.
            let (mut z0, mut z1) = ([0f32; BLOCK], [0f32; BLOCK]);
            let mut pairs = row.chunks_exact(2).zip(diff.chunks_exact(2));
            for (l, df) in pairs.by_ref() {
                for lane in 0..BLOCK {
                    z0[lane] = madd::<FMA>(z0[lane], l[0], df[0][lane]);
                    z1[lane] = madd::<FMA>(z1[lane], l[1], df[1][lane]);
                }
            }
            if i % 2 == 0 {
                for lane in 0..BLOCK {
                    z0[lane] = madd::<FMA>(z0[lane], row[i], diff[i][lane]);
                }
            }
            for lane in 0..BLOCK {
                let z = z0[lane] + z1[lane];
                maha[lane] = madd::<FMA>(maha[lane], z, z);
            }
        }
        maha.map(|m| self.log_norm as f32 - 0.5 * m)
    }
}

/// Points evaluated together by [`Gmm::log_pdf_block`].
pub const BLOCK: usize = 16;

/// A Gaussian mixture P(X | w, u, Σ) = Σ_i w_i N(X | u_i, Σ_i).
#[derive(Debug, Clone)]
pub struct Gmm {
    pub weights: Vec<f64>,
    /// ln w_i, kept beside the weights for per-pixel evaluation.
    log_weights: Vec<f64>,
    pub components: Vec<Gaussian>,
}

fn log_sum_exp(v: &[f64]) -> f64 {
    let m = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if m == f64::NEG_INFINITY {
        return m;
    }
    m + v.iter().map(|x| (x - m).exp()).sum::<f64>().ln()
}

/// Weighted mean and covariance of the samples.
fn moments(data: &[&[f32]], resp: &[f64], d: usize) -> (DVector<f64>, DMatrix<f64>, f64) {
    let total: f64 = resp.iter().sum();
    let mut mean = DVector::zeros(d);
    for (x, r) in data.iter().zip(resp) {
        for i in 0..d {
            mean[i] += r * x[i] as f64;
        }
    }
    mean /= total.max(1e-300);
    let mut cov = DMatrix::zeros(d, d);
    let mut diff = DVector::zeros(d);
    for (x, r) in data.iter().zip(resp) {
        for i in 0..d {
            diff[i] = x[i] as f64 - mean[i];
        }
        cov.ger(*r, &diff, &diff, 1.0);
    }
    cov /= total.max(1e-300);
    (mean, cov, total)
}

impl Gmm {
    /// ln P(x).
    pub fn log_pdf(&self, x: &[f32]) -> f64 {
        let mut v = [0f64; 32];
        let n = self.components.len().min(32);
        for ((vi, lw), c) in v.iter_mut().zip(&self.log_weights).zip(&self.components) {
            *vi = lw + c.log_pdf(x);
        }
        log_sum_exp(&v[..n])
    }

    /// ln P(x) for BLOCK points given feature-major, `x[i][lane]`, with `diff` scratch of at
    /// least d rows. Departure (speed, §3.1.4): the text's per-pixel evaluation, but sixteen
    /// pixels at a time and in single precision (the maps are stored as f32 anyway).
    /// `fma`: use AVX2 + FMA; pass [`fma_available`]'s answer.
    pub fn log_pdf_block(
        &self,
        fma: bool,
        x: &[[f32; BLOCK]],
        diff: &mut [[f32; BLOCK]],
    ) -> [f32; BLOCK] {
        #[cfg(target_arch = "x86_64")]
        if fma {
            // SAFETY: `fma` is only true when the CPU reported AVX2 and FMA.
            return unsafe { self.log_pdf_block_fma(x, diff) };
        }
        let _ = fma;
        self.log_pdf_block_with::<false>(x, diff)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn log_pdf_block_fma(&self, x: &[[f32; BLOCK]], diff: &mut [[f32; BLOCK]]) -> [f32; BLOCK] {
        self.log_pdf_block_with::<true>(x, diff)
    }

    #[inline(always)]
    fn log_pdf_block_with<const FMA: bool>(
        &self,
        x: &[[f32; BLOCK]],
        diff: &mut [[f32; BLOCK]],
    ) -> [f32; BLOCK] {
        // Log-sum-exp over the components, with a vectorisable exp.
        let n = self.components.len();
        // A stack buffer for the usual few components (zeroing 32 rows per block costs more).
        let mut few = [[0f32; BLOCK]; 4];
        let mut many = Vec::new();
        let values: &mut [[f32; BLOCK]] = if n <= few.len() {
            &mut few[..n]
        } else {
            many.resize(n, [0f32; BLOCK]);
            &mut many
        };
        let mut max = [f32::NEG_INFINITY; BLOCK];
        for ((v, lw), c) in values
            .iter_mut()
            .zip(&self.log_weights)
            .zip(&self.components)
        {
            *v = c.log_pdf_block_with::<FMA>(x, diff);
            for (m, vi) in max.iter_mut().zip(v.iter_mut()) {
                *vi += *lw as f32;
                *m = m.max(*vi);
            }
        }
        let mut sum = [0f32; BLOCK];
        for v in values.iter() {
            for lane in 0..BLOCK {
                sum[lane] += exp_nonpositive(v[lane] - max[lane]);
            }
        }
        std::array::from_fn(|lane| max[lane] + sum[lane].ln())
    }

    /// EM from an initial partition of the samples (one group per component, e.g. one per user
    /// box); at most `max_iter` iterations, stopping when the mean log-likelihood gains < 1e-6.
    pub fn fit(
        data: &[&[f32]],
        groups: &[Vec<usize>],
        ridge: &[f64],
        max_iter: usize,
    ) -> Result<Gmm> {
        let m = groups.len();
        if ridge.len() < data.first().map_or(0, |x| x.len()) {
            return Err(FacadeError::Numerical(
                "ridge shorter than the features".into(),
            ));
        }
        if m == 0 || m > 32 || data.is_empty() {
            return Err(FacadeError::BadTraining(format!(
                "a mixture needs 1 to 32 components and some samples (got {m} components, {} samples)",
                data.len()
            )));
        }
        let d = data[0].len();
        let n = data.len();
        // Initial responsibilities: hard membership of each group.
        let mut resp = vec![vec![0f64; n]; m];
        for (k, g) in groups.iter().enumerate() {
            if g.is_empty() {
                return Err(FacadeError::BadTraining(
                    "a training box has no pixels".into(),
                ));
            }
            for &i in g {
                resp[k][i] = 1.0;
            }
        }
        let mut gmm = Gmm::m_step(data, &resp, d, ridge)?;
        let mut last = f64::NEG_INFINITY;
        for _ in 0..max_iter {
            // E step.
            let mut ll = 0.0;
            let mut lp = vec![0f64; m];
            for (i, x) in data.iter().enumerate() {
                for ((l, w), c) in lp.iter_mut().zip(&gmm.weights).zip(&gmm.components) {
                    *l = w.ln() + c.log_pdf(x);
                }
                let z = log_sum_exp(&lp);
                ll += z;
                for k in 0..m {
                    resp[k][i] = (lp[k] - z).exp();
                }
            }
            ll /= n as f64;
            gmm = Gmm::m_step(data, &resp, d, ridge)?;
            if ll - last < 1e-6 {
                break;
            }
            last = ll;
        }
        Ok(gmm)
    }

    fn m_step(data: &[&[f32]], resp: &[Vec<f64>], d: usize, ridge: &[f64]) -> Result<Gmm> {
        let n = data.len() as f64;
        let mut weights = Vec::new();
        let mut components = Vec::new();
        for r in resp {
            let (mean, cov, total) = moments(data, r, d);
            // A component that lost all its samples keeps a tiny weight and a broad shape.
            weights.push((total / n).max(1e-6));
            components.push(Gaussian::new(mean, cov, ridge)?);
        }
        let s: f64 = weights.iter().sum();
        weights.iter_mut().for_each(|w| *w /= s);
        let log_weights = weights.iter().map(|w| w.ln()).collect();
        Ok(Gmm {
            weights,
            log_weights,
            components,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaussian_log_pdf_matches_the_formula() {
        let g = Gaussian::new(
            DVector::from_vec(vec![1.0, 2.0]),
            DMatrix::from_row_slice(2, 2, &[4.0, 0.0, 0.0, 1.0]),
            &[0.0, 0.0],
        )
        .unwrap();
        // x = (3, 2): Mahalanobis² = 1, |Σ| = 4.
        let want = -0.5 * (2.0 * (2.0 * std::f64::consts::PI).ln() + 4f64.ln()) - 0.5;
        assert!((g.log_pdf(&[3.0, 2.0]) - want).abs() < 1e-12);
    }

    #[test]
    fn block_evaluation_matches_the_scalar_one() {
        // Three correlated 3-D clusters, one component each.
        let pts: Vec<[f32; 3]> = (0..90)
            .map(|i| {
                let (c, t) = ((i / 30) as f32, (i % 30) as f32 / 30.0);
                [c + t, 2.0 * c - t * t, 0.5 * t + (i % 7) as f32 * 0.05]
            })
            .collect();
        let data: Vec<&[f32]> = pts.iter().map(|p| &p[..]).collect();
        let groups: Vec<Vec<usize>> = (0..3).map(|c| (c * 30..c * 30 + 30).collect()).collect();
        let g = Gmm::fit(&data, &groups, &[1e-3; 3], 20).unwrap();
        for chunk in pts.chunks(BLOCK) {
            let mut x = [[0f32; BLOCK]; 3];
            for (lane, p) in chunk.iter().enumerate() {
                for i in 0..3 {
                    x[i][lane] = p[i];
                }
            }
            let block = g.log_pdf_block(fma_available(), &x, &mut [[0f32; BLOCK]; 3]);
            let plain = g.log_pdf_block(false, &x, &mut [[0f32; BLOCK]; 3]);
            assert!(
                block
                    .iter()
                    .zip(&plain)
                    .all(|(a, b)| (a - b).abs() < 1e-3 * a.abs().max(1.0))
            );
            for (lane, p) in chunk.iter().enumerate() {
                let want = g.log_pdf(p);
                assert!(
                    (block[lane] as f64 - want).abs() < 1e-3 * want.abs().max(1.0),
                    "{} vs {want}",
                    block[lane]
                );
            }
        }
    }

    #[test]
    fn em_separates_two_clusters() {
        let pts: Vec<[f32; 1]> = (0..200)
            .map(|i| {
                [if i < 100 {
                    (i % 10) as f32 * 0.1
                } else {
                    10.0 + (i % 10) as f32 * 0.1
                }]
            })
            .collect();
        let data: Vec<&[f32]> = pts.iter().map(|p| &p[..]).collect();
        // Start from a poor split: both groups mix the clusters.
        let groups = vec![(0..120).collect::<Vec<_>>(), (120..200).collect()];
        let g = Gmm::fit(&data, &groups, &[1e-6], 100).unwrap();
        let mut means: Vec<f64> = g.components.iter().map(|c| c.mean[0]).collect();
        means.sort_by(|a, b| a.total_cmp(b));
        assert!(
            (means[0] - 0.45).abs() < 0.01 && (means[1] - 10.45).abs() < 0.01,
            "{means:?}"
        );
        assert!((g.weights[0] - 0.5).abs() < 0.01);
    }
}
