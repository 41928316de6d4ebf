//! Drawn scale bars (issue 11; §5.1.1 takes the drawing's scale as given): the longest ruled
//! horizontal line with graduation ticks that stands apart from the castle, so that a user who
//! reads its length off the drawing once gets a model in metres.

use image::GrayImage;
use serde::Serialize;

use crate::binarize::{Connectivity, binarize, components, threshold_level};

pub mod eval;

/// A scale bar: its two ends, in the drawing's pixels (`y0 == y1` for a horizontal bar,
/// `x0 == x1` for a vertical one).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ScaleBar {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
    /// Length in pixels, end to end.
    pub length_px: u32,
}

impl ScaleBar {
    /// Units per pixel when the bar is `length` units long.
    pub fn scale(&self, length: f64) -> f64 {
        length / f64::from(self.length_px.max(1))
    }

    /// "from (x0, y0) to (x1, y1), N px", for messages that let the user check the bar.
    pub fn describe(&self) -> String {
        format!(
            "from ({}, {}) to ({}, {}), {} px",
            self.x0, self.y0, self.x1, self.y1, self.length_px
        )
    }
}

/// What the finder looks for, for messages when it finds nothing.
pub const LOOKED_FOR: &str = "a horizontal ruled line at least 40 px long with three or more evenly spaced ticks, apart from the walls";

/// How far from the line, in pixels, the paper must be clear for the line to count as thin
/// (a bar up to 2 × CLEAR − 1 px thick); ticks and lettering that reach this far leave gaps.
const CLEAR: usize = 4;
/// Shortest bar (px): on shorter lines a pixel is more than 2.5 % of the scale, and the short
/// lines that pass the other tests were edges of buildings.
const MIN_LENGTH: f64 = 40.0;
/// The longest gap (ticks, numerals touching the line, breaks in the engraving) a bar may have.
const MAX_GAP: usize = 6;
/// Share of the bar's length where the thin line is seen.
const MIN_COVER: f64 = 0.8;
/// Graduations a bar must show (its two ends and at least one division) …
const MIN_TICKS: usize = 3;
/// … at most one per this many pixels (hachures and hatching are denser).
const MIN_TICK_SPACING: usize = 6;
/// Share of the gaps between ticks that must be whole multiples or fractions of the unit.
const MIN_EVEN: f64 = 0.75;
/// Ticks are short strokes: ink that runs on this far from the line is a crossing line.
const MAX_TICK: usize = 14;
/// Share of the bar's length (ticks aside) with clear paper for 10 px on its clearer side …
const MIN_CLEAR_SIDE: f64 = 0.9;
/// … and on its other side, where the numerals are.
const MIN_LETTERED_SIDE: f64 = 0.4;
/// With lettering on both sides: share of the clearer side free within 10 px …
const MIN_LETTERED_BOTH: f64 = 0.6;
/// … and of both sides free 16–30 px out.
const MIN_FAR_CLEAR_BOTH: f64 = 0.7;
/// Distances from the line (px) beyond its numerals, where the paper must be clear …
const FAR: (isize, isize) = (16, 30);
/// … along this share of the bar: buildings' outlines have walls there.
const MIN_FAR_CLEAR: f64 = 0.7;
/// How close the castle's walls may come to a bar.
const CASTLE_MARGIN: usize = 8;
/// Share of the bar's length along which the paper on one side is the open sheet around the
/// drawing (connected to the sheet's border), not a room or courtyard of the castle.
const MIN_OPEN: f64 = 0.6;

