//! Element detection of §4.2: seeds at peaks of the distance transform, each grown into a small
//! element and maximised by conjugate gradient; significant maxima are kept and duplicates
//! suppressed.

use super::element::Theta;
use super::likelihood::{DistanceMap, Fit, fit};
use super::optimise::{ShapeBounds, maximise};
use super::params::{GothicParams, Progress};

/// A seed: a local maximum of D and its value (the radius of the empty disc around it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seed {
    pub x: usize,
    pub y: usize,
    pub radius: f32,
}

/// Peaks of D at least `min_radius` deep, strongest first; a peak inside the disc of a
/// stronger one is the same opening and is dropped. At most `max_seeds`.
pub fn seeds(dt: &DistanceMap, min_radius: f32, max_seeds: usize) -> Vec<Seed> {
    let (w, h) = (dt.width, dt.height);
    let mut peaks = Vec::new();
    for y in 1..h.saturating_sub(1) {
        for x in 1..w.saturating_sub(1) {
            let d = dt.get(x, y);
            if d < min_radius {
                continue;
            }
            let is_peak = (-1i64..=1).all(|dy| {
                (-1i64..=1)
                    .all(|dx| dt.get((x as i64 + dx) as usize, (y as i64 + dy) as usize) <= d)
            });
            if is_peak {
                peaks.push(Seed { x, y, radius: d });
            }
        }
    }
    peaks.sort_by(|a, b| {
        b.radius
            .total_cmp(&a.radius)
            .then((a.y, a.x).cmp(&(b.y, b.x)))
    });
    let mut kept: Vec<Seed> = Vec::new();
    for p in peaks {
        let taken = kept.iter().any(|k| {
            let d = (k.x as f32 - p.x as f32).hypot(k.y as f32 - p.y as f32);
            d < 0.8 * k.radius
        });
        if !taken {
            kept.push(p);
            if kept.len() >= max_seeds {
                break;
            }
        }
    }
    kept
}

/// The first Θ for a seed: walk from the seed to the nearest edge left, right, up and down
/// (an empty opening is bounded by edges) and fit a round-headed element to that box.
/// The disc of §4.2's "small windows within peaks" is the fallback when a walk leaves the image.
pub fn initial_theta(dt: &DistanceMap, seed: Seed) -> Theta {
    let walk = |dx: i64, dy: i64| -> f64 {
        let (mut x, mut y) = (seed.x as i64, seed.y as i64);
        let mut n = 0.0;
        loop {
            x += dx;
            y += dy;
            if x < 0 || y < 0 || x >= dt.width as i64 || y >= dt.height as i64 {
                return seed.radius as f64;
            }
            n += 1.0;
            if dt.get(x as usize, y as usize) < 1.0 {
                return n;
            }
        }
    };
    let (left, right, up, down) = (walk(-1, 0), walk(1, 0), walk(0, -1), walk(0, 1));
    let w = left + right;
    let x0 = seed.x as f64 - left;
    let y0 = seed.y as f64 + down;
    let tall = up + down;
    let v = (w / 2.0).min(tall * 0.5);
    Theta {
        x0,
        y0,
        h: (tall - v).max(0.0),
        w,
        v,
    }
}

/// A maximum of eq. 4.2 and its fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate {
    pub theta: Theta,
    pub fit: Fit,
}

/// Whether a fit is significant: the contour lies on edges on average (§4.2 keeps "those
/// parameter vectors having significant probability"; the thresholds are ours).
pub fn significant(f: &Fit, params: &GothicParams) -> bool {
    f.mean_distance <= params.max_mean_distance && f.support >= params.min_support
}

/// Whether Θ is within the size bounds and the image.
pub fn plausible(t: &Theta, bounds: ShapeBounds, width: usize, height: usize) -> bool {
    let [x0, y0, x1, y1] = t.bbox();
    t.w >= bounds.min_width * 0.95
        && t.h >= -0.5
        && t.v >= -0.5
        && t.h + t.v >= bounds.min_height * 0.95
        && x0 >= -1.0
        && y0 >= -1.0
        && x1 <= width as f64
        && y1 <= height as f64
}

