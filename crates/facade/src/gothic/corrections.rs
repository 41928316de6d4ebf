//! The user's corrections of detected Gothic elements (issue 22; not in ch. 4): an element is
//! picked by a point inside it, then deleted or given its springing line, apex, width, centre
//! or sill by hand — mapped onto Θ = [x0, y0, h, w, v] of §4.1 — or a new element is added from
//! the same handles. Applied after detection (§4.2) and before grouping and the enclosing
//! arches, so the hierarchy and the block program follow the corrected elements.
//!
//! Handles are in the estimate's pixels (x right, y down); each one moves only its own line:
//! setting the springing line keeps the apex and the sill where they were, and so on.

use serde::{Deserialize, Serialize};

use super::detect::{Candidate, iou};
use super::element::Theta;
use super::likelihood::{DistanceMap, fit};
use super::params::GothicParams;

/// How far (px) outside every element a point may be and still pick the nearest one: a
/// re-detected element moves by a pixel or two, the user's point must still find it.
pub const PICK_SLACK: f64 = 10.0;

/// Most corrections of one photo (bounds the work of a request).
pub const MAX_CORRECTIONS: usize = 1000;

/// One correction (PROJECT.toml `[[gothic.element]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ElementCorrection {
    /// A point inside the detected element [x, y]; for `add`, the new element's centre line
    /// passes through its x.
    pub point: [f64; 2],
    /// y of the springing line (the top of the jambs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub springing: Option<f64>,
    /// y of the apex.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub apex: Option<f64>,
    /// The element's width (px); the centre stays unless `centre` is given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// x of the element's vertical axis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub centre: Option<f64>,
    /// y of the sill (the bottom edge, y0 of Θ).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sill: Option<f64>,
    /// Remove the element.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub delete: bool,
    /// A new element the detection missed: `springing`, `apex`, `width` and `sill` are then
    /// all required; its axis is at `centre`, or at the point's x.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub add: bool,
}

/// What a correction does, decided once from its keys.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Action {
    Delete,
    Move,
    Add,
}

/// A correction that cannot be applied: `index` is its position in the list (from 0).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("element #{}: {problem}", index + 1)]
pub struct CorrectionError {
    pub index: usize,
    pub problem: String,
}

/// What one correction did to the estimate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Applied {
    /// The correction's position in the list (from 0).
    pub correction: usize,
    pub action: Action,
    /// The element's id in the corrected estimate (none for a deletion).
    pub element: Option<usize>,
    /// The shape as detected (none for an added element).
    pub detected: Option<Theta>,
}

impl ElementCorrection {
    /// A correction that only picks the element at `point` (the handles are set after).
    pub fn at(point: [f64; 2]) -> ElementCorrection {
        ElementCorrection {
            point,
            springing: None,
            apex: None,
            width: None,
            centre: None,
            sill: None,
            delete: false,
            add: false,
        }
    }

    /// Delete, move or add; the checks that need no image (finite numbers, a positive width,
    /// the apex not below the springing line, the springing line not below the sill, the keys
    /// an addition needs).
    pub fn action(&self) -> Result<Action, String> {
        let values = [
            ("point x", Some(self.point[0])),
            ("point y", Some(self.point[1])),
            ("springing", self.springing),
            ("apex", self.apex),
            ("width", self.width),
            ("centre", self.centre),
            ("sill", self.sill),
        ];
        for (name, v) in values {
            if v.is_some_and(|v| !v.is_finite()) {
                return Err(format!("{name} must be a finite number of pixels"));
            }
        }
        if let Some(w) = self.width
            && w <= 0.0
        {
            return Err(format!("width = {w}: must be more than 0 px"));
        }
        if let (Some(a), Some(s)) = (self.apex, self.springing)
            && a > s
        {
            return Err(format!(
                "apex = {a} is below the springing line ({s}); y grows downwards, the apex is \
                 the smaller y"
            ));
        }
        if let (Some(s), Some(b)) = (self.springing, self.sill)
            && s > b
        {
            return Err(format!("springing = {s} is below the sill ({b})"));
        }
        let has_handle = [
            self.springing,
            self.apex,
            self.width,
            self.centre,
            self.sill,
        ]
        .iter()
        .any(Option::is_some);
        match (self.delete, self.add) {
            (true, true) => Err("delete and add cannot both be true".into()),
            (true, false) if has_handle => {
                Err("a deleted element takes no springing, apex, width, centre or sill".into())
            }
            (true, false) => Ok(Action::Delete),
            (false, true) => {
                let missing: Vec<&str> = [
                    ("springing", self.springing),
                    ("apex", self.apex),
                    ("width", self.width),
                    ("sill", self.sill),
                ]
                .iter()
                .filter(|(_, v)| v.is_none())
                .map(|(n, _)| *n)
                .collect();
                if missing.is_empty() {
                    Ok(Action::Add)
                } else {
                    Err(format!(
                        "an added element needs springing, apex, width and sill; missing {}",
                        missing.join(", ")
                    ))
                }
            }
            (false, false) if has_handle => Ok(Action::Move),
            (false, false) => Err(
                "says nothing to do: give delete = true, add = true or a handle (springing, \
                 apex, width, centre, sill)"
                    .into(),
            ),
        }
    }

