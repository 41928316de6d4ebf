//! Drawn scale bars (issue 11; §5.1.1 takes the drawing's scale as given): the longest
//! horizontal ruled bar of the drawing, so that a user who reads its length off the drawing
//! once gets a model in metres.

use image::GrayImage;
use serde::Serialize;

use crate::binarize::{binarize, threshold_level};

/// A scale bar: its left and right ends and its baseline row, in the drawing's pixels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ScaleBar {
    pub x0: u32,
    pub x1: u32,
    pub y: u32,
    /// Length in pixels, end to end.
    pub length_px: u32,
}

impl ScaleBar {
    /// Units per pixel when the bar is `length` units long.
    pub fn scale(&self, length: f64) -> f64 {
        length / f64::from(self.length_px.max(1))
    }
}

/// Finds the scale bar: among the 8-connected ink regions that are not the largest one (the
/// castle) nor inside its extent, those at least 6 % of the image wide, at most a quarter as
/// tall as wide, and with a 3-row band inked along at least 90 % of their width (the ruled
/// line; ticks may hang off it). The widest wins. None when no region qualifies.
pub fn find(grey: &GrayImage) -> Option<ScaleBar> {
    let (w, h) = grey.dimensions();
    if w == 0 || h == 0 {
        return None;
    }
    let bin = binarize(grey, threshold_level(grey));
    let comps = regions(&bin);
    let castle = comps.iter().max_by_key(|c| c.pixels.len())?;
    let cb = castle.bbox;
    let min_width = (f64::from(w) * 0.06).max(12.0) as u32;
    let mut best: Option<ScaleBar> = None;
    for c in &comps {
        let b = c.bbox;
        let (bw, bh) = (b[2] - b[0] + 1, b[3] - b[1] + 1);
        // Regions inside the castle's extent are walls (binarize keeps them as the castle).
        let inside = b[0] >= cb[0] && b[1] >= cb[1] && b[2] <= cb[2] && b[3] <= cb[3];
        if inside || bw < min_width || bh * 4 > bw {
            continue;
        }
        // Columns inked within a 3-row band around each row: a slightly tilted or broken
        // 1-px line still counts.
        let mut cols = vec![vec![false; bw as usize]; bh as usize];
        for &(x, y) in &c.pixels {
            cols[(y - b[1]) as usize][(x - b[0]) as usize] = true;
        }
        let band = |r: usize| {
            (0..bw as usize)
                .filter(|&x| {
                    (r.saturating_sub(1)..=(r + 1).min(bh as usize - 1)).any(|q| cols[q][x])
                })
                .count()
        };
        // The baseline: the best-covered band, and within ties the row with most ink.
        let own = |r: usize| cols[r].iter().filter(|&&c| c).count();
        let Some((row, count)) = (0..bh as usize)
            .map(|r| (r, band(r)))
            .max_by_key(|&(r, n)| (n, own(r), std::cmp::Reverse(r)))
        else {
            continue;
        };
        if (count as f64) < 0.9 * f64::from(bw) {
            continue;
        }
        if best.is_none_or(|bb| bw > bb.length_px) {
            best = Some(ScaleBar {
                x0: b[0],
                x1: b[2],
                y: b[1] + row as u32,
                length_px: bw,
            });
        }
    }
    best
}

struct Region {
    pixels: Vec<(u32, u32)>,
    bbox: [u32; 4],
}

/// 8-connected regions of ink (255) by flood fill; the pixel lists are bounded by the image.
fn regions(bin: &GrayImage) -> Vec<Region> {
    let (w, h) = bin.dimensions();
    let mut seen = vec![false; (w as usize) * (h as usize)];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for y0 in 0..h {
        for x0 in 0..w {
            let i0 = (y0 * w + x0) as usize;
            if seen[i0] || bin.get_pixel(x0, y0)[0] != 255 {
                continue;
            }
            seen[i0] = true;
            stack.push((x0, y0));
            let mut r = Region {
                pixels: Vec::new(),
                bbox: [x0, y0, x0, y0],
            };
            while let Some((x, y)) = stack.pop() {
                r.pixels.push((x, y));
                r.bbox = [
                    r.bbox[0].min(x),
                    r.bbox[1].min(y),
                    r.bbox[2].max(x),
                    r.bbox[3].max(y),
                ];
                for dy in -1i64..=1 {
                    for dx in -1i64..=1 {
                        let (nx, ny) = (i64::from(x) + dx, i64::from(y) + dy);
                        if nx < 0 || ny < 0 || nx >= i64::from(w) || ny >= i64::from(h) {
                            continue;
                        }
                        let j = (ny as u32 * w + nx as u32) as usize;
                        if !seen[j] && bin.get_pixel(nx as u32, ny as u32)[0] == 255 {
                            seen[j] = true;
                            stack.push((nx as u32, ny as u32));
                        }
                    }
                }
            }
            out.push(r);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Luma;

    /// A 300 × 200 sheet with a square "castle" and, below it, a 120-px bar with ticks.
    fn sheet(bar: bool) -> GrayImage {
        GrayImage::from_fn(300, 200, |x, y| {
            let castle = (20..=120).contains(&x)
                && (20..=120).contains(&y)
                && !((30..=110).contains(&x) && (30..=110).contains(&y));
            let line = (150..=269).contains(&x) && y == 170;
            let tick = (150..=269).contains(&x) && (x - 150) % 20 == 0 && (164..=170).contains(&y);
            Luma([if castle || (bar && (line || tick)) {
                0
            } else {
                255
            }])
        })
    }

    #[test]
    fn finds_a_ruled_bar_with_ticks_and_its_length() {
        let b = find(&sheet(true)).unwrap();
        assert_eq!((b.x0, b.x1, b.y, b.length_px), (150, 269, 170, 120));
        assert!((b.scale(30.0) - 0.25).abs() < 1e-12);
    }

    #[test]
    fn no_bar_no_answer_and_the_castle_is_never_the_bar() {
        assert_eq!(find(&sheet(false)), None);
        assert_eq!(find(&GrayImage::from_pixel(50, 40, Luma([255]))), None);
    }
}
