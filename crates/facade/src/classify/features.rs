//! Per-pixel feature vectors of §3.1.3: the RGB values plus a PCA reduction of the L × L × 3
//! patch around the pixel (L = 21) to 5 numbers per channel — 18 dimensions.

use image::RgbImage;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// Feature settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeatureParams {
    /// Patch side L (odd).
    pub patch: usize,
    /// Principal components kept per channel.
    pub components: usize,
    /// Patches sampled (seeded) to estimate the principal components.
    pub pca_samples: usize,
    /// Texture features are computed every `stride` pixels and interpolated bilinearly between.
    /// Departure (speed, §3.1.3): 21 × 21 patches vary slowly, so stride 2 costs little accuracy
    /// for a quarter of the work; 1 is the text.
    pub stride: usize,
    pub seed: u64,
}

impl Default for FeatureParams {
    fn default() -> Self {
        FeatureParams {
            patch: 21,
            components: 5,
            pca_samples: 500,
            stride: 2,
            seed: 7,
        }
    }
}

/// Row-major per-pixel features (`dim` values per pixel, RGB first, scaled to [0, 1]).
#[derive(Debug, Clone)]
pub struct Features {
    pub width: usize,
    pub height: usize,
    pub dim: usize,
    pub data: Vec<f32>,
}

impl Features {
    pub fn at(&self, x: usize, y: usize) -> &[f32] {
        let i = (y * self.width + x) * self.dim;
        &self.data[i..i + self.dim]
    }
}

/// One colour channel, padded by replication so every patch is inside.
struct Plane {
    pad: usize,
    stride: usize,
    v: Vec<f32>,
}

impl Plane {
    fn new(img: &RgbImage, c: usize, pad: usize) -> Plane {
        let (w, h) = (img.width() as usize, img.height() as usize);
        let stride = w + 2 * pad;
        let mut v = vec![0f32; stride * (h + 2 * pad)];
        for py in 0..h + 2 * pad {
            let y = py.saturating_sub(pad).min(h - 1);
            for px in 0..stride {
                let x = px.saturating_sub(pad).min(w - 1);
                v[py * stride + px] = img.get_pixel(x as u32, y as u32)[c] as f32 / 255.0;
            }
        }
        Plane { pad, stride, v }
    }
    /// Row `dy` (0..L) of the patch centred on (x, y).
    fn row(&self, x: usize, y: usize, dy: usize, l: usize) -> &[f32] {
        let (px, py) = (x + self.pad - l / 2, y + self.pad - l / 2 + dy);
        let i = py * self.stride + px;
        &self.v[i..i + l]
    }
}

/// Principal directions of one channel's patches: `components` orthonormal vectors of length L²
/// and the patch mean. Orthogonal (subspace) iteration on the sample covariance, applied as
/// Xᵀ(X V) without forming the L² × L² matrix; at most 30 rounds. Only the span of the top
/// components matters to the mixtures downstream, so this replaces a full eigen-decomposition.
fn pca(
    plane: &Plane,
    w: usize,
    h: usize,
    p: &FeatureParams,
    rng: &mut ChaCha8Rng,
) -> (Vec<Vec<f32>>, Vec<f32>) {
    let l = p.patch;
    let d = l * l;
    let k = p.components.min(d);
    if k == 0 {
        return (Vec::new(), vec![0.0; d]);
    }
    let n = p.pca_samples.max(k + 1);
    let mut x = vec![0f32; n * d];
    for s in 0..n {
        let (px, py) = (rng.random_range(0..w), rng.random_range(0..h));
        for dy in 0..l {
            x[s * d + dy * l..s * d + dy * l + l].copy_from_slice(plane.row(px, py, dy, l));
        }
    }
    let mut mean = vec![0f32; d];
    for row in x.chunks(d) {
        mean.iter_mut()
            .zip(row)
            .for_each(|(m, v)| *m += v / n as f32);
    }
    for row in x.chunks_mut(d) {
        row.iter_mut().zip(&mean).for_each(|(v, m)| *v -= m);
    }
    let mut v: Vec<Vec<f32>> = (0..k)
        .map(|_| (0..d).map(|_| rng.random_range(-1.0f32..1.0)).collect())
        .collect();
    orthonormalise(&mut v);
    for _ in 0..30 {
        // W = Xᵀ (X V).
        let mut wv = vec![vec![0f32; d]; k];
        for row in x.chunks(d) {
            for (j, vj) in v.iter().enumerate() {
                let y = dot(row, vj);
                wv[j].iter_mut().zip(row).for_each(|(o, r)| *o += y * r);
            }
        }
        orthonormalise(&mut wv);
        let change: f32 = wv
            .iter()
            .zip(&v)
            .map(|(a, b)| 1.0 - a.iter().zip(b).map(|(p, q)| p * q).sum::<f32>().abs())
            .fold(0.0, f32::max);
        v = wv;
        if change < 1e-5 {
            break;
        }
    }
    (v, mean)
}