    /// The same correction moved by (dx, dy) px (rectified photo ↔ façade cut-out).
    pub fn shifted(&self, dx: f64, dy: f64) -> ElementCorrection {
        let x = |v: Option<f64>| v.map(|v| v + dx);
        let y = |v: Option<f64>| v.map(|v| v + dy);
        ElementCorrection {
            point: [self.point[0] + dx, self.point[1] + dy],
            springing: y(self.springing),
            apex: y(self.apex),
            width: self.width,
            centre: x(self.centre),
            sill: y(self.sill),
            ..self.clone()
        }
    }

    /// `base` with this correction's handles: each handle moves its own line only.
    pub fn reshape(&self, base: &Theta) -> Theta {
        let sill = self.sill.unwrap_or(base.y0);
        let springing = self.springing.unwrap_or(base.springing());
        let apex = self.apex.unwrap_or(base.apex());
        let w = self.width.unwrap_or(base.w);
        let centre = self.centre.unwrap_or(base.x0 + base.w / 2.0);
        Theta {
            x0: centre - w / 2.0,
            y0: sill,
            h: sill - springing,
            w,
            v: springing - apex,
        }
    }

    /// The element of Θ = [x0, y0, h, w, v] an addition describes.
    fn added(&self) -> Theta {
        let base = Theta {
            x0: self.centre.unwrap_or(self.point[0]),
            y0: 0.0,
            h: 0.0,
            w: 0.0,
            v: 0.0,
        };
        self.reshape(&base)
    }
}

/// Handles of an element as the page shows them: springing line, apex, width, centre, sill.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Handles {
    pub springing: f64,
    pub apex: f64,
    pub width: f64,
    pub centre: f64,
    pub sill: f64,
}

impl Handles {
    pub fn of(t: &Theta) -> Handles {
        Handles {
            springing: t.springing(),
            apex: t.apex(),
            width: t.w,
            centre: t.x0 + t.w / 2.0,
            sill: t.y0,
        }
    }
}

/// The smallest of `shapes` containing `point` (a window inside its enclosing arch is the
/// window).
pub fn pick_containing(shapes: &[Theta], point: [f64; 2]) -> Option<usize> {
    let [x, y] = point;
    let area = |t: &Theta| t.w * (t.h + t.v);
    shapes
        .iter()
        .enumerate()
        .filter(|(_, t)| t.contains(x, y))
        .min_by(|a, b| area(a.1).total_cmp(&area(b.1)))
        .map(|(i, _)| i)
}

