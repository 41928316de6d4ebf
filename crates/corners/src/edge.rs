//! The edge image of §2.1.1: Gaussian smoothing (W × W, σ), central-difference gradient,
//! squared magnitude E = ‖∇(I ⋆ G)‖², Canny-style thinning along the gradient, and the
//! image-wide mean threshold that leaves the candidate set Ê.

use rayon::prelude::*;

/// A grey image as `f32` samples, row-major (x right, y down).
#[derive(Debug, Clone, PartialEq)]
pub struct Gray {
    pub width: usize,
    pub height: usize,
    pub data: Vec<f32>,
}

impl Gray {
    /// Wraps samples; `data.len()` must be `width * height`.
    pub fn new(width: usize, height: usize, data: Vec<f32>) -> Self {
        assert_eq!(data.len(), width * height, "Gray::new: wrong sample count");
        Self {
            width,
            height,
            data,
        }
    }

    /// From an 8-bit grey image (values 0..255).
    pub fn from_luma8(img: &image::GrayImage) -> Self {
        let (w, h) = img.dimensions();
        Self::new(
            w as usize,
            h as usize,
            img.as_raw().iter().map(|&v| v as f32).collect(),
        )
    }

    /// From any decoded image: colour is converted to luma, 16-bit and float samples keep their
    /// precision, alpha is ignored; values are scaled to 0..255 so thresholds do not depend on
    /// the bit depth.
    pub fn from_dynamic(img: &image::DynamicImage) -> Self {
        let l = img.to_luma32f();
        let (w, h) = l.dimensions();
        Self::new(
            w as usize,
            h as usize,
            l.into_raw().into_iter().map(|v| v * 255.0).collect(),
        )
    }

    #[inline]
    pub fn at(&self, x: usize, y: usize) -> f32 {
        self.data[y * self.width + x]
    }
}

/// Edge points of Ê: positions (sub-pixel along the gradient when asked) and magnitudes E.
#[derive(Debug, Clone)]
pub struct EdgeMap {
    pub width: usize,
    pub height: usize,
    /// E = ‖∇‖² at kept edge points, 0 elsewhere.
    pub mag: Vec<f32>,
    /// Sub-pixel offset (dx, dy) of each kept edge point from its pixel centre.
    pub offset: Vec<[f32; 2]>,
    /// Gradient orientation of each kept edge point as the doubled-angle unit vector
    /// (cos 2θ, sin 2θ), so opposite gradients agree; (0, 0) elsewhere.
    pub orient: Vec<[f32; 2]>,
    /// The image-wide mean of E used as threshold.
    pub mean: f32,
}

impl EdgeMap {
    /// Number of kept edge points.
    pub fn count(&self) -> usize {
        self.mag.iter().filter(|&&m| m > 0.0).count()
    }
}

/// Normalised 1-D Gaussian of `size` taps (odd) and standard deviation `sigma`.
pub fn gaussian_kernel(size: usize, sigma: f64) -> Vec<f32> {
    let size = size.max(1) | 1;
    let r = (size / 2) as i64;
    let s = sigma.max(1e-6);
    let k: Vec<f64> = (-r..=r)
        .map(|i| (-(i * i) as f64 / (2.0 * s * s)).exp())
        .collect();
    let sum: f64 = k.iter().sum();
    k.into_iter().map(|v| (v / sum) as f32).collect()
}

/// Separable convolution with edge replication, rows in parallel.
pub fn smooth(img: &Gray, kernel: &[f32]) -> Gray {
    let (w, h) = (img.width, img.height);
    let r = (kernel.len() / 2) as isize;
    let mut tmp = vec![0f32; w * h];
    tmp.par_chunks_mut(w.max(1))
        .enumerate()
        .for_each(|(y, row)| {
            // Replicate the border into a padded row so the inner loop has no bounds logic.
            let src = &img.data[y * w..(y + 1) * w];
            let ru = r as usize;
            let mut pad = Vec::with_capacity(w + 2 * ru);
            pad.extend(std::iter::repeat_n(src[0], ru));
            pad.extend_from_slice(src);
            pad.extend(std::iter::repeat_n(src[w - 1], ru));
            // One pass per tap over the whole row, which the compiler vectorises.
            for (k, &g) in kernel.iter().enumerate() {
                for (o, &p) in row.iter_mut().zip(&pad[k..k + w]) {
                    *o += g * p;
                }
            }
        });
    let mut out = vec![0f32; w * h];
    out.par_chunks_mut(w.max(1))
        .enumerate()
        .for_each(|(y, row)| {
            for (k, &g) in kernel.iter().enumerate() {
                let yy = (y as isize + k as isize - r).clamp(0, h as isize - 1) as usize;
                let src = &tmp[yy * w..(yy + 1) * w];
                for (o, &s) in row.iter_mut().zip(src) {
                    *o += g * s;
                }
            }
        });
    Gray::new(w, h, out)
}

