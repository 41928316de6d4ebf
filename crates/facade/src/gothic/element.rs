//! The Gothic element model of §4.1: Θ = [x0, y0, h, w, v], its constraint points p1…p5
//! (eq. 4.1) and its closed contour, sampled at sub-pixel arc-length steps for eq. 4.2.
//!
//! Image coordinates: x right, y down, so "up by h" is −h in y. (x0, y0) is the bottom-left
//! corner, h the jamb height, w the width and v the apex rise above the springing line y0 − h.

use serde::{Deserialize, Serialize};

use super::dual::Real;

/// Θ of §4.1 in image pixels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Theta {
    pub x0: f64,
    pub y0: f64,
    pub h: f64,
    pub w: f64,
    pub v: f64,
}

/// What the apex rise makes of the element (ARCHITECTURE.md, GOTHIC.json).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ArchKind {
    /// v = 0: a box.
    Rectangle,
    /// 0 < v < w/2: one arc through both springers and the apex (not in §4.1, which only has
    /// the two arcs; it makes the family continuous from the rectangle to the round arch).
    Segmental,
    /// v = w/2.
    Round,
    /// v > w/2: two arcs of radius (w²/4 + v²)/w centred on the springing line.
    Pointed,
}

/// A point on the contour and the arc length it stands for (`f64`, or [`Dual`](super::dual::Dual)
/// with their derivatives by Θ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample<R = f64> {
    pub x: R,
    pub y: R,
    pub ds: R,
}

/// How many samples each piece of the contour gets. Fixed during one optimisation so the
/// cost is a smooth function of Θ (a changing count would make it jump).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SampleCounts {
    pub sill: usize,
    pub jamb: usize,
    pub arch: usize,
}

/// Below this rise (px) the arch is drawn as a straight lintel: the segmental radius diverges.
const FLAT_RISE: f64 = 1e-3;

impl Theta {
    /// p1…p5 of eq. 4.1: p2 = p1 + [w, 0], p3 = p2 + [0, h], p5 = p1 + [0, h],
    /// p4 = (p3 + p5)/2 + [0, v], with "up" as −y.
    pub fn constraint_points(&self) -> [[f64; 2]; 5] {
        let p1 = [self.x0, self.y0];
        let p2 = [self.x0 + self.w, self.y0];
        let p3 = [p2[0], p2[1] - self.h];
        let p5 = [p1[0], p1[1] - self.h];
        let p4 = [(p3[0] + p5[0]) / 2.0, (p3[1] + p5[1]) / 2.0 - self.v];
        [p1, p2, p3, p4, p5]
    }

    /// y of the springing line (top of the jambs).
    pub fn springing(&self) -> f64 {
        self.y0 - self.h
    }

    /// y of the apex.
    pub fn apex(&self) -> f64 {
        self.y0 - self.h - self.v
    }

    /// [x_min, y_min, x_max, y_max].
    pub fn bbox(&self) -> [f64; 4] {
        [self.x0, self.apex(), self.x0 + self.w, self.y0]
    }

    /// Classification with `tol` px of slack around v = 0 and v = w/2.
    pub fn kind(&self, tol: f64) -> ArchKind {
        if self.v <= tol {
            ArchKind::Rectangle
        } else if (self.v - self.w / 2.0).abs() <= tol {
            ArchKind::Round
        } else if self.v < self.w / 2.0 {
            ArchKind::Segmental
        } else {
            ArchKind::Pointed
        }
    }

    /// Radius of the two arcs of a round or pointed arch.
    pub fn pointed_radius(&self) -> f64 {
        (self.w * self.w / 4.0 + self.v * self.v) / self.w
    }

    /// Radius of the single arc of a segmental arch.
    pub fn segmental_radius(&self) -> f64 {
        (self.w * self.w / 4.0 + self.v * self.v) / (2.0 * self.v)
    }

