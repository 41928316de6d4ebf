//! ilastik's pixel-classification feature bank: per channel and scale σ, the smoothed value,
//! gradient magnitude, Laplacian of Gaussian, difference of Gaussians, and the eigenvalues of
//! the structure tensor and of the Hessian. Which scales and families are computed is a
//! [`FilterBank`]; the default is the subset measured best for its time on the façade sets
//! (docs/pixelclass.md).

use rayon::prelude::*;

use crate::channels::Channels;
use crate::filters::{derivatives, eigen2, plane, smooth};

/// One family of filter responses.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub enum Family {
    /// Gaussian smoothing G_σ.
    Smoothing,
    /// |∇G_σ|.
    GradientMagnitude,
    /// ∂²G_σ/∂x² + ∂²G_σ/∂y²: blobs of size ~σ√2.
    LaplacianOfGaussian,
    /// G_σ − G_{0.66σ} (ilastik's ratio): a cheaper band-pass.
    DifferenceOfGaussians,
    /// Eigenvalues of the gradient outer product at σ smoothed at σ/2 (ilastik's inner and
    /// outer scales): edges (one large) versus corners and texture (two large).
    StructureTensor,
    /// Eigenvalues of the Hessian of G_σ: ridges, valleys and blobs.
    Hessian,
}

impl Family {
    pub const ALL: [Family; 6] = [
        Family::Smoothing,
        Family::GradientMagnitude,
        Family::LaplacianOfGaussian,
        Family::DifferenceOfGaussians,
        Family::StructureTensor,
        Family::Hessian,
    ];

    /// Feature planes one channel and scale contribute.
    pub fn planes(self) -> usize {
        match self {
            Family::StructureTensor | Family::Hessian => 2,
            _ => 1,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Family::Smoothing => "gauss",
            Family::GradientMagnitude => "gradmag",
            Family::LaplacianOfGaussian => "log",
            Family::DifferenceOfGaussians => "dog",
            Family::StructureTensor => "ste",
            Family::Hessian => "hess",
        }
    }
}

/// Scales (pixels of the image the bank runs on) and families to compute for every channel.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FilterBank {
    pub sigmas: Vec<f32>,
    pub families: Vec<Family>,
}

impl FilterBank {
    /// ilastik's full bank: all six families at σ = 0.7, 1, 1.6, 3.5, 5, 10.
    pub fn ilastik() -> FilterBank {
        FilterBank {
            sigmas: vec![0.7, 1.0, 1.6, 3.5, 5.0, 10.0],
            families: Family::ALL.to_vec(),
        }
    }

    /// Feature planes for `channels` input channels.
    pub fn dim(&self, channels: usize) -> usize {
        channels * self.sigmas.len() * self.families.iter().map(|f| f.planes()).sum::<usize>()
    }
}

impl Default for FilterBank {
    /// The measured default (docs/pixelclass.md): smoothing, gradient magnitude, LoG and
    /// Hessian eigenvalues — one blur per channel and scale, all else differences of it — at
    /// σ = 1, 2, 4, 8, 16. On the façade sets the structure tensor and DoG added nothing
    /// measurable for twice the time, and the coarse scales (windows are tens of pixels across)
    /// mattered more than the fine ones.
    fn default() -> FilterBank {
        FilterBank {
            sigmas: vec![1.0, 2.0, 4.0, 8.0, 16.0],
            families: vec![
                Family::Smoothing,
                Family::GradientMagnitude,
                Family::LaplacianOfGaussian,
                Family::Hessian,
            ],
        }
    }
}

/// Feature planes (`planes[f][y * width + x]`) with a name per plane, e.g. `c0 σ1.6 hess1`.
#[derive(Debug, Clone)]
pub struct Features {
    pub width: usize,
    pub height: usize,
    pub planes: Vec<Vec<f32>>,
    pub names: Vec<String>,
}

impl Features {
    pub fn dim(&self) -> usize {
        self.planes.len()
    }

    /// The feature vector of pixel `i` (row-major index), gathered across planes.
    pub fn pixel(&self, i: usize) -> Vec<f32> {
        self.planes.iter().map(|p| p[i]).collect()
    }
}

