//! Whole-image passes of the parser (§5.1.2–5.1.6) written for speed, each giving exactly what
//! the general operation it stands for gives: square (L∞) dilation, erosion, opening and
//! closing as imageproc's `morphology`, and the Euclidean distance transform as imageproc's
//! `Norm::L2` (connected components by runs are `raster::components`').
//!
//! Why: on the 3000 × 2000 benchmark scan these passes were most of the parse after the wall
//! ink (issue 26: morphology by two distance transforms per step, the L2 transform in `f64`
//! through per-pixel accessors). Here morphology is separable and the distance transform works
//! in integers (Meijster et al. 2000) — same outputs, checked against the originals in the tests.

use image::GrayImage;
use rayon::prelude::*;

/// 255 where a pixel of `raw` for which `set` holds lies within L∞ distance `k` inside the
/// image, 0 elsewhere: runs of a row widened by `k`, then each row the union of the `2k + 1`
/// rows around it (the square is the product of two segments).
fn dilate_where(raw: &[u8], w: usize, h: usize, k: usize, set: impl Fn(u8) -> bool) -> Vec<u8> {
    let mut rows = vec![0u8; w * h];
    for (src, dst) in raw.chunks(w).zip(rows.chunks_mut(w)) {
        let mut x = 0;
        while x < w {
            if !set(src[x]) {
                x += 1;
                continue;
            }
            let a = x;
            while x < w && set(src[x]) {
                x += 1;
            }
            dst[a.saturating_sub(k)..(x + k).min(w)].fill(255);
        }
    }
    let mut out = vec![0u8; w * h];
    for (y, dst) in out.chunks_mut(w).enumerate() {
        for near in y.saturating_sub(k)..(y + k + 1).min(h) {
            for (d, &s) in dst.iter_mut().zip(&rows[near * w..(near + 1) * w]) {
                *d |= s;
            }
        }
    }
    out
}

/// imageproc's `dilate(img, Norm::LInf, k)`: 255 within L∞ distance `k` of a non-zero pixel.
pub fn dilate(img: &GrayImage, k: u8) -> GrayImage {
    let (w, h) = (img.width(), img.height());
    if exotic(w, h, k) {
        return imageproc::morphology::dilate(img, imageproc::distance_transform::Norm::LInf, k);
    }
    let out = dilate_where(img.as_raw(), w as usize, h as usize, usize::from(k), |p| {
        p > 0
    });
    GrayImage::from_raw(w, h, out).expect("w × h pixels")
}

/// imageproc's `erode(img, Norm::LInf, k)`: 0 within L∞ distance `k` of a zero pixel (outside
/// the image is not zero), 255 elsewhere.
pub fn erode(img: &GrayImage, k: u8) -> GrayImage {
    let (w, h) = (img.width(), img.height());
    if exotic(w, h, k) {
        return imageproc::morphology::erode(img, imageproc::distance_transform::Norm::LInf, k);
    }
    let mut out = dilate_where(img.as_raw(), w as usize, h as usize, usize::from(k), |p| {
        p == 0
    });
    for p in &mut out {
        *p = 255 - *p;
    }
    GrayImage::from_raw(w, h, out).expect("w × h pixels")
}

/// imageproc caps its distances at min(w + h, 255): a radius that reaches the cap (a tiny
/// image, or an image without the pixels measured from) is left to imageproc itself.
fn exotic(w: u32, h: u32, k: u8) -> bool {
    u32::from(k) >= (w + h).min(255)
}

/// imageproc's `open(img, Norm::LInf, k)`.
pub fn open(img: &GrayImage, k: u8) -> GrayImage {
    dilate(&erode(img, k), k)
}

/// imageproc's `close(img, Norm::LInf, k)`.
pub fn close(img: &GrayImage, k: u8) -> GrayImage {
    erode(&dilate(img, k), k)
}

/// `raster::morphology::open_close(img, Norm::LInf, k)`: opening, then closing.
pub fn open_close(img: &GrayImage, k: u8) -> GrayImage {
    close(&open(img, k), k)
}