/// Finds the scale bar. Ink that belongs to the castle (the largest 8-connected region) is
/// left out; in the rest, every row is scanned for a thin straight line at least 40 px and 6 %
/// of the drawing's width long, seen along 80 % of its length with gaps of at most 6 px, crossed
/// by three or more short ticks that divide it evenly and are no denser than one per 6 px, with
/// clear paper beside it, on the open sheet, away from the walls; it is trimmed to its outer
/// full-height ticks. The longest wins. None when nothing qualifies.
///
/// Departs from the earlier rule (one connected region with a 90 %-inked row, outside the
/// castle's bounding box): real bars are broken by ticks and numerals and often sit within the
/// bounding box of the moats. Coucy's bar is now found tick to tick: 157 px for 50 m,
/// 0.318 m/px, hand-read 0.32.
pub fn find(grey: &GrayImage) -> Option<ScaleBar> {
    let (w, h) = (grey.width() as usize, grey.height() as usize);
    if w == 0 || h == 0 {
        return None;
    }
    let bin = binarize(grey, threshold_level(grey));
    let inked = components(&bin, 255, Connectivity::Eight);
    let castle = (1..inked.sizes.len()).max_by_key(|&l| inked.sizes[l])?;
    let ink: Vec<bool> = inked
        .labels
        .iter()
        .map(|&l| l != 0 && l as usize != castle)
        .collect();
    let castle_ink: Vec<bool> = inked.labels.iter().map(|&l| l as usize == castle).collect();
    let open = sheet_around_the_drawing(&bin);
    // Only horizontal bars: on the 236 public-domain plans every vertical candidate that passed
    // these tests was a section line or the outline of a wall, and no plan had only a vertical bar.
    let grid = Grid {
        ink: &ink,
        castle: &castle_ink,
        open: &open,
        w,
        h,
    };
    longest_bar(&grid).map(|(x0, x1, y)| ScaleBar {
        x0: x0 as u32,
        y0: y as u32,
        x1: x1 as u32,
        y1: y as u32,
        length_px: (x1 - x0 + 1) as u32,
    })
}

/// Paper pixels 4-connected to the sheet's border.
fn sheet_around_the_drawing(bin: &GrayImage) -> Vec<bool> {
    let (w, h) = (bin.width() as usize, bin.height() as usize);
    let paper = components(bin, 0, Connectivity::Four);
    let mut outside = vec![false; paper.sizes.len()];
    for x in 0..w {
        outside[paper.labels[x] as usize] = true;
        outside[paper.labels[(h - 1) * w + x] as usize] = true;
    }
    for y in 0..h {
        outside[paper.labels[y * w] as usize] = true;
        outside[paper.labels[y * w + w - 1] as usize] = true;
    }
    outside[0] = false;
    paper.labels.iter().map(|&l| outside[l as usize]).collect()
}

/// The masks, read along rows: position `along` (x) on line `line` (y).
struct Grid<'a> {
    ink: &'a [bool],
    castle: &'a [bool],
    open: &'a [bool],
    w: usize,
    h: usize,
}

impl Grid<'_> {
    /// Length of a line and the number of lines.
    fn dims(&self) -> (usize, usize) {
        (self.w, self.h)
    }

    fn index(&self, along: usize, line: isize) -> Option<usize> {
        if line < 0 || line as usize >= self.h || along >= self.w {
            return None;
        }
        Some(line as usize * self.w + along)
    }

    /// Ink at position `along` on line `line`; outside the image is paper.
    fn at(&self, along: usize, line: isize) -> bool {
        self.index(along, line).is_some_and(|i| self.ink[i])
    }

    /// Any ink at the position, the castle's included.
    fn any_ink_at(&self, along: usize, line: isize) -> bool {
        self.index(along, line)
            .is_some_and(|i| self.ink[i] || self.castle[i])
    }

    /// The castle's own ink at the position.
    fn castle_at(&self, along: usize, line: isize) -> bool {
        self.index(along, line).is_some_and(|i| self.castle[i])
    }

    /// Open sheet at the position; outside the image counts as open.
    fn open_at(&self, along: usize, line: isize) -> bool {
        self.index(along, line).is_none_or(|i| self.open[i])
    }
}

/// The longest bar along the grid's lines: (start, end, line).
fn longest_bar(g: &Grid) -> Option<(usize, usize, usize)> {
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
            let ticks = Ticks::of(g, start, end, l);
            let (start, end) = ticks.extend(g, start, end, l);
            let ticked = ticks.centres(g, start, end, l);
            let Some(&(first, zero_height)) = ticked.first() else {
                continue;
            };
            // The bar runs from its zero tick to its last full-length one; the line may
            // overrun them a little (Coucy: under the word "mètres", whose letters are short
            // "ticks"); a wall's outline runs on.
            let overrun = (0.08 * (end - start) as f64).max(MAX_GAP as f64 + 2.0);
            let within = || {
                ticked
                    .iter()
                    .rev()
                    .take_while(|&&(c, _)| end as f64 - c <= overrun)
            };
            let Some(&(last, _)) = within()
                .find(|&&(_, h)| h * 10 >= zero_height * 7)
                .or_else(|| within().next())
            else {
                continue;
            };
            if first - start as f64 > overrun {
                continue;
            }
            let centres: Vec<f64> = ticked
                .iter()
                .map(|&(c, _)| c)
                .filter(|&c| c <= last)
                .collect();
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
            {
                continue;
            }
            best = Some((start, end, l as usize));
        }
    }
    best
}

