//! The scan for a bar along the lines of a `Grid` (rows; columns via the transposed masks):
//! thin ruled lines, their graduations and the tests that tell a bar from a wall's outline.

use super::grid::Grid;
use super::rules::{
    CASTLE_MARGIN, CLEAR, MAX_GAP, MAX_PLAIN_UNITS, MAX_TICK, MIN_COVER, MIN_EVEN, MIN_LENGTH,
    MIN_PLAIN_UNIT, MIN_TICK_SPACING, MIN_TICKED_SHARE, MIN_TICKS, MIN_VERTICAL_TICKS,
};
use super::ticks::{Ticks, reach};

/// The longest bar along the grid's lines: (start, end, line).
pub(super) fn longest_bar(g: &Grid, numbered: bool) -> Option<(usize, usize, usize)> {
    let (len, lines) = g.dims();
    let min_len = ((len as f64) * 0.06).max(MIN_LENGTH) as usize;
    let clear = CLEAR as isize;
    let mut best: Option<(usize, usize, usize)> = None;
    for line in 0..lines {
        let l = line as isize;
        let thin = |a: usize| {
            (l - 1..=l + 1).any(|q| g.at(a, q)) && !g.at(a, l - clear) && !g.at(a, l + clear)
        };
        // A short stroke across the line (a tick, also in a finely divided first unit) is
        // still the line; a long one is a crossing line.
        let on_line =
            |a: usize| thin(a) || (g.at(a, l) && reach(g, a, l).iter().all(|&r| r <= MAX_TICK));
        let mut a = 0;
        while a < len {
            if !thin(a) {
                a += 1;
                continue;
            }
            let (start, mut end, mut seen) = (a, a, 0usize);
            while a < len && a - end <= MAX_GAP {
                if on_line(a) {
                    end = a;
                    seen += 1;
                }
                a += 1;
            }
            if end + 1 - start < min_len || (seen as f64) < MIN_COVER * (end + 1 - start) as f64 {
                continue;
            }
            let l = snap_to_ink(g, start, end, l);
            let (run_start, run_end) = (start, end);
            let mut ticks = Ticks::of(g, start, end, l);
            let (mut start, mut end) = ticks.extend(g, start, end, l);
            let mut ticked = ticks.centres(g, start, end, l);
            if ticked.len() < MIN_TICKS {
                ticks = Ticks::of_checkered(g, run_start, run_end, l);
                (start, end) = ticks.extend(g, run_start, run_end, l);
                ticked = ticks.centres(g, start, end, l);
            }
            let Some(centres) = graduations(&ticked, start, end) else {
                continue;
            };
            let (first, last) = (centres[0], centres[centres.len() - 1]);
            let count = centres.len();
            let (start, end) = (first.round() as usize, last.round() as usize);
            if end <= start
                || best.is_some_and(|(s, e, _)| e - s >= end - start)
                || count < MIN_TICKS
                || count * MIN_TICK_SPACING > end - start + 1
                || !evenly_divided(&centres)
                || !ticks.on_open_sheet(g, start, end, l)
                || !ticks.stands_free(g, start, end, l)
                || near_the_castle(g, start, end, l)
                || numbered
                    && (count < MIN_VERTICAL_TICKS
                        || !evenly_divided_all(&centres)
                        || !ticks.numbered(g, &centres, l))
            {
                continue;
            }
            best = Some((start, end, l as usize));
        }
    }
    best
}

/// Whether the castle's walls come within CASTLE_MARGIN px of the line along more than a
/// tenth of it: the outlines of buildings and the edges of hatched walls lie along walls; a
/// bar is drawn apart.
fn near_the_castle(g: &Grid, start: usize, end: usize, line: isize) -> bool {
    let m = CASTLE_MARGIN as isize;
    let near = (start..=end)
        .filter(|&a| (line - m..=line + m).any(|q| g.castle_at(a, q)))
        .count();
    near * 10 > end + 1 - start
}