/// Gram–Schmidt in place; a vector that collapses is replaced by a unit axis.
fn orthonormalise(v: &mut [Vec<f32>]) {
    for i in 0..v.len() {
        for j in 0..i {
            let (a, b) = v.split_at_mut(i);
            let dot: f32 = b[0].iter().zip(&a[j]).map(|(p, q)| p * q).sum();
            b[0].iter_mut().zip(&a[j]).for_each(|(p, q)| *p -= dot * q);
        }
        let norm = v[i].iter().map(|p| p * p).sum::<f32>().sqrt();
        if norm > 1e-12 {
            v[i].iter_mut().for_each(|p| *p /= norm);
        } else {
            v[i].iter_mut().for_each(|p| *p = 0.0);
            let len = v[i].len();
            v[i][i % len] = 1.0;
        }
    }
}

/// Dot product with eight independent partial sums, so the compiler can vectorise it.
fn dot(a: &[f32], b: &[f32]) -> f32 {
    let mut acc = [0f32; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f32 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for i in 0..8 {
            acc[i] += x[i] * y[i];
        }
    }
    acc.iter().sum::<f32>() + tail
}

/// Computes the features of every pixel.
pub fn compute(img: &RgbImage, p: &FeatureParams) -> Features {
    let (w, h) = (img.width() as usize, img.height() as usize);
    let l = p.patch | 1;
    let p = FeatureParams { patch: l, ..*p };
    let k = p.components.min(l * l);
    let dim = 3 + 3 * k;
    if w == 0 || h == 0 {
        return Features {
            width: w,
            height: h,
            dim,
            data: Vec::new(),
        };
    }
    let mut rng = ChaCha8Rng::seed_from_u64(p.seed);
    let planes: Vec<Plane> = (0..3).map(|c| Plane::new(img, c, l / 2)).collect();
    let bases: Vec<(Vec<Vec<f32>>, Vec<f32>)> = planes
        .iter()
        .map(|pl| pca(pl, w, h, &p, &mut rng))
        .collect();
    // Texture coefficients on the coarse grid (its last points may lie past the border).
    let s = p.stride.max(1);
    let (gw, gh) = ((w - 1) / s + 2, (h - 1) / s + 2);
    let grid = super::project::project_grid(img, &bases, l, s, gw, gh);
    let mut data = vec![0f32; w * h * dim];
    let kk = 3 * k;
    let raw = img.as_raw();
    data.par_chunks_mut(w * dim)
        .enumerate()
        .for_each(|(y, row)| {
            // Bilinear: first between grid rows gy and gy + 1 for the whole row, then along x.
            let (gy, fy) = (y / s, (y % s) as f32 / s as f32);
            let top = &grid[gy * gw * kk..(gy + 1) * gw * kk];
            let bot = &grid[(gy + 1) * gw * kk..(gy + 2) * gw * kk];
            let mid: Vec<f32> = top.iter().zip(bot).map(|(t, b)| t + (b - t) * fy).collect();
            for (x, out) in row.chunks_exact_mut(dim).enumerate() {
                let rgb = &raw[(y * w + x) * 3..(y * w + x) * 3 + 3];
                for (o, v) in out.iter_mut().zip(rgb) {
                    *o = *v as f32 / 255.0;
                }
                let (gx, fx) = (x / s, (x % s) as f32 / s as f32);
                let left = &mid[gx * kk..(gx + 1) * kk];
                let right = &mid[(gx + 1) * kk..(gx + 2) * kk];
                for ((o, l), r) in out[3..].iter_mut().zip(left).zip(right) {
                    *o = l + (r - l) * fx;
                }
            }
        });
    Features {
        width: w,
        height: h,
        dim,
        data,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Rgb;

    #[test]
    fn eighteen_dimensions_and_rgb_first() {
        let mut img = RgbImage::from_pixel(30, 24, Rgb([10, 20, 30]));
        for x in 0..30 {
            img.put_pixel(x, 12, Rgb([200, 100, 0]));
        }
        let f = compute(
            &img,
            &FeatureParams {
                pca_samples: 60,
                ..Default::default()
            },
        );
        assert_eq!(f.dim, 18);
        assert_eq!(f.data.len(), 30 * 24 * 18);
        assert!((f.at(3, 3)[0] - 10.0 / 255.0).abs() < 1e-6);
        // Texture differs near the stripe and far from it.
        let near = f.at(15, 12)[3..].iter().map(|v| v.abs()).sum::<f32>();
        let far = f.at(15, 0)[3..].iter().map(|v| v.abs()).sum::<f32>();
        assert!(near > far + 0.1, "{near} {far}");
    }
}
