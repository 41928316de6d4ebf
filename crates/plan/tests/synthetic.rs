//! Plans drawn in the test: a curtain-wall polygon with round and square towers, a great hall,
//! a chapel and rooms, plus grid lines, text-like blobs and specks. Checks tower counts and
//! labels at known points.

use image::{DynamicImage, GrayImage, Luma};
use plan::label::Label;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

const INK: Luma<u8> = Luma([20]);

struct Canvas(GrayImage);

impl Canvas {
    fn new(w: u32, h: u32) -> Canvas {
        Canvas(GrayImage::from_pixel(w, h, Luma([245])))
    }
    fn put(&mut self, x: i64, y: i64, v: Luma<u8>) {
        if x >= 0 && y >= 0 && x < self.0.width() as i64 && y < self.0.height() as i64 {
            self.0.put_pixel(x as u32, y as u32, v);
        }
    }
    /// A wall of thickness `t` from a to b.
    fn wall(&mut self, a: (f64, f64), b: (f64, f64), t: f64) {
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
    fn poly(&mut self, pts: &[(f64, f64)], t: f64) {
        for k in 0..pts.len() {
            self.wall(pts[k], pts[(k + 1) % pts.len()], t);
        }
    }
    /// A round tower: a ring of outer radius `r` and wall `t`, its inside cleared first.
    fn round_tower(&mut self, c: (f64, f64), r: f64, t: f64) {
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
    /// A square tower centred at c with half side `h`, inside cleared.
    fn square_tower(&mut self, c: (f64, f64), h: f64, t: f64) {
        for y in (c.1 - h) as i64..=(c.1 + h) as i64 {
            for x in (c.0 - h) as i64..=(c.0 + h) as i64 {
                let inner = (x as f64 - c.0).abs() < h - t && (y as f64 - c.1).abs() < h - t;
                self.put(x, y, if inner { Luma([245]) } else { INK });
            }
        }
    }
    fn blob(&mut self, x: i64, y: i64, w: i64, h: i64) {
        for yy in y..y + h {
            for xx in x..x + w {
                self.put(xx, yy, INK);
            }
        }
    }
}

/// A castle: an irregular hexagonal curtain wall, round towers at four corners and square
/// towers at two, a great hall, a chapel and three small rooms along the walls; grid lines,
/// letters and specks over it all.
fn castle(seed: u64) -> (GrayImage, Vec<((u32, u32), Label)>) {
    let mut c = Canvas::new(900, 700);
    let t = 10.0;
    let hex = [
        (200.0, 150.0),
        (600.0, 130.0),
        (720.0, 350.0),
        (620.0, 560.0),
        (230.0, 570.0),
        (140.0, 360.0),
    ];
    c.poly(&hex, t);
    // Inner buildings against the south wall: great hall, chapel, three rooms.
    c.wall((168.0, 440.0), (684.0, 440.0), 8.0);
    c.wall((420.0, 440.0), (420.0, 562.0), 8.0);
    c.wall((520.0, 440.0), (520.0, 562.0), 8.0);
    c.wall((570.0, 440.0), (570.0, 562.0), 8.0);
    c.wall((470.0, 440.0), (470.0, 562.0), 8.0);
    let rounds = [hex[0], hex[1], hex[3], hex[4]];
    for p in rounds {
        c.round_tower(p, 34.0, 9.0);
    }
    for p in [hex[2], hex[5]] {
        c.square_tower(p, 30.0, 9.0);
    }
    // Grid lines (1 px) across the sheet, text-like blobs inside rooms, specks everywhere.
    for k in 0..9 {
        let x = 50 + 100 * k;
        for y in 0..700 {
            c.put(x, y, INK);
        }
    }
    for k in 0..7 {
        let y = 40 + 100 * k;
        for x in 0..900 {
            c.put(x, y, INK);
        }
    }
    for (x, y) in [(300, 300), (330, 300), (500, 250), (320, 500), (640, 250)] {
        c.blob(x, y, 7, 11);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for _ in 0..400 {
        let (x, y) = (rng.random_range(0..900), rng.random_range(0..700));
        c.blob(x, y, 2, 2);
    }
    let truth = vec![
        ((30, 30), Label::CastleSurroundings),
        ((880, 680), Label::CastleSurroundings),
        ((400, 300), Label::Courtyard),
        ((600, 250), Label::Courtyard),
        ((320, 520), Label::GreatHall),
        ((250, 500), Label::GreatHall),
        ((200, 150), Label::TowerRoom),
        ((600, 130), Label::TowerRoom),
        ((720, 350), Label::TowerRoom),
        ((140, 360), Label::TowerRoom),
        ((620, 560), Label::TowerRoom),
        ((230, 570), Label::TowerRoom),
        ((400, 143), Label::CastleOuterWall),
        ((200, 120), Label::TowerWall),
        ((114, 360), Label::TowerWall),
        ((350, 440), Label::GreatHallWall),
        ((620, 490), Label::Chapel),
        ((445, 500), Label::UnknownRoom),
    ];
    (c.0, truth)
}

fn parse(img: GrayImage) -> plan::ParsedPlan {
    plan::parse(&DynamicImage::ImageLuma8(img), &plan::Options::default()).unwrap()
}

#[test]
fn castle_towers_and_labels_at_known_points() {
    let (img, truth) = castle(7);
    let p = parse(img);
    assert_eq!(p.towers, 6, "towers; warnings {:?}", p.warnings);
    let towers = p.faces.iter().filter(|f| f.label == Label::TowerRoom).count();
    assert_eq!(towers, 6);
    let wrong: Vec<_> = truth
        .iter()
        .filter(|(xy, l)| p.label_at(xy.0, xy.1) != *l)
        .map(|(xy, l)| (xy, l, p.label_at(xy.0, xy.1)))
        .collect();
    assert!(wrong.is_empty(), "{wrong:?}");
}

#[test]
fn round_tower_rooms_fit_circles() {
    let (img, _) = castle(3);
    let p = parse(img);
    let circles = p
        .faces
        .iter()
        .filter(|f| f.label == Label::TowerRoom)
        .filter(|f| matches!(f.shape, Some(plan::fit::Fit::Circle { .. })))
        .count();
    assert!(circles >= 4, "{:?}", p.faces.iter().map(|f| (&f.label, &f.shape)).collect::<Vec<_>>());
}

#[test]
fn every_pixel_has_a_legend_label() {
    let (img, _) = castle(11);
    let p = parse(img);
    assert_eq!(p.labels.len(), 900 * 700);
    assert!(p.labels.iter().all(|&l| (l as usize) < Label::ALL.len()));
    // Walls take wall labels, open space room labels.
    for (i, &l) in p.labels.iter().enumerate() {
        assert_eq!(Label::ALL[l as usize].is_wall(), p.walls.data[i] == 1, "pixel {i}");
    }
}
