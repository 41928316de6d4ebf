//! Floors and windows inside one façade (§3.1.6–3.1.7): window vs wall. The vertical parameters
//! {h_1, h, h_NL, N_L, w_h, w_grd, w'_h, w'_grd, w''_h, w''_grd} and the horizontal ones
//! {w_off, w_w, w_gap, N_w} are searched separately and exhaustively over gradient peaks; the
//! two searches alternate a bounded number of rounds in [`super::joint`] (each round can only
//! raise the merit), whose `fit_floors` runs them on one façade.

use crate::model::{FacadeParams, MAX_FLOORS, MAX_WINDOWS};

/// Smallest floor height, window width and window gap considered (pixels).
pub(super) const MIN_SIZE: usize = 3;

/// Best contiguous band [t, b) of a profile with positive sum (Kadane); `None` if none is.
fn best_band(prof: &[f64]) -> Option<(f64, usize, usize)> {
    let (mut best, mut cur, mut start) = (None::<(f64, usize, usize)>, 0.0, 0);
    for (i, v) in prof.iter().enumerate() {
        if cur <= 0.0 {
            cur = 0.0;
            start = i;
        }
        cur += v;
        if cur > 0.0 && best.is_none_or(|b| cur > b.0) {
            best = Some((cur, start, i + 1));
        }
    }
    best
}

/// Vertical layout, in coordinates relative to the façade top (rows 0..fh).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct Vertical {
    pub(super) merit: f64,
    pub(super) n_l: u32,
    pub(super) h_1: usize,
    pub(super) h_nl: usize,
    /// (window height, window-to-floor-bottom) for ground, middle, top.
    pub(super) ground: (usize, usize),
    pub(super) middle: (usize, usize),
    pub(super) top: (usize, usize),
}

impl Vertical {
    /// Window row set (relative rows), as intervals.
    pub(super) fn rows(&self, fh: usize) -> Vec<(usize, usize)> {
        let p = self.params_stub(fh);
        p.floor_bands()
            .into_iter()
            .filter(|b| b.2 > 0.0)
            .map(|(_, y1, wh, wg)| ((y1 - wg - wh).round() as usize, (y1 - wg).round() as usize))
            .collect()
    }

    pub(super) fn params_stub(&self, fh: usize) -> FacadeParams {
        let mid = self.n_l.saturating_sub(2).max(1) as f64;
        FacadeParams {
            x_fl: 0.0,
            y_ft: 0.0,
            x_fr: 0.0,
            y_fb: fh as f64,
            h_1: self.h_1 as f64,
            h: if self.n_l > 2 {
                (fh - self.h_1 - self.h_nl) as f64 / mid
            } else {
                0.0
            },
            h_nl: self.h_nl as f64,
            n_l: self.n_l,
            w_off: 0.0,
            w_w: 0.0,
            w_gap: 0.0,
            w_h: self.middle.0 as f64,
            w_grd: self.middle.1 as f64,
            w_h_ground: self.ground.0 as f64,
            w_grd_ground: self.ground.1 as f64,
            w_h_top: self.top.0 as f64,
            w_grd_top: self.top.1 as f64,
            n_w: 0,
        }
    }
}

/// Window band of one floor [f0, f1) of the row profile: (merit, height, distance to bottom).
pub(super) fn floor_band(rows: &[f64], f0: usize, f1: usize) -> (f64, (usize, usize)) {
    match best_band(&rows[f0..f1]) {
        Some((m, t, b)) => (m, (b - t, f1 - f0 - b)),
        None => (0.0, (0, 0)),
    }
}

/// Exhaustive search of the vertical parameters given the row profile (window-minus-wall
/// log-likelihood summed over the current window columns). `cands` are relative split rows.
pub(super) fn search_vertical(rows: &[f64], cands: &[usize]) -> Vertical {
    search_vertical_kinds([rows, rows, rows], cands, &[])
}

