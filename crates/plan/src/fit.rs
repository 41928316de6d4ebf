//! Shape priors (§5.1.5): explicit algebraic fits of lines and circles (Taubin's method) to
//! edge chains, circles and rectangles to face loops, scored by the Euclidean errors of
//! eqs. 5.1–5.2; the model with the smallest error is kept.

use serde::Serialize;

/// A fitted model, in image pixels.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum Fit {
    /// `a x + b y + c = 0` with `a² + b² = 1`, from `p0` to `p1` (the chain's ends projected).
    Line {
        a: f64,
        b: f64,
        c: f64,
        p0: [f64; 2],
        p1: [f64; 2],
        error: f64,
    },
    /// An arc of the circle (`center`, `radius`) from angle `start` sweeping `sweep` radians
    /// (positive = clockwise on screen, y down).
    Arc {
        center: [f64; 2],
        radius: f64,
        start: f64,
        sweep: f64,
        error: f64,
    },
    Circle {
        center: [f64; 2],
        radius: f64,
        error: f64,
    },
    /// Centre, full side lengths, and the angle of the first side from the x axis.
    Rectangle {
        center: [f64; 2],
        size: [f64; 2],
        angle: f64,
        error: f64,
    },
}

impl Fit {
    /// The same model with every length multiplied by `k` (for a drawing resampled by 1/k).
    pub fn scaled(&self, k: f64) -> Fit {
        let m = |p: &[f64; 2]| [p[0] * k, p[1] * k];
        match self {
            Fit::Line {
                a,
                b,
                c,
                p0,
                p1,
                error,
            } => Fit::Line {
                a: *a,
                b: *b,
                c: c * k,
                p0: m(p0),
                p1: m(p1),
                error: error * k,
            },
            Fit::Arc {
                center,
                radius,
                start,
                sweep,
                error,
            } => Fit::Arc {
                center: m(center),
                radius: radius * k,
                start: *start,
                sweep: *sweep,
                error: error * k,
            },
            Fit::Circle {
                center,
                radius,
                error,
            } => Fit::Circle {
                center: m(center),
                radius: radius * k,
                error: error * k,
            },
            Fit::Rectangle {
                center,
                size,
                angle,
                error,
            } => Fit::Rectangle {
                center: m(center),
                size: m(size),
                angle: *angle,
                error: error * k,
            },
        }
    }

    pub fn error(&self) -> f64 {
        match self {
            Fit::Line { error, .. }
            | Fit::Arc { error, .. }
            | Fit::Circle { error, .. }
            | Fit::Rectangle { error, .. } => *error,
        }
    }
}

fn mean(pts: &[[f64; 2]]) -> [f64; 2] {
    let n = pts.len() as f64;
    let (sx, sy) = pts
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p[0], b + p[1]));
    [sx / n, sy / n]
}