    /// Whether (x, y) is inside the element (its opening, jambs and arch).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        if x < self.x0 || x > self.x0 + self.w || y > self.y0 || y < self.apex() {
            return false;
        }
        let ys = self.springing();
        if y >= ys || self.v <= FLAT_RISE {
            return y >= ys;
        }
        if self.v >= self.w / 2.0 {
            let r = self.pointed_radius();
            let (cl, cr) = (self.x0 + r, self.x0 + self.w - r);
            let dl = (x - cl).hypot(y - ys);
            let dr = (x - cr).hypot(y - ys);
            dl <= r && dr <= r
        } else {
            let r = self.segmental_radius();
            let (cx, cy) = (self.x0 + self.w / 2.0, ys + r - self.v);
            (x - cx).hypot(y - cy) <= r
        }
    }

    /// The same shape grown by `t` px on every side (approximately, for the arch).
    pub fn grown(&self, t: f64) -> Theta {
        Theta {
            x0: self.x0 - t,
            y0: self.y0 + t,
            h: self.h + t,
            w: self.w + 2.0 * t,
            v: self.v + t,
        }
    }

    /// Lengths of the sill, one jamb and the whole arch.
    fn piece_lengths(&self) -> (f64, f64, f64) {
        let arch = if self.v <= FLAT_RISE {
            self.w
        } else if self.v >= self.w / 2.0 {
            let r = self.pointed_radius();
            2.0 * r * ((r - self.w / 2.0) / r).clamp(-1.0, 1.0).acos()
        } else {
            let r = self.segmental_radius();
            2.0 * r * (self.w / 2.0 / r).clamp(-1.0, 1.0).asin()
        };
        (self.w.abs(), self.h.abs(), arch)
    }

    /// The contour length ∮ ds.
    pub fn perimeter(&self) -> f64 {
        let (s, j, a) = self.piece_lengths();
        s + 2.0 * j + a
    }

    /// Counts that keep every sample step at or below `step` px for this Θ.
    pub fn counts(&self, step: f64) -> SampleCounts {
        let (s, j, a) = self.piece_lengths();
        let n = |len: f64| ((len / step).ceil() as usize).clamp(2, 100_000);
        SampleCounts {
            sill: n(s),
            jamb: n(j),
            arch: n(a),
        }
    }

    /// The contour p1 → p2 → p3 → (arch through p4) → p5 → p1 at the given counts, each piece
    /// split into equal arc-length steps, one sample at the middle of each step.
    pub fn contour(&self, counts: SampleCounts) -> Vec<Sample> {
        contour_of([self.x0, self.y0, self.h, self.w, self.v], counts)
    }

    /// Contour at sub-pixel steps of `step` px.
    pub fn contour_at(&self, step: f64) -> Vec<Sample> {
        self.contour(self.counts(step))
    }
}

/// [`Theta::contour`] over any [`Real`] Θ = [x0, y0, h, w, v]: with `f64` the contour itself,
/// with [`Dual`](super::dual::Dual) also ∂p/∂Θ and ∂ds/∂Θ of every sample (the analytic
/// gradient of eq. 4.2's integral). Which pieces make up the arch is decided on the values.
pub fn contour_of<R: Real>(theta: [R; 5], counts: SampleCounts) -> Vec<Sample<R>> {
    let [x0, y0, h, w, _] = theta;
    let mut out = Vec::with_capacity(counts.sill + 2 * counts.jamb + counts.arch + 1);
    let p1 = [x0, y0];
    let p2 = [x0 + w, y0];
    let p3 = [p2[0], p2[1] - h];
    let p5 = [p1[0], p1[1] - h];
    line(&mut out, p1, p2, counts.sill);
    line(&mut out, p2, p3, counts.jamb);
    arch(&mut out, theta, counts.arch);
    line(&mut out, p5, p1, counts.jamb);
    out
}

fn arch<R: Real>(out: &mut Vec<Sample<R>>, theta: [R; 5], n: usize) {
    let [x0, y0, h, w, v] = theta;
    let ys = y0 - h;
    let half_w = w.scale(0.5);
    if v.value() <= FLAT_RISE {
        line(out, [x0 + w, ys], [x0, ys], n);
    } else if v.value() >= half_w.value() {
        // Right arc p3 → p4 is centred left of p3, the left arc p4 → p5 right of p5.
        let r = (w * w.scale(0.25) + v * v) / w;
        let phi = ((r - half_w) / r).acos_clamped();
        let half = n.div_ceil(2);
        let right = x0 + w - r;
        let left = x0 + r;
        let pi = R::constant(std::f64::consts::PI);
        arc(out, [right, ys], r, R::constant(0.0), phi, half);
        arc(out, [left, ys], r, pi - phi, pi, half);
    } else {
        let r = (w * w.scale(0.25) + v * v) / v.scale(2.0);
        let alpha = (half_w / r).asin_clamped();
        let c = [x0 + half_w, ys + r - v];
        let mid = R::constant(std::f64::consts::FRAC_PI_2);
        arc(out, c, r, mid - alpha, mid + alpha, n);
    }
}