/// The graduations of a bar from its zero to its far end, or None when the line does not end
/// on them. The bar runs from its zero tick to its last full-length one; the line may overrun
/// them a little (Coucy: under the word "mètres", whose letters are short "ticks"); a wall's
/// outline runs on. A line end a whole number of units past the outer tick is the bar's end
/// too (session 6): Armitage's 0–1000 ft bars, whose second half is a plain line, and his bars
/// whose first unit is a black box without a tick at the zero.
fn graduations(ticked: &[(f64, usize)], start: usize, end: usize) -> Option<Vec<f64>> {
    let &(first, zero_height) = ticked.first()?;
    let (start, end) = (start as f64, end as f64);
    let overrun = (0.08 * (end - start)).max(MAX_GAP as f64 + 2.0);
    let within = || {
        ticked
            .iter()
            .rev()
            .take_while(|&&(c, _)| end - c <= overrun)
    };
    let last = within()
        .find(|&&(_, h)| h * 10 >= zero_height * 7)
        .or_else(|| within().next())
        .map(|&(c, _)| c);
    let mut centres: Vec<f64> = ticked
        .iter()
        .map(|&(c, _)| c)
        .filter(|&c| last.is_none_or(|l| c <= l))
        .collect();
    // Units by the median or the finest of the gaps of 12 px or more (subdivisions of the
    // first unit are finer; on finer units any length is nearly a whole number of them); an end without a tick needs three ticks on the line to say what a unit
    // is, spread over 30 % of the bar at least (letters and specks bunch up).
    let mut gaps: Vec<f64> = centres
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|&g| g >= MIN_PLAIN_UNIT)
        .collect();
    gaps.sort_unstable_by(f64::total_cmp);
    let units = [gaps.first(), gaps.get(gaps.len() / 2)];
    let ticks_span = centres.last()? - centres[0];
    let tick_count = centres.len();
    let whole_units_away = |d: f64| {
        tick_count >= MIN_TICKS
            && units
                .iter()
                .flatten()
                .any(|&&u| d <= MAX_PLAIN_UNITS * u && whole_multiple(d, u))
            && ticks_span >= MIN_TICKED_SHARE * (end - start)
    };
    if first - start > overrun {
        if !whole_units_away(first - start) {
            return None;
        }
        centres.insert(0, start);
    }
    if last.is_none() {
        let outer = *centres.last()?;
        if !whole_units_away(end - outer) {
            return None;
        }
        centres.push(end);
    }
    Some(centres)
}

/// The median gap between neighbouring ticks (None with fewer than two).
fn median_gap(centres: &[f64]) -> Option<f64> {
    let mut gaps: Vec<f64> = centres.windows(2).map(|w| w[1] - w[0]).collect();
    gaps.sort_unstable_by(f64::total_cmp);
    gaps.get(gaps.len() / 2).copied()
}

/// Whether `big` is a whole multiple of `small`, to 12 % of `small` (at least 1.5 px).
fn whole_multiple(big: f64, small: f64) -> bool {
    let k = (big / small).round();
    k >= 1.0 && (big - k * small).abs() <= (0.12 * small).max(1.5)
}

/// Whether the ticks divide the bar evenly: most gaps between neighbouring ticks are whole
/// multiples or whole fractions of the median gap (a bar's units and their subdivisions),
/// where the stubs of walls along a building's outline fall anywhere.
fn evenly_divided(centres: &[f64]) -> bool {
    let Some(unit) = median_gap(centres) else {
        return false;
    };
    let gaps: Vec<f64> = centres.windows(2).map(|w| w[1] - w[0]).collect();
    let even = gaps
        .iter()
        .filter(|&&g| whole_multiple(g.max(unit), g.min(unit)))
        .count();
    even as f64 >= MIN_EVEN * gaps.len() as f64
}

/// Whether every gap between neighbouring ticks is at least MIN_TICK_SPACING and a whole
/// multiple or fraction of the median gap (the test for vertical bars, stricter than
/// [`evenly_divided`]: letters, arrows and hachures beside a line bunch their "ticks").
fn evenly_divided_all(centres: &[f64]) -> bool {
    median_gap(centres).is_some_and(|unit| {
        centres.windows(2).all(|w| {
            let gap = w[1] - w[0];
            gap >= MIN_TICK_SPACING as f64 && whole_multiple(gap.max(unit), gap.min(unit))
        })
    })
}

/// The line of the band (±1) with most ink over the bar: the bar's own row or column.
fn snap_to_ink(g: &Grid, start: usize, end: usize, line: isize) -> isize {
    (line - 1..=line + 1)
        .max_by_key(|&q| {
            (
                (start..=end).filter(|&a| g.at(a, q)).count(),
                -(q - line).abs(),
            )
        })
        .unwrap_or(line)
}