/// First shapes for the seeds: the walked box with a round head and with a pointed one
/// (two starts, because CG from a round head inside a pointed opening stops at the inscribed
/// round arch). Seeds along one opening's ridge walk to the same box; only one is kept.
pub fn starts(dt: &DistanceMap, seeds: &[Seed]) -> Vec<Theta> {
    starts_with(dt, seeds, false)
}

/// [`starts`], and with `more` (issue 23; not in §4.2) two more kinds of first shape:
/// - the walked box as a rectangle, for doors on the ground line (its bottom in the lowest
///   quarter of the image; CG from a round head seldom flattens it: the head's sides then
///   leave every edge at once);
/// - the box as wide as the seed's empty disc, when the walk went further: a walk leaks
///   through a gap of a weak edge (dark glass against dark brick) and CG from a box twice too
///   wide settles on the joints beside the opening.
pub fn starts_with(dt: &DistanceMap, seeds: &[Seed], more: bool) -> Vec<Theta> {
    let mut boxes: Vec<Theta> = Vec::new();
    for s in seeds {
        let t = initial_theta(dt, *s);
        let disc = 2.0 * s.radius as f64;
        let narrow = Theta {
            x0: s.x as f64 - s.radius as f64,
            w: disc,
            v: (disc / 2.0).min(0.5 * (t.h + t.v)),
            h: (t.h + t.v - (disc / 2.0).min(0.5 * (t.h + t.v))).max(0.0),
            ..t
        };
        let extra = (more && t.w > 1.3 * disc).then_some(narrow);
        for t in std::iter::once(t).chain(extra) {
            if boxes.iter().all(|b| iou(b, &t) < 0.8) {
                boxes.push(t);
            }
        }
    }
    let mut out = Vec::with_capacity(3 * boxes.len());
    for b in boxes {
        out.push(b);
        // Rectangles only for openings standing in the lowest quarter of the façade (doors on
        // the ground line): higher up a rectangle around a pointed lancet, its top on a bed
        // joint, fits nearly as well as the lancet and was kept where the lancet's own fit
        // fell short (held-out seed 201).
        if more && b.y0 >= 0.75 * dt.height as f64 {
            out.push(Theta {
                h: b.h + b.v,
                v: 0.0,
                ..b
            });
        }
        let tall = b.h + b.v;
        let v = (0.85 * b.w).min(0.9 * tall);
        if v > b.v + 1.0 {
            out.push(Theta {
                h: tall - v,
                v,
                ..b
            });
        }
    }
    out
}

/// Maximises from every start and keeps the significant, plausible results.
pub fn detect(dt: &DistanceMap, params: &GothicParams) -> Vec<Candidate> {
    detect_with(dt, params, &|_| {})
}

/// [`detect`], telling `progress` after each start.
pub fn detect_with(
    dt: &DistanceMap,
    params: &GothicParams,
    progress: &(dyn Fn(Progress) + Sync),
) -> Vec<Candidate> {
    let seeds = seeds(dt, params.min_seed_radius, params.max_seeds);
    // Departure from §4.2: rectangle and disc-wide starts besides the walked box (issue 23).
    let starts = starts_with(dt, &seeds, params.more_starts);
    detect_from_starts_with(dt, &starts, params, progress)
}

/// [`detect`] from given first shapes (the class-driven mode seeds one per window blob and
/// adds rectangles).
pub fn detect_from_starts(
    dt: &DistanceMap,
    starts: &[Theta],
    params: &GothicParams,
) -> Vec<Candidate> {
    detect_from_starts_with(dt, starts, params, &|_| {})
}

/// [`detect_from_starts`], telling `progress` after each start.
pub fn detect_from_starts_with(
    dt: &DistanceMap,
    starts: &[Theta],
    params: &GothicParams,
    progress: &(dyn Fn(Progress) + Sync),
) -> Vec<Candidate> {
    let bounds = params.bounds();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let total = starts.len();
    progress(Progress::Detecting { done: 0, total });
    let mut out: Vec<Candidate> = rayon_map(starts, |start| {
        let theta = maximise(dt, *start, params.step, bounds, params.max_iters);
        let f = fit(dt, &theta, params.step);
        let ok = plausible(&theta, bounds, dt.width, dt.height) && significant(&f, params);
        let done = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        progress(Progress::Detecting { done, total });
        ok.then_some(Candidate { theta, fit: f })
    });
    out.sort_by(|a, b| a.fit.mean_distance.total_cmp(&b.fit.mean_distance));
    suppress_duplicates(out, params.duplicate_iou)
}

