//! Repetition (issue 23): identical elements stand at a regular spacing, so the spacing both
//! splits a row of identical elements into its groups and tells where a member the seeds
//! missed should be. Departures from §4.2, whose groups are clusters of (h, w, v) alone:
//! - a row of identical elements is split where the spacing jumps ([`split_by_spacing`]):
//!   the lancets of two bays, or of the two sub-arches of one tracery window, are identical
//!   but belong under different arches (figure 4.4);
//! - where a gap is a whole number of spacings, and one spacing beyond either end, the
//!   group's shape is tried ([`fill_gaps`]); and an element in no group is tried at every
//!   shift along its sill line ([`copies`]). A try is kept when eq. 4.2 finds it significant.

use super::detect::{Candidate, iou, plausible, significant};
use super::element::Theta;
use super::likelihood::{DistanceMap, fit};
use super::params::GothicParams;

/// Splits `members` (indices into `shapes`, sorted left to right) where the spacing from one
/// member to the next exceeds (1 + `tol`) × the smaller of its neighbouring spacings (a jump),
/// or, in a group of three, the other spacing. Pieces of one member are dropped.
pub fn split_by_spacing(shapes: &[Theta], members: &[usize], tol: f64) -> Vec<Vec<usize>> {
    let pitch: Vec<f64> = members
        .windows(2)
        .map(|p| shapes[p[1]].x0 - shapes[p[0]].x0)
        .collect();
    let mut out: Vec<Vec<usize>> = vec![vec![members[0]]];
    for (i, &p) in pitch.iter().enumerate() {
        let before = i.checked_sub(1).map(|j| pitch[j]);
        let after = pitch.get(i + 1).copied();
        let neighbour = match (before, after) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        let jump = neighbour.is_some_and(|q| p > (1.0 + tol) * q);
        if jump {
            out.push(Vec::new());
        }
        if let Some(last) = out.last_mut() {
            last.push(members[i + 1]);
        }
    }
    out.retain(|g| g.len() >= 2);
    out
}

/// The shape `t` tried at (x0 + dx, y0 + dy) for dx, dy within ±`reach` px (1-px steps): the
/// best position by eq. 4.2's mean distance, if significant, plausible, clear of `others`, and
/// fitting nearly as well as the element it copies (mean distance `model`): within 1.5 × or
/// 0.2 px of it, the test the joint re-estimation of a group applies to its members.
fn try_at(
    dt: &DistanceMap,
    t: Theta,
    reach: i32,
    others: &[Theta],
    model: f64,
    params: &GothicParams,
) -> Option<Candidate> {
    let mut best: Option<(f64, Theta)> = None;
    let coarse = t.contour_at(1.0);
    for dy in -reach..=reach {
        for dx in -reach..=reach {
            let (ox, oy) = (dx as f64, dy as f64);
            let (sum, len) = coarse.iter().fold((0.0, 0.0), |(s, l), p| {
                (s + dt.at(p.x + ox, p.y + oy) * p.ds, l + p.ds)
            });
            let mean = sum / len.max(1e-9);
            if best.is_none_or(|(b, _)| mean < b) {
                best = Some((
                    mean,
                    Theta {
                        x0: t.x0 + ox,
                        y0: t.y0 + oy,
                        ..t
                    },
                ));
            }
        }
    }
    let (_, theta) = best?;
    let f = fit(dt, &theta, params.step);
    // Clear of every element of its size by 3 px: the gap between two identical neighbours
    // has their jambs for its own and fits eq. 4.2 as well as they do (a phantom between
    // the lancets of two sub-arches); real repeated elements stand apart.
    let grown = theta.grown(3.0);
    let clear = others
        .iter()
        .all(|o| iou(o, &grown) <= 0.0 || !alike(o, &theta));
    let ok = clear
        && f.mean_distance <= (1.5 * model).max(model + 0.2)
        && plausible(&theta, params.bounds(), dt.width, dt.height)
        && significant(&f, params);
    ok.then_some(Candidate { theta, fit: f })
}

/// Whether two elements are of a size (an arch around an element does not block it).
fn alike(a: &Theta, b: &Theta) -> bool {
    let area = |t: &Theta| t.w * (t.h + t.v);
    let r = area(a) / area(b).max(1e-9);
    (0.5..2.0).contains(&r)
}

