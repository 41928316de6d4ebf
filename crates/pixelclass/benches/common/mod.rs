//! The synthetic 1-Mpx façade the benches and the megapixel example share.

use image::{Rgb, RgbImage};
use pixelclass::Sample;

/// A 1000 x 1000 wall of noisy bricks with a grid of dark windows under a sky band, and 3
/// boxes of 9 x 9 labelled pixels per class (sky 0, wall 1, window 2).
pub fn scene() -> (RgbImage, Vec<Sample>) {
    let n = 1000u32;
    let img = RgbImage::from_fn(n, n, |x, y| {
        let noise = ((x.wrapping_mul(7919) ^ y.wrapping_mul(104_729)) % 23) as u8;
        if y < 150 {
            Rgb([140 + noise, 180 + noise, 225])
        } else if is_window(x, y) {
            Rgb([35 + noise, 45 + noise, 60 + noise])
        } else {
            let mortar = if y % 12 == 0 || (x + 20 * (y / 12 % 2)) % 40 == 0 {
                40
            } else {
                0
            };
            Rgb([170 + noise + mortar, 95 + noise + mortar, 70 + mortar])
        }
    });
    let mut s = Vec::new();
    let boxes = [
        (100, 50, 0),
        (500, 80, 0),
        (900, 30, 0),
        (10, 300, 1),
        (450, 460, 1),
        (700, 900, 1),
        (150, 200, 2),
        (520, 520, 2),
        (880, 840, 2),
    ];
    for (x0, y0, c) in boxes {
        for y in y0..y0 + 9 {
            for x in x0..x0 + 9 {
                s.push(Sample { x, y, class: c });
            }
        }
    }
    (img, s)
}

/// The scene's true class at (x, y).
#[allow(dead_code)]
pub fn truth(x: u32, y: u32) -> usize {
    if y < 150 {
        0
    } else if is_window(x, y) {
        2
    } else {
        1
    }
}

fn is_window(x: u32, y: u32) -> bool {
    (x % 120) >= 30 && (x % 120) < 90 && (y % 160) >= 40 && (y % 160) < 130
}
