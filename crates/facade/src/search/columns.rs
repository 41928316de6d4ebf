//! Floors and windows inside one façade under `Grammar::Columns`: the departures from §3.1.6
//! that issue 21 measured on CMP and Art-deco, each marked below. The floors are the text's
//! (ground, N_L − 2 equal middle floors, top; one window band per floor kind, eqs. 3.2–3.4)
//! and windows stay aligned from floor to floor, but
//!
//! - (departure 1, §3.1.6 "N_w windows of width w_w, w_gap apart") the window columns are any
//!   set of disjoint intervals of the façade's width — [`best_intervals`], a dynamic programme
//!   at pixel resolution — rather than N_w ≤ 10 equal windows at one pitch whose edges are
//!   gradient peaks: real façades pair windows, mix widths, and an equal pitch drifts off
//!   the windows across a wide façade;
//! - (departure 2, §3.1.6 "the same windows in every floor") the ground, middle and top floors
//!   each have their own columns (shop fronts, doors, attic dormers), searched in alternation
//!   with the vertical parameters over one row profile per floor kind;
//! - (departure 3, §3.1.6 "every floor has its N_w windows") a cell of the grid whose pixels
//!   favour wall (window − wall sum ≤ 0) is wall: missing windows, blind bays, a door's place.

use super::floors::{MIN_SIZE, Vertical, search_vertical_kinds};
use super::gradients::{Gradients, Integral};
use super::params::SearchParams;
use crate::model::{Facade, FacadeParams, Floor, MAX_COLUMNS};

/// Disjoint intervals [a, b) of `prof` that maximise the sum of `prof` over them less `cost`
/// per interval, each at least `min_w` long and at least `min_gap` from the next, left to
/// right; at most [`MAX_COLUMNS`] (the strongest). Empty when no interval is worth its cost.
/// O(n²).
pub fn best_intervals(
    prof: &[f64],
    min_w: usize,
    min_gap: usize,
    cost: f64,
) -> Vec<(usize, usize)> {
    let n = prof.len();
    let min_w = min_w.max(1);
    let mut pre = vec![0f64; n + 1];
    for (i, v) in prof.iter().enumerate() {
        pre[i + 1] = pre[i] + v;
    }
    // best[b]: the best selection inside [0, b); from[b]: the last interval's start, if the
    // selection ends with an interval ending at b.
    let mut best = vec![0f64; n + 1];
    let mut from: Vec<Option<usize>> = vec![None; n + 1];
    for b in 1..=n {
        best[b] = best[b - 1];
        if b < min_w {
            continue;
        }
        for a in 0..=b - min_w {
            let before = if a >= min_gap { best[a - min_gap] } else { 0.0 };
            let v = before + pre[b] - pre[a] - cost;
            if v > best[b] {
                best[b] = v;
                from[b] = Some(a);
            }
        }
    }
    let mut out = Vec::new();
    let mut b = n;
    while b > 0 {
        match from[b] {
            Some(a) => {
                out.push((a, b));
                b = a.saturating_sub(min_gap);
            }
            None => b -= 1,
        }
    }
    out.reverse();
    if out.len() > MAX_COLUMNS as usize {
        let mut by_sum: Vec<(usize, usize)> = out.clone();
        by_sum.sort_by(|x, y| (pre[y.1] - pre[y.0]).total_cmp(&(pre[x.1] - pre[x.0])));
        by_sum.truncate(MAX_COLUMNS as usize);
        by_sum.sort_unstable();
        out = by_sum;
    }
    out
}

/// Floor kinds in [`Vertical`]'s order of profiles.
const GROUND: usize = 0;
const MIDDLE: usize = 1;
const TOP: usize = 2;

/// Kind of floor `i` of `n`, counted from the ground.
fn kind(i: usize, n: usize) -> usize {
    if i == 0 {
        GROUND
    } else if i + 1 == n {
        TOP
    } else {
        MIDDLE
    }
}

