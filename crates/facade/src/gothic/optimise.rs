//! Local maximisation of eq. 4.2 by nonlinear conjugate gradient (§4.2; `argmin`'s
//! Polak–Ribière CG with a Moré–Thuente line search), for one element or for a group of
//! elements sharing (h, w, v) with one (x0, y0) each (the joint re-estimation of §4.2).

use argmin::core::{CostFunction, Error, Executor, Gradient, State};
use argmin::solver::conjugategradient::NonlinearConjugateGradient;
use argmin::solver::conjugategradient::beta::PolakRibiere;
use argmin::solver::linesearch::MoreThuenteLineSearch;

use super::element::{SampleCounts, Theta};
use super::likelihood::DistanceMap;

/// Bounds the optimiser keeps Θ within, by a quadratic penalty (CG is unconstrained).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeBounds {
    pub min_width: f64,
    pub min_height: f64,
}

/// Penalty weight per px² outside the bounds: a few px outside costs more than any fit gains.
const PENALTY: f64 = 0.5;
/// Central-difference step (px): half a pixel smooths the kinks of the bilinear D.
const FD_STEP: f64 = 0.5;

/// Parameters → shapes: `shared` means [h, w, a, x0_1, y0_1, …], otherwise [x0, y0, h, w, a],
/// with a = h + v the total height. Optimising a instead of v makes "lower the springing
/// line at a fixed apex" (round → pointed) one coordinate instead of a diagonal valley, in
/// which CG stalls on the kinks of D.
#[derive(Debug, Clone)]
struct ContourCost<'a> {
    dt: &'a DistanceMap,
    counts: Vec<SampleCounts>,
    shared: bool,
    bounds: ShapeBounds,
}

fn shapes(p: &[f64], shared: bool) -> Vec<Theta> {
    if shared {
        p[3..]
            .chunks_exact(2)
            .map(|xy| Theta {
                x0: xy[0],
                y0: xy[1],
                h: p[0],
                w: p[1],
                v: p[2] - p[0],
            })
            .collect()
    } else {
        vec![Theta {
            x0: p[0],
            y0: p[1],
            h: p[2],
            w: p[3],
            v: p[4] - p[2],
        }]
    }
}

impl ContourCost<'_> {
    /// Σ∮ρ(D) ds / Σ∮ds plus the bound penalty. Departures from eq. 4.2: (1) the raw
    /// integral is smallest for a vanishing contour, so the mean per unit length is minimised;
    /// (2) ρ(D) = √(D² + 1) − 1 (≈ D − 1 away from edges, quadratic on them) replaces D so
    /// the cost is smooth at its minimum, where D's V-shaped kink stops the CG line search.
    /// Reported fits (`likelihood::fit`) use D itself.
    fn value(&self, p: &[f64]) -> f64 {
        let shapes = shapes(p, self.shared);
        let (mut integral, mut len) = (0.0, 0.0);
        for (t, c) in shapes.iter().zip(&self.counts) {
            for s in t.contour(*c) {
                let d = self.dt.at(s.x, s.y);
                integral += ((d * d + 1.0).sqrt() - 1.0) * s.ds;
                len += s.ds;
            }
        }
        let t = shapes[0];
        let low = |x: f64, min: f64| if x < min { (min - x).powi(2) } else { 0.0 };
        let penalty = low(t.w, self.bounds.min_width)
            + low(t.h, 0.0)
            + low(t.v, 0.0)
            + low(t.h + t.v, self.bounds.min_height);
        if len > 0.0 {
            integral / len + PENALTY * penalty
        } else {
            f64::MAX
        }
    }
}

impl CostFunction for ContourCost<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, p: &Vec<f64>) -> Result<f64, Error> {
        Ok(self.value(p))
    }
}

impl Gradient for ContourCost<'_> {
    type Param = Vec<f64>;
    type Gradient = Vec<f64>;
    fn gradient(&self, p: &Vec<f64>) -> Result<Vec<f64>, Error> {
        let mut q = p.clone();
        Ok((0..p.len())
            .map(|i| {
                q[i] = p[i] + FD_STEP;
                let up = self.value(&q);
                q[i] = p[i] - FD_STEP;
                let down = self.value(&q);
                q[i] = p[i];
                (up - down) / (2.0 * FD_STEP)
            })
            .collect())
    }
}

