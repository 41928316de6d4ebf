//! Pixel-literal masks for the unit tests: rows of `#` (255) and `.` (0), as imageproc's tests
//! write their images.

use image::{GrayImage, Luma};

/// A mask from rows of `#` and `.`.
pub fn mask(rows: &[&str]) -> GrayImage {
    GrayImage::from_fn(rows[0].len() as u32, rows.len() as u32, |x, y| {
        Luma([if rows[y as usize].as_bytes()[x as usize] == b'#' {
            255
        } else {
            0
        }])
    })
}

/// A mask's rows of `#` (255) and `.` (anything else).
pub fn rows(img: &GrayImage) -> Vec<String> {
    (0..img.height())
        .map(|y| {
            (0..img.width())
                .map(|x| {
                    if img.get_pixel(x, y)[0] == 255 {
                        '#'
                    } else {
                        '.'
                    }
                })
                .collect()
        })
        .collect()
}