/// Window rows per floor kind (relative to the façade top), from a vertical layout.
fn kind_rows(ver: &Vertical, fh: usize) -> [Vec<(usize, usize)>; 3] {
    let bands = ver.params_stub(fh).floor_bands();
    let n = bands.len();
    let mut out: [Vec<(usize, usize)>; 3] = Default::default();
    for (i, (_, y1, wh, wg)) in bands.into_iter().enumerate() {
        if wh > 0.0 {
            let (a, b) = ((y1 - wg - wh).round() as usize, (y1 - wg).round() as usize);
            out[kind(i, n)].push((a, b.min(fh)));
        }
    }
    out
}

/// Fits the floors and windows of the façade `r` = [x0, y0, x1, y1] under `Grammar::Columns`,
/// given the integral of the (clipped) window-minus-wall log-likelihood.
pub fn fit_columns(r: [usize; 4], d: &Integral, grads: &Gradients, p: &SearchParams) -> Facade {
    let [x0, y0, x1, y1] = r;
    let (fw, fh) = (x1 - x0, y1 - y0);
    let y_cands: Vec<usize> = grads.y_peaks(r, p).into_iter().map(|y| y - y0).collect();
    let col_profile = |rows: &[(usize, usize)]| -> Vec<f64> {
        (0..fw)
            .map(|x| {
                rows.iter()
                    .map(|&(a, b)| d.sum(x0 + x, y0 + a, x0 + x + 1, y0 + b))
                    .sum()
            })
            .collect()
    };
    let row_profile = |cols: &[(usize, usize)]| -> Vec<f64> {
        (0..fh)
            .map(|y| {
                cols.iter()
                    .map(|&(a, b)| d.sum(x0 + a, y0 + y, x0 + b, y0 + y + 1))
                    .sum()
            })
            .collect()
    };
    // Start as the text does: rows whose sum over the whole width is above the median row's
    // (at the median too when that leaves none).
    let all = row_profile(&[(0, fw)]);
    let mut sorted = all.clone();
    sorted.sort_by(|a, b| a.total_cmp(b));
    let median = sorted.get(fh / 2).copied().unwrap_or(0.0);
    let mut start: Vec<(usize, usize)> = (0..fh)
        .filter(|&y| all[y] > median)
        .map(|y| (y, y + 1))
        .collect();
    if start.is_empty() {
        start = (0..fh)
            .filter(|&y| all[y] >= median)
            .map(|y| (y, y + 1))
            .collect();
    }
    // Departure 1's regularisers: windows and gaps at least `min_window_frac` of the façade's
    // width, and each column costs `column_cost` pixels of evidence per window row (without
    // them a noisy map gives a barcode of one-pixel columns).
    let min_w = ((p.min_window_frac * fw as f64).round() as usize).max(MIN_SIZE);
    let columns_of = |prof: &[f64], rows: usize| -> Vec<(usize, usize)> {
        best_intervals(prof, min_w, min_w, p.column_cost * rows as f64)
    };
    let span = |rows: &[(usize, usize)]| -> usize { rows.iter().map(|r| r.1 - r.0).sum() };
    let first = columns_of(&col_profile(&start), start.len());
    let mut cols: [Vec<(usize, usize)>; 3] = [first.clone(), first.clone(), first];
    let mut ver = Vertical {
        n_l: 1,
        h_1: fh,
        ..Default::default()
    };
    if cols[MIDDLE].is_empty() {
        return facade_of(r, &ver, &[Vec::new(), Vec::new(), Vec::new()], d);
    }
    for _ in 0..p.rounds.max(1) {
        let profiles = cols.clone().map(|c| row_profile(&c));
        let new_ver = search_vertical_kinds(
            [&profiles[GROUND], &profiles[MIDDLE], &profiles[TOP]],
            &y_cands,
        );
        // Departure 2: each floor kind's columns from its own window rows; a kind without
        // window rows keeps the columns of all window rows, so it can gain windows next round.
        let rows = kind_rows(&new_ver, fh);
        let every: Vec<(usize, usize)> = rows.iter().flatten().copied().collect();
        if every.is_empty() {
            ver = new_ver;
            break;
        }
        let common = columns_of(&col_profile(&every), span(&every));
        let new_cols = rows.clone().map(|k| {
            if k.is_empty() {
                common.clone()
            } else {
                columns_of(&col_profile(&k), span(&k))
            }
        });
        let same = new_ver == ver && new_cols == cols;
        ver = new_ver;
        cols = new_cols;
        if same {
            break;
        }
    }
    facade_of(r, &ver, &cols, d)
}