/// The element `point` picks among `shapes`: the smallest one containing it, else the nearest
/// within [`PICK_SLACK`] px of its box.
pub fn pick(shapes: &[Theta], point: [f64; 2]) -> Option<usize> {
    if let Some(i) = pick_containing(shapes, point) {
        return Some(i);
    }
    let [x, y] = point;
    let box_distance = |t: &Theta| {
        let [x0, y0, x1, y1] = t.bbox();
        let dx = (x0 - x).max(0.0).max(x - x1);
        let dy = (y0 - y).max(0.0).max(y - y1);
        dx.hypot(dy)
    };
    shapes
        .iter()
        .enumerate()
        .map(|(i, t)| (i, box_distance(t)))
        .filter(|(_, d)| *d <= PICK_SLACK)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

/// The detected elements with the corrections applied, ready for grouping.
#[derive(Debug, Clone)]
pub struct Corrected {
    pub items: Vec<Candidate>,
    /// Set by the user: kept as they are (no joint re-estimation, no round-arch snap, never
    /// replaced by an enclosing arch).
    pub pinned: Vec<bool>,
    /// The shapes the user deleted: an enclosing arch proposed over the same box is not made
    /// again.
    pub deleted: Vec<Theta>,
    /// Per correction, what it did; `element` is the index into `items`.
    pub applied: Vec<Applied>,
    /// Corrections whose point no detected element contains: applied after grouping, when
    /// the enclosing arches exist ([`resolve`]).
    pub deferred: Vec<(usize, ElementCorrection, Action)>,
}

impl Corrected {
    /// The detected elements as they are.
    pub fn none(found: Vec<Candidate>) -> Corrected {
        Corrected {
            pinned: vec![false; found.len()],
            items: found,
            deleted: Vec::new(),
            applied: Vec::new(),
            deferred: Vec::new(),
        }
    }
}

/// Applies `corrections` to the detected elements `found` of an image `width` × `height`.
/// Every correction picks its element among the detected ones (not among the results of the
/// corrections before it), so the order of the list does not matter; two corrections picking
/// the same element are refused.
pub fn apply(
    dt: &DistanceMap,
    found: Vec<Candidate>,
    corrections: &[ElementCorrection],
    params: &GothicParams,
) -> Result<Corrected, CorrectionError> {
    if corrections.len() > MAX_CORRECTIONS {
        return Err(CorrectionError {
            index: MAX_CORRECTIONS,
            problem: format!(
                "{} corrections of one photo; at most {MAX_CORRECTIONS}",
                corrections.len()
            ),
        });
    }
    let (width, height) = (dt.width as f64, dt.height as f64);
    let detected: Vec<Theta> = found.iter().map(|c| c.theta).collect();
    let mut picked: Vec<Option<usize>> = vec![None; detected.len()];
    let mut items: Vec<Option<Candidate>> = found.into_iter().map(Some).collect();
    let mut pinned = vec![false; items.len()];
    let mut deleted = Vec::new();
    let mut applied = Vec::new();
    let mut added = Vec::new();
    let mut deferred = Vec::new();
    for (index, c) in corrections.iter().enumerate() {
        let fail = |problem: String| CorrectionError { index, problem };
        let action = c.action().map_err(fail)?;
        let [x, y] = c.point;
        if !(0.0..=width).contains(&x) || !(0.0..=height).contains(&y) {
            return Err(fail(format!(
                "point [{x}, {y}] is outside the photo (0..{width} × 0..{height} px)"
            )));
        }
        let target = match action {
            Action::Add => None,
            Action::Delete | Action::Move => {
                // Only an element containing the point here: one the hierarchy makes (an
                // enclosing arch no seed found) is picked after grouping (`resolve`).
                let Some(i) = pick_containing(&detected, c.point) else {
                    deferred.push((index, c.clone(), action));
                    continue;
                };
                if let Some(other) = picked[i] {
                    return Err(fail(format!(
                        "picks the same element as element #{}; give each element one entry",
                        other + 1
                    )));
                }
                picked[i] = Some(index);
                Some(i)
            }
        };
        let shape = match (action, target) {
            (Action::Delete, Some(i)) => {
                deleted.push(detected[i]);
                items[i] = None;
                applied.push(Applied {
                    correction: index,
                    action,
                    element: None,
                    detected: Some(detected[i]),
                });
                continue;
            }
            (_, Some(i)) => c.reshape(&detected[i]),
            (_, None) => c.added(),
        };
        check_shape(&shape, width, height).map_err(fail)?;
        let candidate = Candidate {
            theta: shape,
            fit: fit(dt, &shape, params.step),
        };
        match target {
            Some(i) => {
                items[i] = Some(candidate);
                pinned[i] = true;
                applied.push(Applied {
                    correction: index,
                    action,
                    element: Some(i),
                    detected: Some(detected[i]),
                });
            }
            None => added.push((index, candidate)),
        }
    }
    // Deleted items leave the list; indices of the rest (and of the applied moves) follow.
    let mut new_index = vec![None; items.len()];
    let mut kept = Vec::new();
    let mut kept_pinned = Vec::new();
    for (i, item) in items.into_iter().enumerate() {
        if let Some(c) = item {
            new_index[i] = Some(kept.len());
            kept.push(c);
            kept_pinned.push(pinned[i]);
        }
    }
    for a in &mut applied {
        a.element = a.element.and_then(|i| new_index[i]);
    }
    for (index, c) in added {
        applied.push(Applied {
            correction: index,
            action: Action::Add,
            element: Some(kept.len()),
            detected: None,
        });
        kept.push(c);
        kept_pinned.push(true);
    }
    applied.sort_by_key(|a| a.correction);
    Ok(Corrected {
        items: kept,
        pinned: kept_pinned,
        deleted,
        applied,
        deferred,
    })
}

/// The elements after grouping and the enclosing arches, as `organise` holds them.
pub(crate) struct Organised<'a> {
    pub items: &'a mut Vec<Candidate>,
    pub pinned: &'a mut Vec<bool>,
    pub group_of: &'a mut Vec<Option<usize>>,
    pub groups: &'a mut Vec<Vec<usize>>,
}

