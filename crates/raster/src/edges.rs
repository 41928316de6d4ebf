//! Prewitt edges thinned by non-maximum suppression, for the stages that want thin edges of a
//! photo or an engraving: rectification's line segments (§3.1.1) and the contour likelihood of
//! the Gothic elements (§4.2). One gradient (imageproc's 3 × 3 Prewitt kernels, magnitude in
//! f32), a threshold relative to a percentile of the magnitudes, and the two thinnings those
//! stages use ([`Thinning`]); [`EdgeRule`] says which.
//!
//! The corner detector's edges (§2.1.1: Gaussian smoothing, central differences, Canny
//! thinning) are the dissertation's own algorithm and stay in `corners::edge`.

use image::{GrayImage, ImageBuffer, Luma};
use imageproc::gradients::{horizontal_prewitt, vertical_prewitt};

/// A signed gradient image, as imageproc's Prewitt filters return it.
pub type SignedImage = ImageBuffer<Luma<i16>, Vec<i16>>;

/// Prewitt gradients of a grey image and their magnitude.
#[derive(Debug, Clone)]
pub struct Gradient {
    pub width: u32,
    pub height: u32,
    /// ∂I/∂x (imageproc's `horizontal_prewitt`).
    pub gx: SignedImage,
    /// ∂I/∂y (imageproc's `vertical_prewitt`).
    pub gy: SignedImage,
    /// √(gx² + gy²) per pixel, row-major.
    pub magnitude: Vec<f32>,
}

impl Gradient {
    /// The gradients of `gray`.
    pub fn prewitt(gray: &GrayImage) -> Gradient {
        let (width, height) = gray.dimensions();
        let gx = horizontal_prewitt(gray);
        let gy = vertical_prewitt(gray);
        let magnitude = gx
            .pixels()
            .zip(gy.pixels())
            .map(|(a, b)| (a[0] as f32).hypot(b[0] as f32))
            .collect();
        Gradient {
            width,
            height,
            gx,
            gy,
            magnitude,
        }
    }

    /// The magnitude at (x, y); 0 outside the image.
    pub fn magnitude_at(&self, x: i64, y: i64) -> f32 {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            0.0
        } else {
            self.magnitude[y as usize * self.width as usize + x as usize]
        }
    }
}

/// The magnitude the threshold is a share of: a percentile, taken in one of two ways.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reference {
    /// The magnitude of rank ⌊q n⌋ (at most n − 1) among the n non-zero magnitudes; with none,
    /// no pixel is an edge.
    NonZero(f64),
    /// The magnitude of rank ⌊q (N − 1)⌋ among all N magnitudes.
    All(f64),
}

/// How an edge is thinned: which neighbours a pixel's magnitude must not fall below.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Thinning {
    /// The two neighbours along the gradient direction rounded to the 8-neighbourhood: at
    /// least the one ahead, above the one behind, so a step between two pixels keeps one.
    /// Pixels on the image border are never edges.
    Gradient,
    /// The two neighbours along the dominant gradient axis (x when |gx| ≥ |gy|): at least
    /// both and above one, so a step between two pixels keeps both (the zero line of a
    /// distance transform then lies on the step).
    Axis,
}

/// Which pixels are edges: magnitude at least `share` × the [`Reference`] magnitude and at
/// least `floor` (so flat images with faint noise have none), then thinned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeRule {
    pub reference: Reference,
    pub share: f64,
    pub floor: f64,
    pub thinning: Thinning,
}

/// Thinned edges and the gradient they came from.
#[derive(Debug, Clone)]
pub struct Edges {
    pub gradient: Gradient,
    /// 255 on edge pixels, 0 elsewhere.
    pub mask: GrayImage,
}

impl Edges {
    /// The edge pixels in raster order, each with its unit gradient (gx / m, gy / m).
    pub fn unit_gradients(&self) -> Vec<(u32, u32, f32, f32)> {
        let g = &self.gradient;
        self.mask
            .enumerate_pixels()
            .filter(|(_, _, p)| p[0] != 0)
            .map(|(x, y, _)| {
                let m = g.magnitude[(y * g.width + x) as usize];
                (
                    x,
                    y,
                    g.gx.get_pixel(x, y)[0] as f32 / m,
                    g.gy.get_pixel(x, y)[0] as f32 / m,
                )
            })
            .collect()
    }
}

