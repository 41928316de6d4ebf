//! Class-driven Gothic detection for photographs: a documented departure from §4.2, whose
//! likelihood sees image edges only. The ch. 3 pixel classes (§3.1.2–3.1.4: user boxes → one
//! GMM per class → ln P_kj) give a window map; its outline replaces the Prewitt edges as the
//! source of D, and one seed per window blob replaces the peaks of D. Θ, eq. 4.2 and the
//! conjugate-gradient MLE are unchanged.
//!
//! Why: glazing bars, frames, shutters and railings fill photographed windows with edges, so
//! the deepest peaks of D lie on the piers and contours lock onto panes (docs/gothic.md).

use image::{GrayImage, Luma, RgbImage};
use raster::components::{Connectivity, components_where};

use super::detect::{self, Seed};
use super::element::Theta;
use super::likelihood::DistanceMap;
use super::model::GothicEstimate;
use super::organise;
use super::params::GothicParams;
use crate::classify::{self, Class, ClassifyParams, LogLikelihoods, Training};
use crate::{FacadeError, Result};

/// How the class log-likelihoods become a window map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClassMapParams {
    /// Per-pixel log-likelihood ratios are clipped to ±this (nats) before smoothing, so a few
    /// confident pixels cannot outvote their neighbourhood.
    pub clip: f32,
    /// Half-side (px) of the box mean over the clipped ratio: bridges glazing bars and mullions
    /// a few pixels wide that the texture features classify as wall.
    pub smooth_radius: usize,
    /// A pixel is window where the smoothed ratio exceeds this (nats).
    pub threshold: f32,
    /// Smallest depth (px; distance from the blob's outline to its innermost pixel) of a
    /// window blob that seeds an element: shallower blobs are noise.
    pub min_depth: f32,
    /// Where D's edges come from. `None`: the outline of the window map itself. `Some(b)`: the
    /// image's Prewitt edges (§4.2) within `b` px of that outline, so the contour sits on the
    /// real frame while glazing bars deep inside and wall texture far outside are dropped (the
    /// map's outline is only as sharp as the 21-px texture features of ch. 3).
    pub band: Option<f32>,
}

impl Default for ClassMapParams {
    fn default() -> Self {
        ClassMapParams {
            clip: 5.0,
            smooth_radius: 2,
            threshold: 0.0,
            min_depth: 4.0,
            band: Some(8.0),
        }
    }
}

/// The window map: `true` where the smoothed window-vs-rest ratio is above the threshold.
#[derive(Debug, Clone, PartialEq)]
pub struct WindowMap {
    pub width: usize,
    pub height: usize,
    pub window: Vec<bool>,
}

/// ln P(window) − max(ln P(wall), ln P(background)) per pixel, clipped, box-smoothed and
/// thresholded. Both the window and the wall log-likelihoods are needed.
pub fn window_map(ll: &LogLikelihoods, p: &ClassMapParams) -> Result<WindowMap> {
    let (w, h) = (ll.width, ll.height);
    let missing = |c: Class| {
        FacadeError::BadTraining(format!(
            "class-driven Gothic detection needs {} boxes (window and wall are required)",
            c.name()
        ))
    };
    let win = ll
        .get(Class::Window)
        .ok_or_else(|| missing(Class::Window))?;
    let wall = ll.get(Class::Wall).ok_or_else(|| missing(Class::Wall))?;
    let background = ll.get(Class::Background);
    let ratio: Vec<f64> = (0..w * h)
        .map(|i| {
            let rest = background.map_or(wall[i], |b| wall[i].max(b[i]));
            ((win[i] - rest).clamp(-p.clip, p.clip)) as f64
        })
        .collect();
    let smooth = box_mean(&ratio, w, h, p.smooth_radius);
    Ok(WindowMap {
        width: w,
        height: h,
        window: smooth.iter().map(|&v| v > p.threshold as f64).collect(),
    })
}