fn line<R: Real>(out: &mut Vec<Sample<R>>, a: [R; 2], b: [R; 2], n: usize) {
    let len = (b[0] - a[0]).hypot(b[1] - a[1]);
    let ds = len.scale(1.0 / n as f64);
    for i in 0..n {
        let t = (i as f64 + 0.5) / n as f64;
        out.push(Sample {
            x: a[0] + (b[0] - a[0]).scale(t),
            y: a[1] + (b[1] - a[1]).scale(t),
            ds,
        });
    }
}

/// Counter-clockwise on screen (angles measured upwards, y down) from `from` to `to`.
fn arc<R: Real>(out: &mut Vec<Sample<R>>, c: [R; 2], r: R, from: R, to: R, n: usize) {
    let sweep = to - from;
    let ds = r * sweep.scale(sweep.value().signum() / n as f64);
    for i in 0..n {
        let a = from + sweep.scale((i as f64 + 0.5) / n as f64);
        out.push(Sample {
            x: c[0] + r * a.cos(),
            y: c[1] - r * a.sin(),
            ds,
        });
    }
}

impl Theta {
    /// Whether this element contains `inner` with `tol` px of slack: the corners and apex of
    /// `inner` lie inside this one grown by `tol`, and this one is larger (figure 4.4's
    /// nesting; [`hierarchy::contains`](super::hierarchy::contains)).
    pub fn encloses(&self, inner: &Theta, tol: f64) -> bool {
        let g = self.grown(tol);
        let big = self.w * (self.h + self.v) > 1.2 * inner.w * (inner.h + inner.v);
        big && inner
            .constraint_points()
            .iter()
            .all(|p| g.contains(p[0], p[1]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn theta(v: f64) -> Theta {
        Theta {
            x0: 10.0,
            y0: 100.0,
            h: 40.0,
            w: 20.0,
            v,
        }
    }

    #[test]
    fn constraint_points_follow_eq_4_1() {
        let [p1, p2, p3, p4, p5] = theta(15.0).constraint_points();
        assert_eq!(p1, [10.0, 100.0]);
        assert_eq!(p2, [30.0, 100.0]);
        assert_eq!(p3, [30.0, 60.0]);
        assert_eq!(p5, [10.0, 60.0]);
        assert_eq!(p4, [20.0, 45.0]);
    }

    #[test]
    fn contour_passes_through_the_apex_and_has_the_right_length() {
        for v in [0.0, 5.0, 10.0, 15.0] {
            let t = theta(v);
            let s = t.contour_at(0.25);
            assert!(s.iter().all(|p| p.ds <= 0.25 + 1e-9));
            let len: f64 = s.iter().map(|p| p.ds).sum();
            assert!((len - t.perimeter()).abs() < 1e-6, "v={v}");
            let top = s.iter().map(|p| p.y).fold(f64::MAX, f64::min);
            assert!((top - t.apex()).abs() < 0.05, "v={v}: {top}");
        }
        // A round arch's arc is a half circle of radius w/2.
        let round = theta(10.0);
        assert!((round.perimeter() - (20.0 + 80.0 + std::f64::consts::PI * 10.0)).abs() < 1e-9);
    }

    #[test]
    fn every_contour_sample_lies_on_the_boundary_of_the_inside() {
        for v in [0.0, 6.0, 10.0, 16.0] {
            let t = theta(v);
            for p in t.contour_at(1.0) {
                let inner = t.contains(p.x * 0.98 + 20.0 * 0.02, p.y * 0.98 + 80.0 * 0.02);
                let outer = t.contains(p.x * 1.02 - 20.0 * 0.02, p.y * 1.02 - 80.0 * 0.02);
                assert!(inner && !outer, "v={v} at ({}, {})", p.x, p.y);
            }
        }
    }

    #[test]
    fn kinds() {
        assert_eq!(theta(0.0).kind(0.5), ArchKind::Rectangle);
        assert_eq!(theta(4.0).kind(0.5), ArchKind::Segmental);
        assert_eq!(theta(10.2).kind(0.5), ArchKind::Round);
        assert_eq!(theta(14.0).kind(0.5), ArchKind::Pointed);
    }
}