/// [`search_vertical`] with one row profile per floor kind — ground, middle, top — each summed
/// over that kind's own window columns (the per-kind columns of `Grammar::Columns`; the text's
/// grammar passes one profile three times). `blind` lists floors the user said have no
/// windows, counted from the ground (1 = ground floor): layouts with fewer floors are not
/// considered, and those floors add no merit and no rows to the middle floors' fold (issue 22;
/// a blind middle floor then has no window band of its own, which [`Vertical`] cannot say: the
/// caller empties it).
pub(super) fn search_vertical_kinds(
    profiles: [&[f64]; 3],
    cands: &[usize],
    blind: &[usize],
) -> Vertical {
    let [ground_rows, middle_rows, top_rows] = profiles;
    let rows = middle_rows;
    let fh = rows.len();
    let mut best = Vertical {
        merit: f64::NEG_INFINITY,
        ..Default::default()
    };
    // Ties go to fewer floors: a window-less sliver floor adds no merit, and §3.1.7 does not
    // say which of equal-merit layouts to keep (departure, measured on synthetic façades whose
    // floor lines carry no edge: without it an empty 10-px attic floor was added).
    let mut consider = |v: Vertical| {
        let tol = 1e-9 * best.merit.abs().max(1.0);
        if !best.merit.is_finite()
            || v.merit > best.merit + tol
            || (v.merit >= best.merit - tol && v.n_l < best.n_l)
        {
            best = v;
        }
    };
    let fewest = blind.iter().copied().max().unwrap_or(1);
    let is_blind = |floor: usize| blind.contains(&floor);
    // A blind floor's band: none, worth nothing.
    let band = |floor: usize, rows: &[f64], f0: usize, f1: usize| {
        if is_blind(floor) {
            (0.0, (0, 0))
        } else {
            floor_band(rows, f0, f1)
        }
    };
    // One floor.
    if fewest <= 1 {
        let (m, g) = band(1, ground_rows, 0, fh);
        consider(Vertical {
            merit: m,
            n_l: 1,
            h_1: fh,
            ground: g,
            ..Default::default()
        });
    }
    for &c in cands {
        if c < MIN_SIZE || c + MIN_SIZE > fh || fewest > 2 {
            continue;
        }
        // Two floors split at c.
        let (mt, t) = band(2, top_rows, 0, c);
        let (mg, g) = band(1, ground_rows, c, fh);
        consider(Vertical {
            merit: mt + mg,
            n_l: 2,
            h_1: fh - c,
            h_nl: c,
            ground: g,
            top: t,
            ..Default::default()
        });
    }
    // Three or more floors: top floor [0, a), ground [b, fh), equal middle floors in [a, b).
    for (i, &a) in cands.iter().enumerate() {
        if a < MIN_SIZE {
            continue;
        }
        let top_free = floor_band(top_rows, 0, a);
        for &b in &cands[i + 1..] {
            if b + MIN_SIZE > fh {
                continue;
            }
            let (mg, g) = band(1, ground_rows, b, fh);
            let span = b - a;
            for mid in 1..=(MAX_FLOORS as usize - 2) {
                let hm = span as f64 / mid as f64;
                if hm < MIN_SIZE as f64 {
                    break;
                }
                let n = mid + 2;
                if fewest > n {
                    continue;
                }
                let (mt, t) = if is_blind(n) { (0.0, (0, 0)) } else { top_free };
                // Fold the middle floors onto one: shared window height and offset (eqs. 3.3, 3.4).
                let len = hm.floor() as usize;
                let mut folded = vec![0f64; len];
                // Middle floor k from the top is floor n − 1 − k from the ground.
                for k in (0..mid).filter(|k| !is_blind(n - 1 - k)) {
                    // Aligned to each floor's bottom edge.
                    let bottom = (a as f64 + (k + 1) as f64 * hm).round() as usize;
                    for (o, f) in folded.iter_mut().enumerate() {
                        *f += rows[bottom - len + o];
                    }
                }
                let (mm, mband) = match best_band(&folded) {
                    Some((m, t0, b0)) => (m, (b0 - t0, len - b0)),
                    None => (0.0, (0, 0)),
                };
                consider(Vertical {
                    merit: mt + mg + mm,
                    n_l: mid as u32 + 2,
                    h_1: fh - b,
                    h_nl: a,
                    ground: g,
                    middle: mband,
                    top: t,
                });
            }
        }
    }
    if !best.merit.is_finite() {
        // No layout has as many floors as a blind floor's number: one floor, windowless if
        // the ground floor is blind.
        let (m, g) = band(1, ground_rows, 0, fh);
        best = Vertical {
            merit: m,
            n_l: 1,
            h_1: fh,
            ground: g,
            ..Default::default()
        };
    }
    best
}

