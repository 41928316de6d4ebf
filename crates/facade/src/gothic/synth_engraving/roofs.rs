//! Roofs in elevation — cones, pyramids, hipped roofs, domes — their shape (for the owner map)
//! and their drawing: ribs or slate courses, a shaded side, outline, finial.

use std::f64::consts::PI;

use super::ashlar::coursing;
use super::basics::{Rect, Rng, chance, int, uniform};
use super::pen::{Canvas, Clip, P};
use super::style::{Pen, Shade, Wall};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum RoofShape {
    Cone,
    Pyramid,
    /// A hipped roof: a trapezoid with a ridge.
    Hip,
    /// A dome (the White Tower's turrets).
    Dome,
}

/// A roof seen in elevation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Roof {
    pub x0: f64,
    pub x1: f64,
    /// y of the eaves and of the apex (or ridge).
    pub base: f64,
    pub apex: f64,
    /// Half length of the ridge (0 for a cone, pyramid or dome).
    pub ridge: f64,
    pub shape: RoofShape,
    pub finial: bool,
}

impl Roof {
    pub fn cx(&self) -> f64 {
        0.5 * (self.x0 + self.x1)
    }
    /// Half width of the roof at height y (negative outside its height).
    pub fn half_at(&self, y: f64) -> f64 {
        if y < self.apex || y > self.base {
            return -1.0;
        }
        let half = 0.5 * (self.x1 - self.x0);
        let t = (y - self.apex) / (self.base - self.apex).max(1e-9);
        match self.shape {
            RoofShape::Dome => half * (1.0 - (1.0 - t) * (1.0 - t)).max(0.0).sqrt(),
            _ => self.ridge + t * (half - self.ridge),
        }
    }
    pub fn contains(&self, x: f64, y: f64) -> bool {
        (x - self.cx()).abs() <= self.half_at(y)
    }
    pub fn rect(&self) -> Rect {
        Rect {
            x0: self.x0,
            y0: self.apex,
            x1: self.x1,
            y1: self.base,
        }
    }
}

/// A roof: outline, slate courses and hatching, finial.
pub(super) fn draw(
    rng: &mut Rng,
    canvas: &mut Canvas,
    roof: &Roof,
    id: u16,
    pen: Pen,
    behind: Clip,
) {
    let own = move |_: usize, _: usize, o: u16| o == id;
    let (cx, half) = (roof.cx(), 0.5 * (roof.x1 - roof.x0));
    let rh = roof.base - roof.apex;
    let course = uniform(rng, 3.5, 8.0);
    match roof.shape {
        RoofShape::Cone | RoofShape::Dome => {
            // Ribs from eaves to apex, closer on the shadow side.
            let s = uniform(rng, 3.0, 6.0);
            let mut x = roof.x0;
            while x <= roof.x1 {
                let f = (x - cx) / half.max(1.0);
                let pts: Vec<P> = (0..=12)
                    .map(|i| {
                        let y = roof.apex + rh * i as f64 / 12.0;
                        [cx + f * roof.half_at(y).max(0.0), y]
                    })
                    .collect();
                canvas.polyline(&pts, false, pen.fine, uniform(rng, 0.8, 1.0) as f32, &own);
                x += if f > 0.2 { 0.55 * s } else { s };
            }
        }
        _ => {
            let wall = Wall {
                course,
                jitter: 0.1,
                stone: uniform(rng, 4.0, 9.0),
                joints: 0.8,
                lines: 0.9,
                weight: 0.8,
                stipple: 0.0,
                shade: Shade::None,
            };
            coursing(rng, canvas, roof.rect(), &wall, pen, false, &own);
            let band = [cx, roof.apex, roof.x1, roof.base];
            let s = uniform(rng, 2.0, 3.5);
            canvas.hatch(rng, band, PI - 1.1, s, pen.fine, 1.0, 0.2, &own);
        }
    }
    if roof.shape != RoofShape::Pyramid && roof.shape != RoofShape::Hip {
        let mut y = roof.base - course;
        while y > roof.apex + 2.0 {
            let hw = roof.half_at(y);
            if chance(rng, 0.8) {
                canvas.segment([cx - hw, y], [cx + hw, y], pen.fine * 0.8, 0.8, &own);
            }
            y -= course;
        }
    }
    let outline: Vec<P> = match roof.shape {
        RoofShape::Dome => (0..=24)
            .map(|i| {
                let a = PI * i as f64 / 24.0;
                let y = roof.base - rh * a.sin();
                [cx - half * a.cos(), y]
            })
            .collect(),
        _ => vec![
            [roof.x0, roof.base],
            [cx - roof.ridge, roof.apex],
            [cx + roof.ridge, roof.apex],
            [roof.x1, roof.base],
        ],
    };
    canvas.polyline(&outline, true, pen.outline, 1.0, behind);
    if roof.finial {
        let top = roof.apex - uniform(rng, 8.0, 25.0);
        canvas.segment([cx, roof.apex], [cx, top], pen.outline * 0.8, 1.0, behind);
        match int(rng, 0, 2) {
            0 => canvas.disc([cx, roof.apex - 2.0], uniform(rng, 1.5, 3.0), 1.0, behind),
            1 => {
                let y = top + 0.3 * (roof.apex - top);
                canvas.segment([cx - 4.0, y], [cx + 4.0, y], pen.fine, 1.0, behind);
            }
            _ => {
                let flag = [[cx, top], [cx + 8.0, top + 2.5], [cx, top + 5.0]];
                canvas.polyline(&flag, true, pen.fine, 1.0, behind);
            }
        }
    }
}
