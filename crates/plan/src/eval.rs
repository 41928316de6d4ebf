//! Accuracy on an annotated development set of real plans (issue 11; the labels of §5.1.6):
//! labels right at annotated points and exact tower counts. Data in (the set's JSON text and
//! parsed plans), figures out; reading files and drawings is the caller's business.

use serde::Deserialize;

use crate::ParsedPlan;
use crate::label::Label;

/// The development set: plans with their tower count and points with their true labels.
#[derive(Debug, Clone, Deserialize)]
pub struct DevSet {
    /// Annotated points may be this many pixels off a thin wall or small room.
    pub tolerance_px: u32,
    pub plans: Vec<DevPlan>,
}

#[derive(Debug, Clone, Deserialize)]
pub struct DevPlan {
    /// Path relative to the data set's folder (as in its manifest.json).
    pub file: String,
    pub castle: String,
    /// The book it comes from ([`crate::ink::train::source_of`] groups the tomes of one work).
    #[serde(default)]
    pub book: String,
    pub towers: usize,
    pub points: Vec<DevPoint>,
}

#[derive(Debug, Clone, Deserialize)]
pub struct DevPoint {
    pub x: u32,
    pub y: u32,
    #[serde(deserialize_with = "label_by_name")]
    pub label: Label,
}

fn label_by_name<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Label, D::Error> {
    let name = String::deserialize(d)?;
    Label::ALL
        .into_iter()
        .find(|l| l.name() == name)
        .ok_or_else(|| serde::de::Error::custom(format!("unknown label '{name}'")))
}

impl DevSet {
    pub fn from_json(text: &str) -> Result<DevSet, serde_json::Error> {
        serde_json::from_str(text)
    }
}

/// The parsed label at an annotated point: the label of the nearest pixel of the same kind
/// (wall or open space) as the true label within `tol` pixels, so that an annotation a pixel
/// or two off a 3-px wall still asks about that wall; the label at the point itself when no
/// pixel of that kind is near.
pub fn label_near(plan: &ParsedPlan, p: &DevPoint, tol: u32) -> Label {
    let want_wall = p.label.is_wall();
    let (w, h) = (plan.width as i64, plan.height as i64);
    let (px, py) = (i64::from(p.x), i64::from(p.y));
    let t = i64::from(tol);
    let mut best: Option<(i64, Label)> = None;
    for y in (py - t).max(0)..=(py + t).min(h - 1) {
        for x in (px - t).max(0)..=(px + t).min(w - 1) {
            let d = (x - px).pow(2) + (y - py).pow(2);
            if d > t * t || best.is_some_and(|(bd, _)| bd <= d) {
                continue;
            }
            let l = plan.label_at(x as u32, y as u32);
            if l.is_wall() == want_wall {
                best = Some((d, l));
            }
        }
    }
    match best {
        Some((_, l)) => l,
        None if p.x < plan.width && p.y < plan.height => plan.label_at(p.x, p.y),
        None => Label::CastleSurroundings,
    }
}

/// One plan's result.
#[derive(Debug, Clone)]
pub struct PlanScore {
    pub file: String,
    pub points: usize,
    pub right: usize,
    pub true_towers: usize,
    /// None when the drawing could not be parsed.
    pub found_towers: Option<usize>,
    /// (true, found) label of each point answered wrongly.
    pub confusions: Vec<(Label, Label)>,
}

/// Scores a parsed plan (or a failure) against its annotation.
pub fn score(plan: Option<&ParsedPlan>, truth: &DevPlan, tol: u32) -> PlanScore {
    let mut s = PlanScore {
        file: truth.file.clone(),
        points: truth.points.len(),
        right: 0,
        true_towers: truth.towers,
        found_towers: plan.map(|p| p.towers),
        confusions: Vec::new(),
    };
    if let Some(plan) = plan {
        for p in &truth.points {
            let got = label_near(plan, p, tol);
            if got == p.label {
                s.right += 1;
            } else {
                s.confusions.push((p.label, got));
            }
        }
    } else {
        s.confusions = truth
            .points
            .iter()
            .map(|p| (p.label, Label::CastleSurroundings))
            .collect();
    }
    s
}

/// Totals over the set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Totals {
    pub plans: usize,
    pub points: usize,
    pub right: usize,
    pub towers_exact: usize,
    /// Sum of |found − true| tower counts.
    pub tower_abs_error: usize,
}

