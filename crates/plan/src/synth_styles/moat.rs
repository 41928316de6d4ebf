//! Hachured scarps and ditches drawn right against the walls, as Viollet-le-Duc and the
//! antiquarian plans draw them (Coucy, Sully, Montargis, Arques, Langres, Richmond, the Tickhill
//! motte): strokes perpendicular to the outer face of the curtain and its towers, 2–5 px apart
//! and 0.5–4 wall thicknesses long (even, alternating long and short, wedge-shaped, or denser
//! near the wall), the ditch's outer edge as a line, and dense concentric contour-like bands.
//! Never wall: every pixel goes through [`Sheet::ink`], which refuses wall pixels.

use std::f64::consts::PI;

use image::Luma;
use imageproc::distance_transform::euclidean_squared_distance_transform;
use rand::RngExt;

use super::degrade::splitmix;
use super::geometry::{Mask, P, Rng, add, bbox, mul, rot, scan, sub, u, unit};
use super::layout::Layout;
use super::sheet::Sheet;

/// The castle's footprint (walls, courtyards and the ground inside the curtain) and each
/// pixel's distance to it, with the stretches of the outside that are hachured.
struct Outside {
    foot: Mask,
    /// Euclidean distance to the footprint, per pixel (0 inside it).
    dist: Vec<f64>,
    arcs: Vec<(f64, f64)>,
    centre: P,
    radius: P,
}

impl Outside {
    fn new(lay: &Layout, rng: &mut Rng) -> Outside {
        let mut foot = lay.main.or(&lay.inner);
        foot.fill(&lay.curtain, true);
        fill_holes(&mut foot);
        let img = foot.to_gray();
        let dist = euclidean_squared_distance_transform(&img)
            .pixels()
            .map(|&Luma([d])| d.sqrt())
            .collect();
        // Some plans hachure the whole way round, most only a few stretches.
        let arcs = if rng.random_bool(0.3) {
            vec![(0.0, 2.0 * PI)]
        } else {
            (0..rng.random_range(1..=3))
                .map(|_| (u(rng, 0.0, 2.0 * PI), u(rng, 0.3, 1.3) * PI))
                .collect()
        };
        Outside {
            foot,
            dist,
            arcs,
            centre: lay.centre,
            radius: lay.radius,
        }
    }
    /// The angle of `p` around the castle's centre, in the castle's own proportions.
    fn angle(&self, p: P) -> f64 {
        let d = sub(p, self.centre);
        (d.1 / self.radius.1).atan2(d.0 / self.radius.0)
    }
    fn hachured(&self, p: P) -> bool {
        let a = self.angle(p);
        self.arcs
            .iter()
            .any(|&(start, len)| (a - start).rem_euclid(2.0 * PI) < len)
    }
    /// Pixels just outside the footprint on the hachured stretches, about `sp` apart (greedy
    /// in scan order), chained along the outline (each next seed the nearest unvisited one).
    fn seeds(&self, sp: f64) -> Vec<P> {
        let (w, h) = (self.foot.w, self.foot.h);
        let cell = sp.max(1.0);
        let (gw, gh) = (
            (w as f64 / cell) as usize + 1,
            (h as f64 / cell) as usize + 1,
        );
        let mut grid: Vec<Vec<P>> = vec![Vec::new(); gw * gh];
        let mut seeds = Vec::new();
        for y in 0..h {
            for x in 0..w {
                let d = self.dist[y * w + x];
                let p = (x as f64, y as f64);
                if d == 0.0 || d > 1.5 || !self.hachured(p) {
                    continue;
                }
                let (gx, gy) = ((p.0 / cell) as usize, (p.1 / cell) as usize);
                let near = (gy.saturating_sub(1)..(gy + 2).min(gh)).any(|yy| {
                    (gx.saturating_sub(1)..(gx + 2).min(gw)).any(|xx| {
                        grid[yy * gw + xx]
                            .iter()
                            .any(|q| (q.0 - p.0).hypot(q.1 - p.1) < sp)
                    })
                });
                if !near {
                    grid[gy * gw + gx].push(p);
                    seeds.push(p);
                }
            }
        }
        chain(seeds)
    }
    /// The outward normal at `p`: away from the mean of the footprint's pixels around it.
    fn normal(&self, p: P, r: f64) -> P {
        let (mut s, mut n) = ((0.0, 0.0), 0.0);
        let (w, h) = (self.foot.w, self.foot.h);
        scan(
            w,
            h,
            sub(p, (r, r)),
            add(p, (r, r)),
            |q| (q.0 - p.0).hypot(q.1 - p.1) <= r,
            |i| {
                if self.foot.m[i] {
                    s = add(s, ((i % w) as f64, (i / w) as f64));
                    n += 1.0;
                }
            },
        );
        if n == 0.0 {
            return unit(sub(p, self.centre));
        }
        unit(sub(p, mul(s, 1.0 / n)))
    }
    /// How far a ray from `p` along `dir` goes, up to `len`, while it moves straight away from
    /// the footprint: it stops where it leaves the sheet, meets the footprint again or crosses
    /// the seam where another face of the walls is as near (so strokes never cross there).
    fn reach(&self, p: P, dir: P, len: f64) -> f64 {
        let d0 = self.dist_at(p).unwrap_or(0.0);
        let mut s = 1.0;
        while s < len {
            let q = add(p, mul(dir, s));
            match self.dist_at(q) {
                Some(d) if d > 0.0 && d >= d0 + 0.8 * s - 1.0 => s += 0.5,
                _ => return (s - 1.0).max(0.0),
            }
        }
        len
    }
    fn dist_at(&self, p: P) -> Option<f64> {
        let (x, y) = (p.0.round(), p.1.round());
        let inside = x >= 0.0 && y >= 0.0 && x < self.foot.w as f64 && y < self.foot.h as f64;
        inside.then(|| self.dist[y as usize * self.foot.w + x as usize])
    }
}

