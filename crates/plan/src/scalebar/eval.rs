//! Scoring the scale-bar finder against bars read by eye (issue 11, session 6;
//! `tests/data/scalebars.json`): each plan's finding is right, in part, wrong or missed, and
//! the set's precision and recall follow. Data in, figures out; files are the caller's.

use serde::Deserialize;

use super::ScaleBar;

/// The annotated set: per plan, the drawn bar's two ends or none.
#[derive(Debug, Clone, Deserialize)]
pub struct BarSet {
    /// Ends may be off by this many pixels …
    pub tolerance_px: f64,
    /// … or by this share of the true bar's length, whichever is larger.
    pub tolerance_share: f64,
    pub plans: Vec<BarPlan>,
}

#[derive(Debug, Clone, Deserialize)]
pub struct BarPlan {
    /// Path relative to the data set's folder (as in its manifest.json).
    pub file: String,
    /// `[x0, y0, x1, y1]`, horizontal (`y0 == y1`) or vertical (`x0 == x1`); None: no bar.
    pub bar: Option<[u32; 4]>,
}

impl BarSet {
    pub fn from_json(text: &str) -> Result<BarSet, serde_json::Error> {
        serde_json::from_str(text)
    }
}

/// What the finder did on one plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Both ends within tolerance of the drawn bar's ends.
    Right,
    /// Along the drawn bar (same direction, same line, overlapping) but an end is off.
    InPart,
    /// A bar reported where none is drawn, or away from the drawn one.
    Wrong,
    /// A bar is drawn and nothing was reported.
    Missed,
    /// No bar drawn and none reported.
    NoneRight,
}

impl Outcome {
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Right => "right",
            Outcome::InPart => "in part",
            Outcome::Wrong => "wrong",
            Outcome::Missed => "missed",
            Outcome::NoneRight => "none, right",
        }
    }
}

/// How a reported bar compares with the drawn one (`truth`), at tolerance
/// max(`tol_px`, `tol_share` × the true length) on each end, the ends taken in either order.
pub fn judge(
    found: Option<&ScaleBar>,
    truth: Option<[u32; 4]>,
    tol_px: f64,
    tol_share: f64,
) -> Outcome {
    let (f, t) = match (found, truth) {
        (None, None) => return Outcome::NoneRight,
        (None, Some(_)) => return Outcome::Missed,
        (Some(_), None) => return Outcome::Wrong,
        (Some(f), Some(t)) => (f, t.map(f64::from)),
    };
    let (a, b) = (
        [f64::from(f.x0), f64::from(f.y0)],
        [f64::from(f.x1), f64::from(f.y1)],
    );
    let (p, q) = ([t[0], t[1]], [t[2], t[3]]);
    let dist = |u: [f64; 2], v: [f64; 2]| (u[0] - v[0]).hypot(u[1] - v[1]);
    let tol = (tol_share * dist(p, q)).max(tol_px);
    let same_order = dist(a, p).max(dist(b, q));
    let swapped = dist(a, q).max(dist(b, p));
    if same_order.min(swapped) <= tol {
        return Outcome::Right;
    }
    // Along the drawn bar: the same direction, on its line (within the tolerance, at least
    // 4 px: ticks and numerals sit a few pixels off it), and overlapping it.
    let vertical = |e: [f64; 4]| (e[2] - e[0]).abs() < (e[3] - e[1]).abs();
    let fe = [a[0], a[1], b[0], b[1]];
    if vertical(fe) != vertical(t) {
        return Outcome::Wrong;
    }
    let (along, across) = if vertical(t) { (1, 0) } else { (0, 1) };
    let span = |e: [f64; 4]| (e[along].min(e[along + 2]), e[along].max(e[along + 2]));
    let ((f0, f1), (t0, t1)) = (span(fe), span(t));
    let on_line = (fe[across] - t[across]).abs() <= tol.max(4.0);
    if on_line && f0.max(t0) < f1.min(t1) {
        Outcome::InPart
    } else {
        Outcome::Wrong
    }
}