/// How far ink reaches from the line on each side at `along` (contiguous, capped at
/// MAX_TICK + 1, which marks a line that crosses rather than a tick).
fn reach(g: &Grid, along: usize, line: isize) -> [usize; 2] {
    [-1isize, 1].map(|dir| {
        (1..=MAX_TICK + 1)
            .take_while(|&k| g.at(along, line + dir * k as isize))
            .count()
    })
}

/// Graduations of a bar: columns where ink reaches at least 2 px farther from the line than
/// it typically does along the bar (so a 3-px-thick line is not all ticks), but stops short.
struct Ticks {
    typical: [usize; 2],
}

impl Ticks {
    fn of(g: &Grid, start: usize, end: usize, line: isize) -> Ticks {
        let mut reaches: Vec<[usize; 2]> = (start..=end).map(|a| reach(g, a, line)).collect();
        let mut typical = [0; 2];
        for (side, t) in typical.iter_mut().enumerate() {
            reaches.sort_unstable_by_key(|r| r[side]);
            *t = reaches[reaches.len() / 2][side];
        }
        Ticks { typical }
    }

    fn at(&self, g: &Grid, along: usize, line: isize) -> bool {
        let r = reach(g, along, line);
        let short = r[0] <= MAX_TICK && r[1] <= MAX_TICK;
        short && (r[0] >= self.typical[0] + 2 || r[1] >= self.typical[1] + 2)
    }

    /// The ends moved onto a tick within the gap distance just past them: a bar's end tick
    /// is where the user reads its zero and its full length.
    fn extend(&self, g: &Grid, start: usize, end: usize, line: isize) -> (usize, usize) {
        let (len, _) = g.dims();
        let start = (start.saturating_sub(MAX_GAP)..start)
            .find(|&a| self.at(g, a, line))
            .unwrap_or(start);
        let end = ((end + 1)..(end + 1 + MAX_GAP).min(len))
            .rev()
            .find(|&a| self.at(g, a, line))
            .unwrap_or(end);
        (start, end)
    }

    /// Centres of the runs of tick positions along the bar, with each tick's height (its
    /// farthest reach from the line).
    fn centres(&self, g: &Grid, start: usize, end: usize, line: isize) -> Vec<(f64, usize)> {
        let mut centres = Vec::new();
        let mut run: Option<(usize, usize)> = None;
        for a in start..=end + 1 {
            let t = a <= end && self.at(g, a, line);
            match (t, run) {
                (true, _) => {
                    let height = reach(g, a, line).into_iter().max().unwrap_or(0);
                    run = Some(run.map_or((a, height), |(s, h)| (s, h.max(height))));
                }
                (false, Some((s, height))) => {
                    centres.push(((s + a - 1) as f64 / 2.0, height));
                    run = None;
                }
                _ => {}
            }
        }
        centres
    }

