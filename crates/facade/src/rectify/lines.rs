//! Straight edge segments for rectification (§3.1.1): Prewitt edges, thinned by non-maximum
//! suppression (`raster::edges`), Hough lines (imageproc), then the edge pixels supporting each
//! Hough line split into runs and refitted by total least squares so each segment is
//! sub-degree accurate.

use image::GrayImage;
use imageproc::hough::{LineDetectionOptions, detect_lines};
use raster::edges::{EdgeRule, Reference, Thinning, prewitt_edges};
use serde::{Deserialize, Serialize};

/// A straight edge segment in image pixels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Segment {
    pub x0: f64,
    pub y0: f64,
    pub x1: f64,
    pub y1: f64,
}

impl Segment {
    pub fn new(x0: f64, y0: f64, x1: f64, y1: f64) -> Self {
        Segment { x0, y0, x1, y1 }
    }
    /// Length in pixels (the weight w_n of §3.1.1).
    pub fn length(&self) -> f64 {
        (self.x1 - self.x0).hypot(self.y1 - self.y0)
    }
    pub fn midpoint(&self) -> (f64, f64) {
        (0.5 * (self.x0 + self.x1), 0.5 * (self.y0 + self.y1))
    }
    /// Unit direction.
    pub fn direction(&self) -> (f64, f64) {
        let l = self.length().max(1e-12);
        ((self.x1 - self.x0) / l, (self.y1 - self.y0) / l)
    }
    /// Angle to the x axis folded into [0°, 90°]: 0 is horizontal, 90 vertical.
    pub fn tilt_degrees(&self) -> f64 {
        let (dx, dy) = self.direction();
        dy.abs().atan2(dx.abs()).to_degrees()
    }
    /// The homogeneous line (a, b, c), a² + b² = 1, through both end points.
    pub fn line(&self) -> [f64; 3] {
        let (dx, dy) = self.direction();
        let (a, b) = (-dy, dx);
        [a, b, -(a * self.x0 + b * self.y0)]
    }
    pub fn scaled(&self, s: f64) -> Segment {
        Segment::new(self.x0 * s, self.y0 * s, self.x1 * s, self.y1 * s)
    }
}

/// Parameters of the segment detector.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineParams {
    /// Images larger than this (longest side) are downscaled for detection; segments are
    /// returned in input pixels.
    pub max_side: u32,
    /// Minimum segment length as a fraction of the (detection) image diagonal.
    pub min_length_frac: f64,
    /// Edge pixels: gradient magnitude above this fraction of the 98th percentile.
    pub edge_frac: f64,
    /// At most this many Hough lines are examined (strongest first).
    pub max_hough_lines: usize,
}

impl Default for LineParams {
    fn default() -> Self {
        LineParams {
            max_side: 800,
            min_length_frac: 0.03,
            edge_frac: 0.25,
            max_hough_lines: 400,
        }
    }
}

/// Detects straight edge segments (§3.1.1, figure 3.2a).
pub fn detect_segments(gray: &GrayImage, params: &LineParams) -> Vec<Segment> {
    let (w0, h0) = gray.dimensions();
    if w0 < 8 || h0 < 8 {
        return Vec::new();
    }
    let side = w0.max(h0);
    let scale = if side > params.max_side {
        params.max_side as f64 / side as f64
    } else {
        1.0
    };
    let small;
    let img = if scale < 1.0 {
        let (w, h) = (
            ((w0 as f64 * scale).round() as u32).max(8),
            ((h0 as f64 * scale).round() as u32).max(8),
        );
        small = image::imageops::resize(gray, w, h, image::imageops::FilterType::Triangle);
        &small
    } else {
        gray
    };
    let blurred = imageproc::filter::gaussian_blur_f32(img, 1.0);
    // Magnitude above `edge_frac` of the 98th percentile of the non-zero magnitudes, with an
    // absolute floor so flat images with faint noise have no edges; one pixel per edge.
    let rule = EdgeRule {
        reference: Reference::NonZero(0.98),
        share: params.edge_frac,
        floor: 30.0,
        thinning: Thinning::Gradient,
    };
    let edges = prewitt_edges(&blurred, &rule);
    let (w, h) = edges.mask.dimensions();
    let pixels = edges.unit_gradients();
    let diag = (w as f64).hypot(h as f64);
    let min_len = (params.min_length_frac * diag).max(10.0);
    let mut lines = detect_lines(
        &edges.mask,
        LineDetectionOptions {
            vote_threshold: (min_len * 0.8) as u32,
            suppression_radius: 4,
        },
    );
    if lines.is_empty() {
        return Vec::new();
    }
    // Strongest lines first: count votes by re-walking is costly, so rank by support below.
    lines.truncate(params.max_hough_lines * 4);
    let mut used = vec![false; pixels.len()];
    let mut index = vec![u32::MAX; (w * h) as usize];
    for (k, &(x, y, _, _)) in pixels.iter().enumerate() {
        index[(y * w + x) as usize] = k as u32;
    }
    let mut candidates: Vec<(usize, Vec<usize>)> = lines
        .iter()
        .enumerate()
        .map(|(i, l)| {
            (
                i,
                line_support(&pixels, w, h, &index, l.r as f64, l.angle_in_degrees as f64),
            )
        })
        .collect();
    candidates.sort_by_key(|c| std::cmp::Reverse(c.1.len()));
    candidates.truncate(params.max_hough_lines);
    let mut out = Vec::new();
    for (i, support) in candidates {
        let l = lines[i];
        let (s, c) = (l.angle_in_degrees as f64).to_radians().sin_cos();
        // Position along the line, runs split at gaps.
        let mut pts: Vec<(f64, usize)> = support
            .into_iter()
            .filter(|&k| !used[k])
            .map(|k| {
                let (x, y, _, _) = pixels[k];
                (-(x as f64) * s + y as f64 * c, k)
            })
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut start = 0;
        for j in 1..=pts.len() {
            if j == pts.len() || pts[j].0 - pts[j - 1].0 > 4.0 {
                let run = &pts[start..j];
                if let Some(seg) = fit_run(run, &pixels, min_len) {
                    for &(_, k) in run {
                        used[k] = true;
                    }
                    out.push(seg.scaled(1.0 / scale));
                }
                start = j;
            }
        }
    }
    out
}

