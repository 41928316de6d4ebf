//! Local maximisation of eq. 4.2 by nonlinear conjugate gradient (§4.2; `argmin`'s
//! Polak–Ribière CG with a Moré–Thuente line search), for one element or for a group of
//! elements sharing (h, w, v) with one (x0, y0) each (the joint re-estimation of §4.2).

use argmin::core::{CostFunction, Error, Executor, Gradient, State};
use argmin::solver::conjugategradient::NonlinearConjugateGradient;
use argmin::solver::conjugategradient::beta::PolakRibiere;
use argmin::solver::linesearch::MoreThuenteLineSearch;

use super::dual::{Dual, Real};
use super::element::{SampleCounts, Theta, contour_of};
use super::likelihood::DistanceMap;

/// Bounds the optimiser keeps Θ within, by a quadratic penalty (CG is unconstrained).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeBounds {
    pub min_width: f64,
    pub min_height: f64,
}

/// Penalty weight per px² outside the bounds: a few px outside costs more than any fit gains.
const PENALTY: f64 = 0.5;

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

/// ρ(D) = √(D² + 1) − 1 and ρ'(D).
fn rho(d: f64) -> (f64, f64) {
    let s = (d * d + 1.0).sqrt();
    (s - 1.0, d / s)
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
                integral += rho(self.dt.at(s.x, s.y)).0 * s.ds;
                len += s.ds;
            }
        }
        let t0 = shapes[0];
        if len > 0.0 {
            integral / len + PENALTY * penalty([t0.x0, t0.y0, t0.h, t0.w, t0.v], self.bounds)
        } else {
            f64::MAX
        }
    }

    /// Member `k`'s Θ = [x0, y0, h, w, v] as duals in its five own parameters, and where
    /// those sit in `p`.
    fn member(&self, p: &[f64], k: usize) -> ([Dual; 5], [usize; 5]) {
        let index = if self.shared {
            [3 + 2 * k, 4 + 2 * k, 0, 1, 2]
        } else {
            [0, 1, 2, 3, 4]
        };
        let var = |j: usize| Dual::var(p[index[j]], j);
        let h = var(2);
        (([var(0), var(1), h, var(3), var(4) - h]), index)
    }

    /// The cost and its analytic gradient. For the mean C = I / L with I = ∮ρ(D) ds and
    /// L = ∮ds: ∂I = ∮ ρ'(D) (∂D/∂x ∂x + ∂D/∂y ∂y) ds + ∮ ρ(D) ∂ds, with ∇D the gradient
    /// of the bilinear D at each sample and ∂x, ∂y, ∂ds from the contour construction in
    /// [`Dual`]s; ∂C = (∂I − C ∂L) / L. Not in §4.2, which leaves the gradient unspecified:
    /// it replaces ten cost evaluations (central differences) by one.
    fn value_and_gradient(&self, p: &[f64]) -> (f64, Vec<f64>) {
        let mut integral = 0.0;
        let mut len = 0.0;
        let mut d_integral = vec![0.0; p.len()];
        let mut d_len = vec![0.0; p.len()];
        let mut first = None;
        for (k, c) in self.counts.iter().enumerate() {
            let (theta, index) = self.member(p, k);
            first.get_or_insert((theta, index));
            let mut di = [0.0; 5];
            let mut dl = [0.0; 5];
            for s in contour_of(theta, *c) {
                let (d, ddx, ddy) = self.dt.at_with_gradient(s.x.v, s.y.v);
                let (r, dr) = rho(d);
                integral += r * s.ds.v;
                len += s.ds.v;
                let (gx, gy) = (dr * ddx * s.ds.v, dr * ddy * s.ds.v);
                for j in 0..5 {
                    di[j] += gx * s.x.d[j] + gy * s.y.d[j] + r * s.ds.d[j];
                    dl[j] += s.ds.d[j];
                }
            }
            for j in 0..5 {
                d_integral[index[j]] += di[j];
                d_len[index[j]] += dl[j];
            }
        }
        let Some((theta, index)) = first.filter(|_| len > 0.0) else {
            return (f64::MAX, vec![0.0; p.len()]);
        };
        let mean = integral / len;
        let mut grad: Vec<f64> = d_integral
            .iter()
            .zip(&d_len)
            .map(|(di, dl)| (di - mean * dl) / len)
            .collect();
        let pen = penalty(theta, self.bounds);
        for j in 0..5 {
            grad[index[j]] += PENALTY * pen.d[j];
        }
        (mean + PENALTY * pen.v, grad)
    }
}