/// The corrections whose point no detected element contained, applied to the organised
/// elements (the enclosing arches included): the smallest element containing the point, else
/// the nearest within [`PICK_SLACK`] px. A moved element leaves its group.
pub(crate) fn resolve(
    dt: &DistanceMap,
    o: Organised,
    deferred: &[(usize, ElementCorrection, Action)],
    applied: &mut Vec<Applied>,
    params: &GothicParams,
) -> Result<(), CorrectionError> {
    let (width, height) = (dt.width as f64, dt.height as f64);
    let mut remove = vec![false; o.items.len()];
    let mut taken: Vec<Option<usize>> =
        applied.iter().fold(vec![None; o.items.len()], |mut t, a| {
            if let Some(i) = a.element.filter(|&i| i < t.len()) {
                t[i] = Some(a.correction);
            }
            t
        });
    let shapes: Vec<Theta> = o.items.iter().map(|c| c.theta).collect();
    for (index, c, action) in deferred {
        let fail = |problem: String| CorrectionError {
            index: *index,
            problem,
        };
        let [x, y] = c.point;
        let i = pick(&shapes, c.point).ok_or_else(|| {
            fail(format!(
                "no element contains [{x}, {y}] or lies within {PICK_SLACK} px of it ({} \
                 found)",
                shapes.len()
            ))
        })?;
        if let Some(other) = taken[i] {
            return Err(fail(format!(
                "picks the same element as element #{}; give each element one entry",
                other + 1
            )));
        }
        taken[i] = Some(*index);
        let detected = Some(shapes[i]);
        if *action == Action::Delete {
            remove[i] = true;
            applied.push(Applied {
                correction: *index,
                action: *action,
                element: None,
                detected,
            });
            continue;
        }
        let shape = c.reshape(&shapes[i]);
        check_shape(&shape, width, height).map_err(fail)?;
        o.items[i] = Candidate {
            theta: shape,
            fit: fit(dt, &shape, params.step),
        };
        o.pinned[i] = true;
        if let Some(g) = o.group_of[i].take() {
            o.groups[g].retain(|&m| m != i);
        }
        applied.push(Applied {
            correction: *index,
            action: *action,
            element: Some(i),
            detected,
        });
    }
    // The deleted ones leave; indices and groups follow.
    let mut new_index = vec![None; remove.len()];
    let mut n = 0;
    for (i, r) in remove.iter().enumerate() {
        if !r {
            new_index[i] = Some(n);
            n += 1;
        }
    }
    let mut k = 0;
    o.items.retain(|_| {
        k += 1;
        !remove[k - 1]
    });
    let mut k = 0;
    o.pinned.retain(|_| {
        k += 1;
        !remove[k - 1]
    });
    let mut group_of: Vec<Option<usize>> = o
        .group_of
        .iter()
        .zip(&remove)
        .filter(|(_, r)| !**r)
        .map(|(g, _)| *g)
        .collect();
    let mut new_group = vec![None; o.groups.len()];
    let mut groups = Vec::new();
    for (g, members) in o.groups.iter().enumerate() {
        let members: Vec<usize> = members.iter().filter_map(|&m| new_index[m]).collect();
        if members.len() >= 2 {
            new_group[g] = Some(groups.len());
            groups.push(members);
        }
    }
    for g in &mut group_of {
        *g = g.and_then(|g| new_group[g]);
    }
    *o.group_of = group_of;
    *o.groups = groups;
    for a in applied.iter_mut() {
        a.element = a.element.and_then(|i| new_index[i]);
    }
    applied.sort_by_key(|a| a.correction);
    Ok(())
}