/// New members for a group (sorted left to right, one shared shape): in every gap that is
/// k ≥ 2 spacings (within `tol`) and one spacing beyond either end. `others` are every element
/// already found: a new member may not overlap one of its size, except one of the `loose`
/// ones (found alone, in no cluster), which it replaces — the index is returned with it. A
/// lancet whose own fit put its sill on the bed joint below (10 px off, so in no group) is
/// the group's shape at the group's spacing.
pub fn fill_gaps(
    dt: &DistanceMap,
    members: &[Theta],
    others: &[Theta],
    loose: &[usize],
    tol: f64,
    params: &GothicParams,
) -> Vec<(Candidate, Option<usize>)> {
    if members.len() < 2 {
        return Vec::new();
    }
    let pitch: Vec<f64> = members.windows(2).map(|p| p[1].x0 - p[0].x0).collect();
    let unit = pitch.iter().copied().fold(f64::MAX, f64::min);
    if unit < members[0].w {
        return Vec::new();
    }
    let mut tries: Vec<Theta> = Vec::new();
    for (i, &p) in pitch.iter().enumerate() {
        let k = (p / unit).round();
        if k >= 2.0 && (p - k * unit).abs() <= tol * unit {
            let step = p / k;
            for j in 1..k as usize {
                tries.push(Theta {
                    x0: members[i].x0 + j as f64 * step,
                    ..members[i]
                });
            }
        }
    }
    let (first, last) = (members[0], members[members.len() - 1]);
    tries.push(Theta {
        x0: first.x0 - unit,
        ..first
    });
    tries.push(Theta {
        x0: last.x0 + unit,
        ..last
    });
    let reach = (tol * unit).clamp(1.0, 4.0) as i32;
    let model = members
        .iter()
        .map(|m| fit(dt, m, params.step).mean_distance)
        .fold(0.0, f64::max);
    let mut out: Vec<(Candidate, Option<usize>)> = Vec::new();
    for t in tries {
        let replaced = loose
            .iter()
            .copied()
            .filter(|&j| out.iter().all(|(_, r)| *r != Some(j)))
            .find(|&j| alike(&others[j], &t) && iou(&others[j], &t) >= 0.3);
        let mut blocked: Vec<Theta> = (0..others.len())
            .filter(|&j| Some(j) != replaced)
            .map(|j| others[j])
            .collect();
        blocked.extend(out.iter().map(|(c, _)| c.theta));
        out.extend(try_at(dt, t, reach, &blocked, model, params).map(|c| (c, replaced)));
    }
    out
}

/// Copies of a lone element along its sill line: every shift of 1 px up to 4 widths either
/// side (clear of the element itself) is scored by eq. 4.2's mean distance at 1-px samples;
/// the local minima below the significance threshold are tried with [`try_at`], best first.
pub fn copies(
    dt: &DistanceMap,
    t: &Theta,
    others: &[Theta],
    params: &GothicParams,
) -> Vec<Candidate> {
    let coarse = t.contour_at(1.0);
    let len: f64 = coarse.iter().map(|p| p.ds).sum();
    let model = fit(dt, t, params.step).mean_distance;
    let span = (4.0 * t.w).round() as i64;
    let near = (t.w + 2.0).round() as i64;
    let shifts: Vec<i64> = (-span..=span).filter(|d| d.abs() >= near).collect();
    let score: Vec<f64> = shifts
        .iter()
        .map(|&d| {
            coarse
                .iter()
                .map(|p| dt.at(p.x + d as f64, p.y) * p.ds)
                .sum::<f64>()
                / len.max(1e-9)
        })
        .collect();
    let mut minima: Vec<(f64, i64)> = (0..shifts.len())
        .filter(|&i| {
            let s = score[i];
            s <= 2.0 * params.max_mean_distance
                && (i == 0 || score[i - 1] >= s)
                && (i + 1 == score.len() || score[i + 1] > s)
        })
        .map(|i| (score[i], shifts[i]))
        .collect();
    minima.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out: Vec<Candidate> = Vec::new();
    for (_, d) in minima {
        let shifted = Theta {
            x0: t.x0 + d as f64,
            ..*t
        };
        let mut blocked: Vec<Theta> = others.to_vec();
        blocked.push(*t);
        blocked.extend(out.iter().map(|c| c.theta));
        out.extend(try_at(dt, shifted, 2, &blocked, model, params));
    }
    out
}