    /// Whether the bar stands free of the drawing: clear paper within 10 px of the line on
    /// one side and mostly clear on the other, where only numerals and ticks may be. Outlines
    /// of buildings, which pass every other test, have walls or hatching along one side.
    fn stands_free(&self, g: &Grid, start: usize, end: usize, line: isize) -> bool {
        let mut near = [0usize; 2];
        let mut far = [0usize; 2];
        let mut counted = 0usize;
        for a in (start..=end).filter(|&a| !self.at(g, a, line)) {
            counted += 1;
            let r = reach(g, a, line);
            for (side, dir) in [-1isize, 1].into_iter().enumerate() {
                // From the line's own edge here: engraved lines wander by a pixel.
                let from = r[side] as isize + 1;
                if (from..from + 10).all(|k| !g.at(a, line + dir * k)) {
                    near[side] += 1;
                }
                if (FAR.0..=FAR.1).all(|k| !g.any_ink_at(a, line + dir * k)) {
                    far[side] += 1;
                }
            }
        }
        let share = |n: usize| n as f64 / counted.max(1) as f64;
        let lettered_side_ok = share(near[0].min(near[1])) >= MIN_LETTERED_SIDE;
        // One side clear close by; the other (numerals) clear beyond the numerals.
        let sides = [(0, 1), (1, 0)].into_iter().any(|(clear, lettered)| {
            share(near[clear]) >= MIN_CLEAR_SIDE && share(far[lettered]) >= MIN_FAR_CLEAR
        });
        // Or lettering close on both sides ("0 100 200 300" above, "Feet" below: Armitage)
        // with the paper clear beyond it on both.
        let lettered_both = share(near[0].max(near[1])) >= MIN_LETTERED_BOTH
            && far.iter().all(|&n| share(n) >= MIN_FAR_CLEAR_BOTH);
        lettered_side_ok && (sides || lettered_both)
    }