/// A corrected shape must be an element inside the photo (the checks of
/// [`ElementCorrection::action`] again, on the handles it kept from the detection).
fn check_shape(t: &Theta, width: f64, height: f64) -> Result<(), String> {
    if t.w <= 0.0 {
        return Err(format!("width {:.1}: must be more than 0 px", t.w));
    }
    if t.v < 0.0 {
        return Err(format!(
            "the apex ({:.1}) would be below the springing line ({:.1})",
            t.apex(),
            t.springing()
        ));
    }
    if t.h < 0.0 {
        return Err(format!(
            "the springing line ({:.1}) would be below the sill ({:.1})",
            t.springing(),
            t.y0
        ));
    }
    let [x0, y0, x1, y1] = t.bbox();
    // Half a pixel of slack: the detection itself may put an edge on the border.
    if x0 < -0.5 || y0 < -0.5 || x1 > width + 0.5 || y1 > height + 0.5 {
        return Err(format!(
            "the element [{x0:.1}, {y0:.1}, {x1:.1}, {y1:.1}] reaches outside the photo \
             (0..{width} × 0..{height} px)"
        ));
    }
    Ok(())
}

/// Whether an enclosing arch proposed over `theta` would bring back a deleted element.
pub fn is_deleted(deleted: &[Theta], theta: &Theta, params: &GothicParams) -> bool {
    deleted
        .iter()
        .any(|d| iou(d, theta) >= params.duplicate_iou)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn theta() -> Theta {
        Theta {
            x0: 10.0,
            y0: 100.0,
            h: 40.0,
            w: 30.0,
            v: 15.0,
        }
    }

    #[test]
    fn each_handle_moves_only_its_own_line() {
        let t = theta();
        let mut c = ElementCorrection::at([25.0, 80.0]);
        c.apex = Some(30.0);
        let moved = c.reshape(&t);
        assert_eq!(moved.apex(), 30.0);
        assert_eq!(
            (moved.springing(), moved.y0, moved.w, moved.x0),
            (60.0, 100.0, 30.0, 10.0)
        );
        let mut c = ElementCorrection::at([25.0, 80.0]);
        c.springing = Some(50.0);
        let moved = c.reshape(&t);
        assert_eq!(
            (moved.springing(), moved.apex(), moved.h),
            (50.0, 45.0, 50.0)
        );
        let mut c = ElementCorrection::at([25.0, 80.0]);
        c.width = Some(40.0);
        let moved = c.reshape(&t);
        assert_eq!(
            (moved.x0, moved.w, moved.x0 + moved.w / 2.0),
            (5.0, 40.0, 25.0)
        );
        let mut c = ElementCorrection::at([25.0, 80.0]);
        c.centre = Some(50.0);
        assert_eq!(c.reshape(&t).x0, 35.0);
    }

    #[test]
    fn the_handles_read_back_what_was_set() {
        let h = Handles::of(&theta());
        assert_eq!(
            (h.springing, h.apex, h.width, h.centre, h.sill),
            (60.0, 45.0, 30.0, 25.0, 100.0)
        );
    }

    #[test]
    fn bad_values_are_refused_with_the_reason() {
        let mut c = ElementCorrection::at([1.0, 1.0]);
        assert!(c.action().unwrap_err().contains("nothing to do"));
        c.width = Some(0.0);
        assert!(c.action().unwrap_err().contains("more than 0"));
        c.width = None;
        c.apex = Some(50.0);
        c.springing = Some(40.0);
        assert!(c.action().unwrap_err().contains("below the springing"));
        c.apex = Some(f64::NAN);
        assert!(c.action().unwrap_err().contains("finite"));
        let mut d = ElementCorrection::at([1.0, 1.0]);
        d.delete = true;
        assert_eq!(d.action(), Ok(Action::Delete));
        d.apex = Some(3.0);
        assert!(d.action().is_err());
        let mut a = ElementCorrection::at([1.0, 1.0]);
        a.add = true;
        a.apex = Some(3.0);
        assert!(a.action().unwrap_err().contains("springing, width, sill"));
    }

    #[test]
    fn a_point_picks_the_smallest_element_containing_it_or_a_near_one() {
        let outer = Theta {
            x0: 0.0,
            y0: 200.0,
            h: 100.0,
            w: 200.0,
            v: 100.0,
        };
        let inner = theta();
        let shapes = [outer, inner];
        assert_eq!(pick(&shapes, [25.0, 80.0]), Some(1));
        assert_eq!(pick(&shapes, [150.0, 150.0]), Some(0));
        assert_eq!(pick(&shapes, [205.0, 150.0]), Some(0));
        assert_eq!(pick(&shapes, [250.0, 150.0]), None);
    }
}
