//! Rooms §5.1.5 cannot fit as a circle or a rectangle (an L-shaped range, a chapel with its
//! apse, a trapezoid between two curtains) built all the same (issue 25): the room's open
//! pixels, turned to the sides of their least bounding rectangle, are cut in strips across
//! its longer side, each strip's pixels
//! grouped into intervals along it, and neighbouring strips with the same interval merged — a
//! few rectangles that cover the room as drawn.

use crate::estimate::{Block, Footprint};

/// Strips are this many pixels wide at least …
const MIN_STRIP: f64 = 2.0;
/// … and a room is cut into at most this many.
const MAX_STRIPS: f64 = 24.0;
/// Two pixels of a strip further apart than this along it belong to two intervals (a room
/// bent round a corner crosses a strip twice).
const GAP: f64 = 1.5;
/// Neighbouring strips' intervals closer than this at both ends are one block.
const MERGE: f64 = 1.5;

/// [`cover`] as a footprint in model units, `s` per plan pixel.
pub(super) fn footprint(runs: &[[u32; 3]], strip: f64, s: f64) -> Option<Footprint> {
    let (rotation, blocks) = cover(runs, strip)?;
    let blocks = blocks
        .into_iter()
        .map(|b| Block {
            center: [b.center[0] * s, b.center[1] * s],
            size: [b.size[0] * s, b.size[1] * s],
        })
        .collect();
    Some(Footprint::Blocks { rotation, blocks })
}

