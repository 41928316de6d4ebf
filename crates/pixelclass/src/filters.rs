//! The linear filters under the feature bank: a separable Gaussian and finite differences of
//! the smoothed plane. Hand-written rather than imageproc's: imageproc blurs `ImageBuffer`s
//! one plane at a time without threads and has no derivative or second-order outputs, while
//! here every pass runs over rows in parallel on planar `f32` data the forest reads directly.
//!
//! Derivatives are central differences of the Gaussian-smoothed plane — the smoothing kernel
//! convolved with [-½, 0, ½] (and [1, -2, 1]). That costs one blur per scale instead of the six
//! of exact Gaussian-derivative kernels; the forest only needs features that rank pixels
//! consistently, and it is invariant to any per-feature monotone rescaling, so no
//! scale-normalisation (σ², σ) is applied either.

use rayon::prelude::*;

/// A normalised 1-D Gaussian, radius ⌈3σ⌉ (at least 1).
pub fn gaussian_kernel(sigma: f32) -> Vec<f32> {
    let r = ((3.0 * sigma).ceil() as usize).max(1);
    let mut k: Vec<f32> = (0..=2 * r)
        .map(|i| {
            let d = i as f32 - r as f32;
            (-d * d / (2.0 * sigma * sigma)).exp()
        })
        .collect();
    let s: f32 = k.iter().sum();
    k.iter_mut().for_each(|v| *v /= s);
    k
}

/// Mirror an index into 0..n (…, 1, 0 | 0, 1, …, n-1 | n-1, n-2, …), for any offset.
fn mirror(i: isize, n: usize) -> usize {
    let n = n as isize;
    let period = 2 * n;
    let m = i.rem_euclid(period);
    (if m < n { m } else { period - 1 - m }) as usize
}

/// Convolution with a symmetric odd kernel along rows, then along columns; borders mirrored.
pub fn separable(src: &[f32], w: usize, h: usize, k: &[f32]) -> Vec<f32> {
    let r = k.len() / 2;
    // Rows: pad each row into a buffer so the inner loop is a plain multiply-add over x,
    // which the compiler vectorises.
    let mut tmp = vec![0f32; w * h];
    tmp.par_chunks_mut(w.max(1))
        .zip(src.par_chunks(w.max(1)))
        .for_each_init(
            || vec![0f32; w + 2 * r],
            |buf, (out, row)| {
                for (i, b) in buf.iter_mut().enumerate() {
                    *b = row[mirror(i as isize - r as isize, w)];
                }
                out.fill(0.0);
                for (j, &kj) in k.iter().enumerate() {
                    for (o, &v) in out.iter_mut().zip(&buf[j..j + w]) {
                        *o += kj * v;
                    }
                }
            },
        );
    // Columns: each output row is a weighted sum of whole input rows.
    let mut out = vec![0f32; w * h];
    out.par_chunks_mut(w.max(1)).enumerate().for_each(|(y, o)| {
        for (j, &kj) in k.iter().enumerate() {
            let sy = mirror(y as isize + j as isize - r as isize, h);
            for (a, &v) in o.iter_mut().zip(&tmp[sy * w..sy * w + w]) {
                *a += kj * v;
            }
        }
    });
    out
}

/// Gaussian smoothing at `sigma` (pixels).
pub fn smooth(src: &[f32], w: usize, h: usize, sigma: f32) -> Vec<f32> {
    separable(src, w, h, &gaussian_kernel(sigma))
}

/// First and second central differences of a plane: (gx, gy, gxx, gxy, gyy), borders clamped.
pub struct Derivatives {
    pub gx: Vec<f32>,
    pub gy: Vec<f32>,
    pub gxx: Vec<f32>,
    pub gxy: Vec<f32>,
    pub gyy: Vec<f32>,
}