    /// Whether, on one side, the paper just past the line's typical thickness is the open
    /// sheet along most of the bar.
    fn on_open_sheet(&self, g: &Grid, start: usize, end: usize, line: isize) -> bool {
        [-1isize, 1].into_iter().zip(self.typical).any(|(dir, t)| {
            let at = line + dir * (t as isize + 1);
            let open = (start..=end).filter(|&a| g.open_at(a, at)).count();
            open as f64 >= MIN_OPEN * (end + 1 - start) as f64
        })
    }
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

/// Whether the ticks divide the bar evenly: most gaps between neighbouring ticks are whole
/// multiples or whole fractions of the median gap (a bar's units and their subdivisions),
/// where the stubs of walls along a building's outline fall anywhere.
fn evenly_divided(centres: &[f64]) -> bool {
    let mut gaps: Vec<f64> = centres.windows(2).map(|w| w[1] - w[0]).collect();
    if gaps.is_empty() {
        return false;
    }
    gaps.sort_unstable_by(f64::total_cmp);
    let unit = gaps[gaps.len() / 2];
    let whole = |big: f64, small: f64| {
        let k = (big / small).round();
        k >= 1.0 && (big - k * small).abs() <= (0.12 * small).max(1.5)
    };
    let even = gaps
        .iter()
        .filter(|&&g| whole(g.max(unit), g.min(unit)))
        .count();
    even as f64 >= MIN_EVEN * gaps.len() as f64
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

#[cfg(test)]
mod tests {
    use super::*;
    use image::Luma;

    /// A 300 × 200 sheet: a square "castle" at the top left and whatever `extra` inks.
    fn sheet(extra: impl Fn(u32, u32) -> bool) -> GrayImage {
        GrayImage::from_fn(300, 200, |x, y| {
            let castle = (20..=120).contains(&x)
                && (20..=120).contains(&y)
                && !((30..=110).contains(&x) && (30..=110).contains(&y));
            Luma([if castle || extra(x, y) { 0 } else { 255 }])
        })
    }

    /// A 1-px line on row 170 from x = 150 to 270 with 7-px ticks every 20 px above it.
    fn bar(x: u32, y: u32) -> bool {
        let line = (150..=270).contains(&x) && y == 170;
        let tick =
            (150..=270).contains(&x) && (x - 150).is_multiple_of(20) && (164..=170).contains(&y);
        line || tick
    }

    #[test]
    fn finds_a_ruled_bar_with_ticks_and_its_length() {
        let b = find(&sheet(bar)).unwrap();
        assert_eq!(
            (b.x0, b.y0, b.x1, b.y1, b.length_px),
            (150, 170, 270, 170, 121)
        );
        assert!((b.scale(30.25) - 0.25).abs() < 1e-12);
        assert_eq!(b.describe(), "from (150, 170) to (270, 170), 121 px");
    }

    #[test]
    fn no_bar_no_answer_and_the_castle_is_never_the_bar() {
        assert_eq!(find(&sheet(|_, _| false)), None);
        assert_eq!(find(&GrayImage::from_pixel(50, 40, Luma([255]))), None);
    }

    #[test]
    fn breaks_numerals_and_a_line_running_on_under_a_word_keep_the_bar_whole() {
        let engraved = |x: u32, y: u32| {
            let broken = bar(x, y) && !(203..=207).contains(&x);
            // "25" and "50" above ticks 190 and 250: 5 × 6-px blocks touching nothing.
            let numeral = |c: u32| (c + 2..=c + 6).contains(&x) && (154..=159).contains(&y);
            // The line runs on 7 px past the last tick under a word with 3-px letter stems.
            let run_on = (271..=277).contains(&x) && y == 170;
            let letters =
                (272..=277).contains(&x) && x.is_multiple_of(2) && (167..=169).contains(&y);
            broken || numeral(190) || numeral(250) || run_on || letters
        };
        let b = find(&sheet(engraved)).unwrap();
        assert_eq!((b.x0, b.x1, b.y0), (150, 270, 170));
    }

    #[test]
    fn a_bar_lettered_above_and_below_is_found() {
        // Armitage's style: "0 100 200 300" close above, "Feet" close below, paper beyond.
        let lettered = |x: u32, y: u32| {
            let along = x.wrapping_sub(150) % 20;
            let numerals = (4..14).contains(&along) && (160..=165).contains(&y);
            let word = (180..=230).contains(&x) && !x.is_multiple_of(3) && (174..=179).contains(&y);
            bar(x, y) || (150..=270).contains(&x) && (numerals || word)
        };
        let b = find(&sheet(lettered)).unwrap();
        assert_eq!((b.x0, b.x1, b.y0), (150, 270, 170));
    }

    #[test]
    fn a_bar_inside_the_moats_bounding_box_is_found() {
        // Coucy's bar sits beside a wall that runs down to the sheet's bottom edge.
        let wall = |x: u32, y: u32| (285..=290).contains(&x) && y >= 100;
        let with_wall =
            |x, y| bar(x, y) || wall(x, y) || (120..=285).contains(&x) && (100..=104).contains(&y);
        let b = find(&sheet(with_wall)).unwrap();
        assert_eq!((b.x0, b.x1), (150, 270));
    }

    #[test]
    fn a_line_without_even_ticks_is_not_a_bar() {
        let plain = |x: u32, y: u32| (150..=270).contains(&x) && y == 170;
        assert_eq!(find(&sheet(plain)), None);
        // Stubs of walls at uneven places along an outline.
        let stubs = |x: u32, y: u32| {
            plain(x, y) || [150, 157, 201, 230, 270].contains(&x) && (164..=170).contains(&y)
        };
        assert_eq!(find(&sheet(stubs)), None);
    }

    #[test]
    fn the_edge_of_hachures_is_not_a_bar() {
        let hachured = |x: u32, y: u32| {
            (150..=270).contains(&x)
                && (y == 170 || x.is_multiple_of(3) && (160..=170).contains(&y))
        };
        assert_eq!(find(&sheet(hachured)), None);
    }

    #[test]
    fn an_outline_along_a_wall_is_not_a_bar() {
        // A building's edge: ticks where cross walls meet it, the wall 5 px below.
        let outline =
            |x: u32, y: u32| bar(x, y) || (150..=270).contains(&x) && (175..=180).contains(&y);
        assert_eq!(find(&sheet(outline)), None);
    }

    #[test]
    fn vertical_bars_are_not_searched() {
        let vertical = |x: u32, y: u32| {
            (40..=160).contains(&y)
                && (x == 200 || (y - 40).is_multiple_of(20) && (200..=206).contains(&x))
        };
        assert_eq!(find(&sheet(vertical)), None);
    }

    /// Issue 11: the Coucy plan shipped with the demo (Viollet-le-Duc, tome 3, fig. 16) has a
    /// 50-m bar whose ticks were read by hand at x = 160 and 317 on row 580.
    #[test]
    fn issue_11_coucy_scale_bar_is_found_on_the_real_drawing() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/coucy/plan.png");
        let grey = image::open(path).unwrap().to_luma8();
        let b = find(&grey).unwrap();
        assert!(
            (159..=162).contains(&b.x0) && (316..=318).contains(&b.x1),
            "{b:?}"
        );
        assert!((578..=582).contains(&b.y0), "{b:?}");
        assert!((b.scale(50.0) - 0.32).abs() < 0.01, "{}", b.scale(50.0));
    }
}
