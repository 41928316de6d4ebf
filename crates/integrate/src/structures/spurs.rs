//! Walls among the chains §5.1.6 prunes (issue 25). Chapter 5's graph keeps only what closes
//! faces, so every leaf of the skeleton goes: the walls running out into the field, and the
//! buildings drawn as solid masses, whose skeleton is a spine with a whisker at each corner.
//! The pruned pieces ([`plan::Spur`]) that are thick enough to stand and meet end to end, two
//! at a point, are joined into one run — the skeleton cuts a wall wherever a whisker branches
//! off it, and judged piece by piece, an outwork's wall long in all was lost as short pieces —
//! and a run long enough is a wall; the whiskers are not.

use std::collections::HashMap;

use plan::ParsedPlan;
use plan::label::Label;

use crate::estimate::Role;

use super::walls::{Run, SPUR_FROM, corners, field_on_right, typical_thickness, weighted_median};

/// A chain is a wall only when longer than this many of its thicknesses — the shorter ones are
/// the skeleton's whiskers at a thick wall's corners and ends. Over the 34 shared plans the
/// median plan–model IoU is the same at 1.5 (0.801) with 2 % more structures, and 0.831 when
/// every chain counts, but with 80 % more: stubs and hachure marks built as walls.
const SPUR_LENGTH: f64 = 2.0;

/// The spurs that are walls, joined into runs: curtain when the plan labels most of a run
/// outer or tower wall — an outwork's wall, crenellated — else inner walls.
pub(super) fn runs(plan: &ParsedPlan) -> Vec<Run> {
    let typical = typical_thickness(plan);
    let thick: Vec<usize> = plan
        .spurs
        .iter()
        .enumerate()
        .filter(|(_, s)| s.points.len() > 1 && s.thickness >= SPUR_FROM * typical)
        .map(|(k, _)| k)
        .collect();
    join(plan, &thick)
        .into_iter()
        .filter_map(|chain| run(plan, &chain))
        .collect()
}

fn length(points: &[(u32, u32)]) -> f64 {
    points
        .windows(2)
        .map(|w| {
            (f64::from(w[1].0) - f64::from(w[0].0)).hypot(f64::from(w[1].1) - f64::from(w[0].1))
        })
        .sum()
}

fn ends(points: &[(u32, u32)]) -> [(i64, i64); 2] {
    let key = |(x, y): (u32, u32)| (i64::from(x), i64::from(y));
    [key(points[0]), key(points[points.len() - 1])]
}

/// Every pixel within one (8-neighbours) of `p`.
fn around((x, y): (i64, i64)) -> impl Iterator<Item = (i64, i64)> {
    (-1..=1).flat_map(move |dy| (-1..=1).map(move |dx| (x + dx, y + dy)))
}

