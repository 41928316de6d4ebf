//! Pens and strokes: an ink layer (0 paper … 1 full ink) with an owner map saying which wall,
//! roof or opening every pixel belongs to, and anti-aliased strokes clipped to owners.
//!
//! Ink combines by maximum, so crossing strokes do not darken past full ink and a polyline's
//! overlapping pieces do not thicken it.

use super::basics::{Rng, uniform};

/// A point (x, y) in pixels; pixel (x, y) has its centre at (x + 0.5, y + 0.5).
pub(super) type P = [f64; 2];

/// Where a stroke may ink: called with the pixel and its owner.
pub(super) type Clip<'a> = &'a dyn Fn(usize, usize, u16) -> bool;

/// Any pixel.
pub(super) fn anywhere(_: usize, _: usize, _: u16) -> bool {
    true
}

/// The ink layer and its owners.
#[derive(Debug, Clone)]
pub(super) struct Canvas {
    pub w: usize,
    pub h: usize,
    pub ink: Vec<f32>,
    pub owner: Vec<u16>,
    /// Depth layer of each owner id (the mass it belongs to; -1 for paper and unknown ids).
    layer: Vec<i16>,
}

impl Canvas {
    pub fn new(w: usize, h: usize) -> Canvas {
        Canvas {
            w,
            h,
            ink: vec![0.0; w * h],
            owner: vec![0; w * h],
            layer: Vec::new(),
        }
    }

    pub fn set_layer(&mut self, id: u16, layer: usize) {
        let i = id as usize;
        if self.layer.len() <= i {
            self.layer.resize(i + 1, -1);
        }
        self.layer[i] = layer as i16;
    }

    /// Depth layer of an owner id: -1 for paper.
    pub fn layer(&self, id: u16) -> i16 {
        self.layer.get(id as usize).copied().unwrap_or(-1)
    }

    pub fn owner_at(&self, x: usize, y: usize) -> u16 {
        self.owner[y * self.w + x]
    }

    /// The pixel range [lo, hi] whose centres may lie in [a, b] along an axis of `n` pixels.
    fn span(a: f64, b: f64, n: usize) -> std::ops::RangeInclusive<usize> {
        let lo = (a - 0.5).floor().max(0.0) as usize;
        let hi = ((b - 0.5).ceil() as i64).min(n as i64 - 1);
        if hi < lo as i64 {
            return std::ops::RangeInclusive::new(1, 0);
        }
        lo..=hi as usize
    }

    /// Gives pixels of `rect` whose centres satisfy `inside` to owner `id`.
    pub fn claim(&mut self, id: u16, rect: [f64; 4], inside: impl Fn(f64, f64) -> bool) {
        for y in Self::span(rect[1], rect[3], self.h) {
            for x in Self::span(rect[0], rect[2], self.w) {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                if px >= rect[0]
                    && px <= rect[2]
                    && py >= rect[1]
                    && py <= rect[3]
                    && inside(px, py)
                {
                    self.owner[y * self.w + x] = id;
                }
            }
        }
    }

    #[inline]
    fn dab(&mut self, x: usize, y: usize, a: f32, clip: Clip) {
        let i = y * self.w + x;
        if a > self.ink[i] && clip(x, y, self.owner[i]) {
            self.ink[i] = a.min(1.0);
        }
    }

    /// Every pixel of `rect` the clip allows, inked to `strength`.
    pub fn fill(&mut self, rect: [f64; 4], strength: f32, clip: Clip) {
        for y in Self::span(rect[1], rect[3], self.h) {
            for x in Self::span(rect[0], rect[2], self.w) {
                self.dab(x, y, strength, clip);
            }
        }
    }

