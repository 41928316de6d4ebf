//! The openings drawn: the inside of each (black, hatched, cross-hatched, barred, or white and
//! seen through with its soffit and a jamb hatched), a lighter reveal, the outline along the
//! contour of Θ, and the dressings round it: voussoirs, lintel, sill, a dormer's gable, the
//! hatched tympanum of an enclosing arch. Every fill is clipped to the opening's own pixels in
//! the owner map, which are the pixels of the truth mask.

use std::f64::consts::{FRAC_PI_2, PI};

use super::basics::{Rng, chance, int, opening_id, uniform};
use super::openings::{Inside, Opening};
use super::pen::{Canvas, P, anywhere};
use super::style::{Fill, Pen, Style};
use crate::gothic::element::Theta;

pub(super) fn draw(rng: &mut Rng, style: &Style, openings: &[Opening], canvas: &mut Canvas) {
    let pen = style.pen;
    for (j, o) in openings.iter().enumerate() {
        let id = opening_id(j);
        let own = move |_: usize, _: usize, p: u16| p == id;
        if o.enclosing {
            if let Inside::Tympanum { angle, spacing } = o.inside {
                canvas.hatch(
                    rng,
                    o.theta.bbox(),
                    angle,
                    spacing,
                    pen.fine,
                    0.9,
                    0.2,
                    &own,
                );
            }
        } else {
            inside(rng, canvas, o, id, pen);
        }
        if !o.bare {
            let contour: Vec<P> = o.theta.contour_at(1.0).iter().map(|s| [s.x, s.y]).collect();
            canvas.polyline(&contour, true, pen.outline, 1.0, &anywhere);
        }
        if o.ring > 0.0 && o.theta.v > 1e-3 {
            voussoirs(rng, canvas, &o.theta, o.ring, pen);
        }
        dressings(rng, canvas, o, pen);
    }
}

/// The opening's inside.
fn inside(rng: &mut Rng, canvas: &mut Canvas, o: &Opening, id: u16, pen: Pen) {
    let t = o.theta;
    let bbox = t.bbox();
    let band = t.w * uniform(rng, 0.2, 0.35);
    let in_band = move |x: usize| match o.reveal {
        Some(true) => (x as f64 + 0.5) < t.x0 + band,
        Some(false) => (x as f64 + 0.5) > t.x0 + t.w - band,
        None => false,
    };
    let main = move |x: usize, _: usize, p: u16| p == id && !in_band(x);
    let mut spacing = 3.0;
    match o.fill {
        Fill::Solid => canvas.fill(bbox, uniform(rng, 0.9, 1.0) as f32, &main),
        Fill::Hatched { angle, spacing: s } => {
            spacing = s;
            let width = (s * uniform(rng, 0.4, 0.8)).clamp(0.8, 3.0);
            canvas.hatch(rng, bbox, angle, s, width, 1.0, 0.15, &main);
        }
        Fill::Cross { angle, spacing: s } => {
            spacing = s;
            let width = (s * uniform(rng, 0.3, 0.55)).clamp(0.8, 2.5);
            let turn = if chance(rng, 0.7) {
                FRAC_PI_2
            } else {
                uniform(rng, 0.6, 1.2)
            };
            canvas.hatch(rng, bbox, angle, s, width, 1.0, 0.15, &main);
            canvas.hatch(rng, bbox, angle + turn, s, width, 1.0, 0.15, &main);
        }
        Fill::Barred { bars: (nv, nh) } => {
            let bw = uniform(rng, 1.2, 2.6);
            let on_bar = |p: f64, a: f64, len: f64, n: usize| {
                (1..=n).any(|i| (p - (a + len * i as f64 / (n as f64 + 1.0))).abs() < bw / 2.0)
            };
            let open = move |x: usize, y: usize, p: u16| {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                main(x, y, p)
                    && !on_bar(px, t.x0, t.w, nv)
                    && !on_bar(py, t.apex(), t.y0 - t.apex(), nh)
            };
            canvas.fill(bbox, 1.0, &open);
        }
        Fill::Open => {
            // The soffit and one jamb of the passage, hatched.
            let d = uniform(rng, 3.0, (0.15 * t.w).max(3.5));
            let inner = Theta {
                x0: t.x0 + d,
                w: (t.w - 2.0 * d).max(1.0),
                v: if t.v > 0.0 { (t.v - d).max(0.0) } else { 0.0 },
                h: t.h - if t.v > 0.0 { 0.0 } else { d },
                ..t
            };
            let left = chance(rng, 0.5);
            let ys = t.springing();
            let soffit = move |x: usize, y: usize, p: u16| {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                let side = if left {
                    px < t.x0 + d
                } else {
                    px > t.x0 + t.w - d
                };
                p == id && !inner.contains(px, py) && (py < ys || side)
            };
            let angle = if chance(rng, 0.5) { FRAC_PI_2 } else { 0.0 };
            let s = uniform(rng, 1.8, 3.0);
            canvas.hatch(rng, bbox, angle, s, pen.fine, 1.0, 0.1, &soffit);
            // The ground seen through, sometimes a distant line of country.
            if chance(rng, 0.4) {
                let y = t.y0 - uniform(rng, 0.1, 0.3) * t.h;
                let far = move |x: usize, y: usize, p: u16| {
                    p == id && inner.contains(x as f64 + 0.5, y as f64 + 0.5)
                };
                canvas.hand(rng, [t.x0, y], [t.x0 + t.w, y], pen.fine, 0.8, 0.8, &far);
            }
        }
    }
    if o.reveal.is_some() {
        let lit = move |x: usize, _: usize, p: u16| p == id && in_band(x);
        let angle = if chance(rng, 0.5) { 0.0 } else { FRAC_PI_2 };
        let width = (pen.fine * 0.8).max(0.6);
        canvas.hatch(
            rng,
            bbox,
            angle,
            (spacing * 1.8).max(3.0),
            width,
            1.0,
            0.1,
            &lit,
        );
    }
}