/// Edge pixels (`pixels`, with their unit gradients, at `index` in the `w` × `h` image) within
/// 2 px of the line x cos θ + y sin θ = r whose gradient is parallel to its normal (within
/// ~25°), found by walking along the line rather than scanning every edge pixel.
fn line_support(
    pixels: &[(u32, u32, f32, f32)],
    w: u32,
    h: u32,
    index: &[u32],
    r: f64,
    deg: f64,
) -> Vec<usize> {
    let (s, c) = deg.to_radians().sin_cos();
    let (w, h) = (w as i64, h as i64);
    let mut out = Vec::new();
    let mut visit = |x: i64, y: i64| {
        if x < 0 || y < 0 || x >= w || y >= h {
            return;
        }
        let k = index[(y * w + x) as usize];
        if k == u32::MAX {
            return;
        }
        let (px, py, gx, gy) = pixels[k as usize];
        let d = px as f64 * c + py as f64 * s - r;
        if d.abs() <= 2.0 && (gx as f64 * c + gy as f64 * s).abs() > 0.9 {
            out.push(k as usize);
        }
    };
    if s.abs() >= c.abs() {
        for x in 0..w {
            let y = ((r - x as f64 * c) / s).round() as i64;
            for dy in -3..=3 {
                visit(x, y + dy);
            }
        }
    } else {
        for y in 0..h {
            let x = ((r - y as f64 * s) / c).round() as i64;
            for dx in -3..=3 {
                visit(x + dx, y);
            }
        }
    }
    out
}

/// Total-least-squares fit of a run of edge pixels; `None` when too short or too sparse.
fn fit_run(run: &[(f64, usize)], pixels: &[(u32, u32, f32, f32)], min_len: f64) -> Option<Segment> {
    if run.len() < 2
        || run[run.len() - 1].0 - run[0].0 < min_len
        || (run.len() as f64) < 0.6 * min_len
    {
        return None;
    }
    let n = run.len() as f64;
    let (mut mx, mut my) = (0.0, 0.0);
    for &(_, k) in run {
        mx += pixels[k].0 as f64;
        my += pixels[k].1 as f64;
    }
    mx /= n;
    my /= n;
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for &(_, k) in run {
        let (dx, dy) = (pixels[k].0 as f64 - mx, pixels[k].1 as f64 - my);
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    // Principal direction of the 2x2 scatter matrix.
    let theta = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let (dy, dx) = theta.sin_cos();
    let (mut tmin, mut tmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for &(_, k) in run {
        let t = (pixels[k].0 as f64 - mx) * dx + (pixels[k].1 as f64 - my) * dy;
        tmin = tmin.min(t);
        tmax = tmax.max(t);
    }
    if tmax - tmin < min_len {
        return None;
    }
    Some(Segment::new(
        mx + tmin * dx,
        my + tmin * dy,
        mx + tmax * dx,
        my + tmax * dy,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Luma;

    #[test]
    fn finds_the_edges_of_a_tilted_rectangle() {
        let mut img = GrayImage::from_pixel(200, 160, Luma([40]));
        // A bright parallelogram: top/bottom edges tilted by atan(0.1), left/right vertical.
        for y in 0..160u32 {
            for x in 0..200u32 {
                let top = 40.0 + 0.1 * x as f64;
                if (50..150).contains(&x) && (y as f64) > top && (y as f64) < top + 70.0 {
                    img.put_pixel(x, y, Luma([200]));
                }
            }
        }
        let segs = detect_segments(&img, &LineParams::default());
        let tilt = 0.1f64.atan().to_degrees();
        let horiz = segs
            .iter()
            .filter(|s| (s.tilt_degrees() - tilt).abs() < 0.5)
            .count();
        let vert = segs.iter().filter(|s| s.tilt_degrees() > 89.5).count();
        assert!(horiz >= 2 && vert >= 2, "{segs:?}");
    }

    #[test]
    fn flat_image_has_no_segments() {
        let img = GrayImage::from_pixel(100, 100, Luma([128]));
        assert!(detect_segments(&img, &LineParams::default()).is_empty());
    }
}
