//! The user's small window boxes grown into whole windows (issue 21; not in the dissertation).
//! A user who draws a few small boxes inside windows (§3.1.2) gives the classifier glass only;
//! a user who outlines whole windows gives it the window's extent, the ring of wall around it
//! and a template for its repeats, and reads the façade far better (docs/facade.md). So after
//! a first classification each small window box is grown, one pixel row or column at a time,
//! while the strip just beyond a side is mostly window on that map; a box that stays window-sized
//! is then treated as a whole window. Pure: the map and boxes in, boxes out.

use crate::classify::{Class, LogLikelihoods, PixelBox};
use crate::search::Integral;

/// Settings of [`grow_windows`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrowParams {
    /// A side moves out while the mean window probability of the strip just beyond it is at
    /// least this.
    pub threshold: f64,
    /// A grown box wider than this fraction of the image's width, or taller than this fraction
    /// of its height, is no window (the map leaked into a wall or a shop front): dropped.
    pub max_frac: f64,
    /// A grown box whose sides are not both at least this many times the drawn box's is
    /// dropped: the map stopped at the box, which then is no evidence of the window's extent.
    pub min_growth: f64,
    /// Each side of a grown box then moves to the strongest image edge along it within this
    /// fraction of the box's size (a window's frame is where the photo's brightness jumps; the
    /// map's edge is blurred). 0: no snapping.
    pub snap: f64,
}

impl Default for GrowParams {
    fn default() -> Self {
        GrowParams {
            threshold: 0.6,
            max_frac: 0.3,
            min_growth: 1.0,
            snap: 0.15,
        }
    }
}

/// The window class's probability at every pixel: the soft-max of the classes' ln p (ln P for
/// the text's mixtures, equal priors). `None` without a window map.
pub fn window_probability(ll: &LogLikelihoods) -> Option<Vec<f32>> {
    let win = ll.get(Class::Window)?;
    let others: Vec<&[f32]> = Class::ALL
        .iter()
        .filter(|&&c| c != Class::Window)
        .filter_map(|&c| ll.get(c))
        .collect();
    Some(
        (0..win.len())
            .map(|i| {
                let denom: f32 = others.iter().map(|m| (m[i] - win[i]).exp()).sum();
                1.0 / (1.0 + denom)
            })
            .collect(),
    )
}

/// Each of `boxes` grown on the window probability `prob` (`w` × `h`, row-major): every side
/// moves out by one pixel while the strip just beyond it, as long as the box's current side,
/// has mean probability ≥ `p.threshold`, until no side moves. `None` for a box that grew past
/// `p.max_frac` of the image or not by `p.min_growth` in both directions.
pub fn grow_windows(
    prob: &[f32],
    w: usize,
    h: usize,
    boxes: &[PixelBox],
    p: &GrowParams,
) -> Vec<Option<PixelBox>> {
    let prob: Vec<f64> = prob.iter().map(|&v| v as f64).collect();
    let sat = Integral::new(&prob, w, h);
    let mean =
        |b: &PixelBox| sat.sum(b[0], b[1], b[2], b[3]) / ((b[2] - b[0]) * (b[3] - b[1])) as f64;
    let (max_w, max_h) = (
        (w as f64 * p.max_frac).ceil() as usize,
        (h as f64 * p.max_frac).ceil() as usize,
    );
    boxes
        .iter()
        .map(|&b0| {
            let mut b = b0;
            loop {
                let mut moved = false;
                let strips = [
                    (b[0] > 0).then(|| [b[0] - 1, b[1], b[0], b[3]]),
                    (b[1] > 0).then(|| [b[0], b[1] - 1, b[2], b[1]]),
                    (b[2] < w).then(|| [b[2], b[1], b[2] + 1, b[3]]),
                    (b[3] < h).then(|| [b[0], b[3], b[2], b[3] + 1]),
                ];
                for (side, strip) in strips.into_iter().enumerate() {
                    let Some(s) = strip else { continue };
                    if mean(&s) >= p.threshold {
                        match side {
                            0 => b[0] -= 1,
                            1 => b[1] -= 1,
                            2 => b[2] += 1,
                            _ => b[3] += 1,
                        }
                        moved = true;
                    }
                }
                if b[2] - b[0] > max_w || b[3] - b[1] > max_h {
                    return None;
                }
                if !moved {
                    break;
                }
            }
            let grew = |a: usize, a0: usize| a as f64 >= p.min_growth * a0 as f64;
            (grew(b[2] - b[0], b0[2] - b0[0]) && grew(b[3] - b[1], b0[3] - b0[1])).then_some(b)
        })
        .collect()
}

/// Each of `boxes` grown on `ll`'s window probability ([`grow_windows`]) and its sides snapped
/// to `img`'s brightness steps ([`snap_to_edges`]): the growth step as `facade::parse_photo`
/// runs it. `None` without a window map.
pub fn grow_on(
    img: &image::RgbImage,
    ll: &LogLikelihoods,
    boxes: &[PixelBox],
    p: &GrowParams,
) -> Option<Vec<Option<PixelBox>>> {
    let (w, h) = (ll.width, ll.height);
    let prob = window_probability(ll)?;
    let grey = brightness(img);
    Some(
        grow_windows(&prob, w, h, boxes, p)
            .into_iter()
            .map(|b| b.map(|b| snap_to_edges(&grey, w, h, b, p.snap)))
            .collect(),
    )
}

/// The photo's brightness (mean of R, G, B, 0–1), row-major: what [`snap_to_edges`] reads.
pub fn brightness(img: &image::RgbImage) -> Vec<f32> {
    img.pixels()
        .map(|p| (p.0[0] as f32 + p.0[1] as f32 + p.0[2] as f32) / 765.0)
        .collect()
}