/// Horizontal layout relative to the façade's left edge.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct Horizontal {
    pub(super) merit: f64,
    pub(super) off: usize,
    pub(super) w: usize,
    pub(super) gap: usize,
    pub(super) n: usize,
}

/// Exhaustive search of {w_off, w_w, w_gap, N_w} over candidate columns, given the column
/// profile summed over the current window rows.
pub(super) fn search_horizontal(cols: &[f64], cands: &[usize]) -> Horizontal {
    let fw = cols.len();
    let mut pre = vec![0f64; fw + 1];
    for (i, v) in cols.iter().enumerate() {
        pre[i + 1] = pre[i] + v;
    }
    let mut best = Horizontal::default();
    for (ia, &a) in cands.iter().enumerate() {
        for (ib, &b) in cands.iter().enumerate().skip(ia + 1) {
            let w = b - a;
            if w < MIN_SIZE {
                continue;
            }
            let one = pre[b] - pre[a];
            if one > best.merit {
                best = Horizontal {
                    merit: one,
                    off: a,
                    w,
                    gap: 0,
                    n: 1,
                };
            }
            for &c in &cands[ib + 1..] {
                let gap = c - b;
                if gap < MIN_SIZE {
                    continue;
                }
                let mut m = one;
                for k in 1..MAX_WINDOWS as usize {
                    let x0 = a + k * (w + gap);
                    if x0 + w > fw {
                        break;
                    }
                    m += pre[x0 + w] - pre[x0];
                    if m > best.merit {
                        best = Horizontal {
                            merit: m,
                            off: a,
                            w,
                            gap,
                            n: k + 1,
                        };
                    }
                }
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kadane_finds_the_positive_band() {
        assert_eq!(best_band(&[-1.0, 2.0, 3.0, -10.0, 4.0]), Some((5.0, 1, 3)));
        assert_eq!(best_band(&[-1.0, -2.0]), None);
    }

    #[test]
    fn horizontal_search_recovers_a_window_pattern() {
        // Windows at 5..10, 15..20, 25..30 in a 40-wide façade.
        let cols: Vec<f64> = (0..40)
            .map(|x| {
                if (5..30).contains(&x) && (x - 5) % 10 < 5 {
                    1.0
                } else {
                    -1.0
                }
            })
            .collect();
        let cands = vec![0, 5, 10, 15, 20, 25, 30, 40];
        let h = search_horizontal(&cols, &cands);
        assert_eq!((h.off, h.w, h.gap, h.n), (5, 5, 5, 3));
    }

    #[test]
    fn vertical_search_recovers_equal_middle_floors() {
        // 5 floors of 20 rows; windows rows 5..15 of each floor (bottom offset 5).
        let rows: Vec<f64> = (0..100)
            .map(|y| {
                if (5..15).contains(&(y % 20)) {
                    1.0
                } else {
                    -1.0
                }
            })
            .collect();
        let cands: Vec<usize> = (0..=100).step_by(5).collect();
        let v = search_vertical(&rows, &cands);
        assert_eq!(v.merit, 50.0);
        assert_eq!(
            v.rows(100),
            vec![(5, 15), (25, 35), (45, 55), (65, 75), (85, 95)]
                .into_iter()
                .rev()
                .collect::<Vec<_>>()
        );
    }
}