/// CG in rounds of `ROUND` iterations (argmin's CG has no stopping tolerance of its own):
/// stops when a round improves the cost by less than `TOLERANCE`, or after `max_iters`.
fn run(cost: ContourCost, start: Vec<f64>, max_iters: u64) -> Vec<f64> {
    const ROUND: u64 = 8;
    const TOLERANCE: f64 = 1e-3;
    let mut best = start;
    let mut best_cost = cost.value(&best);
    let mut done = 0;
    while done < max_iters {
        let iters = ROUND.min(max_iters - done);
        done += iters;
        let solver =
            NonlinearConjugateGradient::new(MoreThuenteLineSearch::new(), PolakRibiere::new())
                .restart_orthogonality(0.1);
        let result = Executor::new(cost.clone(), solver)
            .configure(|s| s.param(best.clone()).max_iters(iters))
            .run();
        // A failed line search (a flat or kinked cost) keeps the best point found so far.
        let Ok(r) = result else { break };
        let Some(p) = r
            .state()
            .get_best_param()
            .filter(|p| p.iter().all(|v| v.is_finite()))
        else {
            break;
        };
        let c = cost.value(p);
        let gain = best_cost - c;
        if gain > 0.0 {
            best = p.clone();
            best_cost = c;
        }
        if gain < TOLERANCE {
            break;
        }
    }
    best
}

/// The closest local maximum of eq. 4.2 from `start` (at most `max_iters` CG iterations).
pub fn maximise(
    dt: &DistanceMap,
    start: Theta,
    step: f64,
    bounds: ShapeBounds,
    max_iters: u64,
) -> Theta {
    let cost = ContourCost {
        dt,
        counts: vec![start.counts(step)],
        shared: false,
        bounds,
    };
    let p = run(
        cost,
        vec![start.x0, start.y0, start.h, start.w, start.h + start.v],
        max_iters,
    );
    shapes(&p, false)[0]
}

/// Joint MLE of a group: one shape (h, w, v) shared by every member, one (x0, y0) each.
pub fn maximise_group(
    dt: &DistanceMap,
    members: &[Theta],
    step: f64,
    bounds: ShapeBounds,
    max_iters: u64,
) -> Vec<Theta> {
    let n = members.len() as f64;
    let mean = |f: fn(&Theta) -> f64| members.iter().map(f).sum::<f64>() / n;
    let mut p = vec![mean(|t| t.h), mean(|t| t.w), mean(|t| t.h + t.v)];
    for t in members {
        p.extend([t.x0, t.y0]);
    }
    let first = shapes(&p, true)[0];
    let cost = ContourCost {
        dt,
        counts: vec![first.counts(step); members.len()],
        shared: true,
        bounds,
    };
    shapes(&run(cost, p, max_iters), true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gothic::likelihood::prewitt_edges;
    use image::{GrayImage, Luma};

    fn draw(t: &Theta) -> GrayImage {
        let mut img = GrayImage::from_pixel(80, 100, Luma([200]));
        for (x, y, p) in img.enumerate_pixels_mut() {
            if t.contains(x as f64, y as f64) {
                *p = Luma([30]);
            }
        }
        img
    }

    #[test]
    fn cg_recovers_a_pointed_arch_from_a_rough_start() {
        let truth = Theta {
            x0: 20.0,
            y0: 85.0,
            h: 30.0,
            w: 30.0,
            v: 22.0,
        };
        let dt = DistanceMap::of_edges(&prewitt_edges(&draw(&truth), 0.3));
        let start = Theta {
            x0: 24.0,
            y0: 80.0,
            h: 24.0,
            w: 24.0,
            v: 12.0,
        };
        let bounds = ShapeBounds {
            min_width: 6.0,
            min_height: 6.0,
        };
        let got = maximise(&dt, start, 0.5, bounds, 100);
        for (a, b, name) in [
            (got.x0, truth.x0, "x0"),
            (got.y0, truth.y0, "y0"),
            (got.w, truth.w, "w"),
            (got.apex(), truth.apex(), "apex"),
        ] {
            assert!((a - b).abs() < 2.0, "{name}: {a} vs {b} ({got:?})");
        }
    }
}
