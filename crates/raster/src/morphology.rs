//! Binary morphology on masks (foreground 255, background 0), for the plan parser's
//! pre-processing and clean-up steps (§5.1.2) and its wall and room distances (§5.1.6).
//!
//! Erosion, dilation, opening, closing and distance transforms: call imageproc's
//! (`imageproc::morphology`, `imageproc::distance_transform`), which the stages were measured
//! with; no copy of them is kept here. This module holds only the compositions the stages
//! wrote more than once: [`open_close`], the binary white [`top_hat`] (what an opening
//! removes), [`complement`] and [`distance_to_background`].

pub use imageproc::distance_transform::Norm;
use imageproc::distance_transform::distance_transform;
use imageproc::morphology::{close, open};

use image::{GrayImage, Luma};

/// Opening then closing with the ball of `radius` under `norm` (a (2r + 1)² square for
/// `Norm::LInf`): foreground thinner than 2r + 1 pixels goes, then background gaps as thin
/// are filled.
pub fn open_close(img: &GrayImage, norm: Norm, radius: u8) -> GrayImage {
    close(&open(img, norm, radius), norm, radius)
}

/// The opening of `img` with the ball of `radius` under `norm`, and its binary white top-hat:
/// 255 where `img` is 255 and the opening is 0 (the thin lines and shaved corners the opening
/// removed), 0 elsewhere.
pub fn top_hat(img: &GrayImage, norm: Norm, radius: u8) -> (GrayImage, GrayImage) {
    let opened = open(img, norm, radius);
    let (w, raw, kept) = (img.width() as usize, img.as_raw(), opened.as_raw());
    let removed = GrayImage::from_fn(img.width(), img.height(), |x, y| {
        let i = y as usize * w + x as usize;
        Luma([if raw[i] == 255 && kept[i] == 0 {
            255
        } else {
            0
        }])
    });
    (opened, removed)
}

/// 255 − p for every pixel: foreground and background swapped.
pub fn complement(img: &GrayImage) -> GrayImage {
    GrayImage::from_fn(img.width(), img.height(), |x, y| {
        Luma([255 - img.get_pixel(x, y)[0]])
    })
}

/// Distance under `norm` from each pixel to the nearest background (0) pixel; 0 on the
/// background, saturating at 255 (imageproc's distance transform of the [`complement`]).
pub fn distance_to_background(img: &GrayImage, norm: Norm) -> GrayImage {
    distance_transform(&complement(img), norm)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::literal::{mask, rows};

    /// A 3-px bar with a 1-px line off its end and a 1-px gap in the bar, 2 px from the
    /// border (imageproc's closing counts the outside of the image as foreground).
    fn bar_and_line() -> GrayImage {
        mask(&[
            "............",
            "............",
            "..####.###..",
            "..####.###..",
            "..####.###..",
            "......#.....",
            "......#.....",
            "............",
            "............",
        ])
    }

    #[test]
    fn open_close_drops_the_thin_line_and_fills_the_gap() {
        let blank = "............";
        let bar = "..########..";
        assert_eq!(
            rows(&open_close(&bar_and_line(), Norm::LInf, 1)),
            [blank, blank, bar, bar, bar, blank, blank, blank, blank]
        );
    }

    #[test]
    fn the_top_hat_is_what_the_opening_removed() {
        let (opened, removed) = top_hat(&bar_and_line(), Norm::LInf, 1);
        assert_eq!(opened.get_pixel(2, 2)[0], 255);
        assert_eq!(opened.get_pixel(6, 3)[0], 0, "the gap stays open");
        let blank = "............";
        let line = "......#.....";
        assert_eq!(
            rows(&removed),
            [blank, blank, blank, blank, blank, line, line, blank, blank]
        );
    }

    #[test]
    fn distance_to_the_background_inside_a_bar() {
        let img = mask(&[".......", ".#####.", ".#####.", ".#####.", "......."]);
        assert_eq!(complement(&img).get_pixel(0, 0)[0], 255);
        let d = distance_to_background(&img, Norm::LInf);
        let row: Vec<u8> = (0..7).map(|x| d.get_pixel(x, 2)[0]).collect();
        assert_eq!(row, [0, 1, 2, 2, 2, 1, 0]);
    }
}
