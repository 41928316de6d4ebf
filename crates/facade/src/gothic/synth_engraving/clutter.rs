//! What surrounds the architecture on a plate: the ground line and its texture, small figures
//! (in front of bare wall, or in an open gate), trees, a scale bar, the plate number, letter
//! labels, the engraver's signature, a caption, a frame, and sometimes a ruled sky. Nothing
//! is drawn over an opening except figures in a seen-through gate.

use super::basics::{OPENING_BASE, Rect, Rng, chance, int, uniform};
use super::layout::Scene;
use super::openings::Opening;
use super::pen::{Canvas, P, anywhere};
use super::style::{Fill, Pen, Style};

pub(super) fn draw(
    rng: &mut Rng,
    style: &Style,
    scene: &Scene,
    openings: &[Opening],
    canvas: &mut Canvas,
) {
    let pen = style.pen;
    let (w, h, g) = (canvas.w as f64, canvas.h as f64, scene.ground);
    let reach: Vec<Rect> = openings
        .iter()
        .filter(|o| o.parent.is_none())
        .map(|o| o.reach(2.0, g))
        .collect();
    let free = |r: &Rect| reach.iter().all(|q| !q.overlaps(r));
    let not_opening = |_: usize, _: usize, o: u16| o < OPENING_BASE;
    if chance(rng, 0.12) {
        // A ruled sky, broken by clouds.
        let sky = |_: usize, _: usize, o: u16| o == 0;
        let s = uniform(rng, 3.0, 6.0);
        let k = uniform(rng, 0.6, 0.9) as f32;
        let mut y = uniform(rng, 2.0, 6.0);
        while y < g - 2.0 {
            let mut x = 0.0;
            while x < w {
                let len = uniform(rng, 20.0, 200.0);
                if chance(rng, 0.85) {
                    canvas.segment([x, y], [x + len, y], pen.fine * 0.8, k, &sky);
                }
                x += len + uniform(rng, 0.0, 12.0);
            }
            y += s;
        }
    }
    let gw = pen.outline * uniform(rng, 1.0, 1.6);
    canvas.hand(rng, [0.0, g], [w, g], gw, 1.0, pen.wobble, &anywhere);
    if chance(rng, 0.5) {
        for _ in 0..int(rng, 10, 60) {
            let (x, y) = (uniform(rng, 0.0, w), g + uniform(rng, 3.0, 18.0));
            canvas.segment(
                [x, y],
                [x + uniform(rng, 3.0, 15.0), y],
                pen.fine,
                0.9,
                &not_opening,
            );
        }
    }
    // Figures in open gates and in front of bare wall.
    for o in openings
        .iter()
        .filter(|o| o.figures && o.fill == Fill::Open)
    {
        let t = o.theta;
        for _ in 0..int(rng, 1, 3) {
            let fh = uniform(rng, 14.0, 30.0).min(0.5 * (t.h + t.v));
            let x = uniform(rng, t.x0 + 0.2 * t.w, t.x0 + 0.8 * t.w);
            figure(rng, canvas, [x, t.y0], fh, pen);
        }
    }
    for _ in 0..int(rng, 0, 3) {
        let fh = uniform(rng, 12.0, 28.0);
        let x = uniform(rng, 10.0, w - 10.0);
        let r = Rect {
            x0: x - 0.25 * fh,
            y0: g - fh - 2.0,
            x1: x + 0.25 * fh,
            y1: g,
        };
        if free(&r) {
            figure(rng, canvas, [x, g], fh, pen);
        }
    }
    if chance(rng, 0.3) {
        let th = uniform(rng, 30.0, 0.35 * g.max(40.0));
        let x = if chance(rng, 0.5) {
            uniform(rng, 0.0, 0.15 * w)
        } else {
            uniform(rng, 0.85 * w, w)
        };
        let r = Rect {
            x0: x - 0.45 * th,
            y0: g - th,
            x1: x + 0.45 * th,
            y1: g,
        };
        if free(&r) {
            tree(rng, canvas, [x, g], th, pen);
        }
    }
    let below = h - g;
    if below > 22.0 && chance(rng, 0.7) {
        let len = uniform(rng, 60.0, (0.4 * w).max(61.0));
        let x = uniform(rng, 0.1 * w, (0.9 * w - len).max(0.1 * w));
        let y = g + uniform(rng, 12.0, below - 8.0);
        scale_bar(rng, canvas, [x, y], len, pen);
    }
    if chance(rng, 0.7) {
        let size = uniform(rng, 10.0, 18.0);
        let x = if chance(rng, 0.5) {
            uniform(rng, 4.0, 0.08 * w)
        } else {
            uniform(rng, 0.88 * w, (w - 2.0 * size).max(0.88 * w))
        };
        let y = uniform(rng, 4.0, 0.05 * h + 4.0);
        let r = Rect {
            x0: x,
            y0: y,
            x1: x + 2.0 * size,
            y1: y + size,
        };
        if free(&r) {
            let n = int(rng, 1, 2);
            text(rng, canvas, [x, y], size, n, true, pen.outline * 1.2 + 0.5);
        }
    }
    if below > 12.0 {
        for _ in 0..int(rng, 0, 3) {
            let size = uniform(rng, 6.0, 10.0);
            let (x, y) = (
                uniform(rng, 0.1 * w, 0.9 * w),
                g + uniform(rng, 3.0, (below - size - 2.0).max(3.0)),
            );
            text(rng, canvas, [x, y], size, 1, false, pen.fine * 1.3);
        }
        if chance(rng, 0.5) {
            let size = uniform(rng, 4.0, 6.0);
            let (x, y) = (
                uniform(rng, 0.6 * w, 0.8 * w),
                g + uniform(rng, 3.0, (below - size - 2.0).max(3.0)),
            );
            let n = int(rng, 6, 12);
            text(rng, canvas, [x, y], size, n, false, pen.fine);
        }
    }
    if chance(rng, 0.1) {
        let m = uniform(rng, 3.0, 8.0);
        let pts = [[m, m], [w - m, m], [w - m, h - m], [m, h - m]];
        canvas.polyline(&pts, true, pen.outline, 1.0, &not_opening);
    }
}