/// Counts over a set.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Tally {
    pub right: usize,
    pub in_part: usize,
    pub wrong: usize,
    pub missed: usize,
    pub none_right: usize,
    /// Plans with a drawn bar.
    pub drawn: usize,
    /// Plans where a bar was reported.
    pub reported: usize,
}

impl Tally {
    /// `drawn` follows the truth, since a wrong report on a plan with a bar also misses it.
    pub fn of(judged: impl IntoIterator<Item = (Outcome, bool)>) -> Tally {
        let mut t = Tally::default();
        for (o, has_bar) in judged {
            t.drawn += usize::from(has_bar);
            match o {
                Outcome::Right => t.right += 1,
                Outcome::InPart => t.in_part += 1,
                Outcome::Wrong => t.wrong += 1,
                Outcome::Missed => t.missed += 1,
                Outcome::NoneRight => t.none_right += 1,
            }
            t.reported += usize::from(matches!(
                o,
                Outcome::Right | Outcome::InPart | Outcome::Wrong
            ));
        }
        t
    }

    /// Share of the reported bars that are right.
    pub fn precision(&self) -> f64 {
        self.right as f64 / self.reported.max(1) as f64
    }

    /// Share of the drawn bars found right.
    pub fn recall(&self) -> f64 {
        self.right as f64 / self.drawn.max(1) as f64
    }

    pub fn summary(&self) -> String {
        format!(
            "{} plans, {} with a bar: right {}, in part {}, wrong {}, missed {}, no bar and none reported {}; precision {:.2}, recall {:.2}",
            self.right + self.in_part + self.wrong + self.missed + self.none_right,
            self.drawn,
            self.right,
            self.in_part,
            self.wrong,
            self.missed,
            self.none_right,
            self.precision(),
            self.recall()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bar(x0: u32, y0: u32, x1: u32, y1: u32) -> ScaleBar {
        let length_px = x1.abs_diff(x0).max(y1.abs_diff(y0)) + 1;
        ScaleBar {
            x0,
            y0,
            x1,
            y1,
            length_px,
        }
    }

    #[test]
    fn outcomes_at_the_tolerance() {
        let t = Some([100, 50, 300, 50]);
        // 4 % of 200 px = 8 px.
        assert_eq!(
            judge(Some(&bar(108, 50, 293, 50)), t, 4.0, 0.04),
            Outcome::Right
        );
        assert_eq!(
            judge(Some(&bar(300, 50, 100, 50)), t, 4.0, 0.04),
            Outcome::Right
        );
        assert_eq!(
            judge(Some(&bar(100, 50, 200, 50)), t, 4.0, 0.04),
            Outcome::InPart
        );
        assert_eq!(
            judge(Some(&bar(100, 90, 300, 90)), t, 4.0, 0.04),
            Outcome::Wrong
        );
        assert_eq!(
            judge(Some(&bar(200, 0, 200, 100)), t, 4.0, 0.04),
            Outcome::Wrong
        );
        assert_eq!(judge(None, t, 4.0, 0.04), Outcome::Missed);
        assert_eq!(
            judge(Some(&bar(1, 1, 60, 1)), None, 4.0, 0.04),
            Outcome::Wrong
        );
        assert_eq!(judge(None, None, 4.0, 0.04), Outcome::NoneRight);
        // Short bars: 4 px floor.
        let s = Some([10, 10, 10, 50]);
        assert_eq!(
            judge(Some(&bar(10, 14, 10, 47)), s, 4.0, 0.04),
            Outcome::Right
        );
        assert_eq!(
            judge(Some(&bar(10, 15, 10, 47)), s, 4.0, 0.04),
            Outcome::InPart
        );
    }

    #[test]
    fn tally_and_rates() {
        let t = Tally::of([
            (Outcome::Right, true),
            (Outcome::Wrong, true),
            (Outcome::Missed, true),
            (Outcome::NoneRight, false),
            (Outcome::Wrong, false),
        ]);
        assert_eq!((t.right, t.wrong, t.drawn, t.reported), (1, 2, 3, 3));
        assert!((t.precision() - 1.0 / 3.0).abs() < 1e-12);
        assert!((t.recall() - 1.0 / 3.0).abs() < 1e-12);
    }
}
