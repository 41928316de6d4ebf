//! Hachured slopes and moats removed: an addition to §5.1.2, which leaves them to the user's
//! clean-up (§5.1.1). Bands of short parallel or radial strokes drawn outside the enceinte
//! (Langres, Château-Gaillard, Clitheroe, Sully) survive step (4) as walls or are welded to
//! the castle by the gap closing; removing every thin line takes the thin walls of the 4-bit
//! scans with them (docs/plan.md: 120 → 110 points), so only strokes in a hachure band go.

use image::GrayImage;
use imageproc::distance_transform::{Norm, distance_transform};
use raster::components::{Connectivity, components};
use raster::morphology::top_hat;

use crate::strokes::{Grid, Stroke, angle_between, strokes};

/// Strokes of one band differ in direction by at most this (radians): radial hachures turn
/// slowly from one stroke to the next.
const PARALLEL: f64 = 0.35;
/// A hachure stroke is this many times longer than wide.
const ELONGATED: f64 = 2.5;
/// Similar strokes beside a stroke that make it part of a band.
const BAND: usize = 3;

/// Removes hachures: the thin ink (what an opening with a square of half-side `radius`
/// removes) falls into strokes; a stroke is a hachure when it is short (at most `max_length`),
/// elongated, free at one end at least (a partition wall or the rung of a ladder-like
/// gallery touches thicker ink at both ends), and has three or more strokes beside it of
/// similar length (half to twice) and direction, offset across their axis more than along
/// it, within 1.5 lengths: many short thin strokes, locally parallel, side by side. A long
/// thin wall is one long stroke and stays. Returns the pixels removed.
pub fn drop_hachures(img: &mut GrayImage, radius: u8, max_length: f64) -> usize {
    if radius == 0 {
        return 0;
    }
    let (w, h) = (img.width() as usize, img.height() as usize);
    let (kept, thin) = top_hat(img, Norm::LInf, radius);
    let c = components(&thin, 255, Connectivity::Eight);
    let candidates: Vec<Stroke> = strokes(&c, w, |l| c.sizes[l] >= 3)
        .into_iter()
        .filter(|s| s.elongation() >= ELONGATED && s.length <= max_length)
        .collect();
    // Where each candidate touches the ink the opening keeps, along its own axis.
    let near_kept = distance_transform(&kept, Norm::LInf);
    let index: std::collections::HashMap<u32, usize> = candidates
        .iter()
        .enumerate()
        .map(|(i, s)| (s.label, i))
        .collect();
    let mut contact = vec![[f64::INFINITY, f64::NEG_INFINITY]; candidates.len()];
    for (i, (&l, d)) in c.labels.iter().zip(near_kept.pixels()).enumerate() {
        if l == 0 || d[0] > 1 {
            continue;
        }
        let Some(&k) = index.get(&l) else { continue };
        let s = &candidates[k];
        let a = s.axis();
        let t = ((i % w) as f64 - s.centre[0]) * a[0] + ((i / w) as f64 - s.centre[1]) * a[1];
        contact[k] = [contact[k][0].min(t), contact[k][1].max(t)];
    }
    let free: Vec<bool> = candidates
        .iter()
        .zip(&contact)
        .map(|(s, c)| !(c[0] <= -0.3 * s.length && c[1] >= 0.3 * s.length))
        .collect();
    let grid = Grid::new(&candidates, w, h, 1.5 * max_length);
    let mut drop = vec![false; c.sizes.len()];
    for (k, s) in candidates.iter().enumerate() {
        if !free[k] {
            continue;
        }
        let beside = grid
            .near(&candidates, s.centre, 1.5 * s.length)
            .into_iter()
            .filter(|&j| {
                let o = &candidates[j];
                let (along, across) = s.offset(o);
                j != k
                    && angle_between(s.angle, o.angle) <= PARALLEL
                    && across > along
                    && o.length >= 0.5 * s.length
                    && o.length <= 2.0 * s.length
            })
            .count();
        drop[s.label as usize] = beside >= BAND;
    }
    let mut removed = 0;
    for (p, &l) in img.pixels_mut().zip(&c.labels) {
        if drop[l as usize] {
            p[0] = 0;
            removed += 1;
        }
    }
    removed
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Luma;
    use raster::morphology::open_close;

    /// A 160 × 100 sheet: an 8-px wall along row 50..58 (x 20..140) with a band of 2-px
    /// hachures 12 px long every 5 px below it (hanging from the wall, free at the bottom),
    /// a 2-px thin wall 100 px long above it, and a 2-px partition joining two 8-px walls.
    fn slope_and_walls() -> GrayImage {
        GrayImage::from_fn(160, 100, |x, y| {
            let wall = (50..58).contains(&y) && (20..140).contains(&x);
            let hachure = (58..70).contains(&y) && (25..135).contains(&x) && x % 5 < 2;
            let thin_wall = (20..22).contains(&y) && (30..130).contains(&x);
            let posts = (2..10).contains(&y) && ((30..38).contains(&x) || (60..68).contains(&x));
            let partition = (5..7).contains(&y) && (38..60).contains(&x);
            Luma([if wall || hachure || thin_wall || posts || partition {
                255
            } else {
                0
            }])
        })
    }

    #[test]
    fn hachures_go_thin_walls_and_partitions_stay() {
        let mut img = slope_and_walls();
        let removed = drop_hachures(&mut img, 1, 30.0);
        assert!(removed >= 20 * 2 * 12, "{removed}");
        assert_eq!(img.get_pixel(50, 64)[0], 0, "a hachure");
        assert_eq!(img.get_pixel(100, 64)[0], 0, "a hachure");
        assert_eq!(img.get_pixel(80, 54)[0], 255, "the wall");
        assert_eq!(img.get_pixel(80, 20)[0], 255, "the thin wall");
        assert_eq!(img.get_pixel(50, 5)[0], 255, "the partition");
    }

    #[test]
    fn without_the_step_the_hachures_survive_the_opening() {
        // 3-px strokes (the enlarged 4-bit scans draw hachures 2–4 px wide) survive §5.1.2's
        // 3 × 3 opening, so without the step the band would become a wall.
        let img = GrayImage::from_fn(60, 40, |x, y| {
            Luma([
                if (10..25).contains(&y) && (6..54).contains(&x) && x % 6 < 3 {
                    255
                } else {
                    0
                },
            ])
        });
        let opened = open_close(&img, Norm::LInf, 1);
        assert_eq!(opened.get_pixel(13, 15)[0], 255);
        let mut dropped = img.clone();
        assert!(drop_hachures(&mut dropped, 2, 30.0) > 0);
        assert_eq!(open_close(&dropped, Norm::LInf, 1).get_pixel(13, 15)[0], 0);
    }
}