/// Adds to `m` every pixel not reached from the sheet's border without crossing it (the rooms
/// of towers that stand out of the curtain).
fn fill_holes(m: &mut Mask) {
    let (w, h) = (m.w, m.h);
    let mut seen = vec![false; w * h];
    let mut stack: Vec<usize> = (0..w * h)
        .filter(|&i| {
            let (x, y) = (i % w, i / w);
            (x == 0 || y == 0 || x == w - 1 || y == h - 1) && !m.m[i]
        })
        .collect();
    stack.iter().for_each(|&i| seen[i] = true);
    while let Some(i) = stack.pop() {
        let (x, y) = (i % w, i / w);
        let next = [
            (x > 0).then(|| i - 1),
            (x + 1 < w).then(|| i + 1),
            (y > 0).then(|| i - w),
            (y + 1 < h).then(|| i + w),
        ];
        for j in next.into_iter().flatten() {
            if !seen[j] && !m.m[j] {
                seen[j] = true;
                stack.push(j);
            }
        }
    }
    for (v, s) in m.m.iter_mut().zip(seen) {
        *v |= !s;
    }
}

/// Seeds reordered into chains: from each seed on to the nearest unvisited one.
fn chain(mut rest: Vec<P>) -> Vec<P> {
    let mut out = Vec::with_capacity(rest.len());
    while let Some(mut at) = rest.pop() {
        out.push(at);
        while let Some((k, _)) = rest.iter().enumerate().min_by(|a, b| {
            let (da, db) = (dist2(*a.1, at), dist2(*b.1, at));
            da.total_cmp(&db)
        }) {
            at = rest.swap_remove(k);
            out.push(at);
        }
    }
    out
}

fn dist2(a: P, b: P) -> f64 {
    (a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)
}

/// How the strokes of a scarp vary.
#[derive(Clone, Copy, PartialEq)]
enum Pattern {
    Even,
    Alternating,
    Wedge,
    DenseNearWall,
}

/// Strokes perpendicular to the outer face of the curtain and towers, starting at the wall,
/// sometimes closed by the ditch's outer edge drawn as a line.
pub(super) fn wall_hachures(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let out = Outside::new(lay, rng);
    let s = lay.radius.0.min(lay.radius.1);
    let sp = u(rng, 1.8, 4.5);
    let lw = u(rng, 0.8, 1.5);
    let base = (lay.t * u(rng, 0.5f64.ln(), 4f64.ln()).exp()).clamp(3.0, (s * 0.3).max(4.0));
    let pattern = [
        Pattern::Even,
        Pattern::Alternating,
        Pattern::Wedge,
        Pattern::DenseNearWall,
    ][rng.random_range(0..4)];
    let (m, ph, amp) = (
        rng.random_range(1..5) as f64,
        u(rng, 0.0, 2.0 * PI),
        u(rng, 0.0, 0.35),
    );
    let band = |a: f64| base * (1.0 + amp * (m * a + ph).sin());
    let seeds = out.seeds(if pattern == Pattern::DenseNearWall {
        sp * 0.6
    } else {
        sp
    });
    let nr = (lay.t * 0.8).max(4.0);
    let wedge = u(rng, 1.3, 2.5);
    for (k, &p) in seeds.iter().enumerate() {
        let n = rot(out.normal(p, nr), u(rng, -0.05, 0.05));
        let mut len = band(out.angle(p)) * u(rng, 0.85, 1.15);
        match pattern {
            Pattern::Alternating if k % 2 == 1 => len *= u(rng, 0.35, 0.6),
            Pattern::DenseNearWall if k % 2 == 1 => len *= u(rng, 0.2, 0.4),
            _ => {}
        }
        let start = sub(p, mul(n, 1.0));
        let len = out.reach(p, n, len);
        let end = add(p, mul(n, len));
        // The stroke and half the gap to its neighbours on either side.
        sheet.scarp_band(start, end, sp * 0.75 + lw);
        if pattern == Pattern::Wedge {
            taper(sheet, start, end, lw * wedge, 0.8);
        } else {
            sheet.line(start, end, lw, 0);
        }
    }
    if rng.random_bool(0.5) {
        let far = u(rng, 1.0, 1.4);
        let elw = u(rng, 1.0, 2.0);
        iso_line(sheet, &out, |a| band(a) * far, elw);
    }
}