/// `b` with each side moved to the strongest brightness step along it (mean absolute
/// difference across the side, over the box's current span) within `frac` of the box's size
/// of where it is; the box keeps at least 2 pixels a side. `grey` is `w` × `h`, row-major.
pub fn snap_to_edges(grey: &[f32], w: usize, h: usize, b: PixelBox, frac: f64) -> PixelBox {
    if frac <= 0.0 {
        return b;
    }
    let mut b = b;
    // A step at column x: between pixels x − 1 and x, over rows y0..y1.
    let step_x = |x: usize, y0: usize, y1: usize| {
        (y0..y1)
            .map(|y| (grey[y * w + x] - grey[y * w + x - 1]).abs())
            .sum::<f32>()
            / (y1 - y0) as f32
    };
    let step_y = |y: usize, x0: usize, x1: usize| {
        (x0..x1)
            .map(|x| (grey[y * w + x] - grey[(y - 1) * w + x]).abs())
            .sum::<f32>()
            / (x1 - x0) as f32
    };
    // The strongest step in from..=to; a side stays where it is unless a step is stronger.
    let best = |from: usize, to: usize, at: usize, score: &dyn Fn(usize) -> f32| {
        let here = if (from..=to).contains(&at) {
            score(at)
        } else {
            f32::NEG_INFINITY
        };
        (from..=to)
            .map(|p| (p, score(p)))
            .fold((at, here), |a, c| if c.1 > a.1 { c } else { a })
            .0
    };
    let rx = ((b[2] - b[0]) as f64 * frac).round() as usize;
    let ry = ((b[3] - b[1]) as f64 * frac).round() as usize;
    // Both sides along one axis, each within r of where it is, at least 2 px apart.
    let snap_axis = |lo: usize, hi: usize, r: usize, limit: usize, score: &dyn Fn(usize) -> f32| {
        let lo = best(lo.saturating_sub(r).max(1), (lo + r).min(hi - 2), lo, score);
        let hi = best((hi - r).max(lo + 2), (hi + r).min(limit - 1), hi, score);
        (lo, hi)
    };
    let (y0, y1) = (b[1], b[3]);
    (b[0], b[2]) = snap_axis(b[0], b[2], rx, w, &|x| step_x(x, y0, y1));
    let (x0, x1) = (b[0], b[2]);
    (b[1], b[3]) = snap_axis(b[1], b[3], ry, h, &|y| step_y(y, x0, x1));
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 40 × 30 picture: `inside` on the window [10, 5, 22, 25), `outside` elsewhere.
    fn window_on_wall(inside: f32, outside: f32) -> (Vec<f32>, usize, usize) {
        let (w, h) = (40, 30);
        let v = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                if (10..22).contains(&x) && (5..25).contains(&y) {
                    inside
                } else {
                    outside
                }
            })
            .collect();
        (v, w, h)
    }

    /// The window probability map: 0.9 on the window, 0.1 elsewhere.
    fn map() -> (Vec<f32>, usize, usize) {
        window_on_wall(0.9, 0.1)
    }

    #[test]
    fn a_small_box_grows_to_its_window_exactly() {
        let (v, w, h) = map();
        let p = GrowParams {
            max_frac: 0.8,
            ..Default::default()
        };
        let got = grow_windows(&v, w, h, &[[14, 12, 17, 15], [12, 6, 13, 7]], &p);
        assert_eq!(got, vec![Some([10, 5, 22, 25]), Some([10, 5, 22, 25])]);
    }

    #[test]
    fn a_box_that_outgrows_the_limit_or_does_not_grow_is_dropped() {
        let (v, w, h) = map();
        // The window is 20 of 30 rows tall: over a 0.5 limit.
        let tall = GrowParams {
            max_frac: 0.5,
            ..Default::default()
        };
        assert_eq!(
            grow_windows(&v, w, h, &[[14, 12, 17, 15]], &tall),
            vec![None]
        );
        // A box on the wall does not grow; with growth required it is dropped.
        let p = GrowParams {
            max_frac: 0.8,
            min_growth: 1.5,
            ..Default::default()
        };
        assert_eq!(grow_windows(&v, w, h, &[[30, 2, 33, 5]], &p), vec![None]);
    }

    #[test]
    fn sides_snap_to_the_window_frame_within_reach() {
        // A dark window [10, 5, 22, 25) on a light 40 × 30 wall.
        let (grey, w, h) = window_on_wall(0.2, 0.8);
        // Each side 1 px off: found exactly within 0.2 of the box (2 px across, 3–4 px up
        // and down).
        let snap = |b: PixelBox, frac: f64| snap_to_edges(&grey, w, h, b, frac);
        assert_eq!(snap([11, 6, 21, 24], 0.2), [10, 5, 22, 25]);
        // 4 px off across is out of that reach: no stronger step, the side stays.
        assert_eq!(snap([14, 6, 21, 24], 0.2)[0], 14);
        // No snapping at 0.
        assert_eq!(snap([11, 6, 21, 24], 0.0), [11, 6, 21, 24]);
    }

    #[test]
    fn window_probability_is_the_soft_max() {
        let ll = LogLikelihoods {
            width: 2,
            height: 1,
            maps: [None, Some(vec![0.0, 0.0]), Some(vec![0.0, (3f32).ln()])],
        };
        let p = window_probability(&ll).unwrap();
        assert!((p[0] - 0.5).abs() < 1e-6 && (p[1] - 0.75).abs() < 1e-6);
    }
}
