//! Drawn scale bars (issue 11; §5.1.1 takes the drawing's scale as given): the longest ruled
//! horizontal line with graduation ticks that stands apart from the castle (a vertical one
//! where there is none), so that a user who reads its length off the drawing once gets a
//! model in metres.

use image::GrayImage;
use serde::Serialize;

use raster::components::{Connectivity, components};

use crate::binarize::{binarize, threshold_level};

pub mod eval;
mod scan;
mod ticks;

use scan::longest_bar;

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
pub const LOOKED_FOR: &str = "a horizontal ruled line at least 40 px long with three or more evenly spaced ticks (or a vertical one with five and numerals beside them), apart from the walls";

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
/// A line end without a tick is the bar's end when it lies at most this many units past the
/// outer tick (Armitage's plain halves are five units) …
const MAX_PLAIN_UNITS: f64 = 6.0;
/// … of at least this many pixels …
const MIN_PLAIN_UNIT: f64 = 12.0;
/// … and the ticks span this share of the line (Armitage's 0–300 ft bars may show ticks
/// only up to 100).
const MIN_TICKED_SHARE: f64 = 0.3;
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
/// Ticks a vertical bar must show, every gap a whole multiple or fraction of the unit …
const MIN_VERTICAL_TICKS: usize = 5;
/// … and ticks that must have numerals beside them.
const MIN_NUMBERED: usize = 3;
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
/// full-height ticks, or runs to the line's end when that is a whole number of units past
/// them. The longest wins. Where no row holds a bar, the columns are scanned the same way, a
/// vertical bar needing also five or more ticks all evenly spaced and numerals beside three
/// of them. None when nothing qualifies.
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
    let grid = Grid {
        ink: &ink,
        castle: &castle_ink,
        open: &open,
        w,
        h,
    };
    if let Some((x0, x1, y)) = longest_bar(&grid, false) {
        return Some(ScaleBar {
            x0: x0 as u32,
            y0: y as u32,
            x1: x1 as u32,
            y1: y as u32,
            length_px: (x1 - x0 + 1) as u32,
        });
    }
    // Vertical bars, read as rows of the transposed drawing, only where no horizontal bar is:
    // section lines and walls' outlines pass the horizontal tests, so a vertical bar must
    // also carry numerals beside its ticks.
    let (ink_t, castle_t, open_t) = (
        transposed(&ink, w, h),
        transposed(&castle_ink, w, h),
        transposed(&open, w, h),
    );
    let columns = Grid {
        ink: &ink_t,
        castle: &castle_t,
        open: &open_t,
        w: h,
        h: w,
    };
    longest_bar(&columns, true).map(|(y0, y1, x)| ScaleBar {
        x0: x as u32,
        y0: y0 as u32,
        x1: x as u32,
        y1: y1 as u32,
        length_px: (y1 - y0 + 1) as u32,
    })
}

/// A row-major `w` × `h` mask as an `h` × `w` one: columns become rows.
fn transposed(mask: &[bool], w: usize, h: usize) -> Vec<bool> {
    let mut t = vec![false; mask.len()];
    for y in 0..h {
        for x in 0..w {
            t[x * h + y] = mask[y * w + x];
        }
    }
    t
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

#[cfg(test)]
mod tests;