/// Whether two groups are twins: as many members, of one shape (by
/// [`similar_box`](super::group::similar_box) with the grouping tolerance and `rise_factor`),
/// at one spacing (within `tol`).
pub fn twins(a: &[Theta], b: &[Theta], tol: f64, rise_factor: f64, params: &GothicParams) -> bool {
    let pitch = |m: &[Theta]| {
        if m.len() < 2 {
            0.0
        } else {
            (m[m.len() - 1].x0 - m[0].x0) / (m.len() - 1) as f64
        }
    };
    let (pa, pb) = (pitch(a), pitch(b));
    a.len() == b.len()
        && super::group::similar_box(
            &a[0],
            &b[0],
            params.group_relative,
            params.group_absolute,
            rise_factor,
        )
        && (pa - pb).abs() <= tol * pa.max(pb)
}

/// Departure from §4.2 (issue 23): twin groups (the two pairs of lancets of a tracery window)
/// stand under twin arches — self-similarity one level up — but each arch found on its own
/// may settle on a different line (one on the outer arch's sill), and then the two do not
/// group and the arch over both is never proposed. Each arch is tried translated onto the
/// other group (with ±2 px of search); the consistent pair of the lower summed mean distance
/// is returned, or None when neither translation is significant, fits within 1.5 × (or
/// 0.2 px of) its original and still encloses its group.
pub fn twin_arches(
    dt: &DistanceMap,
    (a_members, a): (&[Theta], &Candidate),
    (b_members, b): (&[Theta], &Candidate),
    params: &GothicParams,
) -> Option<(Candidate, Candidate)> {
    let (dx, dy) = (
        b_members[0].x0 - a_members[0].x0,
        b_members[0].y0 - a_members[0].y0,
    );
    let moved = |c: &Candidate, sign: f64, members: &[Theta]| {
        let t = Theta {
            x0: c.theta.x0 + sign * dx,
            y0: c.theta.y0 + sign * dy,
            ..c.theta
        };
        try_at(dt, t, 2, &[], c.fit.mean_distance, params).filter(|m| {
            super::enclose::within_reach(&m.theta, members)
                && members
                    .iter()
                    .all(|x| super::hierarchy::contains(&m.theta, x, params.nesting_tolerance))
        })
    };
    let keep_a = moved(a, 1.0, b_members).map(|b2| (*a, b2));
    let keep_b = moved(b, -1.0, a_members).map(|a2| (a2, *b));
    let cost = |p: &(Candidate, Candidate)| p.0.fit.mean_distance + p.1.fit.mean_distance;
    match (keep_a, keep_b) {
        (Some(x), Some(y)) => Some(if cost(&x) <= cost(&y) { x } else { y }),
        (x, y) => x.or(y),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(x0: f64) -> Theta {
        Theta {
            x0,
            y0: 100.0,
            h: 40.0,
            w: 20.0,
            v: 16.0,
        }
    }

    #[test]
    fn twin_groups_have_as_many_members_of_one_shape_at_one_spacing() {
        let p = GothicParams::default();
        let (a, b) = ([at(0.0), at(30.0)], [at(80.0), at(111.0)]);
        assert!(twins(&a, &b, 0.25, 1.5, &p));
        assert!(!twins(&a, &[at(80.0), at(111.0), at(142.0)], 0.25, 1.5, &p));
        assert!(!twins(&a, &[at(80.0), at(130.0)], 0.25, 1.5, &p));
        let wide = Theta {
            w: 30.0,
            ..at(80.0)
        };
        assert!(!twins(
            &a,
            &[wide, Theta { x0: 111.0, ..wide }],
            0.25,
            1.5,
            &p
        ));
    }

    #[test]
    fn rows_split_where_the_spacing_jumps() {
        // Two sub-arches of two lancets: spacing 30, 45, 30.
        let s = [at(0.0), at(30.0), at(75.0), at(105.0)];
        assert_eq!(
            split_by_spacing(&s, &[0, 1, 2, 3], 0.25),
            vec![vec![0, 1], vec![2, 3]]
        );
        // Two bays of three, slightly different spacings: the bays, not single windows.
        let s = [at(0.0), at(30.0), at(60.0), at(200.0), at(233.0), at(266.0)];
        assert_eq!(
            split_by_spacing(&s, &[0, 1, 2, 3, 4, 5], 0.25),
            vec![vec![0, 1, 2], vec![3, 4, 5]]
        );
        // A pair and a far single: the pair.
        let s = [at(0.0), at(30.0), at(150.0)];
        assert_eq!(split_by_spacing(&s, &[0, 1, 2], 0.25), vec![vec![0, 1]]);
        // Even spacing: one group.
        assert_eq!(split_by_spacing(&s[..2], &[0, 1], 0.25), vec![vec![0, 1]]);
    }
}
