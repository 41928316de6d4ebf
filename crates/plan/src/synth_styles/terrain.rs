//! Terrain clutter around the castle, never wall: contour lines and hachured slopes.

use std::f64::consts::PI;

use rand::RngExt;

use super::geometry::{P, Rng, add, lerp, mul, sub, u};
use super::layout::{Layout, inward};
use super::sheet::Sheet;

/// A closed wobbly curve around the castle at `f` times its radius.
pub(super) fn ring(lay: &Layout, f: f64, wobble: &[(f64, f64)]) -> Vec<P> {
    (0..=120)
        .map(|k| {
            let a = 2.0 * PI * k as f64 / 120.0;
            let r = f + wobble
                .iter()
                .map(|(m, ph)| 0.04 * (m * a + ph).sin())
                .sum::<f64>();
            add(
                lay.centre,
                (lay.radius.0 * r * a.cos(), lay.radius.1 * r * a.sin()),
            )
        })
        .collect()
}

pub(super) fn wobble(rng: &mut Rng) -> Vec<(f64, f64)> {
    (0..3)
        .map(|_| (rng.random_range(2..6) as f64, u(rng, 0.0, 2.0 * PI)))
        .collect()
}

pub(super) fn contours(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let wob = wobble(rng);
    let mut f = u(rng, 1.3, 1.4);
    for _ in 0..rng.random_range(2..=5) {
        sheet.polyline(&ring(lay, f, &wob), 1.0, 0);
        f += u(rng, 0.08, 0.2);
    }
}

/// A band of short strokes perpendicular to a curve around the castle (a moat or slope).
pub(super) fn hachures(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let wob = wobble(rng);
    let curve = ring(lay, u(rng, 1.3, 1.45), &wob);
    let band = lay.radius.0.min(lay.radius.1) * u(rng, 0.08, 0.2);
    let (sp, lw) = (u(rng, 2.5, 6.0), u(rng, 1.0, 1.6));
    let mut k = 0;
    for s in curve.windows(2) {
        let d = sub(s[1], s[0]);
        let len = d.0.hypot(d.1);
        let out = mul(inward(s[0], s[1], lay.centre), -1.0);
        let mut t = 0.0;
        while t < len {
            let p = lerp(s[0], s[1], t / len);
            let l = band * if k % 2 == 0 { 1.0 } else { u(rng, 0.4, 0.7) };
            sheet.line(p, add(p, mul(out, l)), lw, 0);
            t += sp;
            k += 1;
        }
    }
}