/// Rectangles covering the pixels of `runs` (`[y, x0, x1]`), plan pixels, in the frame turned
/// by the returned angle (the longer side of their least bounding rectangle, from the x axis,
/// y down); `strip` is the wished
/// strip width (the room's wall thickness, so the steps of a slanted side stay within a wall).
pub(super) fn cover(runs: &[[u32; 3]], strip: f64) -> Option<(f64, Vec<Block>)> {
    let pixels: Vec<[f64; 2]> = runs
        .iter()
        .flat_map(|&[y, x0, x1]| (x0..=x1).map(move |x| [f64::from(x), f64::from(y)]))
        .collect();
    if pixels.len() < 4 {
        return None;
    }
    let n = pixels.len() as f64;
    let mean = pixels
        .iter()
        .fold([0.0, 0.0], |m, p| [m[0] + p[0] / n, m[1] + p[1] / n]);
    // The orientation of the least bounding rectangle of the runs' ends (the room's outline):
    // an L-shaped room lies along its sides, where its principal axis would cut it diagonally.
    let ends: Vec<[f64; 2]> = runs
        .iter()
        .flat_map(|&[y, x0, x1]| [[f64::from(x0), f64::from(y)], [f64::from(x1), f64::from(y)]])
        .collect();
    let Some(plan::fit::Fit::Rectangle {
        size, angle: turn, ..
    }) = plan::fit::fit_rectangle(&ends)
    else {
        return None;
    };
    // Strips go across the longer side.
    let angle = if size[0] >= size[1] {
        turn
    } else {
        turn + std::f64::consts::FRAC_PI_2
    };
    let (c, s) = (angle.cos(), angle.sin());
    // (u, v): along the principal axis, then across it.
    let uv: Vec<[f64; 2]> = pixels
        .iter()
        .map(|p| {
            let (dx, dy) = (p[0] - mean[0], p[1] - mean[1]);
            [dx * c + dy * s, -dx * s + dy * c]
        })
        .collect();
    let (u_lo, u_hi) = uv
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), q| (a.min(q[0]), b.max(q[0])));
    let width = strip.max(MIN_STRIP).max((u_hi - u_lo + 1.0) / MAX_STRIPS);
    let count = ((u_hi - u_lo + 1.0) / width).ceil().max(1.0) as usize;
    let mut strips: Vec<Vec<[f64; 2]>> = vec![Vec::new(); count];
    for q in &uv {
        let k = (((q[0] - u_lo + 0.5) / width) as usize).min(count - 1);
        strips[k].push([q[1], q[0]]);
    }
    // Each strip's intervals across it, a pixel wide at each end.
    let mut open: Vec<([f64; 2], [f64; 2])> = Vec::new(); // (u range, v range)
    let mut done: Vec<([f64; 2], [f64; 2])> = Vec::new();
    for mut vs in strips {
        // (v, u) pairs, by v: each interval across the strip with the extent of its pixels
        // along it (a pixel is a unit square about its centre).
        vs.sort_by(|a, b| a[0].total_cmp(&b[0]));
        let mut intervals: Vec<([f64; 2], [f64; 2])> = Vec::new(); // (v range, u range)
        for [v, u] in vs {
            match intervals.last_mut() {
                Some((iv, iu)) if v - iv[1] <= GAP => {
                    iv[1] = v;
                    *iu = [iu[0].min(u), iu[1].max(u)];
                }
                _ => intervals.push(([v, v], [u, u])),
            }
        }
        let mut next = Vec::new();
        for (iv, iu) in intervals {
            let iv = [iv[0] - 0.5, iv[1] + 0.5];
            let u = [iu[0] - 0.5, iu[1] + 0.5];
            let same = open
                .iter()
                .position(|(_, o)| (o[0] - iv[0]).abs() <= MERGE && (o[1] - iv[1]).abs() <= MERGE);
            match same {
                Some(i) => {
                    let (ou, ov) = open.swap_remove(i);
                    next.push((
                        [ou[0].min(u[0]), ou[1].max(u[1])],
                        [ov[0].min(iv[0]), ov[1].max(iv[1])],
                    ));
                }
                None => next.push((u, iv)),
            }
        }
        done.append(&mut open);
        open = next;
    }
    done.append(&mut open);
    let blocks = done
        .into_iter()
        .map(|(u, v)| {
            let (cu, cv) = ((u[0] + u[1]) / 2.0, (v[0] + v[1]) / 2.0);
            Block {
                center: [mean[0] + cu * c - cv * s, mean[1] + cu * s + cv * c],
                size: [u[1] - u[0], v[1] - v[0]],
            }
        })
        .collect();
    Some((angle, blocks))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(blocks: &[Block]) -> f64 {
        blocks.iter().map(|b| b.size[0] * b.size[1]).sum()
    }

    #[test]
    fn a_rectangle_is_one_block_of_its_size() {
        // 40 × 10 pixels at x 10..=49, y 5..=14.
        let runs: Vec<[u32; 3]> = (5..15).map(|y| [y, 10, 49]).collect();
        let (angle, blocks) = cover(&runs, 3.0).unwrap();
        assert!(angle.abs() < 1e-9);
        assert_eq!(blocks.len(), 1, "{blocks:?}");
        assert!((area(&blocks) - 400.0).abs() < 1e-6, "{blocks:?}");
        let b = &blocks[0];
        assert!((b.center[0] - 29.5).abs() < 1e-9 && (b.center[1] - 9.5).abs() < 1e-9);
    }

    #[test]
    fn an_l_shaped_room_is_a_few_blocks_covering_its_pixels_within_a_strip() {
        // A 60 × 10 bar and a 10 × 30 leg under its left end: 900 pixels.
        let mut runs: Vec<[u32; 3]> = (0..10).map(|y| [y, 0, 59]).collect();
        runs.extend((10..40).map(|y| [y, 0, 9]));
        let (angle, blocks) = cover(&runs, 4.0).unwrap();
        // Along the bar (the outline's longer side), not diagonally.
        assert!(angle.abs() < 1e-9, "{angle}");
        assert!(blocks.len() <= 3, "{blocks:?}");
        // Every pixel covered; the strip (4 px) where the leg meets the bar reaches 2 px past
        // the leg down its 30 rows.
        let covered = |x: f64, y: f64| {
            blocks.iter().any(|b| {
                (x - b.center[0]).abs() <= b.size[0] / 2.0
                    && (y - b.center[1]).abs() <= b.size[1] / 2.0
            })
        };
        assert!(
            runs.iter()
                .all(|&[y, x0, x1]| (x0..=x1).all(|x| covered(f64::from(x), f64::from(y))))
        );
        assert!(
            (area(&blocks) - 900.0).abs() <= 60.0 + 1e-9,
            "{} px",
            area(&blocks)
        );
    }
}
