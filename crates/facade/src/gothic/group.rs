//! Self-similar groups of §4.2: elements clustered by their shape (h, w, v), then re-estimated
//! jointly with one shared shape and one position per member.

use super::element::Theta;

/// Whether two shapes are the same up to `rel` of the larger size plus `abs` px.
pub fn similar(a: &Theta, b: &Theta, rel: f64, abs: f64) -> bool {
    let tol = tolerance(a, b, rel, abs);
    (a.w - b.w).abs() <= tol && (a.h - b.h).abs() <= tol && (a.v - b.v).abs() <= tol
}

/// How [`cluster_with`] tells two shapes alike.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Likeness {
    /// §4.2: (h, w, v) within the tolerance ([`similar`]), on one sill line.
    Shape,
    /// By box and rise ([`similar_box`]), on one sill line.
    Box { rise_factor: f64 },
    /// The same head on one apex line ([`similar_head`]), or the same width on one sill line:
    /// candidates for a group, which the joint re-estimation confirms or refuses.
    Loose { rise_factor: f64 },
}

/// Clusters by shape (single linkage). Departure from §4.2, which clusters on (h, w, v) alone:
/// members must also stand on one sill line (y0 within the same tolerance), so identical
/// windows on two storeys or in two bays far apart form separate groups that each get their
/// own enclosing arch. Returns clusters of two or more indices, each sorted left to right.
pub fn cluster(shapes: &[Theta], rel: f64, abs: f64) -> Vec<Vec<usize>> {
    cluster_with(shapes, rel, abs, Likeness::Shape)
}

/// Whether two shapes are the same by their box and rise: w and the total height h + v within
/// `rel` of the larger size plus `abs` px, and v within `rise_factor` times that.
pub fn similar_box(a: &Theta, b: &Theta, rel: f64, abs: f64, rise_factor: f64) -> bool {
    let tol = tolerance(a, b, rel, abs);
    (a.w - b.w).abs() <= tol
        && (a.h + a.v - b.h - b.v).abs() <= tol
        && (a.v - b.v).abs() <= rise_factor * tol
}

/// Whether two shapes have the same head: w within `rel` of the larger size plus `abs` px, v
/// within `rise_factor` times that, and the apex (y0 − h − v) on one line within it; their
/// sills may differ.
pub fn similar_head(a: &Theta, b: &Theta, rel: f64, abs: f64, rise_factor: f64) -> bool {
    let tol = tolerance(a, b, rel, abs);
    (a.w - b.w).abs() <= tol
        && (a.v - b.v).abs() <= rise_factor * tol
        && (a.apex() - b.apex()).abs() <= tol
}

/// The tolerance of two shapes: `rel` of the larger size plus `abs` px.
fn tolerance(a: &Theta, b: &Theta, rel: f64, abs: f64) -> f64 {
    rel * a.w.max(b.w).max(a.h + a.v).max(b.h + b.v) + abs
}

