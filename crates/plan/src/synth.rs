//! Synthetic castle plan drawings for tests, benchmarks and examples: a curtain-wall polygon
//! with round and square towers, a great hall, a chapel and rooms, over grid lines, letters
//! and specks, with the true label at known points. Seeded: same seed, same drawing.

use image::{GrayImage, Luma};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::label::Label;

/// True labels at known points of a drawing.
pub type Truth = Vec<((u32, u32), Label)>;

pub const INK: Luma<u8> = Luma([20]);

/// A sheet of paper to draw walls on.
pub struct Canvas(pub GrayImage);

impl Canvas {
    pub fn new(w: u32, h: u32) -> Canvas {
        Canvas(GrayImage::from_pixel(w, h, Luma([245])))
    }
    pub fn put(&mut self, x: i64, y: i64, v: Luma<u8>) {
        if x >= 0 && y >= 0 && x < self.0.width() as i64 && y < self.0.height() as i64 {
            self.0.put_pixel(x as u32, y as u32, v);
        }
    }
    /// A wall of thickness `t` from a to b.
    pub fn wall(&mut self, a: (f64, f64), b: (f64, f64), t: f64) {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = dx.hypot(dy);
        let r = t / 2.0;
        let (x0, x1) = (a.0.min(b.0) - r - 1.0, a.0.max(b.0) + r + 1.0);
        let (y0, y1) = (a.1.min(b.1) - r - 1.0, a.1.max(b.1) + r + 1.0);
        for y in y0 as i64..=y1 as i64 {
            for x in x0 as i64..=x1 as i64 {
                let (px, py) = (x as f64 - a.0, y as f64 - a.1);
                let s = ((px * dx + py * dy) / (len * len)).clamp(0.0, 1.0);
                if (px - s * dx).hypot(py - s * dy) <= r {
                    self.put(x, y, INK);
                }
            }
        }
    }
    /// A closed polygon of walls.
    pub fn poly(&mut self, pts: &[(f64, f64)], t: f64) {
        for k in 0..pts.len() {
            self.wall(pts[k], pts[(k + 1) % pts.len()], t);
        }
    }
    /// A round tower: a ring of outer radius `r` and wall `t`, its inside cleared first.
    pub fn round_tower(&mut self, c: (f64, f64), r: f64, t: f64) {
        for y in (c.1 - r - 1.0) as i64..=(c.1 + r + 1.0) as i64 {
            for x in (c.0 - r - 1.0) as i64..=(c.0 + r + 1.0) as i64 {
                let d = (x as f64 - c.0).hypot(y as f64 - c.1);
                if d <= r - t {
                    self.put(x, y, Luma([245]));
                } else if d <= r {
                    self.put(x, y, INK);
                }
            }
        }
    }
    /// Vault ribs across a round room of radius `r` centred at c: `n` diameters of width `t`
    /// (as the Dictionnaire draws tower vaults, e.g. Coucy and Villandraut).
    pub fn ribs(&mut self, c: (f64, f64), r: f64, n: usize, t: f64) {
        for k in 0..n {
            let a = std::f64::consts::PI * k as f64 / n as f64;
            let (dx, dy) = (r * a.cos(), r * a.sin());
            self.wall((c.0 - dx, c.1 - dy), (c.0 + dx, c.1 + dy), t);
        }
    }
    /// A square tower centred at c with half side `h`, inside cleared.
    pub fn square_tower(&mut self, c: (f64, f64), h: f64, t: f64) {
        for y in (c.1 - h) as i64..=(c.1 + h) as i64 {
            for x in (c.0 - h) as i64..=(c.0 + h) as i64 {
                let inner = (x as f64 - c.0).abs() < h - t && (y as f64 - c.1).abs() < h - t;
                self.put(x, y, if inner { Luma([245]) } else { INK });
            }
        }
    }
    pub fn blob(&mut self, x: i64, y: i64, w: i64, h: i64) {
        for yy in y..y + h {
            for xx in x..x + w {
                self.put(xx, yy, INK);
            }
        }
    }
}

/// A castle drawn at `scale` times its 900 × 700 design on a `width` × `height` sheet: an
/// irregular hexagonal curtain wall (10 px), round towers at four corners and square towers at
/// two, a great hall, a chapel and three small rooms along the south wall; 1-px grid lines
/// every 100 px, letter-sized blobs and 400 specks over it all. Returns the drawing and the
/// true label at known points.
pub fn castle(seed: u64, scale: f64, width: u32, height: u32) -> (GrayImage, Truth) {
    let mut c = Canvas::new(width, height);
    let s = scale;
    let p = |x: f64, y: f64| (x * s, y * s);
    let hex = [
        p(200.0, 150.0),
        p(600.0, 130.0),
        p(720.0, 350.0),
        p(620.0, 560.0),
        p(230.0, 570.0),
        p(140.0, 360.0),
    ];
    c.poly(&hex, 10.0 * s);
    // Inner buildings against the south wall: great hall, three rooms, chapel.
    c.wall(p(168.0, 440.0), p(684.0, 440.0), 8.0 * s);
    for x in [420.0, 470.0, 520.0, 570.0] {
        c.wall(p(x, 440.0), p(x, 562.0), 8.0 * s);
    }
    for q in [hex[0], hex[1], hex[3], hex[4]] {
        c.round_tower(q, 34.0 * s, 9.0 * s);
    }
    for q in [hex[2], hex[5]] {
        c.square_tower(q, 30.0 * s, 9.0 * s);
    }
    // Grid lines (1 px) across the sheet, letter-sized blobs inside rooms, specks everywhere.
    let (w, h) = (i64::from(width), i64::from(height));
    for x in (50..w).step_by(100) {
        for y in 0..h {
            c.put(x, y, INK);
        }
    }
    for y in (40..h).step_by(100) {
        for x in 0..w {
            c.put(x, y, INK);
        }
    }
    for (x, y) in [
        (300.0, 300.0),
        (330.0, 300.0),
        (500.0, 250.0),
        (320.0, 500.0),
        (640.0, 250.0),
    ] {
        let (x, y) = p(x, y);
        c.blob(x as i64, y as i64, 7, 11);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for _ in 0..400 {
        let (x, y) = (rng.random_range(0..w), rng.random_range(0..h));
        c.blob(x, y, 2, 2);
    }
    let at = |x: f64, y: f64| ((x * s).round() as u32, (y * s).round() as u32);
    let truth = vec![
        ((30, 30), Label::CastleSurroundings),
        ((width - 20, height - 20), Label::CastleSurroundings),
        (at(400.0, 300.0), Label::Courtyard),
        (at(600.0, 250.0), Label::Courtyard),
        (at(320.0, 520.0), Label::GreatHall),
        (at(250.0, 500.0), Label::GreatHall),
        (at(200.0, 150.0), Label::TowerRoom),
        (at(600.0, 130.0), Label::TowerRoom),
        (at(720.0, 350.0), Label::TowerRoom),
        (at(140.0, 360.0), Label::TowerRoom),
        (at(620.0, 560.0), Label::TowerRoom),
        (at(230.0, 570.0), Label::TowerRoom),
        (at(400.0, 143.0), Label::CastleOuterWall),
        (at(200.0, 120.0), Label::TowerWall),
        (at(114.0, 360.0), Label::TowerWall),
        (at(350.0, 440.0), Label::GreatHallWall),
        (at(620.0, 490.0), Label::Chapel),
        (at(445.0, 500.0), Label::UnknownRoom),
    ];
    (c.0, truth)
}