/// Every family of `bank` at every scale for every channel, the (channel, σ) jobs in parallel.
/// The plane order is channel-major, then σ, then family in `bank.families` order.
pub fn compute(ch: &Channels, bank: &FilterBank) -> Features {
    let (w, h) = (ch.width, ch.height);
    let jobs: Vec<(usize, f32)> = (0..ch.planes.len())
        .flat_map(|c| bank.sigmas.iter().map(move |&s| (c, s)))
        .collect();
    let per_job: Vec<Vec<(String, Vec<f32>)>> = jobs
        .par_iter()
        .map(|&(c, sigma)| {
            scale_features(&ch.planes[c], w, h, sigma, &bank.families)
                .into_iter()
                .map(|(name, p)| (format!("c{c} σ{sigma} {name}"), p))
                .collect()
        })
        .collect();
    let (names, planes) = per_job.into_iter().flatten().unzip();
    Features {
        width: w,
        height: h,
        planes,
        names,
    }
}

/// The families of one channel at one scale.
fn scale_features(
    src: &[f32],
    w: usize,
    h: usize,
    sigma: f32,
    families: &[Family],
) -> Vec<(String, Vec<f32>)> {
    let has = |f: Family| families.contains(&f);
    let g = smooth(src, w, h, sigma);
    let second = has(Family::LaplacianOfGaussian) || has(Family::Hessian);
    let first = second || has(Family::GradientMagnitude) || has(Family::StructureTensor);
    let d = first.then(|| derivatives(&g, w, h, second));
    let mut out = Vec::new();
    for &f in families {
        match f {
            Family::Smoothing => out.push((f.name().to_string(), g.clone())),
            Family::GradientMagnitude => {
                let d = d.as_ref().expect("first derivatives computed");
                let m = plane(w, h, |x, y| {
                    let i = y * w + x;
                    d.gx[i].hypot(d.gy[i])
                });
                out.push((f.name().to_string(), m));
            }
            Family::LaplacianOfGaussian => {
                let d = d.as_ref().expect("second derivatives computed");
                let m = plane(w, h, |x, y| d.gxx[y * w + x] + d.gyy[y * w + x]);
                out.push((f.name().to_string(), m));
            }
            Family::DifferenceOfGaussians => {
                let g2 = smooth(src, w, h, 0.66 * sigma);
                let m = plane(w, h, |x, y| g[y * w + x] - g2[y * w + x]);
                out.push((f.name().to_string(), m));
            }
            Family::StructureTensor => {
                let d = d.as_ref().expect("first derivatives computed");
                let outer = 0.5 * sigma;
                let (txx, (txy, tyy)) = rayon::join(
                    || smooth(&product(&d.gx, &d.gx), w, h, outer),
                    || {
                        rayon::join(
                            || smooth(&product(&d.gx, &d.gy), w, h, outer),
                            || smooth(&product(&d.gy, &d.gy), w, h, outer),
                        )
                    },
                );
                let (l1, l2) = eigen_planes(&txx, &txy, &tyy);
                out.push((format!("{}1", f.name()), l1));
                out.push((format!("{}2", f.name()), l2));
            }
            Family::Hessian => {
                let d = d.as_ref().expect("second derivatives computed");
                let (l1, l2) = eigen_planes(&d.gxx, &d.gxy, &d.gyy);
                out.push((format!("{}1", f.name()), l1));
                out.push((format!("{}2", f.name()), l2));
            }
        }
    }
    out
}

fn product(a: &[f32], b: &[f32]) -> Vec<f32> {
    a.par_iter().zip(b).map(|(u, v)| u * v).collect()
}

