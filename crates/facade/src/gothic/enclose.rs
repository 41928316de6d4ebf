//! The enclosing arch of a group searched over a grid of Θ (issue 23): the arch of a real
//! two- or three-light window is usually the wall itself inside a moulding line, so nothing
//! but that line marks it, and the CG of [`hierarchy::enclosing`](super::hierarchy) started
//! from a dozen guesses settles on the mortar joints of the bricks around it.
//!
//! Departure from §4.2, which maximises eq. 4.2 from proposals: the same ∮D ds (D clipped at
//! [`CLIP`] px so one gap in the moulding does not outweigh the rest) is evaluated over every
//! arch centred on the group — half-width, sill, springing line and rise on a grid of
//! [`grid_step`] px — as sums: the sill and the jambs from prefix sums of D along rows and
//! columns, the arch from its own samples, so the grid of thousands of arches costs about as
//! much as a few CG runs. The best few distinct shapes are then maximised by CG like any
//! element (the centring is not kept).

use super::detect::{Candidate, iou};
use super::element::{SampleCounts, Theta, contour_of};
use super::likelihood::{DistanceMap, fit};
use super::optimise::maximise;
use super::params::GothicParams;

/// D is clipped here (px) for the grid: a contour off the moulding is bad whether it is 4 or
/// 20 px off, and a few pixels of missing edge should not decide.
pub const CLIP: f64 = 4.0;

/// Grid step (px) for members of mean width `w`: one pixel up to 30 px wide members, then
/// 1/30 of their width (the grid's size stays the same at any scale).
pub fn grid_step(w: f64) -> f64 {
    (w / 30.0).max(1.0)
}

/// How many distinct grid optima are refined by CG.
const REFINED: usize = 6;

/// Prefix sums of clipped D along rows and along columns.
struct Sums {
    w: usize,
    h: usize,
    /// rows[y * (w + 1) + x] = Σ_{k < x} D(k, y)
    rows: Vec<f64>,
    /// cols[x * (h + 1) + y] = Σ_{k < y} D(x, k)
    cols: Vec<f64>,
}

impl Sums {
    fn of(dt: &DistanceMap) -> Sums {
        let (w, h) = (dt.width, dt.height);
        let mut rows = vec![0.0; (w + 1) * h];
        let mut cols = vec![0.0; (h + 1) * w];
        for y in 0..h {
            for x in 0..w {
                let d = (dt.get(x, y) as f64).min(CLIP);
                rows[y * (w + 1) + x + 1] = rows[y * (w + 1) + x] + d;
                cols[x * (h + 1) + y + 1] = cols[x * (h + 1) + y] + d;
            }
        }
        Sums { w, h, rows, cols }
    }

    /// Σ D over a horizontal line at row y (rounded) from xa to xb; CLIP per px off the image.
    fn row(&self, y: f64, xa: f64, xb: f64) -> f64 {
        let yi = y.round();
        if yi < 0.0 || yi >= self.h as f64 {
            return CLIP * (xb - xa).abs();
        }
        let base = yi as usize * (self.w + 1);
        let at = |x: f64| {
            let x = x.clamp(0.0, self.w as f64);
            let i = x.floor() as usize;
            let f = x - i as f64;
            let a = self.rows[base + i];
            let b = self.rows[base + (i + 1).min(self.w)];
            a + (b - a) * f
        };
        let outside = (xb.max(self.w as f64) - self.w as f64) + (-xa).max(0.0);
        at(xb) - at(xa) + CLIP * outside
    }

    /// Σ D over a vertical line at column x (rounded) from ya to yb.
    fn col(&self, x: f64, ya: f64, yb: f64) -> f64 {
        let xi = x.round();
        if xi < 0.0 || xi >= self.w as f64 {
            return CLIP * (yb - ya).abs();
        }
        let base = xi as usize * (self.h + 1);
        let at = |y: f64| {
            let y = y.clamp(0.0, self.h as f64);
            let i = y.floor() as usize;
            let f = y - i as f64;
            let a = self.cols[base + i];
            let b = self.cols[base + (i + 1).min(self.h)];
            a + (b - a) * f
        };
        let outside = (yb.max(self.h as f64) - self.h as f64) + (-ya).max(0.0);
        at(yb) - at(ya) + CLIP * outside
    }
}

