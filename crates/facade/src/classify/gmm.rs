//! Gaussian mixtures fitted by Expectation Maximisation (§3.1.3): one mixture per semantic class,
//! one component per user box, full covariances with a small ridge so flat boxes stay regular.

use nalgebra::{DMatrix, DVector};

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
        let l_inv = (0..d)
            .flat_map(|j| (j..d).map(move |i| (i, j)))
            .map(|(i, j)| l_inv[(i, j)])
            .collect();
        Ok(Gaussian {
            mean,
            l_inv,
            log_norm: -0.5 * (d as f64 * (2.0 * std::f64::consts::PI).ln() + log_det),
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
}

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
