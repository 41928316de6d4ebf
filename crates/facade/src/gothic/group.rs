//! Self-similar groups of §4.2: elements clustered by their shape (h, w, v), then re-estimated
//! jointly with one shared shape and one position per member.

use super::element::Theta;

/// Whether two shapes are the same up to `rel` of the larger size plus `abs` px.
pub fn similar(a: &Theta, b: &Theta, rel: f64, abs: f64) -> bool {
    let close = |x: f64, y: f64, scale: f64| (x - y).abs() <= rel * scale + abs;
    let size = a.w.max(b.w).max(a.h + a.v).max(b.h + b.v);
    close(a.w, b.w, size) && close(a.h, b.h, size) && close(a.v, b.v, size)
}

/// Clusters by shape (single linkage). Departure from §4.2, which clusters on (h, w, v) alone:
/// members must also stand on one sill line (y0 within the same tolerance), so identical
/// windows on two storeys or in two bays far apart form separate groups that each get their
/// own enclosing arch. Returns clusters of two or more indices, each sorted left to right.
pub fn cluster(shapes: &[Theta], rel: f64, abs: f64) -> Vec<Vec<usize>> {
    cluster_with(shapes, rel, abs, None)
}

/// Whether two shapes are the same by their box and rise: w and the total height h + v within
/// `rel` of the larger size plus `abs` px, and v within `rise_factor` times that.
pub fn similar_box(a: &Theta, b: &Theta, rel: f64, abs: f64, rise_factor: f64) -> bool {
    let size = a.w.max(b.w).max(a.h + a.v).max(b.h + b.v);
    let tol = rel * size + abs;
    (a.w - b.w).abs() <= tol
        && (a.h + a.v - b.h - b.v).abs() <= tol
        && (a.v - b.v).abs() <= rise_factor * tol
}

/// [`cluster`]; with `Some(rise_factor)`, shapes compared by [`similar_box`] instead of
/// [`similar`]. Departure from §4.2 (issue 23): where the head meets the jambs almost
/// tangentially the fit moves v and h against each other at a fixed apex (a lancet found with
/// v = 30 beside its twins' 21, the same box), so the box is held to the tolerance and the
/// rise to `rise_factor` times it.
pub fn cluster_with(
    shapes: &[Theta],
    rel: f64,
    abs: f64,
    rise_factor: Option<f64>,
) -> Vec<Vec<usize>> {
    let same = |a: &Theta, b: &Theta| match rise_factor {
        Some(f) => similar_box(a, b, rel, abs, f),
        None => similar(a, b, rel, abs),
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
            let size = a.w.max(b.w).max(a.h + a.v).max(b.h + b.v);
            let same_row = (a.y0 - b.y0).abs() <= rel * size + abs;
            let apart = a.bbox()[2] <= b.bbox()[0] + abs || b.bbox()[2] <= a.bbox()[0] + abs;
            if same(a, b) && same_row && apart {
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

    #[test]
    fn overlapping_shapes_do_not_group() {
        let shapes = [t(0.0, 100.0, 20.0, 10.0), t(5.0, 100.0, 20.0, 10.0)];
        assert!(cluster(&shapes, 0.05, 1.5).is_empty());
    }
}
