//! Drawn scale bars (issue 11; §5.1.1 takes the drawing's scale as given): the longest ruled
//! horizontal line with graduation ticks that stands apart from the castle (a vertical one
//! where there is none), so that a user who reads its length off the drawing once gets a
//! model in metres.

use image::GrayImage;
use serde::Serialize;

use crate::binarize::{binarize, threshold_level};
use raster::components::{Connectivity, components};

pub mod eval;
mod grid;
mod rules;
mod scan;
mod ticks;

use grid::Grid;
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
    /// Metres per pixel when the bar is `metres` long.
    pub fn metres_per_pixel(&self, metres: f64) -> f64 {
        metres / f64::from(self.length_px.max(1))
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

#[cfg(test)]
mod tests;
