//! Ashlar: courses ruled from the ground up in broken stretches with staggered joints (crowding
//! to the limbs of a round tower) and tooling marks, and the hatched shading of a wall.

use std::f64::consts::FRAC_PI_2;

use super::basics::{Rect, Rng, chance, int, uniform};
use super::pen::{Canvas, Clip};
use super::style::{Pen, Shade, Wall};

/// Courses ruled across `r` from the ground up, in broken stretches, with staggered joints.
pub(super) fn coursing(
    rng: &mut Rng,
    canvas: &mut Canvas,
    r: Rect,
    wall: &Wall,
    pen: Pen,
    round: bool,
    clip: Clip,
) {
    let width = pen.fine * wall.weight;
    let mut lo = r.y1;
    let mut y = r.y1 - wall.course * uniform(rng, 0.3, 1.0);
    let (cx, half) = (0.5 * (r.x0 + r.x1), 0.5 * r.w());
    while lo > r.y0 {
        let yl = y.max(r.y0);
        let mut x = r.x0 - uniform(rng, 0.0, 30.0);
        while x < r.x1 && y > r.y0 {
            let len = uniform(rng, 15.0, 120.0);
            if chance(rng, wall.lines) {
                let k = uniform(rng, 0.75, 1.0) as f32;
                canvas.hand(rng, [x, y], [x + len, y], width, k, 0.5 * pen.wobble, clip);
            }
            x += len
                + if chance(rng, 0.3) {
                    uniform(rng, 1.0, 4.0)
                } else {
                    0.0
                };
        }
        let joint = |canvas: &mut Canvas, rng: &mut Rng, x: f64| {
            if chance(rng, wall.joints) {
                canvas.segment(
                    [x, yl],
                    [x, lo],
                    0.9 * width,
                    uniform(rng, 0.7, 1.0) as f32,
                    clip,
                );
            }
            // Tooling marks on the stone beside the joint.
            if chance(rng, wall.stipple) {
                for _ in 0..int(rng, 1, 3) {
                    let (sx, sy) = (
                        x + uniform(rng, 2.0, wall.stone * 0.8),
                        uniform(rng, yl + 1.5, lo - 1.5),
                    );
                    let len = uniform(rng, 1.0, 4.0);
                    canvas.segment(
                        [sx, sy],
                        [sx + len, sy + uniform(rng, -1.0, 1.0)],
                        0.7 * width,
                        0.8,
                        clip,
                    );
                }
            }
        };
        if round {
            let step = (wall.stone / half.max(1.0)).clamp(0.08, 1.0);
            let mut a = -FRAC_PI_2 + uniform(rng, 0.0, step);
            while a < FRAC_PI_2 {
                joint(canvas, rng, cx + half * a.sin());
                a += step * uniform(rng, 0.6, 1.4);
            }
        } else {
            let mut x = r.x0 + uniform(rng, 0.0, wall.stone);
            while x < r.x1 {
                joint(canvas, rng, x);
                x += wall.stone * uniform(rng, 0.6, 1.4);
            }
        }
        lo = y;
        y -= wall.course * uniform(rng, 1.0 - wall.jitter, 1.0 + wall.jitter);
    }
}

/// The mass's hatched shading.
pub(super) fn shade(
    rng: &mut Rng,
    canvas: &mut Canvas,
    r: Rect,
    wall: &Wall,
    pen: Pen,
    clip: Clip,
) {
    match wall.shade {
        Shade::None => {}
        Shade::Side {
            right,
            frac,
            angle,
            spacing,
        } => {
            // Densest at the edge, sparser inwards.
            let band = frac * r.w() / 3.0;
            for (i, f) in [1.0, 1.6, 2.6].into_iter().enumerate() {
                let (a, b) = if right {
                    (r.x1 - band * (i as f64 + 1.0), r.x1 - band * i as f64)
                } else {
                    (r.x0 + band * i as f64, r.x0 + band * (i as f64 + 1.0))
                };
                canvas.hatch(
                    rng,
                    [a, r.y0, b, r.y1],
                    angle,
                    spacing * f,
                    pen.fine,
                    1.0,
                    0.3,
                    clip,
                );
            }
        }
        Shade::Whole { angle, spacing } => {
            canvas.hatch(rng, r.arr(), angle, spacing, pen.fine, 1.0, 0.3, clip);
        }
        Shade::Cylinder { right, dense } => {
            let mut x = r.x0 + 0.5;
            while x < r.x1 {
                let u = (x - r.x0) / r.w().max(1.0);
                let u = if right { u } else { 1.0 - u };
                // Dark limb on the shadow side, a thin dark limb on the lit side.
                let d = ((u - 0.45) / 0.55)
                    .clamp(0.0, 1.0)
                    .powf(1.3)
                    .max((-u / 0.05).exp());
                let s = dense / d.max(0.04);
                if s < 14.0 {
                    canvas.segment(
                        [x, r.y0],
                        [x, r.y1],
                        pen.fine,
                        uniform(rng, 0.8, 1.0) as f32,
                        clip,
                    );
                }
                x += s.clamp(dense, 14.0) * uniform(rng, 0.85, 1.15);
            }
        }
    }
}
