//! Floors and windows inside one façade with free window rows (issue 21): `Grammar::Rows`,
//! and the default `Grammar::ColumnsOrRows`, which keeps whichever of the two fits explains
//! more window evidence.
//!
//! Departure from §3.1.6's floors (ground, N_L − 2 equal middle floors, top; one window band
//! per floor kind, eqs. 3.2–3.4), beyond `Grammar::Columns`' free columns: the window rows
//! are any disjoint intervals of the façade's height — [`best_intervals`] on the row profile
//! of the window columns, as the columns are on the column profile of the window rows — and
//! the two alternate. Real façades mix floor heights (an entresol over a shop floor,
//! a mansard, a piano nobile), and one window band folded over equal middle floors drifts
//! off the windows of the others. Each floor holds one window row, the floor lines halfway
//! between rows; every floor has the same columns, and a cell of the grid whose pixels
//! favour wall is wall (`Grammar::Columns`' departure 3).
//!
//! Departure from §3.1.7's search over one grammar: the two fits maximise the same sum (the
//! clipped window − wall ratio over the windows), so `ColumnsOrRows` keeps the larger — the
//! maximum over the union of the two model spaces. Measured in docs/facade.md ("Free window
//! rows"): a few façades gain, few lose, CMP and Art-deco rise on average.

use super::columns::{
    Layout, best_intervals_at_most, column_profile, facade_of, fit_columns, row_profile, start_rows,
};
use super::floors::MIN_SIZE;
use super::gradients::{Gradients, Integral};
use super::params::SearchParams;
use crate::model::{Facade, MAX_COLUMNS, MAX_FLOORS};

/// Fits the floors and windows of the façade `r` = [x0, y0, x1, y1] under `Grammar::Rows`,
/// given the integral of the (clipped) window-minus-wall log-likelihood.
pub fn fit_rows(r: [usize; 4], d: &Integral, p: &SearchParams) -> Facade {
    let [x0, y0, x1, y1] = r;
    let (fw, fh) = (x1 - x0, y1 - y0);
    let col_profile = |rows: &[(usize, usize)]| column_profile(d, r, rows);
    let row_profile = |cols: &[(usize, usize)]| row_profile(d, r, cols);
    let span = |v: &[(usize, usize)]| -> usize { v.iter().map(|r| r.1 - r.0).sum() };
    // `Grammar::Columns`' regularisers, the least size in each direction its own.
    let min_w = ((p.min_window_frac * fw as f64).round() as usize).max(MIN_SIZE);
    let min_h = ((p.min_window_frac * fh as f64).round() as usize).max(MIN_SIZE);
    // At most MAX_COLUMNS columns and MAX_FLOORS rows, the strongest (FACADE.json's bounds).
    let intervals = |prof: &[f64], min: usize, across: usize, max: u32| {
        best_intervals_at_most(prof, min, min, p.column_cost * across as f64, max as usize)
    };
    let start = start_rows(&row_profile(&[(0, fw)]));
    let mut cols = intervals(&col_profile(&start), min_w, start.len(), MAX_COLUMNS);
    let mut rows: Vec<(usize, usize)> = Vec::new();
    for _ in 0..p.rounds.max(1) {
        if cols.is_empty() {
            break;
        }
        let new_rows = intervals(&row_profile(&cols), min_h, span(&cols), MAX_FLOORS);
        if new_rows.is_empty() {
            rows = new_rows;
            break;
        }
        let new_cols = intervals(&col_profile(&new_rows), min_w, span(&new_rows), MAX_COLUMNS);
        let same = new_rows == rows && new_cols == cols;
        rows = new_rows;
        cols = new_cols;
        if same {
            break;
        }
    }
    facade_of(
        r,
        &Layout::of_rows(&rows, fh),
        &[cols.clone(), cols.clone(), cols],
        d,
    )
}

/// `Grammar::ColumnsOrRows`: the `Grammar::Columns` fit and the [`fit_rows`] fit of the
/// façade `r`, whichever explains more window evidence ([`window_evidence`]); the columns'
/// fit on a tie.
pub fn fit_columns_or_rows(
    r: [usize; 4],
    d: &Integral,
    grads: &Gradients,
    p: &SearchParams,
) -> Facade {
    let columns = fit_columns(r, d, grads, p);
    let rows = fit_rows(r, d, p);
    if window_evidence(&rows, d) > window_evidence(&columns, d) {
        rows
    } else {
        columns
    }
}