/// Quadratic penalty for leaving the shape bounds, over Θ = [x0, y0, h, w, v].
fn penalty<R: Real>(theta: [R; 5], bounds: ShapeBounds) -> R {
    let [_, _, h, w, v] = theta;
    let low = |x: R, min: f64| {
        if x.value() < min {
            let gap = R::constant(min) - x;
            gap * gap
        } else {
            R::constant(0.0)
        }
    };
    low(w, bounds.min_width) + low(h, 0.0) + low(v, 0.0) + low(h + v, bounds.min_height)
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
        Ok(self.value_and_gradient(p).1)
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
    use crate::gothic::likelihood::edge_rule;
    use image::{GrayImage, Luma};
    use raster::edges::prewitt_edges;

    fn draw(t: &Theta) -> GrayImage {
        let mut img = GrayImage::from_pixel(80, 100, Luma([200]));
        for (x, y, p) in img.enumerate_pixels_mut() {
            if t.contains(x as f64, y as f64) {
                *p = Luma([30]);
            }
        }
        img
    }

    /// A pointed arch drawn dark on light, and the distance map of its Prewitt edges.
    fn pointed_arch() -> (Theta, DistanceMap) {
        let truth = Theta {
            x0: 20.0,
            y0: 85.0,
            h: 30.0,
            w: 30.0,
            v: 22.0,
        };
        let dt = DistanceMap::of_edges(&prewitt_edges(&draw(&truth), &edge_rule(0.3)).mask);
        (truth, dt)
    }

    const BOUNDS: ShapeBounds = ShapeBounds {
        min_width: 6.0,
        min_height: 6.0,
    };

    /// Central differences of the cost with step `eps`.
    fn numeric_gradient(cost: &ContourCost, p: &[f64], eps: f64) -> Vec<f64> {
        let mut q = p.to_vec();
        (0..p.len())
            .map(|i| {
                q[i] = p[i] + eps;
                let up = cost.value(&q);
                q[i] = p[i] - eps;
                let down = cost.value(&q);
                q[i] = p[i];
                (up - down) / (2.0 * eps)
            })
            .collect()
    }

    fn cost<'a>(dt: &'a DistanceMap, members: &[Theta], shared: bool) -> ContourCost<'a> {
        ContourCost {
            dt,
            counts: members.iter().map(|t| t.counts(0.5)).collect(),
            shared,
            bounds: BOUNDS,
        }
    }

    /// A rectangle, a segmental, a round and a pointed head, one of them outside its bounds.
    fn shapes_to_test() -> Vec<[f64; 5]> {
        vec![
            [20.3, 80.6, 30.2, 28.7, 29.9],
            [21.1, 84.2, 25.4, 30.3, 31.7],
            [18.7, 86.4, 24.1, 31.0, 40.1],
            [22.2, 83.3, 21.8, 29.1, 47.4],
            [30.4, 60.2, 2.1, 4.3, 5.0],
        ]
    }

    /// On a D that is linear in x and y the bilinear look-up is exact and smooth, so the
    /// analytic gradient must equal central differences to rounding.
    #[test]
    fn analytic_gradient_equals_central_differences_on_a_linear_distance() {
        let (w, h) = (120, 140);
        let d = (0..w * h)
            .map(|i| 3.0 + 0.07 * (i % w) as f32 + 0.05 * (i / w) as f32)
            .collect();
        let dt = DistanceMap {
            width: w,
            height: h,
            d,
            outside: 500.0,
        };
        for p in shapes_to_test() {
            let start = shapes(&p, false)[0];
            let c = cost(&dt, &[start], false);
            let (value, grad) = c.value_and_gradient(&p);
            assert!((value - c.value(&p)).abs() < 1e-12);
            let fd = numeric_gradient(&c, &p, 1e-5);
            for (i, (a, b)) in grad.iter().zip(&fd).enumerate() {
                assert!((a - b).abs() < 1e-6, "{p:?} param {i}: {a} vs {b}");
            }
        }
    }

    /// On a real distance transform (piecewise bilinear, kinked on cell borders) the analytic
    /// gradient matches small central differences up to the few samples crossing a border.
    #[test]
    fn analytic_gradient_matches_central_differences_on_edges() {
        let (_, dt) = pointed_arch();
        for p in shapes_to_test() {
            let start = shapes(&p, false)[0];
            let c = cost(&dt, &[start], false);
            let grad = c.value_and_gradient(&p).1;
            let fd = numeric_gradient(&c, &p, 1e-4);
            let scale = fd.iter().map(|g| g.abs()).fold(0.05, f64::max);
            for (i, (a, b)) in grad.iter().zip(&fd).enumerate() {
                assert!((a - b).abs() < 0.02 * scale, "{p:?} param {i}: {a} vs {b}");
            }
        }
        // The joint cost of a group: shared [h, w, a], one (x0, y0) each.
        let members = [
            Theta {
                x0: 10.3,
                y0: 84.1,
                h: 28.7,
                w: 22.2,
                v: 11.9,
            },
            Theta {
                x0: 41.6,
                y0: 86.2,
                h: 28.7,
                w: 22.2,
                v: 11.9,
            },
        ];
        let p = vec![28.7, 22.2, 40.6, 10.3, 84.1, 41.6, 86.2];
        let c = cost(&dt, &members, true);
        let grad = c.value_and_gradient(&p).1;
        let fd = numeric_gradient(&c, &p, 1e-4);
        let scale = fd.iter().map(|g| g.abs()).fold(0.05, f64::max);
        for (i, (a, b)) in grad.iter().zip(&fd).enumerate() {
            assert!((a - b).abs() < 0.02 * scale, "group param {i}: {a} vs {b}");
        }
    }

    #[test]
    fn cg_recovers_a_pointed_arch_from_a_rough_start() {
        let (truth, dt) = pointed_arch();
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