/// ∮ clipped D ds and ∮ ds over the arch of Θ (springing line to apex and back), at 1-px steps.
fn arch_sum(dt: &DistanceMap, t: &Theta) -> (f64, f64) {
    let n = (t.perimeter() - t.w - 2.0 * t.h).ceil().max(4.0) as usize;
    let counts = SampleCounts {
        sill: 1,
        jamb: 1,
        arch: n,
    };
    let samples = contour_of([t.x0, t.y0, t.h, t.w, t.v], counts);
    samples[2..2 + n].iter().fold((0.0, 0.0), |(i, l), s| {
        (i + dt.at(s.x, s.y).min(CLIP) * s.ds, l + s.ds)
    })
}

/// The best arch enclosing every member on the grid, refined by CG: significant, plausible,
/// containing every member with at least 2 px to spare at the sides. None when no arch on the
/// grid passes.
pub fn search(dt: &DistanceMap, members: &[Theta], params: &GothicParams) -> Option<Candidate> {
    use rayon::prelude::*;
    if members.is_empty() {
        return None;
    }
    let left = members.iter().map(|t| t.x0).fold(f64::MAX, f64::min);
    let right = members.iter().map(|t| t.x0 + t.w).fold(f64::MIN, f64::max);
    let bottom = members.iter().map(|t| t.y0).fold(f64::MIN, f64::max);
    let apex = members.iter().map(|t| t.apex()).fold(f64::MAX, f64::min);
    let spring = members
        .iter()
        .map(|t| t.springing())
        .fold(f64::MAX, f64::min);
    let mean_w = members.iter().map(|t| t.w).sum::<f64>() / members.len() as f64;
    let step = grid_step(mean_w);
    let cx = (left + right) / 2.0;
    let half0 = (right - left) / 2.0;
    let side = reach(members);
    let count = |span: f64| (span.max(0.0) / step).floor() as usize + 1;
    let margins: Vec<f64> = (0..count(side - 2.0))
        .map(|i| 2.0 + i as f64 * step)
        .collect();
    let sills: Vec<f64> = (0..count(side))
        .map(|i| bottom + 1.0 + i as f64 * step)
        .collect();
    let up = 1.5 * mean_w;
    let springs: Vec<f64> = (0..count(spring - (apex - up)))
        .map(|i| spring - i as f64 * step)
        .collect();
    let rises: Vec<f64> = (0..15).map(|i| 0.3 + 0.05 * i as f64).collect();
    // Departure from §4.2: a grid of arches scored by the clipped ∮D ds, not CG from proposals.
    let sums = Sums::of(dt);
    // For every half-width: each (springing, rise) arch's sum, then every sill in O(1).
    let mut best: Vec<(f64, Theta)> = margins
        .par_iter()
        .flat_map_iter(|&m| {
            let a = half0 + m;
            let (x0, x1) = (cx - a, cx + a);
            let mut out: Vec<(f64, Theta)> = Vec::new();
            for &ys in &springs {
                for &r in &rises {
                    let v = r * 2.0 * a;
                    if ys - v < 0.0 {
                        continue;
                    }
                    let probe = Theta {
                        x0,
                        y0: ys,
                        h: 0.0,
                        w: 2.0 * a,
                        v,
                    };
                    let (ai, al) = arch_sum(dt, &probe);
                    let mut row_best: Option<(f64, Theta)> = None;
                    for &y0 in &sills {
                        let jambs = sums.col(x0, ys, y0) + sums.col(x1, ys, y0);
                        let sill = sums.row(y0, x0, x1);
                        let len = al + 2.0 * (y0 - ys) + 2.0 * a;
                        let mean = (ai + jambs + sill) / len;
                        if row_best.is_none_or(|(b, _)| mean < b) {
                            row_best = Some((
                                mean,
                                Theta {
                                    x0,
                                    y0,
                                    h: y0 - ys,
                                    w: 2.0 * a,
                                    v,
                                },
                            ));
                        }
                    }
                    out.extend(row_best);
                }
            }
            out
        })
        .collect();
    best.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut distinct: Vec<Theta> = Vec::new();
    for (_, t) in best {
        if distinct.iter().all(|d| iou(d, &t) < 0.8) {
            distinct.push(t);
            if distinct.len() >= REFINED {
                break;
            }
        }
    }
    let bounds = params.bounds();
    let mut found: Vec<Candidate> = distinct
        .par_iter()
        .flat_map_iter(|&t| {
            let refined = maximise(dt, t, params.step, bounds, params.max_iters);
            [t, refined]
        })
        .filter_map(|theta| {
            let f = fit(dt, &theta, params.step);
            let ok = super::detect::plausible(&theta, bounds, dt.width, dt.height)
                && super::detect::significant(&f, params)
                && within_reach(&theta, members)
                && members.iter().all(|m| encloses(&theta, m, params));
            ok.then_some(Candidate { theta, fit: f })
        })
        .collect();
    found.sort_by(|a, b| a.fit.mean_distance.total_cmp(&b.fit.mean_distance));
    found.into_iter().next()
}