/// Distance from `p` to the segment `a`–`b` (to `a` when the segment is a point): the one
/// rule for how near a point is to a drawn stroke or a wall's piece.
pub fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// Total-least-squares line (the algebraic line fit): normal = least eigenvector of the
/// scatter matrix. Error by eq. 5.2.
pub fn fit_line(pts: &[[f64; 2]]) -> Option<(f64, f64, f64, f64)> {
    if pts.len() < 2 {
        return None;
    }
    let m = mean(pts);
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for p in pts {
        let (dx, dy) = (p[0] - m[0], p[1] - m[1]);
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    // Direction angle of the major axis; the normal is perpendicular.
    let theta = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let (a, b) = (-theta.sin(), theta.cos());
    let c = -(a * m[0] + b * m[1]);
    let err = pts
        .iter()
        .map(|p| (a * p[0] + b * p[1] + c).abs())
        .sum::<f64>()
        / pts.len() as f64;
    Some((a, b, c, err))
}

/// Taubin's algebraic circle fit (Newton on the characteristic polynomial, as in Chernov's
/// formulation). Error by eq. 5.1, with the absolute distance to the circle (the text's sum
/// of signed terms would let errors cancel). Returns (cx, cy, r, error).
pub fn fit_circle(pts: &[[f64; 2]]) -> Option<(f64, f64, f64, f64)> {
    if pts.len() < 3 {
        return None;
    }
    let m = mean(pts);
    let n = pts.len() as f64;
    let (mut mxx, mut myy, mut mxy, mut mxz, mut myz, mut mzz) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for p in pts {
        let (x, y) = (p[0] - m[0], p[1] - m[1]);
        let z = x * x + y * y;
        mxx += x * x;
        myy += y * y;
        mxy += x * y;
        mxz += x * z;
        myz += y * z;
        mzz += z * z;
    }
    for v in [&mut mxx, &mut myy, &mut mxy, &mut mxz, &mut myz, &mut mzz] {
        *v /= n;
    }
    let mz = mxx + myy;
    let cov = mxx * myy - mxy * mxy;
    let a3 = 4.0 * mz;
    let a2 = -3.0 * mz * mz - mzz;
    let a1 = mzz * mz + 4.0 * cov * mz - mxz * mxz - myz * myz - mz * mz * mz;
    let a0 = mxz * mxz * myy + myz * myz * mxx - mzz * cov - 2.0 * mxz * myz * mxy + mz * mz * cov;
    let (mut x, mut y) = (0.0f64, f64::MAX);
    for _ in 0..50 {
        let y_old = y;
        y = a0 + x * (a1 + x * (a2 + x * a3));
        if y.abs() > y_old.abs() {
            x = 0.0;
            break;
        }
        let dy = a1 + x * (2.0 * a2 + 3.0 * x * a3);
        if dy == 0.0 {
            break;
        }
        let x_old = x;
        x = x_old - y / dy;
        if !x.is_finite() {
            return None;
        }
        if (x - x_old).abs() <= 1e-12 * x.abs().max(1e-12) {
            break;
        }
        if x < 0.0 {
            x = 0.0;
        }
    }
    let det = x * x - x * mz + cov;
    if det.abs() < 1e-12 {
        return None;
    }
    let cx = (mxz * (myy - x) - myz * mxy) / det / 2.0;
    let cy = (myz * (mxx - x) - mxz * mxy) / det / 2.0;
    let r = (cx * cx + cy * cy + mz).sqrt();
    let (cx, cy) = (cx + m[0], cy + m[1]);
    if !(r.is_finite() && cx.is_finite() && cy.is_finite()) {
        return None;
    }
    let err = pts
        .iter()
        .map(|p| ((p[0] - cx).hypot(p[1] - cy) - r).abs())
        .sum::<f64>()
        / n;
    Some((cx, cy, r, err))
}

/// Best of line and arc for an edge chain (§5.1.5). An arc must beat the line clearly and
/// have a radius within a few chord lengths; a straight chain is otherwise a near-infinite
/// circle that would win by rounding.
pub fn fit_edge(pts: &[[f64; 2]]) -> Option<Fit> {
    let (a, b, c, le) = fit_line(pts)?;
    let proj = |p: [f64; 2]| {
        let d = a * p[0] + b * p[1] + c;
        [p[0] - a * d, p[1] - b * d]
    };
    let line = Fit::Line {
        a,
        b,
        c,
        p0: proj(pts[0]),
        p1: proj(pts[pts.len() - 1]),
        error: le,
    };
    let extent = pts
        .iter()
        .map(|p| (p[0] - pts[0][0]).hypot(p[1] - pts[0][1]))
        .fold(0.0, f64::max);
    let Some((cx, cy, r, ce)) = fit_circle(pts) else {
        return Some(line);
    };
    if ce < 0.6 * le && le > 0.75 && r < 4.0 * extent.max(1.0) {
        let ang = |p: [f64; 2]| (p[1] - cy).atan2(p[0] - cx);
        // Sweep: sum of wrapped angle steps along the chain.
        let mut sweep = 0.0;
        for w in pts.windows(2) {
            let mut d = ang(w[1]) - ang(w[0]);
            while d > std::f64::consts::PI {
                d -= std::f64::consts::TAU;
            }
            while d < -std::f64::consts::PI {
                d += std::f64::consts::TAU;
            }
            sweep += d;
        }
        return Some(Fit::Arc {
            center: [cx, cy],
            radius: r,
            start: ang(pts[0]),
            sweep,
            error: ce,
        });
    }
    Some(line)
}

/// Minimum-area rectangle over 90 one-degree orientations, error = mean distance of the
/// points to its boundary.
pub fn fit_rectangle(pts: &[[f64; 2]]) -> Option<Fit> {
    if pts.len() < 4 {
        return None;
    }
    let mut best: Option<(f64, f64, [f64; 4])> = None;
    for k in 0..90 {
        let t = (k as f64).to_radians();
        let (c, s) = (t.cos(), t.sin());
        let mut bb = [f64::MAX, f64::MAX, f64::MIN, f64::MIN];
        for p in pts {
            let (u, v) = (c * p[0] + s * p[1], -s * p[0] + c * p[1]);
            bb = [bb[0].min(u), bb[1].min(v), bb[2].max(u), bb[3].max(v)];
        }
        let area = (bb[2] - bb[0]) * (bb[3] - bb[1]);
        if best.is_none_or(|b| area < b.0) {
            best = Some((area, t, bb));
        }
    }
    let (_, t, bb) = best?;
    let (c, s) = (t.cos(), t.sin());
    let err = pts
        .iter()
        .map(|p| {
            let (u, v) = (c * p[0] + s * p[1], -s * p[0] + c * p[1]);
            let du = (u - bb[0]).min(bb[2] - u);
            let dv = (v - bb[1]).min(bb[3] - v);
            du.min(dv).max(0.0)
        })
        .sum::<f64>()
        / pts.len() as f64;
    let (uc, vc) = ((bb[0] + bb[2]) / 2.0, (bb[1] + bb[3]) / 2.0);
    Some(Fit::Rectangle {
        center: [c * uc - s * vc, s * uc + c * vc],
        size: [bb[2] - bb[0], bb[3] - bb[1]],
        angle: t,
        error: err,
    })
}

/// Circle or rectangle for a face loop, whichever fits better relative to its size; `None`
/// when neither is within `tolerance` of the size (then the loop's edges carry the fits).
pub fn fit_face(pts: &[[f64; 2]], tolerance: f64) -> Option<Fit> {
    // A closed loop's circle spans the loop: a radius beyond the loop's diagonal is a nearly
    // straight chain fitted by a huge circle, whose error relative to its radius is tiny
    // (measured on the Sully plan: r = 25,016 px for a 387 × 500 drawing). Not a circle.
    let (lo, hi) = pts.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        },
    );
    let diagonal = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let circle = fit_circle(pts)
        .filter(|&(_, _, r, _)| r <= diagonal)
        .map(|(cx, cy, r, e)| Fit::Circle {
            center: [cx, cy],
            radius: r,
            error: e,
        });
    let rect = fit_rectangle(pts);
    let rel = |f: &Fit| match f {
        Fit::Circle { radius, error, .. } => error / radius.max(1.0),
        Fit::Rectangle { size, error, .. } => error / (size[0].min(size[1]) / 2.0).max(1.0),
        _ => f64::MAX,
    };
    [circle, rect]
        .into_iter()
        .flatten()
        .filter(|f| rel(f) <= tolerance)
        .min_by(|a, b| rel(a).total_cmp(&rel(b)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_nearly_straight_loop_is_no_circle() {
        // A thin sliver: two long sides 1 px apart; a huge circle fits it within tolerance.
        let mut pts: Vec<[f64; 2]> = (0..200).map(|i| [i as f64, 0.0]).collect();
        pts.extend(
            (0..200)
                .rev()
                .map(|i| [i as f64, 1.0 + (i as f64 / 200.0).powi(2) * 0.01]),
        );
        if let Some(Fit::Circle { radius, .. }) = fit_face(&pts, 0.06) {
            panic!("a circle of radius {radius} for a 200 x 1 px loop");
        }
        // A real ring still fits.
        let ring: Vec<[f64; 2]> = (0..64)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 64.0;
                [50.0 + 20.0 * a.cos(), 50.0 + 20.0 * a.sin()]
            })
            .collect();
        assert!(matches!(fit_face(&ring, 0.06), Some(Fit::Circle { .. })));
    }

    fn circle_pts(cx: f64, cy: f64, r: f64, a0: f64, a1: f64, n: usize) -> Vec<[f64; 2]> {
        (0..n)
            .map(|i| {
                let t = a0 + (a1 - a0) * i as f64 / (n - 1) as f64;
                [(cx + r * t.cos()).round(), (cy + r * t.sin()).round()]
            })
            .collect()
    }

    #[test]
    fn circle_fit_recovers_centre_and_radius() {
        let (cx, cy, r, e) = fit_circle(&circle_pts(50.0, 40.0, 20.0, 0.0, 6.2, 100)).unwrap();
        assert!(
            (cx - 50.0).abs() < 0.3 && (cy - 40.0).abs() < 0.3,
            "{cx} {cy}"
        );
        assert!((r - 20.0).abs() < 0.3 && e < 0.5, "{r} {e}");
    }

    #[test]
    fn line_error_is_mean_distance() {
        let pts = [[0.0, 0.0], [0.0, 1.0], [4.0, 0.0], [4.0, 1.0]];
        let (a, b, _, e) = fit_line(&pts).unwrap();
        assert!(a.abs() < 1e-9 && (b.abs() - 1.0).abs() < 1e-9);
        assert!((e - 0.5).abs() < 1e-9);
    }

    #[test]
    fn straight_chain_is_a_line_half_circle_an_arc() {
        let straight: Vec<[f64; 2]> = (0..40).map(|i| [i as f64, 10.0]).collect();
        assert!(matches!(fit_edge(&straight), Some(Fit::Line { .. })));
        let half = circle_pts(50.0, 50.0, 25.0, 0.0, 3.1, 80);
        match fit_edge(&half) {
            Some(Fit::Arc { radius, sweep, .. }) => {
                assert!((radius - 25.0).abs() < 0.5);
                assert!((sweep - 3.1).abs() < 0.1, "{sweep}");
            }
            f => panic!("{f:?}"),
        }
    }

    #[test]
    fn face_loops_pick_circle_or_rectangle() {
        assert!(matches!(
            fit_face(&circle_pts(30.0, 30.0, 15.0, 0.0, 6.2, 90), 0.1),
            Some(Fit::Circle { .. })
        ));
        let mut rect = Vec::new();
        for i in 0..=40 {
            rect.extend([[i as f64, 0.0], [i as f64, 20.0]]);
        }
        for j in 0..=20 {
            rect.extend([[0.0, j as f64], [40.0, j as f64]]);
        }
        match fit_face(&rect, 0.1) {
            Some(Fit::Rectangle { size, .. }) => {
                assert!((size[0] - 40.0).abs() < 1e-6 && (size[1] - 20.0).abs() < 1e-6);
            }
            f => panic!("{f:?}"),
        }
    }
}