/// imageproc's `distance_transform(img, Norm::L2)` with `from` the pixels measured from:
/// ⌈√d²⌉ of the exact squared Euclidean distance to the nearest pixel with `from` set, capped
/// at 255 (255 everywhere when none is). Meijster's two phases: distances along each column,
/// then the lower envelope of parabolas along each row, in integers.
pub fn euclidean(from: &[bool], w: usize, h: usize) -> GrayImage {
    if w == 0 || h == 0 {
        return GrayImage::new(w as u32, h as u32);
    }
    let g = column_distances(from, w, h);
    let mut out = vec![0u8; w * h];
    // Phase 2, per row (rows in parallel): parabolas (x - i)² + g(i)², their lower envelope
    // from the left (s: the parabolas, t: where each starts to be the lowest).
    let buffers = || (vec![0usize; w], vec![0i64; w], vec![0i64; w]);
    out.par_chunks_mut(w)
        .enumerate()
        .for_each_init(buffers, |(s, t, g2), (y, row)| {
            for (sq, &d) in g2.iter_mut().zip(&g[y * w..(y + 1) * w]) {
                *sq = i64::from(d) * i64::from(d);
            }
            let f = |x: usize, i: usize| {
                let d = x as i64 - i as i64;
                d * d + g2[i]
            };
            // Where the parabola of u starts to lie below that of i (i < u).
            let sep = |i: usize, u: usize| {
                let (i2, u2) = (i as i64, u as i64);
                (u2 * u2 - i2 * i2 + g2[u] - g2[i]).div_euclid(2 * (u2 - i2))
            };
            let mut q = 0isize;
            s[0] = 0;
            t[0] = 0;
            for u in 1..w {
                while q >= 0
                    && f(t[q as usize] as usize, s[q as usize]) > f(t[q as usize] as usize, u)
                {
                    q -= 1;
                }
                if q < 0 {
                    q = 0;
                    s[0] = u;
                } else {
                    let start = 1 + sep(s[q as usize], u);
                    if start < w as i64 {
                        q += 1;
                        s[q as usize] = u;
                        t[q as usize] = start;
                    }
                }
            }
            for x in (0..w).rev() {
                row[x] = ceil_root(f(x, s[q as usize]));
                if x as i64 == t[q as usize] {
                    q -= 1;
                }
            }
        });
    GrayImage::from_raw(w as u32, h as u32, out).expect("w × h pixels")
}

/// [`euclidean`] read at a few pixels: the column phase over the image, the row's minimum
/// searched outwards from each pixel asked for (the parse needs the distance inside the walls
/// only along the skeleton).
pub struct EuclideanAt {
    g: Vec<i32>,
    w: usize,
}

impl EuclideanAt {
    pub fn new(from: &[bool], w: usize, h: usize) -> EuclideanAt {
        EuclideanAt {
            g: column_distances(from, w, h),
            w,
        }
    }

    /// The value of [`euclidean`] at (x, y).
    pub fn at(&self, x: u32, y: u32) -> u8 {
        let (x, w) = (x as usize, self.w);
        let row = &self.g[y as usize * w..(y as usize + 1) * w];
        let mut best = i64::MAX;
        for d in 0..w {
            let dd = (d * d) as i64;
            if dd >= best || (d > x && x + d >= w) {
                break;
            }
            for i in [x.checked_sub(d), Some(x + d).filter(|&i| i < w)]
                .into_iter()
                .flatten()
            {
                let g = i64::from(row[i]);
                best = best.min(dd + g * g);
            }
        }
        ceil_root(best)
    }
}

/// Phase 1: for every pixel, the distance along its column to the nearest `from` pixel, or a
/// value farther than any in the image (whose square still fits an i64 with room to spare).
fn column_distances(from: &[bool], w: usize, h: usize) -> Vec<i32> {
    let far = (w + h + 1) as i32 * 300;
    let mut g = vec![far; w * h];
    let mut run = vec![far; w];
    for y in 0..h {
        for x in 0..w {
            run[x] = if from[y * w + x] { 0 } else { run[x] + 1 };
            g[y * w + x] = run[x];
        }
    }
    run.fill(far);
    for y in (0..h).rev() {
        for x in 0..w {
            run[x] = if from[y * w + x] { 0 } else { run[x] + 1 };
            let v = &mut g[y * w + x];
            *v = (*v).min(run[x]).min(far);
        }
    }
    g
}

/// ⌈√d⌉ capped at 255, as imageproc rounds its Euclidean distances (`(d as f64).sqrt()`
/// clamped to 255, then its ceiling), looked up.
fn ceil_root(d: i64) -> u8 {
    static ROOTS: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    let roots = ROOTS.get_or_init(|| {
        (0..=255 * 255)
            .map(|d: i64| (d as f64).sqrt().clamp(0.0, 255.0).ceil() as u8)
            .collect()
    });
    roots.get(d as usize).copied().unwrap_or(255)
}