/// The spurs `kept` joined end to end where exactly two of them meet: each chain as (spur,
/// walked backwards) in order. Spurs are the pruned leaves of a graph, so they form no rings.
fn join(plan: &ParsedPlan, kept: &[usize]) -> Vec<Vec<(usize, bool)>> {
    let n = kept.len();
    let at: Vec<[(i64, i64); 2]> = kept.iter().map(|&k| ends(&plan.spurs[k].points)).collect();
    // The ends of other kept spurs that each end meets (within a pixel, 8-neighbours).
    let mut by_pixel: HashMap<(i64, i64), Vec<(usize, usize)>> = HashMap::new();
    for (i, pair) in at.iter().enumerate() {
        for (j, &end) in pair.iter().enumerate() {
            by_pixel.entry(end).or_default().push((i, j));
        }
    }
    let others = |i: usize, j: usize| -> Vec<(usize, usize)> {
        let mut v: Vec<(usize, usize)> = around(at[i][j])
            .filter_map(|p| by_pixel.get(&p))
            .flatten()
            .copied()
            .filter(|&(i2, _)| i2 != i)
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let neighbours: Vec<[Vec<(usize, usize)>; 2]> =
        (0..n).map(|i| [others(i, 0), others(i, 1)]).collect();
    // The one end that end (i, j) passes on to, when exactly two ends meet there.
    let link = |i: usize, j: usize| match neighbours[i][j].as_slice() {
        [(i2, j2)] if neighbours[*i2][*j2].len() == 1 => Some((*i2, *j2)),
        _ => None,
    };
    let mut used = vec![false; n];
    let mut out = Vec::new();
    for start in 0..n {
        if used[start] {
            continue;
        }
        // Back to the chain's first piece: (piece, the end it is entered by).
        let (mut i, mut entry) = (start, 0);
        for _ in 0..n {
            match link(i, entry) {
                Some((i2, j2)) if i2 != start && !used[i2] => (i, entry) = (i2, 1 - j2),
                _ => break,
            }
        }
        let mut chain = Vec::new();
        loop {
            used[i] = true;
            chain.push((kept[i], entry == 1));
            match link(i, 1 - entry) {
                Some((i2, j2)) if !used[i2] => (i, entry) = (i2, j2),
                _ => break,
            }
        }
        out.push(chain);
    }
    out
}

/// One run along a chain of spurs, when it is long enough: its straight pieces fitted, as thick
/// as its pieces' length-weighted median.
fn run(plan: &ParsedPlan, chain: &[(usize, bool)]) -> Option<Run> {
    let mut pixels: Vec<(u32, u32)> = Vec::new();
    for &(k, backwards) in chain {
        let points = &plan.spurs[k].points;
        if backwards {
            pixels.extend(points.iter().rev());
        } else {
            pixels.extend(points.iter());
        }
    }
    let thickness = weighted_median(chain.iter().map(|&(k, _)| {
        let spur = &plan.spurs[k];
        (spur.thickness, spur.points.len() as f64)
    }))?;
    if length(&pixels) < SPUR_LENGTH * thickness {
        return None;
    }
    let outer = pixels
        .iter()
        .filter(|&&(x, y)| {
            matches!(
                plan.label_at(x, y),
                Label::CastleOuterWall | Label::TowerWall
            )
        })
        .count();
    let role = if 2 * outer > pixels.len() {
        Role::Curtain
    } else {
        Role::Wall
    };
    let line: Vec<[f64; 2]> = pixels
        .iter()
        .map(|&(x, y)| [f64::from(x), f64::from(y)])
        .collect();
    let (first, last) = (*line.first()?, *line.last()?);
    let mut points = vec![first];
    points.extend(corners(&line, (0.5 * thickness).max(1.5)));
    points.push(last);
    if role == Role::Curtain && field_on_right(plan, &points, false, thickness) {
        points.reverse();
    }
    Some(Run {
        role,
        edges: Vec::new(),
        points,
        closed: false,
        thickness,
        spur: true,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use plan::Spur;

    /// A plan of no graph but one wall edge 6 px thick (the typical thickness), labelled
    /// surroundings everywhere, with these spurs.
    fn plan_with(spurs: Vec<Spur>) -> ParsedPlan {
        let (w, h) = (120u32, 80u32);
        ParsedPlan {
            edges: vec![plan::PlanEdge {
                from: 0,
                to: 0,
                label: Label::CastleOuterWall,
                points: vec![(0, 0), (0, 1)],
                fit: None,
                thickness: 6.0,
            }],
            spurs,
            ..ParsedPlan::empty(w, h)
        }
    }

    /// A straight spur along row `y` from `x0` to `x1` (inclusive, either way).
    fn row(y: u32, x0: u32, x1: u32, thickness: f64) -> Spur {
        let points = if x0 <= x1 {
            (x0..=x1).map(|x| (x, y)).collect()
        } else {
            (x1..=x0).rev().map(|x| (x, y)).collect()
        };
        Spur { points, thickness }
    }

    #[test]
    fn short_pieces_that_meet_end_to_end_are_one_wall() {
        // Three pieces of 8 px (each under 2 × 6 long), the middle one drawn backwards, ends a
        // pixel apart: one run of 32 px from x = 10 to x = 42.
        let plan = plan_with(vec![
            row(20, 10, 18, 6.0),
            row(20, 27, 19, 6.0),
            row(20, 28, 42, 6.0),
        ]);
        let runs = runs(&plan);
        assert_eq!(runs.len(), 1, "{runs:?}");
        let ends = [runs[0].points[0], *runs[0].points.last().unwrap()];
        assert!(
            ends.contains(&[10.0, 20.0]) && ends.contains(&[42.0, 20.0]),
            "{ends:?}"
        );
        assert_eq!(runs[0].thickness, 6.0);
        assert!(runs[0].spur && !runs[0].closed);
    }

    #[test]
    fn whiskers_and_thin_lines_are_not_walls() {
        // A whisker of 10 px (under 2 × 6), and a line of 60 px under 0.6 of the typical wall.
        let plan = plan_with(vec![row(20, 10, 20, 6.0), row(50, 10, 70, 3.0)]);
        assert!(runs(&plan).is_empty());
    }

    #[test]
    fn pieces_are_not_joined_where_three_meet() {
        // Three arms of 20 px from one point (60, 40): each is a wall of its own.
        let down = Spur {
            points: (41..=60).map(|y| (60, y)).collect(),
            thickness: 6.0,
        };
        let plan = plan_with(vec![row(40, 40, 59, 6.0), row(40, 61, 80, 6.0), down]);
        assert_eq!(runs(&plan).len(), 3);
    }
}