/// Points along the head of `t` from the left springer to the right one.
pub(super) fn head_points(t: &Theta, n: usize) -> Vec<P> {
    let n = n.max(2);
    let ys = t.springing();
    let lerp = |a: f64, b: f64, i: usize, m: usize| a + (b - a) * i as f64 / m as f64;
    if t.v <= 1e-3 {
        return (0..=n)
            .map(|i| [lerp(t.x0, t.x0 + t.w, i, n), ys])
            .collect();
    }
    if t.v >= t.w / 2.0 - 1e-9 {
        let r = t.pointed_radius();
        let phi = ((r - t.w / 2.0) / r).clamp(-1.0, 1.0).acos();
        let m = n.div_ceil(2);
        let (cl, cr) = (t.x0 + r, t.x0 + t.w - r);
        let left = (0..=m).map(|i| {
            let a = lerp(PI, PI - phi, i, m);
            [cl + r * a.cos(), ys - r * a.sin()]
        });
        let right = (1..=m).map(|i| {
            let a = lerp(phi, 0.0, i, m);
            [cr + r * a.cos(), ys - r * a.sin()]
        });
        left.chain(right).collect()
    } else {
        let r = t.segmental_radius();
        let (cx, cy) = (t.x0 + t.w / 2.0, ys + r - t.v);
        let alpha = (t.w / 2.0 / r).clamp(-1.0, 1.0).asin();
        (0..=n)
            .map(|i| {
                let a = lerp(FRAC_PI_2 + alpha, FRAC_PI_2 - alpha, i, n);
                [cx + r * a.cos(), cy - r * a.sin()]
            })
            .collect()
    }
}

/// A ring of voussoirs `depth` deep round an arched head: the extrados, the radial joints and
/// the imposts.
fn voussoirs(rng: &mut Rng, canvas: &mut Canvas, t: &Theta, depth: f64, pen: Pen) {
    let outer = Theta {
        x0: t.x0 - depth,
        w: t.w + 2.0 * depth,
        v: t.v + depth,
        ..*t
    };
    let arc = outer.perimeter() - outer.w - 2.0 * outer.h;
    let n = (arc / uniform(rng, 4.0, 10.0)).round().max(3.0) as usize;
    let (a, b) = (head_points(t, n), head_points(&outer, n));
    canvas.polyline(&b, false, pen.outline, 1.0, &anywhere);
    let k = a.len().min(b.len());
    for i in 1..k.saturating_sub(1) {
        canvas.segment(a[i], b[i], pen.fine, 1.0, &anywhere);
    }
    let ys = t.springing();
    canvas.segment([t.x0 - depth, ys], [t.x0, ys], pen.fine, 1.0, &anywhere);
    canvas.segment(
        [t.x0 + t.w, ys],
        [t.x0 + t.w + depth, ys],
        pen.fine,
        1.0,
        &anywhere,
    );
}

/// Lintel, sill ledge and dormer gable.
fn dressings(rng: &mut Rng, canvas: &mut Canvas, o: &Opening, pen: Pen) {
    let t = o.theta;
    let (x0, x1, ys) = (t.x0, t.x0 + t.w, t.springing());
    if o.lintel > 0.0 && t.v <= 1e-3 {
        let top = ys - o.lintel;
        let pts = [
            [x0 - 2.0, ys],
            [x0 - 2.0, top],
            [x1 + 2.0, top],
            [x1 + 2.0, ys],
        ];
        canvas.polyline(&pts, false, pen.outline, 1.0, &anywhere);
        // A flat arch: joints fanning from below the opening.
        if chance(rng, 0.5) {
            let n = int(rng, 3, 7);
            let cy = ys + t.w;
            for i in 1..n {
                let x = x0 + t.w * i as f64 / n as f64;
                let (dx, dy) = (x - (x0 + x1) / 2.0, ys - cy);
                let k = (top - ys) / dy;
                canvas.segment([x, ys], [x + dx * k, top], pen.fine, 1.0, &anywhere);
            }
        }
    }
    if o.sill > 0.0 {
        let (y, b) = (t.y0, t.y0 + o.sill);
        let pts = [[x0 - 3.0, y], [x0 - 3.0, b], [x1 + 3.0, b], [x1 + 3.0, y]];
        canvas.polyline(&pts, true, pen.outline * 0.8, 1.0, &anywhere);
    }
    if o.frame > 0.0 {
        let d = o.frame;
        let outer = Theta {
            x0: x0 - d,
            w: t.w + 2.0 * d,
            v: if t.v > 1e-3 { t.v + d } else { 0.0 },
            h: if t.v > 1e-3 { t.h } else { t.h + d },
            ..t
        };
        let arc = (outer.perimeter() - outer.w - 2.0 * outer.h).max(outer.w);
        let mut pts = vec![[x0 - d, t.y0]];
        pts.extend(head_points(&outer, (arc / 2.0).ceil() as usize));
        pts.push([x1 + d, t.y0]);
        canvas.polyline(&pts, false, pen.fine, 1.0, &anywhere);
    }
    if o.gable > 0.0 {
        let peak = [(x0 + x1) / 2.0, t.apex() - o.gable];
        let pts = [
            [x0 - 3.0, t.y0],
            [x0 - 3.0, ys],
            peak,
            [x1 + 3.0, ys],
            [x1 + 3.0, t.y0],
        ];
        canvas.polyline(&pts, false, pen.outline, 1.0, &anywhere);
    }
}