/// The edge image of §2.1.1. Images narrower or lower than 3 pixels have no interior and
/// give an empty map.
pub fn edge_map(img: &Gray, window: usize, sigma: f64, subpixel: bool) -> EdgeMap {
    let (w, h) = (img.width, img.height);
    let empty = EdgeMap {
        width: w,
        height: h,
        mag: vec![0.0; w * h],
        offset: vec![[0.0; 2]; w * h],
        orient: vec![[0.0; 2]; w * h],
        mean: 0.0,
    };
    if w < 3 || h < 3 {
        return empty;
    }
    let g = smooth(img, &gaussian_kernel(window, sigma));
    // Central differences h_x = [1 0 -1], h_y = h_xᵗ (the sign does not matter for E). Only E
    // is stored; the thinning below recomputes the two differences where it needs them, which
    // is cheaper than writing and reading two more image-sized arrays.
    let grad = |i: usize| (g.data[i + 1] - g.data[i - 1], g.data[i + w] - g.data[i - w]);
    let mut e = vec![0f32; w * h];
    e.par_chunks_mut(w).enumerate().for_each(|(y, re)| {
        if y == 0 || y == h - 1 {
            return;
        }
        let (up, row, down) = (
            &g.data[(y - 1) * w..y * w],
            &g.data[y * w..(y + 1) * w],
            &g.data[(y + 1) * w..(y + 2) * w],
        );
        for x in 1..w - 1 {
            let dx = row[x + 1] - row[x - 1];
            let dy = down[x] - up[x];
            re[x] = dx * dx + dy * dy;
        }
    });
    // Mean of E over the N interior pixels (the text omits the pixels at the image edge).
    let n = ((w - 2) * (h - 2)) as f64;
    let mean = (e.par_iter().map(|&v| v as f64).sum::<f64>() / n) as f32;
    if mean <= 0.0 {
        return EdgeMap { mean, ..empty };
    }
    let mut mag = vec![0f32; w * h];
    let mut offset = vec![[0f32; 2]; w * h];
    let mut orient = vec![[0f32; 2]; w * h];
    mag.par_chunks_mut(w)
        .zip(offset.par_chunks_mut(w))
        .zip(orient.par_chunks_mut(w))
        .enumerate()
        .for_each(|(y, ((rm, ro), rd))| {
            if y < 2 || y + 2 >= h {
                return;
            }
            for x in 2..w.saturating_sub(2) {
                let i = y * w + x;
                let m = e[i];
                // Ê keeps points above the mean (§2.1.1).
                if m <= mean {
                    continue;
                }
                // Canny thinning: compare with the two neighbours along the gradient, the
                // direction quantised to 0°, 45°, 90°, 135°.
                let (dx, dy) = grad(i);
                let (ax, ay) = (dx.abs(), dy.abs());
                let (sx, sy): (isize, isize) = if ay <= ax * 0.414_213_56 {
                    (1, 0)
                } else if ax <= ay * 0.414_213_56 {
                    (0, 1)
                } else if (dx > 0.0) == (dy > 0.0) {
                    (1, 1)
                } else {
                    (1, -1)
                };
                let j = (i as isize + sy * w as isize + sx) as usize;
                let k = (i as isize - sy * w as isize - sx) as usize;
                let (mp, mn) = (e[j], e[k]);
                // Ties broken towards one side so plateaus stay one pixel thick.
                if m < mp || m <= mn {
                    continue;
                }
                rm[x] = m;
                // cos 2θ = (dx² − dy²)/m, sin 2θ = 2 dx dy/m with m = dx² + dy².
                rd[x] = [(dx * dx - dy * dy) / m, 2.0 * dx * dy / m];
                if subpixel {
                    // Departure (§2.1.1 keeps integer positions): a parabola through the three
                    // samples along the gradient places the edge to a fraction of a pixel.
                    let den = mn - 2.0 * m + mp;
                    let t = if den < 0.0 {
                        (0.5 * (mn - mp) / den).clamp(-0.5, 0.5)
                    } else {
                        0.0
                    };
                    ro[x] = [t * sx as f32, t * sy as f32];
                }
            }
        });
    EdgeMap {
        width: w,
        height: h,
        mag,
        offset,
        orient,
        mean,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kernel_is_normalised_and_symmetric() {
        let k = gaussian_kernel(13, 1.4);
        assert_eq!(k.len(), 13);
        assert!((k.iter().sum::<f32>() - 1.0).abs() < 1e-5);
        assert_eq!(k[0], k[12]);
        assert!(k[6] > k[5]);
    }

    #[test]
    fn flat_and_tiny_images_have_no_edges() {
        let flat = Gray::new(20, 20, vec![7.0; 400]);
        assert_eq!(edge_map(&flat, 13, 1.4, true).count(), 0);
        let one = Gray::new(1, 1, vec![3.0]);
        assert_eq!(edge_map(&one, 13, 1.4, true).count(), 0);
    }

    #[test]
    fn a_vertical_step_gives_one_thin_column() {
        // 0 left of x = 10, 100 from x = 10: the edge lies between columns 9 and 10.
        let (w, h) = (20, 12);
        let data = (0..w * h)
            .map(|i| if i % w >= 10 { 100.0 } else { 0.0 })
            .collect();
        let m = edge_map(&Gray::new(w, h, data), 7, 1.0, true);
        for y in 3..h - 3 {
            let cols: Vec<usize> = (0..w).filter(|&x| m.mag[y * w + x] > 0.0).collect();
            assert_eq!(cols.len(), 1, "row {y}: {cols:?}");
            let x = cols[0] as f32 + m.offset[y * w + cols[0]][0];
            assert!((x - 9.5).abs() < 0.1, "row {y}: edge at {x}");
        }
    }
}
