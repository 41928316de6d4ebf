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

use super::floors::{MIN_SIZE, Vertical, floor_band, search_vertical_kinds};
use super::gradients::{Gradients, Integral};
use super::params::SearchParams;
use crate::fixes::Constraints;
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
    best_intervals_at_most(prof, min_w, min_gap, cost, MAX_COLUMNS as usize)
}

/// [`best_intervals`], at most `max` of them (the strongest by their sum of `prof`).
pub fn best_intervals_at_most(
    prof: &[f64],
    min_w: usize,
    min_gap: usize,
    cost: f64,
    max: usize,
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
    if out.len() > max {
        let mut by_sum: Vec<(usize, usize)> = out.clone();
        by_sum.sort_by(|x, y| (pre[y.1] - pre[y.0]).total_cmp(&(pre[x.1] - pre[x.0])));
        by_sum.truncate(max);
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

/// A vertical layout relative to the façade top: each floor bottom-up as (top, bottom, window
/// height, window-to-floor-bottom), and the vertical half of the 18 parameters that sums it up.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Layout {
    bands: Vec<(f64, f64, f64, f64)>,
    stub: FacadeParams,
}

impl Layout {
    /// The layout of floors given bottom-up as (top, bottom, window height,
    /// window-to-floor-bottom), with the 18 parameters' vertical half summing them up: the
    /// middle floors' mean height and window band stand for one middle floor.
    fn of_bands(bands: Vec<(f64, f64, f64, f64)>, fh: usize) -> Layout {
        let n = bands.len();
        let middle: &[(f64, f64, f64, f64)] = if n > 2 { &bands[1..n - 1] } else { &[] };
        let mean = |f: fn(&(f64, f64, f64, f64)) -> f64| {
            if middle.is_empty() {
                0.0
            } else {
                middle.iter().map(f).sum::<f64>() / middle.len() as f64
            }
        };
        let (ground, top) = (bands[0], bands[n - 1]);
        let stub = FacadeParams {
            x_fl: 0.0,
            y_ft: 0.0,
            x_fr: 0.0,
            y_fb: fh as f64,
            h_1: ground.1 - ground.0,
            h: mean(|b| b.1 - b.0),
            h_nl: if n > 1 { top.1 - top.0 } else { 0.0 },
            n_l: n as u32,
            w_off: 0.0,
            w_w: 0.0,
            w_gap: 0.0,
            w_h: mean(|b| b.2),
            w_grd: mean(|b| b.3),
            w_h_ground: ground.2,
            w_grd_ground: ground.3,
            w_h_top: if n > 1 { top.2 } else { 0.0 },
            w_grd_top: if n > 1 { top.3 } else { 0.0 },
            n_w: 0,
        };
        Layout { bands, stub }
    }

    /// One floor per window row (`rows`: relative, top to bottom), the floor lines halfway
    /// between rows; one windowless floor when there is no row.
    pub(super) fn of_rows(rows: &[(usize, usize)], fh: usize) -> Layout {
        if rows.is_empty() {
            return Layout::of_bands(vec![(0.0, fh as f64, 0.0, 0.0)], fh);
        }
        let n = rows.len();
        let line = |k: usize| -> f64 {
            if k + 1 == n {
                fh as f64
            } else {
                (rows[k].1 + rows[k + 1].0) as f64 / 2.0
            }
        };
        let bands = (0..n)
            .rev()
            .map(|k| {
                let top = if k == 0 { 0.0 } else { line(k - 1) };
                let bottom = line(k);
                let (a, b) = (rows[k].0 as f64, rows[k].1 as f64);
                (top, bottom, b - a, bottom - b)
            })
            .collect();
        Layout::of_bands(bands, fh)
    }
}

/// The sum of `d` down each column of the façade `r` over the rows `rows` (relative to the
/// façade's top), left to right.
pub(super) fn column_profile(d: &Integral, r: [usize; 4], rows: &[(usize, usize)]) -> Vec<f64> {
    let [x0, y0, x1, _] = r;
    (x0..x1)
        .map(|x| {
            rows.iter()
                .map(|&(a, b)| d.sum(x, y0 + a, x + 1, y0 + b))
                .sum()
        })
        .collect()
}

/// The sum of `d` along each row of the façade `r` over the columns `cols` (relative to the
/// façade's left edge), top to bottom.
pub(super) fn row_profile(d: &Integral, r: [usize; 4], cols: &[(usize, usize)]) -> Vec<f64> {
    let [x0, y0, _, y1] = r;
    (y0..y1)
        .map(|y| {
            cols.iter()
                .map(|&(a, b)| d.sum(x0 + a, y, x0 + b, y + 1))
                .sum()
        })
        .collect()
}

/// The rows a search starts from: those whose sum `all` over the whole width is above the
/// mean row's (at the mean too when that leaves none).
pub(super) fn start_rows(all: &[f64]) -> Vec<(usize, usize)> {
    let fh = all.len();
    let mean = all.iter().sum::<f64>() / fh.max(1) as f64;
    let mut start: Vec<(usize, usize)> = (0..fh)
        .filter(|&y| all[y] > mean)
        .map(|y| (y, y + 1))
        .collect();
    if start.is_empty() {
        start = (0..fh)
            .filter(|&y| all[y] >= mean)
            .map(|y| (y, y + 1))
            .collect();
    }
    start
}

/// The layout of a searched [`Vertical`], the user's blind floors (from the ground, 1 = the
/// ground floor) without windows.
fn searched_layout(ver: &Vertical, fh: usize, blind: &[usize]) -> Layout {
    let stub = ver.params_stub(fh);
    let mut bands = stub.floor_bands();
    for &floor in blind {
        if let Some(b) = floor.checked_sub(1).and_then(|i| bands.get_mut(i)) {
            (b.2, b.3) = (0.0, 0.0);
        }
    }
    Layout { bands, stub }
}

/// Departure (issue 22, §3.1.6–3.1.7): the user's floor lines `lines` (relative rows, top to
/// bottom, inside the façade) are the floors, of any heights rather than the text's equal
/// middle floors, and only the window bands are searched, each floor's its own on its kind's
/// profile (eqs. 3.3–3.4 share one band among the middle floors, measured from their bottom
/// edges: once a user drags a line the windows do not move with it). Blind floors have none.
fn fixed_layout(profiles: [&[f64]; 3], lines: &[usize], fh: usize, blind: &[usize]) -> Layout {
    let mut edges = vec![0];
    edges.extend_from_slice(lines);
    edges.push(fh);
    let n = edges.len() - 1;
    // Floor i from the ground (0 = ground floor) spans rows edges[n − 1 − i] .. edges[n − i].
    let bands: Vec<(f64, f64, f64, f64)> = (0..n)
        .map(|i| {
            let (t, b) = (edges[n - 1 - i], edges[n - i]);
            let (wh, wg) = if blind.contains(&(i + 1)) {
                (0, 0)
            } else {
                floor_band(profiles[kind(i, n)], t, b).1
            };
            (t as f64, b as f64, wh as f64, wg as f64)
        })
        .collect();
    Layout::of_bands(bands, fh)
}

/// Window rows per floor kind (relative to the façade top), from a vertical layout.
fn kind_rows(layout: &Layout, fh: usize) -> [Vec<(usize, usize)>; 3] {
    let n = layout.bands.len();
    let mut out: [Vec<(usize, usize)>; 3] = Default::default();
    for (i, &(_, y1, wh, wg)) in layout.bands.iter().enumerate() {
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
    fit_columns_with(r, d, grads, p, &Constraints::default())
}

/// [`fit_columns`] under the user's corrections (issue 22): fixed floor lines and column edges
/// are kept and only the rest is searched; blind floors get no windows.
pub(crate) fn fit_columns_with(
    r: [usize; 4],
    d: &Integral,
    grads: &Gradients,
    p: &SearchParams,
    fixed: &Constraints,
) -> Facade {
    let [x0, y0, x1, y1] = r;
    let (fw, fh) = (x1 - x0, y1 - y0);
    let y_cands: Vec<usize> = grads.y_peaks(r, p).into_iter().map(|y| y - y0).collect();
    let col_profile = |rows: &[(usize, usize)]| column_profile(d, r, rows);
    let row_profile = |cols: &[(usize, usize)]| row_profile(d, r, cols);
    let blind = &fixed.blind;
    let layout_for = |profiles: [&[f64]; 3]| -> Layout {
        match &fixed.lines {
            Some(lines) => fixed_layout(profiles, lines, fh, blind),
            None => searched_layout(&search_vertical_kinds(profiles, &y_cands, blind), fh, blind),
        }
    };
    // Departure 4 (session 17): start from the rows whose sum over the whole width is above
    // the mean row's (at the mean too when that leaves none). The text's start (`joint.rs`)
    // takes the median: on a crisp map whose window rows outnumber the wall rows, the window
    // rows (Σ ≈ 0 where windows fill half the width) sit at the median, and one row of sky at
    // the façade's top edge was the whole start — the search then found no window at all.
    // The mean lies between the two kinds of row.
    let start = start_rows(&row_profile(&[(0, fw)]));
    // Departure 1's regularisers: windows and gaps at least `min_window_frac` of the façade's
    // width, and each column costs `column_cost` pixels of evidence per window row (without
    // them a noisy map gives a barcode of one-pixel columns).
    let min_w = ((p.min_window_frac * fw as f64).round() as usize).max(MIN_SIZE);
    let columns_of = |prof: &[f64], rows: usize| -> Vec<(usize, usize)> {
        best_intervals(prof, min_w, min_w, p.column_cost * rows as f64)
    };
    let span = |rows: &[(usize, usize)]| -> usize { rows.iter().map(|r| r.1 - r.0).sum() };
    // The user's columns, when given, are every floor kind's columns in every round.
    let first = match &fixed.columns {
        Some(user) => user.clone(),
        None => columns_of(&col_profile(&start), start.len()),
    };
    let mut cols: [Vec<(usize, usize)>; 3] = [first.clone(), first.clone(), first];
    let flat = vec![0f64; fh];
    let mut layout = match &fixed.lines {
        Some(lines) => fixed_layout([&flat, &flat, &flat], lines, fh, blind),
        None => {
            let one = Vertical {
                n_l: 1,
                h_1: fh,
                ..Default::default()
            };
            searched_layout(&one, fh, blind)
        }
    };
    if cols[MIDDLE].is_empty() {
        return facade_of(r, &layout, &[Vec::new(), Vec::new(), Vec::new()], d);
    }
    for _ in 0..p.rounds.max(1) {
        let profiles = cols.clone().map(|c| row_profile(&c));
        let new_layout = layout_for([&profiles[GROUND], &profiles[MIDDLE], &profiles[TOP]]);
        // Departure 2: each floor kind's columns from its own window rows; a kind without
        // window rows keeps the columns of all window rows, so it can gain windows next round.
        let rows = kind_rows(&new_layout, fh);
        let every: Vec<(usize, usize)> = rows.iter().flatten().copied().collect();
        if every.is_empty() {
            layout = new_layout;
            break;
        }
        let new_cols = match &fixed.columns {
            Some(user) => [user.clone(), user.clone(), user.clone()],
            None => {
                let common = columns_of(&col_profile(&every), span(&every));
                rows.clone().map(|k| {
                    if k.is_empty() {
                        common.clone()
                    } else {
                        columns_of(&col_profile(&k), span(&k))
                    }
                })
            }
        };
        let same = new_layout == layout && new_cols == cols;
        layout = new_layout;
        cols = new_cols;
        if same {
            break;
        }
    }
    facade_of(r, &layout, &cols, d)
}

/// The façade tree of a vertical layout and per-kind columns (relative), in image pixels.
pub(super) fn facade_of(
    r: [usize; 4],
    layout: &Layout,
    cols: &[Vec<(usize, usize)>; 3],
    d: &Integral,
) -> Facade {
    let [x0, y0, x1, y1] = r;
    let (stub, bands) = (layout.stub, &layout.bands);
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

    /// The CLI tests' façade as a crisp map: 120 × 76, a top row of +1 (sky at the façade's
    /// edge), two floors of three 20 × 20 windows (+1) on wall (−1). Window rows sum to 0 and
    /// outnumber the wall rows; the text's median start was that one top row and found no
    /// window. From the mean, all six are found.
    #[test]
    fn a_crisp_map_whose_window_rows_outnumber_the_wall_rows_gives_its_windows() {
        let (w, h) = (120usize, 76usize);
        let win = |x: usize, y: usize| {
            (y == 0)
                || ((11..31).contains(&y) || (46..66).contains(&y))
                    && (0..3).any(|k| (12 + 38 * k..32 + 38 * k).contains(&x))
        };
        let (d, g) = crate::search::gradients::crisp_map(w, h, win);
        let f = fit_columns([0, 0, w, h], &d, &g, &SearchParams::default());
        let mut windows: Vec<[f64; 4]> = f
            .floors
            .iter()
            .flat_map(|fl| fl.windows.iter().copied())
            .filter(|b| b[3] - b[1] > 1.0)
            .collect();
        windows.sort_by(|a, b| (a[1], a[0]).partial_cmp(&(b[1], b[0])).unwrap());
        let expect: Vec<[f64; 4]> = [11.0, 46.0]
            .iter()
            .flat_map(|&y| {
                (0..3).map(move |k| [12.0 + 38.0 * k as f64, y, 32.0 + 38.0 * k as f64, y + 20.0])
            })
            .collect();
        assert_eq!(windows, expect);
    }
}