    /// A straight stroke of `width` px with round caps.
    pub fn segment(&mut self, a: P, b: P, width: f64, strength: f32, clip: Clip) {
        let reach = 0.5 * width.max(0.3) + 0.5;
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len2 = dx * dx + dy * dy;
        let cover = |px: f64, py: f64| {
            let t = if len2 > 1e-12 {
                (((px - a[0]) * dx + (py - a[1]) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let d = (px - a[0] - t * dx).hypot(py - a[1] - t * dy);
            (reach - d).clamp(0.0, 1.0) as f32 * strength
        };
        // Scan along the major axis, across it only as far as the stroke reaches.
        let steep = dy.abs() > dx.abs();
        let (u0, u1, du, dv, v0, nu, nv) = if steep {
            (a[1], b[1], dy, dx, a[0], self.h, self.w)
        } else {
            (a[0], b[0], dx, dy, a[1], self.w, self.h)
        };
        let slope = if du.abs() > 1e-12 { dv / du } else { 0.0 };
        let half = reach * (1.0 + slope * slope).sqrt() + 1.0;
        for u in Self::span(u0.min(u1) - reach, u0.max(u1) + reach, nu) {
            let pu = u as f64 + 0.5;
            let t = if du.abs() > 1e-12 {
                ((pu - u0) / du).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let vc = v0 + t * dv;
            for v in Self::span(vc - half, vc + half, nv) {
                let pv = v as f64 + 0.5;
                let (x, y) = if steep { (v, u) } else { (u, v) };
                let c = if steep { cover(pv, pu) } else { cover(pu, pv) };
                if c > 0.0 {
                    self.dab(x, y, c, clip);
                }
            }
        }
    }

    /// Strokes through `pts`, closed back to the first when `closed`.
    pub fn polyline(&mut self, pts: &[P], closed: bool, width: f64, strength: f32, clip: Clip) {
        for pair in pts.windows(2) {
            self.segment(pair[0], pair[1], width, strength, clip);
        }
        if closed && pts.len() > 2 {
            self.segment(pts[pts.len() - 1], pts[0], width, strength, clip);
        }
    }

    /// A line drawn by hand: pieces of about 15 px, each end moved across the line by a
    /// random walk of at most `wobble` px.
    #[allow(clippy::too_many_arguments)]
    pub fn hand(
        &mut self,
        rng: &mut Rng,
        a: P,
        b: P,
        width: f64,
        strength: f32,
        wobble: f64,
        clip: Clip,
    ) {
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        if wobble <= 0.0 || len < 20.0 {
            self.segment(a, b, width, strength, clip);
            return;
        }
        let n = (len / 15.0).ceil() as usize;
        let (nx, ny) = (-(b[1] - a[1]) / len, (b[0] - a[0]) / len);
        let mut off = 0.0;
        let pts: Vec<P> = (0..=n)
            .map(|i| {
                let t = i as f64 / n as f64;
                if i > 0 && i < n {
                    off = (off + uniform(rng, -0.6, 0.6) * wobble).clamp(-wobble, wobble);
                } else {
                    off = 0.0;
                }
                [
                    a[0] + t * (b[0] - a[0]) + nx * off,
                    a[1] + t * (b[1] - a[1]) + ny * off,
                ]
            })
            .collect();
        self.polyline(&pts, false, width, strength, clip);
    }

    /// Parallel lines at `angle` (radians, 0 = horizontal, y down) every `spacing` px across
    /// `rect`, each moved by up to `jitter` px and inked at 75–100 % of `strength`.
    #[allow(clippy::too_many_arguments)]
    pub fn hatch(
        &mut self,
        rng: &mut Rng,
        rect: [f64; 4],
        angle: f64,
        spacing: f64,
        width: f64,
        strength: f32,
        jitter: f64,
        clip: Clip,
    ) {
        let spacing = spacing.max(1.0);
        let (d, n) = ([angle.cos(), angle.sin()], [-angle.sin(), angle.cos()]);
        let r = [
            rect[0] - width,
            rect[1] - width,
            rect[2] + width,
            rect[3] + width,
        ];
        let corners = [[r[0], r[1]], [r[2], r[1]], [r[0], r[3]], [r[2], r[3]]];
        let proj = |v: [f64; 2], p: &P| v[0] * p[0] + v[1] * p[1];
        let (mut nmin, mut nmax, mut tmin, mut tmax) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for c in &corners {
            nmin = nmin.min(proj(n, c));
            nmax = nmax.max(proj(n, c));
            tmin = tmin.min(proj(d, c));
            tmax = tmax.max(proj(d, c));
        }
        let mut s = nmin + uniform(rng, 0.0, spacing);
        while s <= nmax {
            let o = s + uniform(rng, -jitter, jitter);
            let a = [n[0] * o + d[0] * tmin, n[1] * o + d[1] * tmin];
            let b = [n[0] * o + d[0] * tmax, n[1] * o + d[1] * tmax];
            if let Some((p, q)) = clip_to(a, b, r) {
                let k = strength * uniform(rng, 0.75, 1.0) as f32;
                self.segment(p, q, width, k, clip);
            }
            s += spacing;
        }
    }

    /// A filled disc.
    pub fn disc(&mut self, c: P, radius: f64, strength: f32, clip: Clip) {
        let reach = radius + 0.5;
        for y in Self::span(c[1] - reach, c[1] + reach, self.h) {
            for x in Self::span(c[0] - reach, c[0] + reach, self.w) {
                let d = (x as f64 + 0.5 - c[0]).hypot(y as f64 + 0.5 - c[1]);
                let a = (reach - d).clamp(0.0, 1.0) as f32 * strength;
                if a > 0.0 {
                    self.dab(x, y, a, clip);
                }
            }
        }
    }
}

/// The part of segment a–b inside `r` = [x0, y0, x1, y1] (Liang–Barsky).
pub(super) fn clip_to(a: P, b: P, r: [f64; 4]) -> Option<(P, P)> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a[0] - r[0]),
        (dx, r[2] - a[0]),
        (-dy, a[1] - r[1]),
        (dy, r[3] - a[1]),
    ] {
        if p.abs() < 1e-12 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t0 <= t1).then(|| {
        (
            [a[0] + t0 * dx, a[1] + t0 * dy],
            [a[0] + t1 * dx, a[1] + t1 * dy],
        )
    })
}