fn rayon_map<T: Sync, U: Send>(items: &[T], f: impl Fn(&T) -> Option<U> + Sync + Send) -> Vec<U> {
    use rayon::prelude::*;
    items.par_iter().filter_map(f).collect()
}

/// Intersection over union of two bounding boxes.
pub fn iou(a: &Theta, b: &Theta) -> f64 {
    let ([ax0, ay0, ax1, ay1], [bx0, by0, bx1, by1]) = (a.bbox(), b.bbox());
    let iw = (ax1.min(bx1) - ax0.max(bx0)).max(0.0);
    let ih = (ay1.min(by1) - ay0.max(by0)).max(0.0);
    let inter = iw * ih;
    let union = (ax1 - ax0) * (ay1 - ay0) + (bx1 - bx0) * (by1 - by0) - inter;
    if union > 0.0 { inter / union } else { 0.0 }
}

/// Best first (the input order); drops anything overlapping a kept one by `max_iou` or more.
pub fn suppress_duplicates(sorted: Vec<Candidate>, max_iou: f64) -> Vec<Candidate> {
    let mut kept: Vec<Candidate> = Vec::new();
    for c in sorted {
        if kept.iter().all(|k| iou(&k.theta, &c.theta) < max_iou) {
            kept.push(c);
        }
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(rows: &[&[f32]]) -> DistanceMap {
        DistanceMap {
            width: rows[0].len(),
            height: rows.len(),
            d: rows.iter().flat_map(|r| r.iter().copied()).collect(),
            outside: 10.0,
        }
    }

    #[test]
    fn seeds_are_deep_peaks_strongest_first_one_per_disc() {
        let dt = map(&[
            &[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            &[0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.0],
            &[0.0, 1.0, 3.0, 2.9, 1.0, 2.0, 0.0],
            &[0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.0],
            &[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        ]);
        let s = seeds(&dt, 1.5, 10);
        assert_eq!(s.len(), 2, "{s:?}");
        assert_eq!((s[0].x, s[0].y, s[0].radius), (2, 2, 3.0));
        assert_eq!((s[1].x, s[1].y), (5, 2));
        assert_eq!(seeds(&dt, 2.5, 10).len(), 1);
        assert_eq!(seeds(&dt, 1.5, 1).len(), 1);
    }

    #[test]
    fn initial_theta_spans_the_empty_box_around_the_seed() {
        let mut rows = vec![vec![5.0f32; 9]; 7];
        for (y, row) in rows.iter_mut().enumerate() {
            for (x, v) in row.iter_mut().enumerate() {
                if x == 1 || x == 7 || y == 1 || y == 5 {
                    *v = 0.0;
                }
            }
        }
        let refs: Vec<&[f32]> = rows.iter().map(|r| r.as_slice()).collect();
        let t = initial_theta(
            &map(&refs),
            Seed {
                x: 4,
                y: 3,
                radius: 2.0,
            },
        );
        assert_eq!((t.x0, t.y0, t.w), (1.0, 5.0, 6.0));
        assert_eq!(t.h + t.v, 4.0);
    }

    #[test]
    fn duplicates_are_suppressed_nested_shapes_kept() {
        let c = |x0: f64, w: f64, q: f64| Candidate {
            theta: Theta {
                x0,
                y0: 100.0,
                h: 40.0,
                w,
                v: w / 2.0,
            },
            fit: Fit {
                integral: 0.0,
                mean_distance: q,
                support: 1.0,
            },
        };
        let kept = suppress_duplicates(
            vec![c(10.0, 20.0, 0.1), c(11.0, 20.0, 0.2), c(0.0, 80.0, 0.3)],
            0.6,
        );
        assert_eq!(kept.len(), 2);
        assert_eq!(kept[0].theta.x0, 10.0);
        assert_eq!(kept[1].theta.w, 80.0);
    }
}
