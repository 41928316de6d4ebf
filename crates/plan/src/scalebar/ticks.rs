//! Graduations of a candidate bar: ticks against the line's typical thickness, their centres
//! and heights, and the paper and numerals beside them.

use super::grid::Grid;
use super::rules::{
    FAR, MAX_GAP, MAX_TICK, MIN_CLEAR_SIDE, MIN_FAR_CLEAR, MIN_FAR_CLEAR_BOTH, MIN_LETTERED_BOTH,
    MIN_LETTERED_SIDE, MIN_NUMBERED, MIN_OPEN,
};

/// How far ink reaches from the line on each side at `along` (contiguous, capped at
/// MAX_TICK + 1, which marks a line that crosses rather than a tick).
pub(super) fn reach(g: &Grid, along: usize, line: isize) -> [usize; 2] {
    [-1isize, 1].map(|dir| {
        (1..=MAX_TICK + 1)
            .take_while(|&k| g.at(along, line + dir * k as isize))
            .count()
    })
}

/// Graduations of a bar: columns where ink reaches at least 2 px farther from the line than
/// it typically does along the bar (so a 3-px-thick line is not all ticks), but stops short.
pub(super) struct Ticks {
    typical: [usize; 2],
    /// Checkered: runs of tick columns at least MIN_BOX wide are black boxes, each giving
    /// two graduations (its edges) rather than one.
    checkered: bool,
    /// How far the bar itself reaches on each side (a checkered bar's boxes; 0 otherwise):
    /// the paper beside the bar is looked at beyond it.
    thickness: [usize; 2],
}

/// Narrowest black box of a checkered bar (wider than any tick or numeral stroke).
const MIN_BOX: usize = 12;
/// Black boxes a checkered bar must show.
const MIN_BOXES: usize = 2;

impl Ticks {
    pub(super) fn of(g: &Grid, start: usize, end: usize, line: isize) -> Ticks {
        let mut reaches: Vec<[usize; 2]> = (start..=end).map(|a| reach(g, a, line)).collect();
        let mut typical = [0; 2];
        for (side, t) in typical.iter_mut().enumerate() {
            reaches.sort_unstable_by_key(|r| r[side]);
            *t = reaches[reaches.len() / 2][side];
        }
        Ticks {
            typical,
            checkered: false,
            thickness: [0; 2],
        }
    }

    /// For a line with fewer than three ticks by [`Ticks::of`]: the line read as the edge of
    /// a checkered bar (alternate boxes filled), where the black boxes may be half the line or
    /// more and so set the median reach. "Typical" is then the lower quartile of the reach
    /// over the columns where the line is inked (the white boxes' edge).
    pub(super) fn of_checkered(g: &Grid, start: usize, end: usize, line: isize) -> Ticks {
        let mut reaches: Vec<[usize; 2]> = (start..=end)
            .filter(|&a| g.at(a, line))
            .map(|a| reach(g, a, line))
            .collect();
        let (mut typical, mut thickness) = ([0; 2], [0; 2]);
        for side in 0..2 {
            reaches.sort_unstable_by_key(|r| r[side]);
            typical[side] = reaches.get(reaches.len() / 4).map_or(0, |r| r[side]);
            thickness[side] = reaches.get(reaches.len() * 3 / 4).map_or(0, |r| r[side]);
        }
        Ticks {
            typical,
            checkered: true,
            thickness,
        }
    }

    pub(super) fn at(&self, g: &Grid, along: usize, line: isize) -> bool {
        let r = reach(g, along, line);
        let short = r[0] <= MAX_TICK && r[1] <= MAX_TICK;
        short && (r[0] >= self.typical[0] + 2 || r[1] >= self.typical[1] + 2)
    }

    /// The ends moved onto a tick within the gap distance just past them: a bar's end tick
    /// is where the user reads its zero and its full length.
    pub(super) fn extend(&self, g: &Grid, start: usize, end: usize, line: isize) -> (usize, usize) {
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
    pub(super) fn centres(
        &self,
        g: &Grid,
        start: usize,
        end: usize,
        line: isize,
    ) -> Vec<(f64, usize)> {
        let mut centres = Vec::new();
        let mut boxes = 0;
        let mut run: Option<(usize, usize)> = None;
        for a in start..=end + 1 {
            let t = a <= end && self.at(g, a, line);
            match (t, run) {
                (true, _) => {
                    let height = reach(g, a, line).into_iter().max().unwrap_or(0);
                    run = Some(run.map_or((a, height), |(s, h)| (s, h.max(height))));
                }
                (false, Some((s, height))) if self.checkered && a - s >= MIN_BOX => {
                    boxes += 1;
                    centres.push((s as f64, height));
                    centres.push(((a - 1) as f64, height));
                    run = None;
                }
                (false, Some((s, height))) => {
                    centres.push(((s + a - 1) as f64 / 2.0, height));
                    run = None;
                }
                _ => {}
            }
        }
        // Read as a checkered bar, a line without two black boxes is not one (thick lines and
        // walls' edges would pass as thin ticked lines otherwise).
        if self.checkered && boxes < MIN_BOXES {
            centres.clear();
        }
        centres
    }

    /// Whether the bar stands free of the drawing: clear paper within 10 px of the line on
    /// one side and mostly clear on the other, where only numerals and ticks may be. Outlines
    /// of buildings, which pass every other test, have walls or hatching along one side.
    pub(super) fn stands_free(&self, g: &Grid, start: usize, end: usize, line: isize) -> bool {
        let mut near = [0usize; 2];
        let mut far = [0usize; 2];
        let mut counted = 0usize;
        for a in (start..=end).filter(|&a| !self.at(g, a, line)) {
            counted += 1;
            let r = reach(g, a, line);
            for (side, dir) in [-1isize, 1].into_iter().enumerate() {
                // From the line's own edge here: engraved lines wander by a pixel.
                let from = r[side].max(self.thickness[side]) as isize + 1;
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

    /// Whether numerals stand beside the ticks: ink apart from the line and its ticks (2 to
    /// 14 px beyond the tick's reach, within 6 px along) on one side at half of the ticks
    /// at least, and at three or more of them.
    pub(super) fn numbered(&self, g: &Grid, centres: &[f64], line: isize) -> bool {
        let (len, _) = g.dims();
        [0usize, 1].into_iter().any(|side| {
            let dir = if side == 0 { -1isize } else { 1 };
            let beside = centres
                .iter()
                .filter(|&&c| {
                    let c = c.round() as usize;
                    let from = reach(g, c, line)[side] as isize + 2;
                    (c.saturating_sub(6)..=(c + 6).min(len - 1)).any(|a| {
                        (from..=from + 12).any(|k| g.at(a, line + dir * k))
                            && !g.at(a, line + dir * (from - 1))
                    })
                })
                .count();
            beside >= MIN_NUMBERED && 2 * beside >= centres.len()
        })
    }

    /// Whether, on one side, the paper just past the line's typical thickness is the open
    /// sheet along most of the bar.
    pub(super) fn on_open_sheet(&self, g: &Grid, start: usize, end: usize, line: isize) -> bool {
        [-1isize, 1].into_iter().zip(self.typical).any(|(dir, t)| {
            let at = line + dir * (t as isize + 1);
            let open = (start..=end).filter(|&a| g.open_at(a, at)).count();
            open as f64 >= MIN_OPEN * (end + 1 - start) as f64
        })
    }
}