/// Per-pixel eigenvalues (larger, smaller) of [[a, b], [b, c]].
fn eigen_planes(a: &[f32], b: &[f32], c: &[f32]) -> (Vec<f32>, Vec<f32>) {
    let both: Vec<(f32, f32)> = a
        .par_iter()
        .zip(b)
        .zip(c)
        .map(|((&a, &b), &c)| eigen2(a, b, c))
        .collect();
    both.into_iter().unzip()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn only(ch: &Channels, sigma: f32, f: Family) -> Vec<Vec<f32>> {
        compute(
            ch,
            &FilterBank {
                sigmas: vec![sigma],
                families: vec![f],
            },
        )
        .planes
    }

    fn channels(w: usize, h: usize, f: impl Fn(usize, usize) -> f32) -> Channels {
        Channels::new(w, h, vec![(0..w * h).map(|i| f(i % w, i / w)).collect()]).unwrap()
    }

    #[test]
    fn the_full_bank_has_eight_planes_per_channel_and_scale_with_names() {
        let ch = channels(12, 10, |x, y| (x * y) as f32 / 100.0);
        let bank = FilterBank::ilastik();
        let f = compute(&ch, &bank);
        assert_eq!(f.dim(), 6 * 8);
        assert_eq!(f.dim(), bank.dim(1));
        assert_eq!(f.names[0], "c0 σ0.7 gauss");
        assert_eq!(f.names[7], "c0 σ0.7 hess2");
        assert!(f.planes.iter().all(|p| p.len() == 120));
    }

    #[test]
    fn log_of_a_bright_disc_is_minimal_at_its_centre() {
        let (w, h, r) = (41, 41, 5.0f32);
        let ch = channels(w, h, |x, y| {
            let d = ((x as f32 - 20.0).powi(2) + (y as f32 - 20.0).powi(2)).sqrt();
            if d <= r { 1.0 } else { 0.0 }
        });
        let log = &only(
            &ch,
            r / std::f32::consts::SQRT_2,
            Family::LaplacianOfGaussian,
        )[0];
        let (imin, _) = log
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))
            .unwrap();
        assert_eq!((imin % w, imin / w), (20, 20));
        assert!(log[20 * w + 20] < 0.0);
    }

    #[test]
    fn structure_tensor_of_a_vertical_step_has_one_large_eigenvalue() {
        let (w, h) = (30, 20);
        let ch = channels(w, h, |x, _| if x < 15 { 0.0 } else { 1.0 });
        let p = only(&ch, 1.6, Family::StructureTensor);
        let i = 10 * w + 15;
        assert!(p[0][i] > 0.01, "λ1 {}", p[0][i]);
        assert!(p[1][i].abs() < 1e-6 * p[0][i].max(1.0), "λ2 {}", p[1][i]);
        // Far from the step both vanish.
        assert!(p[0][10 * w + 2].abs() < 1e-6);
    }

    #[test]
    fn hessian_of_a_bright_ridge_is_strongly_negative_across_and_flat_along() {
        let (w, h) = (31, 25);
        let ch = channels(w, h, |x, _| (-((x as f32 - 15.0).powi(2)) / 4.0).exp());
        let p = only(&ch, 1.0, Family::Hessian);
        let i = 12 * w + 15;
        assert!(p[1][i] < -0.05, "λ2 {}", p[1][i]);
        assert!(p[0][i].abs() < 1e-4, "λ1 {}", p[0][i]);
        // A dark valley flips the sign: the larger eigenvalue is the large one.
        let ch = channels(w, h, |x, _| -(-((x as f32 - 15.0).powi(2)) / 4.0).exp());
        let p = only(&ch, 1.0, Family::Hessian);
        assert!(p[0][i] > 0.05 && p[1][i].abs() < 1e-4);
    }

    #[test]
    fn gradient_magnitude_and_dog_of_a_ramp() {
        let (w, h) = (40, 20);
        let ch = channels(w, h, |x, _| 0.02 * x as f32);
        let g = &only(&ch, 1.6, Family::GradientMagnitude)[0];
        assert!((g[10 * w + 20] - 0.02).abs() < 1e-5, "{}", g[10 * w + 20]);
        // A linear ramp is unchanged by any Gaussian away from the borders: DoG = 0.
        let d = &only(&ch, 1.6, Family::DifferenceOfGaussians)[0];
        assert!(d[10 * w + 20].abs() < 1e-5);
    }
}