/// The façade tree of a vertical layout and per-kind columns (relative), in image pixels.
fn facade_of(
    r: [usize; 4],
    ver: &Vertical,
    cols: &[Vec<(usize, usize)>; 3],
    d: &Integral,
) -> Facade {
    let [x0, y0, x1, y1] = r;
    let fh = y1 - y0;
    let stub = ver.params_stub(fh);
    let bands = stub.floor_bands();
    let n = bands.len();
    let (xf, yf) = (x0 as f64, y0 as f64);
    let mut floors: Vec<Floor> = bands
        .iter()
        .enumerate()
        .map(|(i, &(top, bottom, wh, wg))| {
            let mut windows = Vec::new();
            if wh > 0.0 {
                let (a, b) = ((bottom - wg - wh).round(), (bottom - wg).round());
                for &(c0, c1) in &cols[kind(i, n)] {
                    // Departure 3: a cell that favours wall is wall.
                    let s = d.sum(x0 + c0, y0 + a as usize, x0 + c1, (y0 + b as usize).min(y1));
                    if s > 0.0 {
                        windows.push([xf + c0 as f64, yf + a, xf + c1 as f64, yf + b]);
                    }
                }
            }
            Floor {
                y0: yf + top,
                y1: yf + bottom,
                windows,
            }
        })
        .collect();
    floors.reverse();
    // The 18 parameters summarise the grid (what §6–7's program generator reads): the vertical
    // ones as found, the horizontal ones the middle floors' columns (the ground floor's when
    // there are no middle floors) as one mean width and gap.
    let summary = if n >= 3 { &cols[MIDDLE] } else { &cols[GROUND] };
    let nw = summary.len();
    let (w_off, w_w, w_gap) = if nw == 0 {
        (0.0, 0.0, 0.0)
    } else {
        let widths: usize = summary.iter().map(|c| c.1 - c.0).sum();
        let span = summary[nw - 1].1 - summary[0].0;
        let w_w = widths as f64 / nw as f64;
        let w_gap = if nw > 1 {
            (span - widths) as f64 / (nw - 1) as f64
        } else {
            0.0
        };
        (summary[0].0 as f64, w_w, w_gap)
    };
    let has_windows = floors.iter().any(|f| !f.windows.is_empty());
    let params = FacadeParams {
        x_fl: xf,
        y_ft: yf,
        x_fr: x1 as f64,
        y_fb: y1 as f64,
        w_off,
        w_w,
        w_gap,
        n_w: if has_windows { nw as u32 } else { 0 },
        ..stub
    };
    Facade {
        bbox: [xf, yf, x1 as f64, y1 as f64],
        floors,
        params,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intervals_on_literal_profiles() {
        let p = [-1.0, 2.0, 2.0, -1.0, 3.0, -5.0, 1.0, 1.0, 1.0];
        // Free: every positive run.
        assert_eq!(best_intervals(&p, 1, 1, 0.0), vec![(1, 3), (4, 5), (6, 9)]);
        // Windows at least 3 wide: [1, 5) (sum 6) and [6, 9) (3).
        assert_eq!(best_intervals(&p, 3, 1, 0.0), vec![(1, 5), (6, 9)]);
        // Gaps of at least 2: the single wall columns at 3 and 5 cannot separate windows.
        assert_eq!(best_intervals(&p, 1, 2, 0.0), vec![(1, 5), (7, 9)]);
        // A cost of 2.5 per interval: [1, 5) (6 − 2.5) and [6, 9) (3 − 2.5) beat three.
        assert_eq!(best_intervals(&p, 1, 1, 2.5), vec![(1, 5), (6, 9)]);
        // A cost of 4: one interval, [1, 9) (4) < [1, 5) (6).
        assert_eq!(best_intervals(&p, 1, 1, 4.0), vec![(1, 5)]);
        assert!(best_intervals(&[-1.0, -2.0], 1, 1, 0.0).is_empty());
        assert!(best_intervals(&[], 1, 1, 0.0).is_empty());
    }
}