/// A standing figure `fh` px tall with its feet at `foot`: head, robe or legs, arms.
fn figure(rng: &mut Rng, canvas: &mut Canvas, foot: P, fh: f64, pen: Pen) {
    let [x, y] = foot;
    let head = (0.065 * fh).max(1.2);
    canvas.disc([x, y - fh + head], head, 1.0, &anywhere);
    let (sh, top, bot) = (y - fh + 2.2 * head, 0.08 * fh, uniform(rng, 0.1, 0.16) * fh);
    let robe = chance(rng, 0.6);
    let hem = if robe { y } else { y - 0.45 * fh };
    // The body as a trapezoid, filled.
    let inside = move |px: f64, py: f64| {
        let t = ((py - sh) / (hem - sh)).clamp(0.0, 1.0);
        py >= sh && py <= hem && (px - x).abs() <= top + t * (bot - top)
    };
    let body = move |xi: usize, yi: usize, _: u16| inside(xi as f64 + 0.5, yi as f64 + 0.5);
    canvas.fill(
        [x - bot - 1.0, sh, x + bot + 1.0, hem],
        uniform(rng, 0.7, 1.0) as f32,
        &body,
    );
    if !robe {
        for s in [-1.0, 1.0] {
            canvas.segment(
                [x + s * 0.3 * top, hem],
                [x + s * 0.6 * top, y],
                pen.fine * 1.2,
                1.0,
                &anywhere,
            );
        }
    }
    let arm = uniform(rng, 0.25, 0.35) * fh;
    for s in [-1.0, 1.0] {
        let end = [x + s * uniform(rng, 0.1, 0.25) * fh, sh + arm];
        canvas.segment([x + s * top, sh + 1.0], end, pen.fine, 1.0, &anywhere);
    }
}