/// imageproc's `distance_transform(img, Norm::LInf)` with `from` the pixels measured from:
/// the chessboard distance to the nearest one, capped at min(w + h, 255), by the same two
/// sweeps (forward over the left and upper neighbours, backward over the right and lower).
pub fn chessboard(from: &[bool], w: usize, h: usize) -> Vec<u8> {
    let cap = (w + h).min(255) as u16;
    let mut d = vec![0u16; w * h];
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            if from[i] {
                continue;
            }
            let mut v = cap;
            if x > 0 {
                v = v.min(d[i - 1] + 1);
            }
            if y > 0 {
                let up = i - w;
                v = v.min(d[up] + 1);
                if x > 0 {
                    v = v.min(d[up - 1] + 1);
                }
                if x + 1 < w {
                    v = v.min(d[up + 1] + 1);
                }
            }
            d[i] = v;
        }
    }
    for y in (0..h).rev() {
        for x in (0..w).rev() {
            let i = y * w + x;
            let mut v = d[i];
            if x + 1 < w {
                v = v.min(d[i + 1] + 1);
            }
            if y + 1 < h {
                let down = i + w;
                v = v.min(d[down] + 1);
                if x + 1 < w {
                    v = v.min(d[down + 1] + 1);
                }
                if x > 0 {
                    v = v.min(d[down - 1] + 1);
                }
            }
            d[i] = v;
        }
    }
    d.into_iter().map(|v| v as u8).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use imageproc::distance_transform::{Norm, distance_transform};
    use rand::{RngExt, SeedableRng};

    /// Random 0/255 images with blobs and specks, of awkward sizes.
    fn samples() -> Vec<GrayImage> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let mut out = Vec::new();
        for (w, h, p) in [
            (1, 1, 0.5),
            (1, 7, 0.5),
            (9, 1, 0.5),
            (2, 2, 0.0),
            (5, 4, 1.0),
            (31, 17, 0.1),
            (40, 33, 0.45),
            (64, 50, 0.7),
            (120, 90, 0.02),
        ] {
            for _ in 0..4 {
                let mut img = GrayImage::from_fn(w, h, |_, _| {
                    image::Luma([if rng.random_bool(p) { 255 } else { 0 }])
                });
                // Solid blocks, so that the distances and openings are not all 0 or 1.
                for _ in 0..3 {
                    let (x0, y0) = (rng.random_range(0..w), rng.random_range(0..h));
                    let v = if rng.random_bool(0.5) { 255 } else { 0 };
                    for y in y0..(y0 + 12).min(h) {
                        for x in x0..(x0 + 15).min(w) {
                            img.put_pixel(x, y, image::Luma([v]));
                        }
                    }
                }
                out.push(img);
            }
        }
        out
    }

    #[test]
    fn square_morphology_is_imageprocs() {
        use imageproc::morphology as m;
        for img in samples() {
            for k in [1u8, 2, 3, 7] {
                assert_eq!(dilate(&img, k), m::dilate(&img, Norm::LInf, k));
                assert_eq!(erode(&img, k), m::erode(&img, Norm::LInf, k));
                assert_eq!(open(&img, k), m::open(&img, Norm::LInf, k));
                assert_eq!(close(&img, k), m::close(&img, Norm::LInf, k));
            }
        }
    }

    #[test]
    fn euclidean_distances_are_imageprocs() {
        for img in samples() {
            let (w, h) = (img.width() as usize, img.height() as usize);
            let on: Vec<bool> = img.as_raw().iter().map(|&p| p > 0).collect();
            let full = distance_transform(&img, Norm::L2);
            assert_eq!(euclidean(&on, w, h), full);
            let at = EuclideanAt::new(&on, w, h);
            for (x, y, p) in full.enumerate_pixels() {
                assert_eq!(at.at(x, y), p[0], "({x}, {y})");
            }
        }
        for img in samples() {
            let (w, h) = (img.width() as usize, img.height() as usize);
            let on: Vec<bool> = img.as_raw().iter().map(|&p| p > 0).collect();
            let want = distance_transform(&img, Norm::LInf);
            assert_eq!(chessboard(&on, w, h), want.into_raw());
        }
        // Distances past the cap of 255.
        let mut img = GrayImage::new(700, 3);
        img.put_pixel(0, 1, image::Luma([255]));
        let on: Vec<bool> = img.as_raw().iter().map(|&p| p > 0).collect();
        assert_eq!(euclidean(&on, 700, 3), distance_transform(&img, Norm::L2));
    }
}
