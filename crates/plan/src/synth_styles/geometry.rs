//! Points, the seeded random source, and boolean pixel layers (walls, clutter) for the
//! synthetic drawings.

use image::GrayImage;
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

pub(super) type P = (f64, f64);
pub(super) type Rng = ChaCha8Rng;

/// Uniform in [a, b), or a when the range is empty.
pub(super) fn u(rng: &mut Rng, a: f64, b: f64) -> f64 {
    if b > a { rng.random_range(a..b) } else { a }
}

pub(super) fn add(a: P, b: P) -> P {
    (a.0 + b.0, a.1 + b.1)
}
pub(super) fn sub(a: P, b: P) -> P {
    (a.0 - b.0, a.1 - b.1)
}
pub(super) fn mul(a: P, k: f64) -> P {
    (a.0 * k, a.1 * k)
}
pub(super) fn lerp(a: P, b: P, s: f64) -> P {
    add(a, mul(sub(b, a), s))
}
pub(super) fn unit(a: P) -> P {
    let n = a.0.hypot(a.1).max(1e-9);
    (a.0 / n, a.1 / n)
}
pub(super) fn rot(a: P, ang: f64) -> P {
    let (s, c) = ang.sin_cos();
    (a.0 * c - a.1 * s, a.0 * s + a.1 * c)
}

pub(super) fn seg_dist(p: P, a: P, b: P) -> f64 {
    let (d, q) = (sub(b, a), sub(p, a));
    let l2 = (d.0 * d.0 + d.1 * d.1).max(1e-12);
    let s = ((q.0 * d.0 + q.1 * d.1) / l2).clamp(0.0, 1.0);
    (q.0 - s * d.0).hypot(q.1 - s * d.1)
}

pub(super) fn inside_poly(p: P, pts: &[P]) -> bool {
    let mut inside = false;
    for k in 0..pts.len() {
        let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < a.0 + (p.1 - a.1) / (b.1 - a.1) * (b.0 - a.0) {
            inside = !inside;
        }
    }
    inside
}

/// Calls `f` for every pixel of a `w` × `h` sheet in the box lo..hi where `pred` holds.
pub(super) fn scan(
    w: usize,
    h: usize,
    lo: P,
    hi: P,
    pred: impl Fn(P) -> bool,
    mut f: impl FnMut(usize),
) {
    let x0 = lo.0.floor().max(0.0) as usize;
    let y0 = lo.1.floor().max(0.0) as usize;
    let x1 = (hi.0.ceil() + 1.0).clamp(0.0, w as f64) as usize;
    let y1 = (hi.1.ceil() + 1.0).clamp(0.0, h as f64) as usize;
    for y in y0..y1 {
        for x in x0..x1 {
            if pred((x as f64, y as f64)) {
                f(y * w + x);
            }
        }
    }
}

pub(super) fn bbox(pts: &[P], pad: f64) -> (P, P) {
    let lo = pts
        .iter()
        .fold((f64::MAX, f64::MAX), |m, p| (m.0.min(p.0), m.1.min(p.1)));
    let hi = pts
        .iter()
        .fold((f64::MIN, f64::MIN), |m, p| (m.0.max(p.0), m.1.max(p.1)));
    ((lo.0 - pad, lo.1 - pad), (hi.0 + pad, hi.1 + pad))
}

/// A boolean layer of a sheet.
#[derive(Clone)]
pub(super) struct Mask {
    pub(super) w: usize,
    pub(super) h: usize,
    pub(super) m: Vec<bool>,
}

impl Mask {
    pub(super) fn new(w: u32, h: u32) -> Mask {
        let (w, h) = (w as usize, h as usize);
        Mask {
            w,
            h,
            m: vec![false; w * h],
        }
    }
    /// A wall of thickness `t` from a to b (set to `v`).
    pub(super) fn wall(&mut self, a: P, b: P, t: f64, v: bool) {
        let (lo, hi) = bbox(&[a, b], t / 2.0 + 1.0);
        let m = &mut self.m;
        scan(
            self.w,
            self.h,
            lo,
            hi,
            |p| seg_dist(p, a, b) <= t / 2.0,
            |i| m[i] = v,
        );
    }
    pub(super) fn poly(&mut self, pts: &[P], t: f64) {
        for k in 0..pts.len() {
            self.wall(pts[k], pts[(k + 1) % pts.len()], t, true);
        }
    }
    pub(super) fn disc(&mut self, c: P, r: f64, v: bool) {
        let m = &mut self.m;
        let pred = |p: P| (p.0 - c.0).hypot(p.1 - c.1) <= r;
        scan(self.w, self.h, sub(c, (r, r)), add(c, (r, r)), pred, |i| {
            m[i] = v
        });
    }
    pub(super) fn fill(&mut self, pts: &[P], v: bool) {
        let (lo, hi) = bbox(pts, 1.0);
        let m = &mut self.m;
        scan(
            self.w,
            self.h,
            lo,
            hi,
            |p| inside_poly(p, pts),
            |i| m[i] = v,
        );
    }
    pub(super) fn minus(&self, o: &Mask) -> Mask {
        let m = self.m.iter().zip(&o.m).map(|(a, b)| *a && !*b).collect();
        Mask { m, ..*self }
    }
    pub(super) fn or(&self, o: &Mask) -> Mask {
        let m = self.m.iter().zip(&o.m).map(|(a, b)| *a || *b).collect();
        Mask { m, ..*self }
    }
    #[cfg(test)]
    pub(super) fn count(&self) -> usize {
        self.m.iter().filter(|v| **v).count()
    }
    pub(super) fn to_gray(&self) -> GrayImage {
        let px = self.m.iter().map(|&v| if v { 255 } else { 0 }).collect();
        GrayImage::from_raw(self.w as u32, self.h as u32, px).expect("size")
    }
}