/// Mean over the (2r + 1)² box around each pixel, clipped at the image border: the box sums
/// of [`super::hatching_tone::box_sums`] over the clipped box's area.
fn box_mean(v: &[f64], w: usize, h: usize, r: usize) -> Vec<f64> {
    let span = |c: usize, n: usize| (c + r + 1).min(n) - c.saturating_sub(r);
    super::hatching_tone::box_sums(v, w, h, r)
        .into_iter()
        .enumerate()
        .map(|(i, s)| s / (span(i % w, w) * span(i / w, h)) as f64)
        .collect()
}

impl WindowMap {
    /// The outline of the window map as an edge image: both pixels of every 4-neighbour pair
    /// that differ, so the zero line of D is centred on the class boundary (as the thinned
    /// Prewitt edges of a step are).
    pub fn outline(&self) -> GrayImage {
        let (w, h) = (self.width, self.height);
        let mut out = GrayImage::new(w as u32, h as u32);
        for y in 0..h {
            for x in 0..w {
                let a = self.window[y * w + x];
                let right = x + 1 < w && self.window[y * w + x + 1] != a;
                let below = y + 1 < h && self.window[(y + 1) * w + x] != a;
                if right {
                    out.put_pixel(x as u32, y as u32, Luma([255]));
                    out.put_pixel(x as u32 + 1, y as u32, Luma([255]));
                }
                if below {
                    out.put_pixel(x as u32, y as u32, Luma([255]));
                    out.put_pixel(x as u32, y as u32 + 1, Luma([255]));
                }
            }
        }
        out
    }

    /// Distance from each pixel to the nearest non-window pixel (0 outside windows).
    pub fn depth(&self) -> DistanceMap {
        let not_window = GrayImage::from_fn(self.width as u32, self.height as u32, |x, y| {
            Luma([if self.window[y as usize * self.width + x as usize] {
                0
            } else {
                255
            }])
        });
        DistanceMap::of_edges(&not_window)
    }

    /// One seed per 4-connected window blob at least `min_depth` deep, at its deepest pixel
    /// (first in raster order on ties), deepest blobs first, at most `max_seeds`.
    pub fn blob_seeds(&self, min_depth: f32, max_seeds: usize) -> Vec<Seed> {
        let (w, h) = (self.width, self.height);
        let depth = self.depth();
        let blobs = components_where(w, h, Connectivity::Four, |i| self.window[i]);
        // The deepest pixel of each blob, the first in raster order on ties.
        let mut best: Vec<Option<(usize, f32)>> = vec![None; blobs.sizes.len()];
        for (i, &l) in blobs.labels.iter().enumerate() {
            let b = &mut best[l as usize];
            if l > 0 && b.is_none_or(|(_, d)| depth.d[i] > d) {
                *b = Some((i, depth.d[i]));
            }
        }
        let mut out: Vec<Seed> = best
            .into_iter()
            .flatten()
            .filter(|&(_, d)| d >= min_depth)
            .map(|(i, d)| Seed {
                x: i % w,
                y: i / w,
                radius: d,
            })
            .collect();
        out.sort_by(|a, b| {
            b.radius
                .total_cmp(&a.radius)
                .then((a.y, a.x).cmp(&(b.y, b.x)))
        });
        out.truncate(max_seeds);
        out
    }
}

/// The element pipeline of §4.2 driven by a window map: D from the map's outline, seeds one
/// per window blob, then the same maximisation, significance test, grouping and nesting.
pub fn estimate_from_map(
    img: &RgbImage,
    map: &WindowMap,
    params: &GothicParams,
    p: &ClassMapParams,
) -> GothicEstimate {
    let outline = map.outline();
    let edges = match p.band {
        None => outline,
        Some(band) => {
            let near = DistanceMap::of_edges(&outline);
            let mut e = super::image_edges(img, params);
            for (i, px) in e.pixels_mut().enumerate() {
                if near.d[i] > band {
                    px[0] = 0;
                }
            }
            e
        }
    };
    let dt = DistanceMap::of_edges(&edges);
    let seeds = map.blob_seeds(p.min_depth, params.max_seeds);
    // Photographed windows are mostly rectangles, and CG from a round head over a rectangular
    // opening can stop with the arc across the lintel's corners: each walked box also starts
    // as a rectangle.
    let mut starts = detect::starts(&dt, &seeds);
    let rectangles: Vec<Theta> = starts
        .iter()
        .filter(|t| t.v > 0.0)
        .map(|t| Theta {
            h: t.h + t.v,
            v: 0.0,
            ..*t
        })
        .collect();
    starts.extend(rectangles);
    let found = detect::detect_from_starts(&dt, &starts, params);
    organise(&dt, found, params)
}