/// Dense concentric lines following the outline of the castle at steady spacing, wobbling and
/// broken here and there, like the contour hachures of the antiquarian plans.
pub(super) fn hachure_bands(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let out = Outside::new(lay, rng);
    let s = lay.radius.0.min(lay.radius.1);
    let sp = u(rng, 2.5, 5.0);
    let lw = u(rng, 0.9, 1.5);
    let d0 = if rng.random_bool(0.6) {
        0.0
    } else {
        lay.t * u(rng, 0.3, 1.5)
    };
    let width = (lay.t * u(rng, 2.0, 8.0)).clamp(8.0, (s * 0.35).max(10.0));
    // Spacing that grows away from the wall (denser near it) when gamma < 1.
    let gamma = if rng.random_bool(0.4) {
        u(rng, 0.6, 0.9)
    } else {
        1.0
    };
    let (m, ph, amp) = (
        rng.random_range(3..12) as f64,
        u(rng, 0.0, 2.0 * PI),
        u(rng, 0.0, 1.2),
    );
    let (gap, key) = (u(rng, 0.0, 0.25), rng.random::<u64>());
    let dash = u(rng, 10.0, 40.0);
    let (w, h) = (out.foot.w, out.foot.h);
    for i in 0..w * h {
        let d = out.dist[i];
        if d == 0.0 || d < d0 || d > d0 + width {
            continue;
        }
        let p = ((i % w) as f64, (i / w) as f64);
        if !out.hachured(p) {
            continue;
        }
        sheet.scarp(i);
        let a = out.angle(p);
        let r = (d - d0).max(0.0);
        let warped = width * (r / width).powf(gamma) + amp * (m * a + ph + r * 0.2).sin();
        let ring = (warped / sp).floor();
        let f = warped / sp - ring;
        if f * sp >= lw {
            continue;
        }
        let piece = (a * s / dash).floor() as i64;
        let hsh = splitmix(key ^ ((ring as i64 as u64) << 32) ^ (piece as u64));
        if (hsh % 1000) as f64 / 1000.0 < gap {
            continue;
        }
        sheet.ink(i, 0);
    }
    if rng.random_bool(0.4) {
        let elw = u(rng, 1.0, 2.0);
        iso_line(sheet, &out, |_| d0 + width, elw);
    }
}

/// The curve at distance `at(angle)` from the footprint, on the hachured stretches.
fn iso_line(sheet: &mut Sheet, out: &Outside, at: impl Fn(f64) -> f64, lw: f64) {
    let w = out.foot.w;
    for i in 0..out.dist.len() {
        let d = out.dist[i];
        if d == 0.0 {
            continue;
        }
        let p = ((i % w) as f64, (i / w) as f64);
        if (d - at(out.angle(p))).abs() <= lw / 2.0 && out.hachured(p) {
            sheet.ink(i, 0);
        }
    }
}

/// A stroke from `a` (width `w0`) narrowing to `b` (width `w1`): a wedge.
fn taper(sheet: &mut Sheet, a: P, b: P, w0: f64, w1: f64) {
    let (w, h) = (sheet.truth.w, sheet.truth.h);
    let (lo, hi) = bbox(&[a, b], w0 / 2.0 + 1.0);
    let d = sub(b, a);
    let l2 = (d.0 * d.0 + d.1 * d.1).max(1e-12);
    let mut hits = Vec::new();
    scan(
        w,
        h,
        lo,
        hi,
        |p| {
            let q = sub(p, a);
            let s = ((q.0 * d.0 + q.1 * d.1) / l2).clamp(0.0, 1.0);
            let r = ((w0 + (w1 - w0) * s) / 2.0).max(0.55);
            (q.0 - s * d.0).hypot(q.1 - s * d.1) <= r
        },
        |i| hits.push(i),
    );
    hits.into_iter().for_each(|i| sheet.ink(i, 0));
}
