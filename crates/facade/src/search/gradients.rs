//! Gradient profiles for the search of §3.1.7: summed-area tables ([`Integral`]) of the
//! image's absolute intensity differences ([`Gradients`]), and their peaks as candidate split
//! lines.

use image::RgbImage;

use super::params::SearchParams;

/// Summed-area table of a row-major map: O(1) rectangle sums.
pub struct Integral {
    w: usize,
    s: Vec<f64>,
}

impl Integral {
    pub fn new(map: &[f64], w: usize, h: usize) -> Integral {
        let mut s = vec![0f64; (w + 1) * (h + 1)];
        for y in 0..h {
            let mut row = 0.0;
            for x in 0..w {
                row += map[y * w + x];
                s[(y + 1) * (w + 1) + x + 1] = s[y * (w + 1) + x + 1] + row;
            }
        }
        Integral { w, s }
    }
    /// Σ over x0..x1, y0..y1 (exclusive ends).
    pub fn sum(&self, x0: usize, y0: usize, x1: usize, y1: usize) -> f64 {
        if x1 <= x0 || y1 <= y0 {
            return 0.0;
        }
        let at = |x: usize, y: usize| self.s[y * (self.w + 1) + x];
        at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0)
    }
}

/// Absolute horizontal and vertical intensity differences of the image (grey), as integrals, so
/// gradient profiles over any rectangle are cheap.
pub struct Gradients {
    pub gx: Integral,
    pub gy: Integral,
}

impl Gradients {
    pub fn new(img: &RgbImage) -> Gradients {
        let (w, h) = (img.width() as usize, img.height() as usize);
        let g = image::imageops::grayscale(img);
        let v = |x: usize, y: usize| g.get_pixel(x as u32, y as u32)[0] as f64;
        let mut gx = vec![0f64; w * h];
        let mut gy = vec![0f64; w * h];
        for y in 0..h {
            for x in 0..w {
                if x > 0 && x + 1 < w {
                    gx[y * w + x] = (v(x + 1, y) - v(x - 1, y)).abs();
                }
                if y > 0 && y + 1 < h {
                    gy[y * w + x] = (v(x, y + 1) - v(x, y - 1)).abs();
                }
            }
        }
        Gradients {
            gx: Integral::new(&gx, w, h),
            gy: Integral::new(&gy, w, h),
        }
    }

    /// Candidate vertical split lines (x positions) inside the rectangle: peaks of the column
    /// sums of |∂I/∂x|, plus the rectangle's own edges.
    pub fn x_peaks(&self, r: [usize; 4], p: &SearchParams) -> Vec<usize> {
        let prof: Vec<f64> = (r[0]..r[2])
            .map(|x| self.gx.sum(x, r[1], x + 1, r[3]))
            .collect();
        with_ends(peaks(&prof, p.max_peaks, p.peak_separation), r[0], r[2])
    }

    /// Candidate horizontal split lines (y positions): peaks of the row sums of |∂I/∂y|.
    pub fn y_peaks(&self, r: [usize; 4], p: &SearchParams) -> Vec<usize> {
        let prof: Vec<f64> = (r[1]..r[3])
            .map(|y| self.gy.sum(r[0], y, r[2], y + 1))
            .collect();
        with_ends(peaks(&prof, p.max_peaks, p.peak_separation), r[1], r[3])
    }
}

fn with_ends(mut v: Vec<usize>, lo: usize, hi: usize) -> Vec<usize> {
    v.iter_mut().for_each(|p| *p += lo);
    v.push(lo);
    v.push(hi);
    v.sort_unstable();
    v.dedup();
    v
}

/// Indices of local maxima of a profile, strongest first kept, at most `max`, at least `sep` apart;
/// returned sorted (central differences peak on the edge pixels themselves).
pub fn peaks(prof: &[f64], max: usize, sep: usize) -> Vec<usize> {
    let n = prof.len();
    let mut cand: Vec<usize> = (0..n)
        .filter(|&i| {
            let l = if i > 0 {
                prof[i - 1]
            } else {
                f64::NEG_INFINITY
            };
            let r = if i + 1 < n {
                prof[i + 1]
            } else {
                f64::NEG_INFINITY
            };
            prof[i] > 0.0 && prof[i] >= l && prof[i] > r
        })
        .collect();
    cand.sort_by(|&a, &b| prof[b].total_cmp(&prof[a]));
    let mut kept: Vec<usize> = Vec::new();
    for c in cand {
        if kept.len() >= max {
            break;
        }
        if kept.iter().all(|&k| k.abs_diff(c) >= sep) {
            kept.push(c);
        }
    }
    kept.sort_unstable();
    kept
}

/// A crisp map (+1 where `window(x, y)`, −1 elsewhere) of `w` × `h` pixels, as the search
/// reads it, with the matching flat-coloured image's gradients (dark glass on light stone).
#[cfg(test)]
pub(crate) fn crisp_map(
    w: usize,
    h: usize,
    window: impl Fn(usize, usize) -> bool,
) -> (Integral, Gradients) {
    let map: Vec<f64> = (0..w * h)
        .map(|i| if window(i % w, i / w) { 1.0 } else { -1.0 })
        .collect();
    let img = RgbImage::from_fn(w as u32, h as u32, |x, y| {
        if window(x as usize, y as usize) {
            image::Rgb([35, 45, 65])
        } else {
            image::Rgb([185, 135, 95])
        }
    });
    (Integral::new(&map, w, h), Gradients::new(&img))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integral_sums_rectangles() {
        let m: Vec<f64> = (0..12).map(|v| v as f64).collect();
        let i = Integral::new(&m, 4, 3);
        assert_eq!(i.sum(0, 0, 4, 3), 66.0);
        assert_eq!(i.sum(1, 1, 3, 2), 5.0 + 6.0);
        assert_eq!(i.sum(2, 2, 2, 3), 0.0);
    }

    #[test]
    fn peaks_are_separated_and_sorted() {
        let p = [0.0, 5.0, 0.0, 4.0, 0.0, 0.0, 9.0, 8.0, 0.0];
        assert_eq!(peaks(&p, 10, 1), vec![1, 3, 6]);
        assert_eq!(peaks(&p, 2, 1), vec![1, 6]);
        assert_eq!(peaks(&p, 10, 4), vec![1, 6]);
    }
}