/// A tree: trunk and a canopy of short scribbled arcs.
fn tree(rng: &mut Rng, canvas: &mut Canvas, foot: P, th: f64, pen: Pen) {
    let [x, y] = foot;
    canvas.segment([x, y], [x, y - 0.4 * th], pen.outline, 1.0, &anywhere);
    let (cy, rx, ry) = (y - 0.62 * th, 0.4 * th, 0.38 * th);
    for _ in 0..(th * 2.0) as usize {
        let a = uniform(rng, 0.0, std::f64::consts::TAU);
        let r = uniform(rng, 0.0, 1.0).sqrt();
        let c = [x + rx * r * a.cos(), cy + ry * r * a.sin()];
        let s = uniform(rng, 2.0, 5.0);
        let pts = [[c[0] - s, c[1]], [c[0], c[1] - 0.6 * s], [c[0] + s, c[1]]];
        canvas.polyline(&pts, false, pen.fine, 1.0, &anywhere);
    }
}

/// A scale bar: a rule with ticks, sometimes alternately filled, and a number.
fn scale_bar(rng: &mut Rng, canvas: &mut Canvas, at: P, len: f64, pen: Pen) {
    let [x, y] = at;
    let n = int(rng, 4, 10);
    canvas.segment([x, y], [x + len, y], pen.fine * 1.3, 1.0, &anywhere);
    let filled = chance(rng, 0.3);
    for i in 0..=n {
        let xi = x + len * i as f64 / n as f64;
        let th = if i == 0 || i == n { 5.0 } else { 3.0 };
        canvas.segment(
            [xi, y - th],
            [xi, y + if filled { 2.5 } else { 0.0 }],
            pen.fine,
            1.0,
            &anywhere,
        );
        if filled && i < n && i % 2 == 0 {
            canvas.fill([xi, y, xi + len / n as f64, y + 2.5], 1.0, &anywhere);
        }
    }
    if chance(rng, 0.7) {
        let size = uniform(rng, 5.0, 8.0);
        let (at, n) = (
            [x + len * uniform(rng, 0.3, 0.7), y - size - 6.0],
            int(rng, 1, 2),
        );
        text(rng, canvas, at, size, n, true, pen.fine);
    }
}

/// `n` glyphs `size` px tall from `at` (top left): seven-segment digits or letter-like
/// strokes on a 3 × 3 grid of anchors.
fn text(rng: &mut Rng, canvas: &mut Canvas, at: P, size: f64, n: usize, digits: bool, width: f64) {
    const SEGS: [(P, P); 7] = [
        ([0.0, 0.0], [1.0, 0.0]),
        ([1.0, 0.0], [1.0, 1.0]),
        ([1.0, 1.0], [1.0, 2.0]),
        ([0.0, 2.0], [1.0, 2.0]),
        ([0.0, 1.0], [0.0, 2.0]),
        ([0.0, 0.0], [0.0, 1.0]),
        ([0.0, 1.0], [1.0, 1.0]),
    ];
    const DIGITS: [u8; 10] = [0x3f, 0x06, 0x5b, 0x4f, 0x66, 0x6d, 0x7d, 0x07, 0x7f, 0x6f];
    let cw = 0.6 * size;
    let slant = uniform(rng, 0.0, 0.25);
    let map = |x0: f64, p: P, unit: f64| {
        [
            x0 + p[0] * unit + (size - p[1] * unit) * slant,
            at[1] + p[1] * unit,
        ]
    };
    for i in 0..n {
        let x0 = at[0] + i as f64 * cw * 1.5;
        if digits {
            let d = DIGITS[int(rng, 0, 9)];
            for (_, (a, b)) in SEGS.iter().enumerate().filter(|(k, _)| d >> k & 1 == 1) {
                canvas.segment(
                    map(x0, *a, size / 2.0),
                    map(x0, *b, size / 2.0),
                    width,
                    1.0,
                    &anywhere,
                );
            }
        } else {
            let anchor =
                |rng: &mut Rng| [int(rng, 0, 2) as f64 * 0.5, int(rng, 0, 2) as f64 * 0.83];
            for _ in 0..int(rng, 2, 4) {
                let (a, b) = (anchor(rng), anchor(rng));
                canvas.segment(map(x0, a, cw), map(x0, b, cw), width, 1.0, &anywhere);
            }
        }
    }
}
