//! Hatched walls made solid: an addition to §5.1.2 step (2) (small white regions filled),
//! which fills only regions under 0.05 % of the image. A wall drawn as two outlines with
//! parallel hatching between them leaves long slivers of paper between the hatch strokes,
//! often joined around a stroke's end into regions too large for step (2); step (4)'s opening
//! then removes the thin strokes and outlines and the wall is lost (Loftie's White Tower).

use image::GrayImage;
use imageproc::distance_transform::{Norm, distance_transform};
use imageproc::morphology::close;

use crate::binarize::{Connectivity, components};
use crate::strokes::{Grid, angle_between, strokes};

/// Paper slivers count as parallel when their long axes differ by at most this (radians).
const PARALLEL: f64 = 0.26;
/// A sliver is this many times longer than wide.
const ELONGATED: f64 = 3.0;
/// Slivers of a hatch pattern needed around a sliver (its own siblings, not counting itself).
const SIBLINGS: usize = 2;

/// Fills the paper between hatch strokes so a hatched wall becomes solid: a white
/// (4-connected) region is a gap of a hatch pattern when it is a thin sliver — no pixel more
/// than `max_inset` from the ink (rooms and courtyards are much wider, so they are never
/// filled), elongated, off the image border — and at least two other such slivers with the
/// same orientation lie beside it (within its length, and not end to end: offset across its
/// axis at least half the offset along it, since the outlines shift oblique slivers sideways): between parallel slivers there are parallel ink strokes, i.e. hatching. Returns
/// the pixels filled.
pub fn fill_hatching(img: &mut GrayImage, max_inset: u8) -> usize {
    let (w, h) = (img.width() as usize, img.height() as usize);
    // Engraved hatch strokes are broken every few pixels, which joins all the gaps of a
    // pattern into one region: the gaps are found with 1–2-px breaks bridged (closing with a
    // 3 × 3 square), and only their own pixels are filled (the breaks are then specks).
    let bridged = close(img, Norm::LInf, 1);
    let white = components(&bridged, 0, Connectivity::Four);
    // Distance of every paper pixel to the nearest ink: a region's inscribed radius.
    let to_ink = distance_transform(&bridged, Norm::LInf);
    let mut inset = vec![0u8; white.sizes.len()];
    for (&l, d) in white.labels.iter().zip(to_ink.pixels()) {
        inset[l as usize] = inset[l as usize].max(d[0]);
    }
    let limit = (w * h) / 100;
    let slivers = strokes(&white, w, |l| {
        let b = white.bbox[l];
        let on_border = b[0] == 0 || b[1] == 0 || b[2] as usize == w - 1 || b[3] as usize == h - 1;
        inset[l] <= max_inset && white.sizes[l] >= 3 && white.sizes[l] < limit && !on_border
    });
    let slivers: Vec<_> = slivers
        .into_iter()
        .filter(|s| s.elongation() >= ELONGATED)
        .collect();
    if slivers.is_empty() {
        return 0;
    }
    let longest = slivers.iter().map(|s| s.length).fold(0.0, f64::max);
    let grid = Grid::new(&slivers, w, h, longest);
    let mut fill = vec![false; white.sizes.len()];
    for s in &slivers {
        let siblings = grid
            .near(&slivers, s.centre, s.length)
            .into_iter()
            .filter(|&j| {
                let o = &slivers[j];
                let (along, across) = s.offset(o);
                o.label != s.label
                    && angle_between(s.angle, o.angle) <= PARALLEL
                    && 2.0 * across >= along
                    && o.length >= 0.5 * s.length
                    && o.length <= 2.0 * s.length
            })
            .count();
        if siblings >= SIBLINGS {
            fill[s.label as usize] = true;
        }
    }
    let mut filled = 0;
    for (p, &l) in img.pixels_mut().zip(&white.labels) {
        if fill[l as usize] && p[0] == 0 {
            p[0] = 255;
            filled += 1;
        }
    }
    filled
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Luma;

    /// A 120 × 60 sheet: a wall 12 px thick drawn as two 1-px outlines (rows 20 and 31)
    /// joined by 1-px diagonal hatch strokes every 6 px, and below it a 20-px room drawn with
    /// 1-px walls.
    fn hatched_wall_and_room() -> GrayImage {
        GrayImage::from_fn(120, 60, |x, y| {
            let (x, y) = (x as i32, y as i32);
            let outline = (y == 20 || y == 31) && (10..110).contains(&x);
            let ends = (x == 10 || x == 109) && (20..=31).contains(&y);
            let hatch = (21..31).contains(&y) && (10..110).contains(&x) && (x + y) % 6 == 0;
            let room = ((y == 36 || y == 56) && (30..=60).contains(&x))
                || ((x == 30 || x == 60) && (36..=56).contains(&y));
            Luma([if outline || ends || hatch || room {
                255
            } else {
                0
            }])
        })
    }

    #[test]
    fn hatching_becomes_solid_a_room_stays_open() {
        let mut img = hatched_wall_and_room();
        // Without the step the opening of §5.1.2 (4) erases the 1-px outlines and hatching.
        let opened = crate::binarize::open_close(&img);
        assert_eq!(opened.get_pixel(50, 25)[0], 0);
        assert!(fill_hatching(&mut img, 3) > 0);
        let opened = crate::binarize::open_close(&img);
        for x in 20..100 {
            assert_eq!(opened.get_pixel(x, 25)[0], 255, "wall at x = {x}");
        }
        assert_eq!(img.get_pixel(45, 46)[0], 0, "the room");
        assert_eq!(img.get_pixel(5, 5)[0], 0, "the paper around");
    }
}
