//! Hatching suppression before the edges of §4.2, for engraved elevations (not in ch. 4, which
//! works on photographs): where short parallel strokes fill a surface (shading, coursing lines)
//! the strokes are replaced by their tone, so the distance transform sees the outline of a
//! hatched opening instead of every stroke inside it.

use image::{GrayImage, Luma};
use imageproc::filter::gaussian_blur_f32;
use raster::edges::prewitt_edges;
use serde::{Deserialize, Serialize};

use super::likelihood::edge_rule;

/// What counts as hatching.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HatchParams {
    /// Half side (px) of the square window the strokes are counted in.
    pub radius: usize,
    /// Smallest share of the window's pixels on an edge: several strokes, not one outline.
    pub min_density: f64,
    /// Smallest orientation coherence |Σ e^{2iθ}| / n of those edges: parallel strokes.
    pub min_coherence: f64,
    /// σ (px) of the blur that turns the strokes into a tone.
    pub blur: f32,
}

impl Default for HatchParams {
    fn default() -> Self {
        HatchParams {
            radius: 6,
            min_density: 0.2,
            min_coherence: 0.7,
            blur: 1.8,
        }
    }
}

/// Row-major mask of hatched pixels: within `radius` of a pixel whose window holds at least
/// `min_density` edge pixels (thinned Prewitt edges at `edge_threshold`) with gradient
/// directions coherent to at least `min_coherence`.
pub fn hatched(gray: &GrayImage, edge_threshold: f64, p: &HatchParams) -> Vec<bool> {
    let (w, h) = (gray.width() as usize, gray.height() as usize);
    let edges = prewitt_edges(gray, &edge_rule(edge_threshold));
    let (gx, gy) = (&edges.gradient.gx, &edges.gradient.gy);
    // Per edge pixel: 1 and its doubled-angle orientation (cos 2θ, sin 2θ), so a stroke's two
    // sides (opposite gradients) and all parallel strokes add up.
    let mut count = vec![0.0; w * h];
    let mut c2 = vec![0.0; w * h];
    let mut s2 = vec![0.0; w * h];
    for (i, e) in edges.mask.as_raw().iter().enumerate() {
        if *e == 0 {
            continue;
        }
        let (x, y) = (gx.as_raw()[i] as f64, gy.as_raw()[i] as f64);
        let m = x * x + y * y;
        if m > 0.0 {
            count[i] = 1.0;
            c2[i] = (x * x - y * y) / m;
            s2[i] = 2.0 * x * y / m;
        }
    }
    let (count, c2, s2) = (
        box_sums(&count, w, h, p.radius),
        box_sums(&c2, w, h, p.radius),
        box_sums(&s2, w, h, p.radius),
    );
    let area = ((2 * p.radius + 1) * (2 * p.radius + 1)) as f64;
    let core: Vec<f64> = (0..w * h)
        .map(|i| {
            let coherent = c2[i].hypot(s2[i]) >= p.min_coherence * count[i];
            f64::from(u8::from(count[i] >= p.min_density * area && coherent))
        })
        .collect();
    // Where two hatchings of different direction meet (an opening's outline between a ruled
    // wall and a hatched opening) the window is not coherent although every stroke is
    // hatching: the mask is grown by the window so the whole border becomes tone.
    box_sums(&core, w, h, p.radius)
        .into_iter()
        .map(|n| n > 0.0)
        .collect()
}

/// The image with hatched regions replaced by their blurred tone (the rest untouched), and
/// the share of pixels that were hatched.
pub fn suppress(gray: &GrayImage, edge_threshold: f64, p: &HatchParams) -> (GrayImage, f64) {
    let mask = hatched(gray, edge_threshold, p);
    let n = mask.iter().filter(|&&m| m).count();
    if n == 0 {
        return (gray.clone(), 0.0);
    }
    let tone = gaussian_blur_f32(gray, p.blur);
    let mut out = gray.clone();
    for ((o, t), m) in out.pixels_mut().zip(tone.pixels()).zip(&mask) {
        if *m {
            *o = Luma([t[0]]);
        }
    }
    (out, n as f64 / mask.len() as f64)
}

/// Sum of `v` over the (2r + 1)² window around every pixel (clipped at the borders), by a
/// summed-area table.
pub(super) fn box_sums(v: &[f64], w: usize, h: usize, r: usize) -> Vec<f64> {
    let mut sat = vec![0.0; (w + 1) * (h + 1)];
    for y in 0..h {
        let mut row = 0.0;
        for x in 0..w {
            row += v[y * w + x];
            sat[(y + 1) * (w + 1) + x + 1] = sat[y * (w + 1) + x + 1] + row;
        }
    }
    let mut out = vec![0.0; w * h];
    for y in 0..h {
        let (y0, y1) = (y.saturating_sub(r), (y + r + 1).min(h));
        for x in 0..w {
            let (x0, x1) = (x.saturating_sub(r), (x + r + 1).min(w));
            out[y * w + x] =
                sat[y1 * (w + 1) + x1] - sat[y0 * (w + 1) + x1] - sat[y1 * (w + 1) + x0]
                    + sat[y0 * (w + 1) + x0];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_sums_of_ones_count_the_clipped_window() {
        let s = box_sums(&[1.0; 12], 4, 3, 1);
        assert_eq!(
            s,
            vec![4.0, 6.0, 6.0, 4.0, 6.0, 9.0, 9.0, 6.0, 4.0, 6.0, 6.0, 4.0]
        );
    }

    /// Vertical strokes 4 px apart on the left half, one outline on the right half.
    fn strokes_and_an_outline() -> GrayImage {
        GrayImage::from_fn(80, 40, |x, _| {
            let stroke = x < 40 && x % 4 == 0;
            let outline = x == 60;
            Luma([if stroke || outline { 20 } else { 230 }])
        })
    }

    #[test]
    fn parallel_strokes_are_hatching_a_single_line_is_not() {
        let img = strokes_and_an_outline();
        let mask = hatched(&img, 0.2, &HatchParams::default());
        let at = |x: usize, y: usize| mask[y * 80 + x];
        assert!(at(20, 20), "inside the strokes");
        assert!(!at(60, 20) && !at(70, 20), "the lone outline");
        let (out, share) = suppress(&img, 0.2, &HatchParams::default());
        assert!(share > 0.3 && share < 0.7, "{share}");
        // The strokes became a flat tone; the outline is untouched.
        let row: Vec<u8> = (12..28).map(|x| out.get_pixel(x, 20)[0]).collect();
        let (lo, hi) = (row.iter().min().unwrap(), row.iter().max().unwrap());
        assert!(hi - lo < 25, "{row:?}");
        assert_eq!(out.get_pixel(60, 20)[0], 20);
    }
}
