//! The fittings drawn in thin line inside the rooms of a plan — stairs, tables, beds and
//! chests, counters along a wall, wells and basins, doors with their swing — never wall.
//!
//! Castle plans draw stairs, wells, altars and fireplaces; modern plans are full of
//! furniture. The shipped wall ink has seen none of it and reads a room crowded with
//! fittings as wall (R3D's kitchens and cupboards, docs/plan.md "Fittings"). Drawn only when
//! asked ([`super::StyleChoice::furnishing`]).

use std::f64::consts::{FRAC_PI_2, PI};

use rand::RngExt;

use super::geometry::{P, Rng, add, inside_poly, rot, u};
use super::layout::Layout;
use super::sheet::Sheet;

/// Between 6 and 30 fittings inside the curtain, each in one pen (1–2 px, black to mid-grey).
pub(super) fn furnishing(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let span = lay.radius.0.min(lay.radius.1);
    let t = lay.t;
    for _ in 0..rng.random_range(6..=30) {
        let Some(at) = free_point(sheet, lay, rng) else {
            continue;
        };
        let lw = u(rng, 1.0, 2.0);
        let v = rng.random_range(0..=110u8);
        let size = (t * u(rng, 2.0, 9.0)).clamp(6.0, (span * 0.35).max(6.0));
        // Mostly square to the sheet, as furniture is to its room.
        let ang = if rng.random_bool(0.7) {
            FRAC_PI_2 * f64::from(rng.random_range(0..4u8))
        } else {
            u(rng, 0.0, PI)
        };
        let pen = Pen { lw, v, at, ang };
        match rng.random_range(0..5u8) {
            0 => chest(sheet, &pen, size, rng),
            1 => stairs(sheet, &pen, size, rng),
            2 => table(sheet, &pen, size, rng),
            3 => door(sheet, &pen, size, rng),
            _ => counter(sheet, &pen, size, t, rng),
        }
    }
}

/// A pen at a place and angle: points are given in the fitting's own frame.
struct Pen {
    lw: f64,
    v: u8,
    at: P,
    ang: f64,
}

impl Pen {
    fn to_sheet(&self, p: P) -> P {
        add(self.at, rot(p, self.ang))
    }
    fn line(&self, sheet: &mut Sheet, a: P, b: P) {
        sheet.line(self.to_sheet(a), self.to_sheet(b), self.lw, self.v);
    }
    fn polyline(&self, sheet: &mut Sheet, pts: impl IntoIterator<Item = P>) {
        let pts: Vec<P> = pts.into_iter().map(|p| self.to_sheet(p)).collect();
        sheet.polyline(&pts, self.lw, self.v);
    }
    /// The outline of the rectangle [x0, x1] × [y0, y1].
    fn rect(&self, sheet: &mut Sheet, x0: f64, y0: f64, x1: f64, y1: f64) {
        self.polyline(sheet, [(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)]);
    }
    /// An arc of radius `r` about `c` from angle `a0` to `a1`, as short chords.
    fn arc(&self, sheet: &mut Sheet, c: P, r: f64, a0: f64, a1: f64) {
        let n = ((a1 - a0).abs() * r / 3.0).ceil().max(4.0) as usize;
        let at = |k: usize| add(c, rot((r, 0.0), a0 + (a1 - a0) * k as f64 / n as f64));
        self.polyline(sheet, (0..=n).map(at));
    }
}

/// A point inside the curtain and off the walls, if one of 20 tries finds it.
fn free_point(sheet: &Sheet, lay: &Layout, rng: &mut Rng) -> Option<P> {
    let (w, h) = (sheet.truth.w, sheet.truth.h);
    (0..20).find_map(|_| {
        let p = (u(rng, 0.0, w as f64), u(rng, 0.0, h as f64));
        let i = p.1 as usize * w + p.0 as usize;
        (inside_poly(p, &lay.curtain) && !sheet.truth.m[i]).then_some(p)
    })
}

/// A bed, chest or altar: a rectangle, sometimes with an inset rectangle or a diagonal.
fn chest(sheet: &mut Sheet, pen: &Pen, size: f64, rng: &mut Rng) {
    let (a, b) = (size / 2.0, size * u(rng, 0.25, 0.6));
    pen.rect(sheet, -a, -b, a, b);
    match rng.random_range(0..3u8) {
        0 => {
            let d = (size * 0.12).max(2.5);
            pen.rect(sheet, -a + d, -b + d, -a + 3.0 * d, b - d);
        }
        1 => pen.line(sheet, (-a, -b), (a, b)),
        _ => {}
    }
}

/// A flight of stairs: a rectangle crossed by treads 3–7 px apart, sometimes with the line
/// of the climb and its arrow.
fn stairs(sheet: &mut Sheet, pen: &Pen, size: f64, rng: &mut Rng) {
    let (a, b) = (size / 2.0, (size * u(rng, 0.2, 0.45)).max(4.0));
    pen.rect(sheet, -a, -b, a, b);
    let step = u(rng, 3.0, 7.0);
    let mut x = -a + step;
    while x < a {
        pen.line(sheet, (x, -b), (x, b));
        x += step;
    }
    if rng.random_bool(0.4) {
        pen.line(sheet, (-a, 0.0), (a, 0.0));
        pen.line(sheet, (a, 0.0), (a - b * 0.6, -b * 0.5));
        pen.line(sheet, (a, 0.0), (a - b * 0.6, b * 0.5));
    }
}

/// A table, well or basin: a circle, sometimes a ring, sometimes with chairs round it.
fn table(sheet: &mut Sheet, pen: &Pen, size: f64, rng: &mut Rng) {
    let r = size / 2.0;
    pen.arc(sheet, (0.0, 0.0), r, 0.0, 2.0 * PI);
    if rng.random_bool(0.35) {
        pen.arc(sheet, (0.0, 0.0), r * u(rng, 0.55, 0.85), 0.0, 2.0 * PI);
    } else if rng.random_bool(0.5) {
        let (n, c) = (rng.random_range(3..=6u8), (r * 0.25).max(2.0));
        for k in 0..n {
            let p = rot((r + c * 1.6, 0.0), 2.0 * PI * f64::from(k) / f64::from(n));
            pen.rect(sheet, p.0 - c, p.1 - c, p.0 + c, p.1 + c);
        }
    }
}

/// A door: its leaf and the quarter circle it swings through.
fn door(sheet: &mut Sheet, pen: &Pen, size: f64, rng: &mut Rng) {
    let r = size * u(rng, 0.5, 1.0);
    pen.line(sheet, (0.0, 0.0), (r, 0.0));
    pen.arc(sheet, (0.0, 0.0), r, 0.0, FRAC_PI_2);
    if rng.random_bool(0.3) {
        pen.line(sheet, (0.0, 0.0), (0.0, r));
    }
}

/// A counter or bench: a long narrow rectangle, sometimes with a sink or hob in it.
fn counter(sheet: &mut Sheet, pen: &Pen, size: f64, t: f64, rng: &mut Rng) {
    let a = size * u(rng, 0.8, 1.8);
    let b = (t * u(rng, 0.8, 2.0)).max(3.0);
    pen.rect(sheet, -a, -b, a, b);
    if rng.random_bool(0.5) {
        let x = u(rng, -0.6 * a, 0.6 * a);
        pen.arc(sheet, (x, 0.0), b * 0.6, 0.0, 2.0 * PI);
    }
}