impl Totals {
    pub fn of(scores: &[PlanScore]) -> Totals {
        let mut t = Totals {
            plans: scores.len(),
            points: 0,
            right: 0,
            towers_exact: 0,
            tower_abs_error: 0,
        };
        for s in scores {
            t.points += s.points;
            t.right += s.right;
            let found = s.found_towers.unwrap_or(0);
            t.towers_exact += usize::from(found == s.true_towers);
            t.tower_abs_error += found.abs_diff(s.true_towers);
        }
        t
    }

    pub fn accuracy(&self) -> f64 {
        self.right as f64 / self.points.max(1) as f64
    }
}

/// A Markdown table, one row per plan, then the totals and the most frequent confusions.
pub fn table(scores: &[PlanScore]) -> String {
    let mut out =
        String::from("| plan | points right | towers (true / found) |\n| --- | --- | --- |\n");
    for s in scores {
        let found = s
            .found_towers
            .map_or("failed".to_string(), |f| f.to_string());
        out.push_str(&format!(
            "| {} | {} / {} | {} / {} |\n",
            s.file.rsplit('/').next().unwrap_or(&s.file),
            s.right,
            s.points,
            s.true_towers,
            found
        ));
    }
    let t = Totals::of(scores);
    out.push_str(&format!(
        "| **all {} plans** | **{} / {} ({:.0} %)** | **{} exact**, mean error {:.1} |\n",
        t.plans,
        t.right,
        t.points,
        100.0 * t.accuracy(),
        t.towers_exact,
        t.tower_abs_error as f64 / t.plans.max(1) as f64
    ));
    let mut pairs: Vec<((Label, Label), usize)> = Vec::new();
    for c in scores.iter().flat_map(|s| s.confusions.iter()) {
        match pairs.iter_mut().find(|(k, _)| k == c) {
            Some((_, n)) => *n += 1,
            None => pairs.push((*c, 1)),
        }
    }
    pairs.sort_by_key(|p| std::cmp::Reverse(p.1));
    out.push_str("\nMost frequent errors (true → found): ");
    let listed: Vec<String> = pairs
        .iter()
        .take(6)
        .map(|((t, f), n)| format!("{} → {} ({n})", t.name(), f.name()))
        .collect();
    out.push_str(&listed.join(", "));
    out.push('\n');
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{DynamicImage, GrayImage, Luma};

    /// A 120 × 120 sheet with a square enclosure, 8-px walls (outer edge at 30 and 90).
    fn square_plan() -> ParsedPlan {
        let img = GrayImage::from_fn(120, 120, |x, y| {
            let inside = |a: u32, b: u32| (a..=b).contains(&x) && (a..=b).contains(&y);
            Luma([if inside(30, 90) && !inside(38, 82) {
                0
            } else {
                255
            }])
        });
        crate::parse(&DynamicImage::ImageLuma8(img), &crate::Options::default()).unwrap()
    }

    #[test]
    fn a_point_just_off_a_wall_asks_about_the_wall() {
        let p = square_plan();
        assert_eq!(p.label_at(60, 60), Label::Courtyard);
        // (60, 40) is open courtyard two pixels inside the wall's inner edge.
        let near = DevPoint {
            x: 60,
            y: 40,
            label: Label::CastleOuterWall,
        };
        assert!(label_near(&p, &near, 4).is_wall());
        assert!(!label_near(&p, &near, 0).is_wall());
    }

    #[test]
    fn scores_and_totals_count_right_points_and_exact_towers() {
        let p = square_plan();
        let truth = DevPlan {
            book: String::new(),
            file: "plans/square.png".into(),
            castle: "square".into(),
            towers: 0,
            points: vec![
                DevPoint {
                    x: 60,
                    y: 60,
                    label: Label::Courtyard,
                },
                DevPoint {
                    x: 5,
                    y: 5,
                    label: Label::CastleSurroundings,
                },
                DevPoint {
                    x: 60,
                    y: 60,
                    label: Label::GreatHall,
                },
            ],
        };
        let s = score(Some(&p), &truth, 2);
        assert_eq!((s.right, s.points), (2, 3));
        assert_eq!(s.confusions, vec![(Label::GreatHall, Label::Courtyard)]);
        let failed = score(None, &truth, 2);
        assert_eq!(failed.right, 0);
        let t = Totals::of(&[s, failed]);
        assert_eq!((t.points, t.right, t.towers_exact), (6, 2, 2));
        assert!(table(&[]).contains("all 0 plans"));
    }

    #[test]
    fn unknown_label_names_are_refused() {
        let bad = r#"{"tolerance_px": 2, "plans": [{"file": "a", "castle": "b", "towers": 0,
            "points": [{"x": 1, "y": 1, "label": "moat"}]}]}"#;
        assert!(
            DevSet::from_json(bad)
                .unwrap_err()
                .to_string()
                .contains("moat")
        );
    }
}