/// The sum of `d` (the clipped window − wall ratio) over the façade's windows: what both
/// fits maximise.
pub fn window_evidence(f: &Facade, d: &Integral) -> f64 {
    f.floors
        .iter()
        .flat_map(|fl| &fl.windows)
        .map(|w| {
            let [x0, y0, x1, y1] = w.map(|v| v.round().max(0.0) as usize);
            d.sum(x0, y0, x1, y1)
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::search::gradients::crisp_map;

    /// A crisp map with windows at the given column and row intervals.
    fn crisp(
        w: usize,
        h: usize,
        cols: &[(usize, usize)],
        rows: &[(usize, usize)],
    ) -> (Integral, Gradients) {
        let inside = |v: usize, iv: &[(usize, usize)]| iv.iter().any(|&(a, b)| (a..b).contains(&v));
        crisp_map(w, h, |x, y| inside(x, cols) && inside(y, rows))
    }

    fn windows(f: &Facade) -> Vec<[f64; 4]> {
        let mut v: Vec<[f64; 4]> = f.floors.iter().flat_map(|fl| fl.windows.clone()).collect();
        v.sort_by(|a, b| (a[1], a[0]).partial_cmp(&(b[1], b[0])).unwrap());
        v
    }

    /// Four window rows of four heights at uneven spacing (an attic, a piano nobile, an
    /// entresol, a shop floor): free rows find all 16 windows exactly, one floor per row.
    #[test]
    fn free_rows_find_windows_on_floors_of_any_height() {
        let cols = [(10, 30), (50, 70), (90, 110), (130, 150)];
        let rows = [(8, 20), (34, 70), (84, 96), (110, 150)];
        let (d, _) = crisp(160, 160, &cols, &rows);
        let f = fit_rows([0, 0, 160, 160], &d, &SearchParams::default());
        let expect: Vec<[f64; 4]> = rows
            .iter()
            .flat_map(|&(a, b)| {
                cols.iter()
                    .map(move |&(c, e)| [c as f64, a as f64, e as f64, b as f64])
            })
            .collect();
        assert_eq!(windows(&f), expect);
        assert_eq!(f.floors.len(), 4);
        // 4 columns of 20 px over rows 12 + 36 + 12 + 40 px high, every pixel +1.
        assert_eq!(window_evidence(&f, &d), 8000.0);
    }

    /// Fourteen window rows (a tall façade, or a grid of panes): the ten strongest become
    /// floors, FACADE.json's bound, the four weakest (the shortest) left as wall.
    #[test]
    fn free_rows_keep_at_most_the_ten_strongest_rows() {
        let cols = [(10, 30), (50, 70)];
        let rows: Vec<(usize, usize)> = (0..14)
            .map(|k| (10 + 20 * k, 10 + 20 * k + if k % 4 == 1 { 6 } else { 10 }))
            .collect();
        let (d, _) = crisp(80, 290, &cols, &rows);
        let f = fit_rows([0, 0, 80, 290], &d, &SearchParams::default());
        assert_eq!(f.floors.len(), MAX_FLOORS as usize);
        let found: Vec<[f64; 4]> = windows(&f);
        let kept: Vec<[f64; 4]> = rows
            .iter()
            .filter(|r| r.1 - r.0 == 10)
            .flat_map(|&(a, b)| {
                cols.iter()
                    .map(move |&(c, e)| [c as f64, a as f64, e as f64, b as f64])
            })
            .collect();
        assert_eq!(found, kept);
    }

    /// The union keeps the fit that explains more: on the uneven rows above the free rows'
    /// (all the evidence, 16 windows); on a façade whose ground floor has its own columns (a
    /// shop front under two floors of narrow windows) the columns' fit, which gives each
    /// floor kind its columns.
    #[test]
    fn the_union_keeps_the_fit_that_explains_more_window_evidence() {
        let p = SearchParams::default();
        let cols = [(10, 30), (50, 70), (90, 110), (130, 150)];
        let rows = [(8, 20), (34, 70), (84, 96), (110, 150)];
        let (d, g) = crisp(160, 160, &cols, &rows);
        let r = [0, 0, 160, 160];
        let both = fit_columns_or_rows(r, &d, &g, &p);
        assert_eq!(windows(&both), windows(&fit_rows(r, &d, &p)));
        assert!(window_evidence(&both, &d) > window_evidence(&fit_columns(r, &d, &g, &p), &d));

        // Two floors of four narrow windows over a shop floor of one wide front.
        let (w, h) = (160usize, 120usize);
        let upper = |x: usize, y: usize| {
            ((10..34).contains(&y) || (50..74).contains(&y))
                && [(10, 30), (50, 70), (90, 110), (130, 150)]
                    .iter()
                    .any(|&(a, b)| (a..b).contains(&x))
        };
        let shop = |x: usize, y: usize| (90..115).contains(&y) && (20..140).contains(&x);
        let (d, g) = crisp_map(w, h, |x, y| upper(x, y) || shop(x, y));
        let r = [0, 0, w, h];
        let columns = fit_columns(r, &d, &g, &p);
        let both = fit_columns_or_rows(r, &d, &g, &p);
        assert_eq!(windows(&both), windows(&columns));
        assert!(window_evidence(&columns, &d) > window_evidence(&fit_rows(r, &d, &p), &d));
    }
}
