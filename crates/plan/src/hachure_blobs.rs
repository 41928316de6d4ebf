//! Blobs of merged hachures removed: dense hachures that touch each other (Langres), an
//! addition to §5.1.2 beside [`crate::hachure_bands`]. Such a band is one ink blob riddled with
//! specks of paper, which step (2) fills, so the band turns into a solid wall; the stroke test
//! never sees its strokes.

use image::{GrayImage, Rgb, RgbImage};
use imageproc::integral_image::{integral_image, sum_image_pixels};
use raster::components::{Connectivity, components};
use raster::morphology::{Norm, distance_to_background};

/// Removes ink where paper specks are dense: an ink pixel goes when, in the square of
/// half-side `window` around it, at least `min_speck_share` of the pixels are specks (enclosed
/// paper regions of at most `max_speck` pixels, which step (2) would fill) and at least
/// `min_specks` distinct specks lie there. A wall, thick or thin, borders rooms and courtyards
/// (large paper) and holds a speck only where a letter or a door leaf is drawn; a band of
/// merged hachures is all specks between strokes. Solid ink, `core` pixels or more from the
/// paper and specks, and the window around it stay: a black tower round a spiral stair
/// (Narbonne) or a densely hatched wall is not a band. Returns the pixels removed.
pub fn drop_hachure_blobs(
    img: &mut GrayImage,
    window: u32,
    core: u8,
    max_speck: usize,
    min_speck_share: f64,
    min_specks: usize,
) -> usize {
    let (w, h) = (img.width() as usize, img.height() as usize);
    if w == 0 || h == 0 {
        return 0;
    }
    let paper = components(img, 0, Connectivity::Four);
    let speck: Vec<bool> = (0..paper.sizes.len())
        .map(|l| l > 0 && paper.sizes[l] <= max_speck && !paper.touches_border(l, w, h))
        .collect();
    let to_paper = distance_to_background(img, Norm::LInf);
    // Per pixel, as the three channels of one integral image: a speck pixel, the mark of a
    // speck (its first pixel in raster order, so a window counts distinct specks), solid ink.
    let mut seen = vec![false; paper.sizes.len()];
    let marks = RgbImage::from_fn(img.width(), img.height(), |x, y| {
        let i = y as usize * w + x as usize;
        let l = paper.labels[i] as usize;
        let first = speck[l] && !std::mem::replace(&mut seen[l], true);
        Rgb([
            u8::from(speck[l]),
            u8::from(first),
            u8::from(to_paper.as_raw()[i] >= core),
        ])
    });
    let sums = integral_image::<_, u32>(&marks);
    let r = window;
    let (wu, hu) = (img.width(), img.height());
    let mut drop = Vec::new();
    for y in 0..hu {
        let (y0, y1) = (y.saturating_sub(r), (y + r).min(hu - 1));
        for x in 0..wu {
            if img.get_pixel(x, y)[0] != 255 {
                continue;
            }
            let (x0, x1) = (x.saturating_sub(r), (x + r).min(wu - 1));
            let cells = f64::from((x1 - x0 + 1) * (y1 - y0 + 1));
            let [area, count, solid] = sum_image_pixels(&sums, x0, y0, x1, y1);
            if f64::from(area) >= min_speck_share * cells
                && count as usize >= min_specks
                && solid == 0
            {
                drop.push(y as usize * w + x as usize);
            }
        }
    }
    let raw: &mut [u8] = img;
    for &i in &drop {
        raw[i] = 0;
    }
    drop.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Luma;

    /// A 200 × 120 sheet: a 3-px thin-walled room (x 20..80, y 20..80) with a 2-px partition
    /// across it, an 8-px wall (x 100..190, y 10..18), and below the wall a Langres-like band
    /// (x 100..190, y 18..70) of 2-px hachures 1 px apart that touch every 4 px down: one blob
    /// full of 1 × 3 specks of paper.
    fn room_wall_and_band() -> GrayImage {
        GrayImage::from_fn(200, 120, |x, y| {
            let room = (20..80).contains(&x)
                && (20..80).contains(&y)
                && !((23..77).contains(&x) && (23..77).contains(&y));
            let partition = (48..50).contains(&x) && (20..80).contains(&y);
            let wall = (100..190).contains(&x) && (10..18).contains(&y);
            let band =
                (100..190).contains(&x) && (18..70).contains(&y) && (x % 3 < 2 || y % 4 == 0);
            Luma([if room || partition || wall || band {
                255
            } else {
                0
            }])
        })
    }

    #[test]
    fn merged_hachures_go_walls_and_partitions_stay() {
        let mut img = room_wall_and_band();
        let before = img.clone();
        let removed = drop_hachure_blobs(&mut img, 6, 4, 25, 0.15, 4);
        assert!(removed > 0);
        let band_left = (30..60)
            .flat_map(|y| (110..180).map(move |x| (x, y)))
            .filter(|&(x, y)| img.get_pixel(x, y)[0] == 255)
            .count();
        assert_eq!(band_left, 0, "the inside of the band is gone");
        for (x, y) in [(21, 50), (50, 21), (48, 50), (78, 50), (50, 78)] {
            assert_eq!(
                img.get_pixel(x, y)[0],
                255,
                "room wall or partition at {x},{y}"
            );
        }
        assert_eq!(img.get_pixel(140, 12)[0], 255, "the thick wall");
        // Nothing outside the band changed.
        for (p, q) in img.enumerate_pixels().zip(before.enumerate_pixels()) {
            if p.2 != q.2 {
                assert!(
                    (100..190).contains(&p.0) && (13..70).contains(&p.1),
                    "{p:?}"
                );
            }
        }
    }

    #[test]
    fn a_solid_tower_round_a_stair_stays() {
        // Narbonne: a 60 × 60 black tower with a 24 × 24 stair of thin steps in it.
        let stair = |x: u32, y: u32| (28..52).contains(&x) && (28..52).contains(&y);
        let mut img = GrayImage::from_fn(80, 80, |x, y| {
            let tower = (10..70).contains(&x) && (10..70).contains(&y);
            Luma([if tower && !(stair(x, y) && x % 2 == 1 && y % 4 != 0) {
                255
            } else {
                0
            }])
        });
        drop_hachure_blobs(&mut img, 6, 4, 25, 0.15, 4);
        for (x, y, p) in img.enumerate_pixels() {
            let tower = (10..70).contains(&x) && (10..70).contains(&y);
            if tower && !stair(x, y) {
                assert_eq!(p[0], 255, "tower wall at {x},{y}");
            }
        }
    }

    #[test]
    fn loose_specks_are_no_band() {
        // A solid block with four letter-sized holes far apart stays whole.
        let mut img = GrayImage::from_fn(120, 60, |x, y| {
            let hole = (y == 30 || y == 31) && [15, 45, 75, 105].contains(&x);
            Luma(
                [if (5..115).contains(&x) && (10..50).contains(&y) && !hole {
                    255
                } else {
                    0
                }],
            )
        });
        assert_eq!(drop_hachure_blobs(&mut img, 6, 4, 25, 0.15, 4), 0);
    }
}
