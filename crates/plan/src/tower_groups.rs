//! The towers read as tower-wall edges (§5.1.6 (4)): groups of tower-wall edges joined at
//! shared vertices, one tower each, and the warning when a group is too long to be one tower.
//!
//! Departure from counting tower-wall edges one by one: on real drawings a tower's wall is often
//! split into several edges by the walls meeting it (Coucy: 5 towers, 18 tower-wall edges), so
//! the edge count overstates the towers (docs/plan.md, development set).

use crate::label::Label;
use crate::parsed::{ParsedPlan, PlanEdge};

/// A group of tower-wall edges whose extent (the longer side of its skeleton's box) is more
/// than this many times its wall's thickness is warned about ([`long_groups`]): a drawn tower
/// is a few thicknesses across (2–5 on the development set's exact counts, 8.7 at most), and the
/// longer groups (10–26) were all stretches of curtain read as one tower, on plans whose tower
/// counts were wrong (docs/plan.md, "Tower walls too long to be one tower").
pub const LONG_TOWER_WALL: f64 = 10.0;

/// The tower-wall edges of `edges` (their indices) grouped by the vertices they share, among
/// `vertices` vertices; groups in the order of their first edge.
pub fn groups(edges: &[PlanEdge], vertices: usize) -> Vec<Vec<usize>> {
    let mut sets = crate::union_find::UnionFind::new(vertices);
    let towers: Vec<usize> = (0..edges.len())
        .filter(|&e| edges[e].label == Label::TowerWall)
        .collect();
    for &e in &towers {
        sets.union(edges[e].from, edges[e].to);
    }
    let mut out: Vec<Vec<usize>> = Vec::new();
    let mut group_of_root = std::collections::HashMap::new();
    for e in towers {
        let r = sets.root(edges[e].from);
        let g = *group_of_root.entry(r).or_insert_with(|| {
            out.push(Vec::new());
            out.len() - 1
        });
        out[g].push(e);
    }
    out
}

/// The plan's towers: one per group of tower-wall edges, plus the `pixel_towers` found on the
/// pixels (bulges, rings, thick ink; `ParsedPlan::bulge_towers`). One home for the parse and
/// the corrections.
pub(crate) fn count(edges: &[PlanEdge], vertices: usize, pixel_towers: usize) -> usize {
    groups(edges, vertices).len() + pixel_towers
}

/// A group of tower-wall edges longer than [`LONG_TOWER_WALL`] thicknesses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LongGroup {
    /// The centre of its skeleton's box (plan pixels).
    pub centre: [f64; 2],
    /// Its extent in thicknesses of its own wall (mean over its skeleton).
    pub thicknesses: f64,
}

/// The groups of tower-wall edges too long to be one tower.
pub fn long_groups(edges: &[PlanEdge], vertices: usize) -> Vec<LongGroup> {
    groups(edges, vertices)
        .into_iter()
        .filter_map(|g| {
            let mut b = [u32::MAX, u32::MAX, 0, 0];
            let (mut along, mut length) = (0.0, 0usize);
            for &e in &g {
                for &(x, y) in &edges[e].points {
                    b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
                }
                along += edges[e].thickness * edges[e].points.len() as f64;
                length += edges[e].points.len();
            }
            if length == 0 {
                return None;
            }
            let thickness = along / length as f64;
            let extent = f64::from((b[2] - b[0]).max(b[3] - b[1]));
            (thickness > 0.0 && extent > LONG_TOWER_WALL * thickness).then(|| LongGroup {
                centre: [
                    (f64::from(b[0]) + f64::from(b[2])) / 2.0,
                    (f64::from(b[1]) + f64::from(b[3])) / 2.0,
                ],
                thicknesses: extent / thickness,
            })
        })
        .collect()
}

/// How the warning for [`long_groups`] begins: what finds it again among a plan's warnings.
const LONG_WARNING: &str = "tower walls too long to be one tower";

/// The parse's warning when a castle with a courtyard shows no tower.
pub(crate) const NO_TOWERS: &str = "no towers found on the outer wall";

/// The warning for [`long_groups`], if any: where they are, and what the user can do.
pub(crate) fn warning(edges: &[PlanEdge], vertices: usize) -> Option<String> {
    let long = long_groups(edges, vertices);
    let longest = long
        .iter()
        .max_by(|a, b| a.thicknesses.total_cmp(&b.thicknesses))?;
    Some(format!(
        "{LONG_WARNING}: {} group(s) of tower-wall edges, the longest {:.0} wall thicknesses across, centred at ({:.0}, {:.0}); likely a stretch of curving curtain read as one tower, so the towers along it are miscounted — check the tower walls in the labels overlay and correct the towers (`castellan serve`'s plan step, or [[tower]] in PROJECT.toml)",
        long.len(),
        longest.thicknesses,
        longest.centre[0],
        longest.centre[1],
    ))
}

/// The plan's tower warnings after the user's corrections changed its walls or towers: the
/// parse's warning about tower walls too long is said again only if its groups still are
/// (with their figures now), and "no towers" goes once the plan has a tower. The parse's
/// warnings otherwise stand: they describe the drawing, not the labels.
pub(crate) fn rewarn(plan: &mut ParsedPlan) {
    let has_towers = plan.towers > 0;
    let stale = |w: &String| w.starts_with(LONG_WARNING) || (has_towers && w == NO_TOWERS);
    plan.warnings.retain(|w| !stale(w));
    plan.warnings
        .extend(warning(&plan.edges, plan.vertices.len()));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A straight edge between vertices `from` and `to`: the pixels `xs` of row `y`, 5 px thick.
    fn edge(from: usize, to: usize, label: Label, y: u32, xs: std::ops::Range<u32>) -> PlanEdge {
        PlanEdge {
            from,
            to,
            label,
            points: xs.map(|x| (x, y)).collect(),
            fit: None,
            thickness: 5.0,
        }
    }

    #[test]
    fn tower_walls_sharing_a_vertex_are_one_tower_and_other_walls_none() {
        let edges = vec![
            edge(0, 1, Label::TowerWall, 10, 0..10),
            edge(2, 3, Label::TowerWall, 50, 0..10),
            edge(1, 4, Label::TowerWall, 12, 10..20),
            edge(4, 2, Label::CastleOuterWall, 30, 0..30),
        ];
        assert_eq!(groups(&edges, 5), vec![vec![0, 2], vec![1]]);
        assert!(groups(&edges[3..], 5).is_empty());
    }

    #[test]
    fn only_a_group_over_ten_thicknesses_across_is_warned_about() {
        // Walls 5 px thick: a group 20 px across (4 thicknesses) and one whose box runs from
        // x = 100 to 160 (60 px, 12 thicknesses), centred at (130, 42).
        let edges = vec![
            edge(0, 1, Label::TowerWall, 10, 0..21),
            edge(2, 3, Label::TowerWall, 40, 100..131),
            edge(3, 4, Label::TowerWall, 44, 130..161),
        ];
        let long = long_groups(&edges, 5);
        assert_eq!(long.len(), 1);
        assert!((long[0].thicknesses - 12.0).abs() < 1e-9, "{long:?}");
        assert_eq!(long[0].centre, [130.0, 42.0]);
        let w = warning(&edges, 5).unwrap();
        assert!(
            w.starts_with(
                "tower walls too long to be one tower: 1 group(s) of tower-wall edges, the \
                 longest 12 wall thicknesses across, centred at (130, 42)"
            ),
            "{w}"
        );
        assert_eq!(warning(&edges[..1], 5), None);
    }
}