/// Prewitt edges of `gray` under `rule`.
pub fn prewitt_edges(gray: &GrayImage, rule: &EdgeRule) -> Edges {
    let gradient = Gradient::prewitt(gray);
    let mut mask = GrayImage::new(gradient.width, gradient.height);
    let reference = match rule.reference {
        Reference::NonZero(q) => {
            let mut sorted: Vec<f32> = gradient
                .magnitude
                .iter()
                .copied()
                .filter(|m| *m > 0.0)
                .collect();
            if sorted.is_empty() {
                return Edges { gradient, mask };
            }
            let k = ((sorted.len() as f64 * q) as usize).min(sorted.len() - 1);
            *sorted.select_nth_unstable_by(k, f32::total_cmp).1
        }
        Reference::All(q) => {
            if gradient.magnitude.is_empty() {
                return Edges { gradient, mask };
            }
            let mut sorted = gradient.magnitude.clone();
            let k = ((sorted.len() - 1) as f64 * q) as usize;
            *sorted.select_nth_unstable_by(k, f32::total_cmp).1
        }
    };
    let t = (reference as f64 * rule.share).max(rule.floor) as f32;
    let (w, h) = (gradient.width, gradient.height);
    let at = |x: i64, y: i64| gradient.magnitude_at(x, y);
    match rule.thinning {
        Thinning::Gradient => {
            for y in 1..h.saturating_sub(1) {
                for x in 1..w.saturating_sub(1) {
                    let m = gradient.magnitude[(y * w + x) as usize];
                    if m < t {
                        continue;
                    }
                    let (ux, uy) = (
                        gradient.gx.get_pixel(x, y)[0] as f32 / m,
                        gradient.gy.get_pixel(x, y)[0] as f32 / m,
                    );
                    let (sx, sy) = (ux.round() as i64, uy.round() as i64);
                    let (xi, yi) = (x as i64, y as i64);
                    if m >= at(xi + sx, yi + sy) && m > at(xi - sx, yi - sy) {
                        mask.put_pixel(x, y, Luma([255]));
                    }
                }
            }
        }
        Thinning::Axis => {
            for y in 0..h as i64 {
                for x in 0..w as i64 {
                    let m = at(x, y);
                    if m < t {
                        continue;
                    }
                    let i = y as usize * w as usize + x as usize;
                    let (dx, dy) = (
                        gradient.gx.as_raw()[i].unsigned_abs(),
                        gradient.gy.as_raw()[i].unsigned_abs(),
                    );
                    let (a, b) = if dx >= dy {
                        (at(x - 1, y), at(x + 1, y))
                    } else {
                        (at(x, y - 1), at(x, y + 1))
                    };
                    if m >= a && m >= b && (m > a || m > b) {
                        mask.put_pixel(x as u32, y as u32, Luma([255]));
                    }
                }
            }
        }
    }
    Edges { gradient, mask }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 6 × 5 image dark in columns 0–2 and bright (200) in 3–5: Prewitt magnitude 600 in
    /// columns 2 and 3, 0 elsewhere.
    fn step() -> GrayImage {
        GrayImage::from_fn(6, 5, |x, _| Luma([if x < 3 { 0 } else { 200 }]))
    }

    fn rule(reference: Reference, thinning: Thinning) -> EdgeRule {
        EdgeRule {
            reference,
            share: 0.5,
            floor: 1.0,
            thinning,
        }
    }

    #[test]
    fn prewitt_magnitude_of_a_step() {
        let g = Gradient::prewitt(&step());
        assert_eq!(&g.magnitude[..6], &[0.0, 0.0, 600.0, 600.0, 0.0, 0.0]);
        assert_eq!(g.gx.get_pixel(2, 4)[0], 600);
        assert_eq!(g.gy.get_pixel(2, 4)[0], 0);
        assert_eq!(g.magnitude_at(-1, 0), 0.0);
    }

    #[test]
    fn along_the_gradient_a_step_keeps_one_pixel_off_the_border() {
        let e = prewitt_edges(&step(), &rule(Reference::NonZero(0.98), Thinning::Gradient));
        assert_eq!(
            crate::literal::rows(&e.mask),
            ["......", "..#...", "..#...", "..#...", "......"]
        );
        assert_eq!(
            e.unit_gradients(),
            vec![(2, 1, 1.0, 0.0), (2, 2, 1.0, 0.0), (2, 3, 1.0, 0.0)]
        );
    }

    #[test]
    fn along_the_dominant_axis_a_step_keeps_both_pixels() {
        let e = prewitt_edges(&step(), &rule(Reference::All(0.99), Thinning::Axis));
        assert_eq!(crate::literal::rows(&e.mask), ["..##.."; 5]);
    }

    #[test]
    fn the_threshold_is_a_share_of_a_percentile_with_a_floor() {
        // Two steps, of 200 and of 20: magnitudes 600 and 60.
        let img = GrayImage::from_fn(12, 5, |x, _| {
            Luma([if x < 3 {
                0
            } else if x < 8 {
                200
            } else {
                220
            }])
        });
        let mut r = rule(Reference::All(0.99), Thinning::Axis);
        assert_eq!(
            crate::literal::rows(&prewitt_edges(&img, &r).mask)[0],
            "..##........"
        );
        r.share = 0.05;
        assert_eq!(
            crate::literal::rows(&prewitt_edges(&img, &r).mask)[0],
            "..##...##..."
        );
        r.floor = 100.0;
        assert_eq!(
            crate::literal::rows(&prewitt_edges(&img, &r).mask)[0],
            "..##........"
        );
    }

    #[test]
    fn a_flat_image_has_no_edges() {
        let flat = GrayImage::from_pixel(5, 5, Luma([90]));
        for reference in [Reference::NonZero(0.98), Reference::All(0.99)] {
            let e = prewitt_edges(&flat, &rule(reference, Thinning::Gradient));
            assert!(e.mask.pixels().all(|p| p[0] == 0));
        }
        let e = prewitt_edges(
            &GrayImage::new(0, 0),
            &rule(Reference::All(0.99), Thinning::Axis),
        );
        assert_eq!(e.mask.dimensions(), (0, 0));
    }
}