/// How far (px) an enclosing arch's jambs and sill may stand from the group's outer members:
/// 1.5 of the gaps between members or half a member's width, whichever is more, plus 2 px.
/// Departure from §4.2 (issue 23): around the lancets of one sub-arch of a tracery window the
/// jambs of the outer arch and of the other sub-arch are long straight edges too, and an arch
/// standing on them fits eq. 4.2 as well as the sub-arch itself; a window's mouldings keep
/// to the rhythm of its lights, so the search stays within this reach.
pub fn reach(members: &[Theta]) -> f64 {
    let mean_w = members.iter().map(|t| t.w).sum::<f64>() / members.len().max(1) as f64;
    let mut sorted: Vec<&Theta> = members.iter().collect();
    sorted.sort_by(|a, b| a.x0.total_cmp(&b.x0));
    let gap = sorted
        .windows(2)
        .map(|p| p[1].x0 - p[0].x0 - p[0].w)
        .fold(f64::INFINITY, f64::min);
    let gap = if gap.is_finite() { gap.max(0.0) } else { 0.0 };
    (1.5 * gap).max(0.5 * mean_w) + 2.0
}

/// Whether an arch's jambs and sill stand within [`reach`] of the group (see there).
pub fn within_reach(outer: &Theta, members: &[Theta]) -> bool {
    let r = reach(members);
    let left = members.iter().map(|t| t.x0).fold(f64::MAX, f64::min);
    let right = members.iter().map(|t| t.x0 + t.w).fold(f64::MIN, f64::max);
    let bottom = members.iter().map(|t| t.y0).fold(f64::MIN, f64::max);
    left - outer.x0 <= r + 2.0
        && outer.x0 + outer.w - right <= r + 2.0
        && outer.y0 - bottom <= r + 2.0
}

/// Containment for an enclosing arch: [`Theta::encloses`] with the
/// nesting slack, and the jambs at least 2 px outside the member's (a contour on the member's
/// own jamb would fit eq. 4.2 perfectly and enclose nothing).
fn encloses(outer: &Theta, inner: &Theta, params: &GothicParams) -> bool {
    outer.encloses(inner, params.nesting_tolerance)
        && outer.x0 <= inner.x0 - 2.0
        && outer.x0 + outer.w >= inner.x0 + inner.w + 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_sums_match_the_map() {
        let dt = DistanceMap {
            width: 5,
            height: 4,
            d: (0..20).map(|i| (i % 7) as f32 * 0.5).collect(),
            outside: 10.0,
        };
        let s = Sums::of(&dt);
        let direct_row: f64 = (1..4).map(|x| (dt.get(x, 2) as f64).min(CLIP)).sum();
        assert!((s.row(2.0, 1.0, 4.0) - direct_row).abs() < 1e-9);
        let direct_col: f64 = (0..3).map(|y| (dt.get(3, y) as f64).min(CLIP)).sum();
        assert!((s.col(3.0, 0.0, 3.0) - direct_col).abs() < 1e-9);
        // Off the image every pixel costs CLIP.
        assert!((s.col(9.0, 0.0, 2.0) - 2.0 * CLIP).abs() < 1e-9);
    }
}
