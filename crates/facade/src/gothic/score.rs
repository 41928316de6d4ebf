//! How an estimate compares with a synthetic façade's answers (issue 23): element recall at a
//! box IoU, the share of nested elements given the right parent, and the groups found whole.

use super::detect::iou;
use super::model::GothicEstimate;
use super::synth::TrueElement;

/// The figures of one façade (or, summed with [`Score::add`], of a set).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Score {
    /// True elements, and those matched by an estimated element (one to one, box IoU ≥ the
    /// threshold given to [`score`]).
    pub elements: usize,
    pub found: usize,
    /// True elements with a parent, and those whose match has the match of that parent as
    /// its parent (a missed element or parent counts as wrong).
    pub nested: usize,
    pub right_parent: usize,
    /// True groups of two or more identical siblings, and those whose members are all found
    /// and make up exactly one estimated group.
    pub groups: usize,
    pub complete: usize,
    /// Estimated elements matching no true one.
    pub extra: usize,
}

impl Score {
    pub fn add(&mut self, o: &Score) {
        self.elements += o.elements;
        self.found += o.found;
        self.nested += o.nested;
        self.right_parent += o.right_parent;
        self.groups += o.groups;
        self.complete += o.complete;
        self.extra += o.extra;
    }

    /// found / elements (1 when there is nothing to find).
    pub fn recall(&self) -> f64 {
        ratio(self.found, self.elements)
    }

    /// right_parent / nested.
    pub fn parent_accuracy(&self) -> f64 {
        ratio(self.right_parent, self.nested)
    }

    /// complete / groups.
    pub fn groups_complete(&self) -> f64 {
        ratio(self.complete, self.groups)
    }
}

fn ratio(a: usize, b: usize) -> f64 {
    if b == 0 { 1.0 } else { a as f64 / b as f64 }
}

/// For each true element, the id of the estimated element matched to it: pairs taken by
/// decreasing box IoU, each used once, none below `min_iou`.
pub fn matches(truth: &[TrueElement], est: &GothicEstimate, min_iou: f64) -> Vec<Option<usize>> {
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (t, te) in truth.iter().enumerate() {
        for e in &est.elements {
            let q = iou(&te.theta, &e.theta());
            if q >= min_iou {
                pairs.push((q, t, e.id));
            }
        }
    }
    pairs.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut out = vec![None; truth.len()];
    let mut used = vec![false; est.elements.len()];
    for (_, t, e) in pairs {
        if out[t].is_none() && !used[e] {
            out[t] = Some(e);
            used[e] = true;
        }
    }
    out
}

/// The figures of an estimate against a façade's answers.
pub fn score(truth: &[TrueElement], est: &GothicEstimate, min_iou: f64) -> Score {
    let m = matches(truth, est, min_iou);
    let found = m.iter().flatten().count();
    let mut s = Score {
        elements: truth.len(),
        found,
        extra: est.elements.len() - found,
        ..Score::default()
    };
    for (t, te) in truth.iter().enumerate() {
        let Some(p) = te.parent else { continue };
        s.nested += 1;
        let right = match (m[t], m[p]) {
            (Some(e), Some(pe)) => est.elements[e].parent == Some(pe),
            _ => false,
        };
        s.right_parent += usize::from(right);
    }
    let groups: std::collections::BTreeSet<usize> = truth.iter().filter_map(|t| t.group).collect();
    for g in groups {
        let members: Vec<usize> = (0..truth.len())
            .filter(|&t| truth[t].group == Some(g))
            .collect();
        if members.len() < 2 {
            continue;
        }
        s.groups += 1;
        let ids: Option<Vec<usize>> = members.iter().map(|&t| m[t]).collect();
        let complete = ids.is_some_and(|mut ids| {
            let gid = est.elements[ids[0]].group;
            let Some(gid) = gid else { return false };
            let Some(group) = est.groups.iter().find(|g| g.id == gid) else {
                return false;
            };
            let mut have = group.members.clone();
            have.sort_unstable();
            ids.sort_unstable();
            have == ids
        });
        s.complete += usize::from(complete);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gothic::element::{ArchKind, Theta};
    use crate::gothic::model::{Element, Group};

    fn theta(x0: f64, w: f64) -> Theta {
        Theta {
            x0,
            y0: 200.0,
            h: 60.0,
            w,
            v: w * 0.8,
        }
    }

    fn element(id: usize, t: Theta, parent: Option<usize>, group: Option<usize>) -> Element {
        Element {
            id,
            x0: t.x0,
            y0: t.y0,
            h: t.h,
            w: t.w,
            v: t.v,
            group,
            parent,
            kind: ArchKind::Pointed,
            depth: 0,
            mean_distance: 0.0,
            support: 1.0,
        }
    }

    #[test]
    fn recall_parents_and_groups_are_counted() {
        let arch = Theta {
            x0: 10.0,
            y0: 210.0,
            h: 100.0,
            w: 100.0,
            v: 60.0,
        };
        let truth = [
            TrueElement {
                theta: arch,
                parent: None,
                group: None,
            },
            TrueElement {
                theta: theta(20.0, 30.0),
                parent: Some(0),
                group: Some(0),
            },
            TrueElement {
                theta: theta(60.0, 30.0),
                parent: Some(0),
                group: Some(0),
            },
        ];
        // Both lancets found and grouped, the arch missed: no parent is right.
        let est = GothicEstimate {
            width: 200,
            height: 300,
            elements: vec![
                element(0, theta(21.0, 30.0), None, Some(0)),
                element(1, theta(60.0, 30.0), None, Some(0)),
                element(2, theta(150.0, 20.0), None, None),
            ],
            groups: vec![Group {
                id: 0,
                members: vec![0, 1],
                h: 60.0,
                w: 30.0,
                v: 24.0,
                enclosing: None,
            }],
        };
        let s = score(&truth, &est, 0.7);
        assert_eq!((s.elements, s.found, s.extra), (3, 2, 1));
        assert_eq!((s.nested, s.right_parent), (2, 0));
        assert_eq!((s.groups, s.complete), (1, 1));
        // With the arch found and set as parent, both parents are right.
        let mut est2 = est.clone();
        est2.elements[2] = element(2, arch, None, None);
        est2.elements[0].parent = Some(2);
        est2.elements[1].parent = Some(2);
        let s = score(&truth, &est2, 0.7);
        assert_eq!((s.found, s.right_parent, s.extra), (3, 2, 0));
        // A group of one member is not complete.
        est2.groups[0].members = vec![0];
        est2.elements[1].group = None;
        assert_eq!(score(&truth, &est2, 0.7).complete, 0);
    }
}
