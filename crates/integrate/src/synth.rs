//! A synthetic castle with known answers, for tests and the demo: a plan drawing (a curtain
//! wall with two round towers and a free-standing keep) and perspective photos of the keep's
//! south façade at any scale, with the user's training boxes and correspondence points.

use facade::classify::{Class, Training};
use image::{GrayImage, Luma, Rgb, RgbImage};
use nalgebra::{Matrix3, Vector3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The castle, in plan pixels and metres.
#[derive(Debug, Clone)]
pub struct Castle {
    pub plan_size: [u32; 2],
    pub metres_per_pixel: f64,
    /// Curtain wall centreline rectangle [x0, y0, x1, y1] and every wall's thickness (px).
    pub enclosure: [f64; 4],
    pub wall_px: f64,
    /// Round towers: centre and centreline radius (px).
    pub towers: Vec<([f64; 2], f64)>,
    /// Towers drawn solid, with no room (discs studding the curtain, found by the plan as
    /// bulges): centre and outer radius (px). None by default.
    pub solid_towers: Vec<([f64; 2], f64)>,
    /// The keep: centre and centreline size (px).
    pub keep_center: [f64; 2],
    pub keep_size: [f64; 2],
    /// Keep façade (south side), metres.
    pub keep_height: f64,
    pub floors: u32,
    pub windows: u32,
    pub window_width: f64,
    pub window_height: f64,
    pub window_sill: f64,
}

impl Default for Castle {
    fn default() -> Self {
        Castle {
            plan_size: [640, 480],
            metres_per_pixel: 0.1,
            enclosure: [110.0, 100.0, 530.0, 400.0],
            wall_px: 10.0,
            towers: vec![([110.0, 100.0], 36.0), ([530.0, 100.0], 36.0)],
            solid_towers: Vec::new(),
            keep_center: [320.0, 270.0],
            keep_size: [160.0, 90.0],
            keep_height: 15.0,
            floors: 3,
            windows: 4,
            window_width: 1.6,
            window_height: 2.4,
            window_sill: 1.2,
        }
    }
}

/// One synthetic photo of the keep's south façade.
pub struct Photo {
    pub image: RgbImage,
    /// Boxes in the photo's pixels.
    pub training: Training,
    /// A point on the façade, in the photo's pixels.
    pub facade_point: [f64; 2],
}

impl Castle {
    /// The keep's outer south side (the façade's width), metres.
    pub fn keep_width(&self) -> f64 {
        (self.keep_size[0] + self.wall_px) * self.metres_per_pixel
    }

    /// A point inside the keep near its south side, plan pixels.
    pub fn keep_south_point(&self) -> [f64; 2] {
        [
            self.keep_center[0],
            self.keep_center[1] + self.keep_size[1] / 2.0 - 12.0,
        ]
    }

    /// The plan drawing: black walls on white paper.
    pub fn plan(&self) -> GrayImage {
        let [w, h] = self.plan_size;
        let t = self.wall_px / 2.0;
        let [x0, y0, x1, y1] = self.enclosure;
        let on_rect = |x: f64, y: f64, r: [f64; 4]| {
            let inside_outer = x >= r[0] - t && x <= r[2] + t && y >= r[1] - t && y <= r[3] + t;
            let inside_inner = x > r[0] + t && x < r[2] - t && y > r[1] + t && y < r[3] - t;
            inside_outer && !inside_inner
        };
        let [kx, ky] = self.keep_center;
        let [kw, kh] = self.keep_size;
        let keep = [kx - kw / 2.0, ky - kh / 2.0, kx + kw / 2.0, ky + kh / 2.0];
        GrayImage::from_fn(w, h, |px, py| {
            let (x, y) = (f64::from(px), f64::from(py));
            let in_tower_room = self
                .towers
                .iter()
                .any(|(c, r)| (x - c[0]).hypot(y - c[1]) < r - t);
            let tower_wall = self.towers.iter().any(|(c, r)| {
                let d = (x - c[0]).hypot(y - c[1]);
                d >= r - t && d <= r + t
            });
            let solid = self
                .solid_towers
                .iter()
                .any(|(c, r)| (x - c[0]).hypot(y - c[1]) <= *r);
            let wall = tower_wall
                || solid
                || (on_rect(x, y, [x0, y0, x1, y1]) && !in_tower_room)
                || on_rect(x, y, keep);
            Luma([if wall { 0 } else { 255 }])
        })
    }

    /// The rectified south façade at `px_per_m`, with a margin of sky above and ground below.
    /// Returns the image and the façade's rectangle in it.
    pub fn elevation(&self, px_per_m: f64, seed: u64) -> (RgbImage, [f64; 4]) {
        let fw = self.keep_width() * px_per_m;
        let fh = self.keep_height * px_per_m;
        let margin = (0.25 * fw).round();
        let (w, h) = (
            (fw + 2.0 * margin).round() as u32,
            (fh + 2.0 * margin).round() as u32,
        );
        let rect = [margin, margin, margin + fw, margin + fh];
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let noise: Vec<f64> = (0..(w * h))
            .map(|_| rng.random_range(-10.0..10.0))
            .collect();
        let img = RgbImage::from_fn(w, h, |px, py| {
            let (x, y) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
            let e = noise[(py * w + px) as usize];
            let c = self.colour_at(x, y, rect, px_per_m);
            Rgb(c.map(|v| (v + e).clamp(0.0, 255.0) as u8))
        });
        (img, rect)
    }

    /// Colour of the elevation at (x, y) given the façade rectangle.
    fn colour_at(&self, x: f64, y: f64, rect: [f64; 4], px_per_m: f64) -> [f64; 3] {
        if y < rect[1] {
            return [205.0, 225.0, 250.0];
        }
        if y >= rect[3] {
            return [95.0, 125.0, 70.0];
        }
        if x < rect[0] || x >= rect[2] {
            return [205.0, 225.0, 250.0];
        }
        // Metres from the façade's bottom-left corner, y up.
        let (mx, my) = ((x - rect[0]) / px_per_m, (rect[3] - y) / px_per_m);
        let floor_h = self.keep_height / f64::from(self.floors);
        let in_floor = my % floor_h;
        let gap = self.window_gap();
        let off = self.window_offset();
        let col = ((mx - off) / (self.window_width + gap)).floor();
        let in_col = mx - off - col * (self.window_width + gap);
        let window = col >= 0.0
            && col < f64::from(self.windows)
            && in_col < self.window_width
            && in_floor >= self.window_sill
            && in_floor < self.window_sill + self.window_height;
        if window {
            [40.0, 48.0, 62.0]
        } else {
            // Ashlar courses: a darker mortar line every 0.5 m.
            if (my % 0.5) < 0.06 {
                [160.0, 138.0, 110.0]
            } else {
                [176.0, 150.0, 118.0]
            }
        }
    }

    pub fn window_gap(&self) -> f64 {
        let n = f64::from(self.windows);
        (self.keep_width() - n * self.window_width) / (n + 1.0)
    }

    pub fn window_offset(&self) -> f64 {
        self.window_gap()
    }

    /// A perspective photo of the south façade: the elevation at `px_per_m` seen through a
    /// keystone homography of strength `tilt` (0 = rectified).
    pub fn photo(&self, px_per_m: f64, tilt: f64, seed: u64) -> Photo {
        let (elev, rect) = self.elevation(px_per_m, seed);
        let (w, h) = elev.dimensions();
        let (cx, cy) = (f64::from(w) / 2.0, f64::from(h) / 2.0);
        let s = f64::from(w.max(h));
        // Centred keystone: verticals converge upwards and horizontals towards the right.
        let c = Matrix3::new(1.0, 0.0, -cx, 0.0, 1.0, -cy, 0.0, 0.0, 1.0);
        let k = Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.6 * tilt / s, -tilt / s, 1.0);
        let hm = c.try_inverse().expect("translation") * k * c;
        let inv = hm.try_inverse().expect("keystone is invertible");
        let map = |m: &Matrix3<f64>, x: f64, y: f64| {
            let p = m * Vector3::new(x, y, 1.0);
            [p[0] / p[2], p[1] / p[2]]
        };
        let image = RgbImage::from_fn(w, h, |px, py| {
            let [sx, sy] = map(&inv, f64::from(px), f64::from(py));
            let (ix, iy) = (sx.round(), sy.round());
            if ix >= 0.0 && iy >= 0.0 && ix < f64::from(w) && iy < f64::from(h) {
                *elev.get_pixel(ix as u32, iy as u32)
            } else {
                Rgb([205, 225, 250])
            }
        });
        // Training boxes and the façade point, placed in the elevation and mapped to the photo.
        let m = px_per_m;
        let fl = self.keep_height / f64::from(self.floors);
        let (x0, yb) = (rect[0], rect[3]);
        let win = |col: f64, floor: f64| {
            let left =
                x0 + (self.window_offset() + col * (self.window_width + self.window_gap())) * m;
            let bottom = yb - (floor * fl + self.window_sill) * m;
            let top = bottom - self.window_height * m;
            [
                left + 0.25 * self.window_width * m,
                top + 0.25 * self.window_height * m,
                left + 0.75 * self.window_width * m,
                bottom - 0.25 * self.window_height * m,
            ]
        };
        let wall = |floor: f64| {
            let y = yb - (floor * fl + self.window_sill * 0.4) * m;
            [
                x0 + 0.2 * self.window_gap() * m,
                y - 0.3 * m,
                x0 + 0.8 * self.window_gap() * m,
                y + 0.3 * m,
            ]
        };
        let bounding = |b: [f64; 4]| {
            let ps = [
                map(&hm, b[0], b[1]),
                map(&hm, b[2], b[1]),
                map(&hm, b[0], b[3]),
                map(&hm, b[2], b[3]),
            ];
            [
                ps[0][0].max(ps[2][0]),
                ps[0][1].max(ps[1][1]),
                ps[1][0].min(ps[3][0]),
                ps[2][1].min(ps[3][1]),
            ]
        };
        let sky = [
            rect[0] + 0.2 * (rect[2] - rect[0]),
            rect[1] * 0.2,
            rect[0] + 0.8 * (rect[2] - rect[0]),
            rect[1] * 0.7,
        ];
        let grass = [
            rect[0] + 0.2 * (rect[2] - rect[0]),
            rect[3] + 0.3 * (f64::from(h) - rect[3]),
            rect[0] + 0.8 * (rect[2] - rect[0]),
            rect[3] + 0.8 * (f64::from(h) - rect[3]),
        ];
        let mut classes = std::collections::BTreeMap::new();
        classes.insert(
            Class::Window,
            vec![
                bounding(win(0.0, 0.0)),
                bounding(win(2.0, 1.0)),
                bounding(win(3.0, 2.0)),
            ],
        );
        classes.insert(
            Class::Wall,
            vec![
                bounding(wall(0.0)),
                bounding(wall(1.0)),
                bounding(wall(2.0)),
            ],
        );
        classes.insert(Class::Background, vec![bounding(sky), bounding(grass)]);
        let point = map(&hm, (rect[0] + rect[2]) / 2.0, (rect[1] + rect[3]) / 2.0);
        Photo {
            image,
            training: Training {
                classes,
                ..Default::default()
            },
            facade_point: point,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plan_has_black_walls_where_drawn() {
        let c = Castle::default();
        let p = c.plan();
        assert_eq!(p.get_pixel(110, 250)[0], 0, "west curtain wall");
        assert_eq!(p.get_pixel(320, 250)[0], 255, "inside the keep");
        assert_eq!(p.get_pixel(320, 225)[0], 0, "keep's north wall");
        assert_eq!(p.get_pixel(110, 100)[0], 255, "inside a tower");
        assert_eq!(p.get_pixel(146, 100)[0], 0, "tower ring");
    }

    #[test]
    fn photos_keep_the_facade_layout_and_boxes_stay_on_their_class() {
        let c = Castle::default();
        let photo = c.photo(20.0, 0.0, 1);
        let (elev, _) = c.elevation(20.0, 1);
        assert_eq!(photo.image.dimensions(), elev.dimensions());
        for b in &photo.training.classes[&Class::Window] {
            let p = photo
                .image
                .get_pixel(((b[0] + b[2]) / 2.0) as u32, ((b[1] + b[3]) / 2.0) as u32);
            assert!(p[0] < 80, "{b:?} {p:?}");
        }
        for b in &photo.training.classes[&Class::Wall] {
            let p = photo
                .image
                .get_pixel(((b[0] + b[2]) / 2.0) as u32, ((b[1] + b[3]) / 2.0) as u32);
            assert!(p[0] > 120, "{b:?} {p:?}");
        }
    }
}
