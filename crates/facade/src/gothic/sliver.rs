//! Slivers (issue 23): thin contours between an element's jamb and the moulding of the arch
//! around it, or between two lancets, fit eq. 4.2 as well as any element (both of their long
//! sides are real edges) and are not elements. Departure from §4.2, which keeps every
//! significant maximum: an ungrouped element narrower than [`GothicParams::sliver_of_group`]
//! of the width of a group standing in the same parent, or than
//! [`GothicParams::sliver_of_parent`] of its parent's width (the spacing of the jambs it stands
//! between), is dropped.

use super::element::Theta;
use super::hierarchy::parents;
use super::params::GothicParams;

/// Which items to keep: `false` for the slivers (never a grouped or `pinned` item).
pub fn keep(
    shapes: &[Theta],
    group_of: &[Option<usize>],
    pinned: &[bool],
    params: &GothicParams,
) -> Vec<bool> {
    let parent = parents(shapes, params.nesting_tolerance);
    (0..shapes.len())
        .map(|i| {
            if group_of[i].is_some() || pinned[i] {
                return true;
            }
            let w = shapes[i].w;
            let Some(p) = parent[i] else { return true };
            let group_w = (0..shapes.len())
                .filter(|&j| parent[j] == Some(p) && group_of[j].is_some())
                .map(|j| shapes[j].w)
                .fold(0.0, f64::max);
            w >= params.sliver_of_group * group_w && w >= params.sliver_of_parent * shapes[p].w
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_thin_element_beside_a_group_under_an_arch_goes() {
        let arch = Theta {
            x0: 0.0,
            y0: 200.0,
            h: 120.0,
            w: 120.0,
            v: 70.0,
        };
        let lancet = |x0: f64, w: f64| Theta {
            x0,
            y0: 190.0,
            h: 80.0,
            w,
            v: w * 0.9,
        };
        let shapes = [
            arch,
            lancet(15.0, 30.0),
            lancet(60.0, 30.0),
            lancet(100.0, 8.0),
        ];
        let groups = [None, Some(0), Some(0), None];
        let params = GothicParams::default();
        let k = keep(&shapes, &groups, &[false; 4], &params);
        assert_eq!(k, vec![true, true, true, false]);
        // The user's element stays.
        let k = keep(&shapes, &groups, &[false, false, false, true], &params);
        assert!(k[3]);
    }
}