/// [`cluster`] with the shapes compared as `likeness` says. `Box`: departure from §4.2 (issue
/// 23): where the head meets the jambs almost tangentially the fit moves v and h against each
/// other at a fixed apex (a lancet found with v = 30 beside its twins' 21, the same box), so
/// the box is held to the tolerance and the rise to `rise_factor` times it. `Loose`:
/// departure from §4.2 (issue 23): a lancet whose fit ran down its jambs onto a line below
/// its sill (the moulding of the sub-arch it stands in) has its twins' head but not their
/// box, and one whose head ran up onto the mortar above has their width and sill but not
/// their head; either joins its twins, and the joint re-estimation (from the best-fitting
/// member, `joint_fit`) brings it back to their shape or refuses the group.
pub fn cluster_with(shapes: &[Theta], rel: f64, abs: f64, likeness: Likeness) -> Vec<Vec<usize>> {
    let same = |a: &Theta, b: &Theta| {
        let tol = tolerance(a, b, rel, abs);
        let sill_line = (a.y0 - b.y0).abs() <= tol;
        match likeness {
            Likeness::Shape => similar(a, b, rel, abs) && sill_line,
            Likeness::Box { rise_factor } => similar_box(a, b, rel, abs, rise_factor) && sill_line,
            Likeness::Loose { rise_factor } => {
                ((a.w - b.w).abs() <= tol && sill_line) || similar_head(a, b, rel, abs, rise_factor)
            }
        }
    };
    let n = shapes.len();
    let mut root: Vec<usize> = (0..n).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    for i in 0..n {
        for j in i + 1..n {
            let (a, b) = (&shapes[i], &shapes[j]);
            // Twins stand side by side, not one over the other; `Loose` lets two arches that
            // share a pier overlap by the tolerance.
            let overlap = match likeness {
                Likeness::Loose { .. } => tolerance(a, b, rel, abs),
                _ => abs,
            };
            let apart =
                a.bbox()[2] <= b.bbox()[0] + overlap || b.bbox()[2] <= a.bbox()[0] + overlap;
            if same(a, b) && apart {
                let (ri, rj) = (find(&mut root, i), find(&mut root, j));
                root[ri] = rj;
            }
        }
    }
    let mut groups: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for i in 0..n {
        let r = find(&mut root, i);
        groups.entry(r).or_default().push(i);
    }
    let mut out: Vec<Vec<usize>> = groups.into_values().filter(|g| g.len() >= 2).collect();
    for g in &mut out {
        g.sort_by(|&a, &b| shapes[a].x0.total_cmp(&shapes[b].x0));
    }
    out.sort_by(|a, b| shapes[a[0]].x0.total_cmp(&shapes[b[0]].x0));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(x0: f64, y0: f64, w: f64, v: f64) -> Theta {
        Theta {
            x0,
            y0,
            h: 40.0,
            w,
            v,
        }
    }

    #[test]
    fn clusters_by_shape_and_sill_line() {
        let shapes = [
            t(0.0, 100.0, 20.0, 10.0),
            t(30.0, 101.0, 21.0, 10.5),
            t(60.0, 100.0, 20.0, 17.0), // pointed: another shape
            t(90.0, 100.0, 20.5, 16.0),
            t(120.0, 200.0, 20.0, 10.0), // another storey
            t(150.0, 100.0, 20.0, 10.0),
        ];
        let g = cluster(&shapes, 0.05, 1.5);
        assert_eq!(g, vec![vec![0, 1, 5], vec![2, 3]]);
    }

    const BOX: Likeness = Likeness::Box { rise_factor: 1.5 };
    const LOOSE: Likeness = Likeness::Loose { rise_factor: 1.5 };

    #[test]
    fn loose_clusters_join_by_head_or_by_width_on_the_sill_line() {
        // Twins 20 wide, 40 + 10 high, sills at 100, apexes at 50.
        let twin = |x0| t(x0, 100.0, 20.0, 10.0);
        // Its jambs ran 8 px down: the same head (apex 50), another box and sill.
        let long = Theta {
            h: 48.0,
            ..t(60.0, 108.0, 20.0, 10.0)
        };
        // Its head ran 8 px up: the same width and sill, another head.
        let tall = Theta {
            h: 48.0,
            ..t(90.0, 100.0, 20.0, 10.0)
        };
        let shapes = [twin(0.0), twin(30.0), long, tall];
        assert_eq!(cluster_with(&shapes, 0.05, 1.5, BOX), vec![vec![0, 1]]);
        assert_eq!(
            cluster_with(&shapes, 0.05, 1.5, LOOSE),
            vec![vec![0, 1, 2, 3]]
        );
        // Another width on the sill line, or the same width with its apex 8 px lower, is
        // no twin either way.
        let wide = t(60.0, 100.0, 28.0, 10.0);
        let low = t(60.0, 108.0, 20.0, 10.0);
        for other in [wide, low] {
            let shapes = [twin(0.0), other];
            assert!(
                cluster_with(&shapes, 0.05, 1.5, LOOSE).is_empty(),
                "{other:?}"
            );
        }
    }

    #[test]
    fn loose_twins_may_share_a_pier() {
        // Two arches 60 wide overlapping by 3 px (tolerance 0.05 × 60 + 1.5 = 4.5 px).
        let arch = |x0| Theta {
            x0,
            y0: 100.0,
            h: 40.0,
            w: 60.0,
            v: 20.0,
        };
        let shapes = [arch(0.0), arch(57.0)];
        assert!(cluster_with(&shapes, 0.05, 1.5, BOX).is_empty());
        assert_eq!(cluster_with(&shapes, 0.05, 1.5, LOOSE), vec![vec![0, 1]]);
        let shapes = [arch(0.0), arch(54.0)];
        assert!(
            cluster_with(&shapes, 0.05, 1.5, LOOSE).is_empty(),
            "6 px over"
        );
    }

    #[test]
    fn overlapping_shapes_do_not_group() {
        let shapes = [t(0.0, 100.0, 20.0, 10.0), t(5.0, 100.0, 20.0, 10.0)];
        assert!(cluster(&shapes, 0.05, 1.5).is_empty());
    }
}