/// [`estimate_from_map`] on the window map of `img` under the user's training boxes (§3.1.2).
pub fn estimate_with_classes(
    img: &RgbImage,
    training: &Training,
    params: &GothicParams,
    classify_params: &ClassifyParams,
    p: &ClassMapParams,
) -> Result<GothicEstimate> {
    super::check_size(img)?;
    let ll = classify::classify(img, training, classify_params)?;
    let map = window_map(&ll, p)?;
    Ok(estimate_from_map(img, &map, params, p))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(rows: &[&str]) -> WindowMap {
        WindowMap {
            width: rows[0].len(),
            height: rows.len(),
            window: rows
                .iter()
                .flat_map(|r| r.bytes().map(|b| b == b'#'))
                .collect(),
        }
    }

    #[test]
    fn ratio_is_clipped_smoothed_and_thresholded() {
        // One wall pixel with a huge contrary ratio inside a 3 x 3 window block is outvoted once
        // clipped; the lone window pixel at the right is outvoted by its wall neighbours.
        let (w, h) = (7, 3);
        let mut win = vec![-1.0f32; w * h];
        for y in 0..3 {
            for x in 0..3 {
                win[y * w + x] = 1.0;
            }
        }
        win[w + 1] = -1000.0;
        win[w + 6] = 3.0;
        let ll = LogLikelihoods {
            width: w,
            height: h,
            maps: [None, Some(vec![0.0; w * h]), Some(win)],
        };
        let p = ClassMapParams {
            clip: 2.0,
            smooth_radius: 1,
            ..ClassMapParams::default()
        };
        let m = window_map(&ll, &p).unwrap();
        assert!(m.window[w + 1], "the clipped outlier is window again");
        assert!(!m.window[w + 6], "the isolated pixel is wall");
        assert!(m.window[0] && !m.window[w + 4]);
    }

    #[test]
    fn a_missing_class_is_an_error() {
        let ll = LogLikelihoods {
            width: 2,
            height: 2,
            maps: [None, None, Some(vec![0.0; 4])],
        };
        let e = window_map(&ll, &ClassMapParams::default()).unwrap_err();
        assert!(e.to_string().contains("wall boxes"), "{e}");
    }

    #[test]
    fn outline_marks_both_sides_of_the_class_boundary() {
        let m = map(&["..##", "..##"]);
        let o = m.outline();
        let row: Vec<u8> = (0..4).map(|x| o.get_pixel(x, 0)[0]).collect();
        assert_eq!(row, vec![0, 255, 255, 0]);
    }

    #[test]
    fn one_seed_per_blob_at_its_deepest_pixel() {
        let m = map(&[
            "..........",
            ".#####....",
            ".#####.##.",
            ".#####.##.",
            ".#####....",
            ".#####....",
            "..........",
        ]);
        let s = m.blob_seeds(1.0, 10);
        assert_eq!(s.len(), 2, "{s:?}");
        assert_eq!((s[0].x, s[0].y, s[0].radius), (3, 3, 3.0));
        assert_eq!((s[1].x, s[1].y, s[1].radius), (7, 2, 1.0));
        assert_eq!(m.blob_seeds(1.5, 10).len(), 1, "the shallow blob is noise");
        assert_eq!(m.blob_seeds(1.0, 1).len(), 1);
    }
}