pub fn derivatives(g: &[f32], w: usize, h: usize, second: bool) -> Derivatives {
    let at = |x: usize, y: usize| g[y * w + x];
    let xm = |x: usize| x.saturating_sub(1);
    let xp = |x: usize| (x + 1).min(w - 1);
    let ym = |y: usize| y.saturating_sub(1);
    let yp = |y: usize| (y + 1).min(h - 1);
    let (gx, gy) = rayon::join(
        || plane(w, h, |x, y| (at(xp(x), y) - at(xm(x), y)) * 0.5),
        || plane(w, h, |x, y| (at(x, yp(y)) - at(x, ym(y))) * 0.5),
    );
    if !second {
        return Derivatives {
            gx,
            gy,
            gxx: Vec::new(),
            gxy: Vec::new(),
            gyy: Vec::new(),
        };
    }
    let gxx = plane(w, h, |x, y| at(xp(x), y) - 2.0 * at(x, y) + at(xm(x), y));
    let gyy = plane(w, h, |x, y| at(x, yp(y)) - 2.0 * at(x, y) + at(x, ym(y)));
    let gxy = plane(w, h, |x, y| {
        (at(xp(x), yp(y)) - at(xm(x), yp(y)) - at(xp(x), ym(y)) + at(xm(x), ym(y))) * 0.25
    });
    Derivatives {
        gx,
        gy,
        gxx,
        gxy,
        gyy,
    }
}

/// A plane filled by `f(x, y)`, rows in parallel.
pub fn plane(w: usize, h: usize, f: impl Fn(usize, usize) -> f32 + Sync) -> Vec<f32> {
    let mut out = vec![0f32; w * h];
    out.par_chunks_mut(w.max(1)).enumerate().for_each(|(y, o)| {
        for (x, v) in o.iter_mut().enumerate() {
            *v = f(x, y);
        }
    });
    out
}

/// Eigenvalues (larger first) of the symmetric 2x2 matrix [[a, b], [b, c]].
pub fn eigen2(a: f32, b: f32, c: f32) -> (f32, f32) {
    let m = 0.5 * (a + c);
    let r = (0.25 * (a - c) * (a - c) + b * b).sqrt();
    (m + r, m - r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaussian_of_a_constant_is_the_constant() {
        let (w, h) = (23, 17);
        let src = vec![0.37f32; w * h];
        for sigma in [0.7, 1.6, 5.0, 10.0] {
            // σ = 10 has a kernel wider than the image: the mirror must still hold.
            let g = smooth(&src, w, h, sigma);
            assert!(g.iter().all(|v| (v - 0.37).abs() < 1e-5), "σ = {sigma}");
        }
    }

    #[test]
    fn gaussian_preserves_the_mean_and_spreads_an_impulse() {
        let (w, h) = (41, 41);
        let mut src = vec![0f32; w * h];
        src[20 * w + 20] = 1.0;
        let g = smooth(&src, w, h, 2.0);
        let sum: f32 = g.iter().sum();
        assert!((sum - 1.0).abs() < 1e-4, "{sum}");
        // Variance along x of the spread impulse is σ².
        let var: f32 = (0..w * h)
            .map(|i| g[i] * ((i % w) as f32 - 20.0).powi(2))
            .sum();
        assert!((var - 4.0).abs() < 0.05, "{var}");
        assert!(g[20 * w + 20] > g[20 * w + 22] && g[20 * w + 22] > g[20 * w + 25]);
    }

    #[test]
    fn central_differences_of_a_ramp_and_a_parabola() {
        let (w, h) = (9, 7);
        let g: Vec<f32> = (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f32, (i / w) as f32);
                3.0 * x + 0.5 * y * y + x * y
            })
            .collect();
        let d = derivatives(&g, w, h, true);
        let i = 3 * w + 4;
        assert!((d.gx[i] - (3.0 + 3.0)).abs() < 1e-5);
        assert!((d.gy[i] - (3.0 + 4.0)).abs() < 1e-5);
        assert!((d.gxx[i]).abs() < 1e-5);
        assert!((d.gyy[i] - 1.0).abs() < 1e-5);
        assert!((d.gxy[i] - 1.0).abs() < 1e-5);
    }

    #[test]
    fn eigenvalues_of_symmetric_2x2() {
        let (l1, l2) = eigen2(2.0, 1.0, 2.0);
        assert!((l1 - 3.0).abs() < 1e-6 && (l2 - 1.0).abs() < 1e-6);
        let (l1, l2) = eigen2(0.0, 0.0, -4.0);
        assert_eq!((l1, l2), (0.0, -4.0));
    }
}
