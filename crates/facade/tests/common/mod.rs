//! Synthetic façades with known answers, shared by the integration tests.
#![allow(dead_code)]

use image::{Rgb, RgbImage};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A façade layout: sky above, wall rectangle, a grid of windows, light noise.
pub struct Synth {
    pub img: RgbImage,
    /// Façade rectangle [x0, y0, x1, y1] (inclusive-exclusive).
    pub facade: [u32; 4],
    /// Window rectangles.
    pub windows: Vec<[u32; 4]>,
}

pub fn facade(w: u32, h: u32, floors: u32, cols: u32, seed: u64) -> Synth {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let facade = [w / 10, h / 5, w - w / 10, h - h / 20];
    let mut img = RgbImage::new(w, h);
    let fw = facade[2] - facade[0];
    let fh = facade[3] - facade[1];
    let fl_h = fh / floors;
    let pitch = fw / cols;
    let mut windows = Vec::new();
    for f in 0..floors {
        for c in 0..cols {
            let x0 = facade[0] + c * pitch + pitch / 4;
            let x1 = x0 + pitch / 2;
            let y0 = facade[1] + f * fl_h + fl_h / 4;
            let y1 = y0 + fl_h / 2;
            windows.push([x0, y0, x1, y1]);
        }
    }
    for (x, y, p) in img.enumerate_pixels_mut() {
        let inside = |r: &[u32; 4]| x >= r[0] && x < r[2] && y >= r[1] && y < r[3];
        let base: [f64; 3] = if windows.iter().any(inside) {
            [40.0, 50.0, 70.0]
        } else if inside(&facade) {
            // Brick-like texture: horizontal courses.
            let course = if (y / 4) % 2 == 0 { 0.0 } else { 12.0 };
            [170.0 + course, 120.0 + course, 90.0]
        } else if y < facade[1] {
            [150.0, 190.0, 235.0]
        } else {
            [90.0, 110.0, 80.0]
        };
        let n: f64 = rng.random_range(-8.0..8.0);
        *p = Rgb(base.map(|b| (b + n).clamp(0.0, 255.0) as u8));
    }
    Synth {
        img,
        facade,
        windows,
    }
}
