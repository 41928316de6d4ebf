//! Gothic façades (Sui 2011, ch. 4): every arched or rectangular element of a rectified façade
//! as a whole shape Θ = [x0, y0, h, w, v] (§4.1), self-similar groups, nested enclosing arches,
//! and the masonry between them as stones and mortar (§4.2), then a block-level VSG program.
//!
//! # Pipeline (one file per step)
//! - [`element`]: Θ, the constraint points of eq. 4.1 and the contour sampled at sub-pixel
//!   arc-length steps.
//! - [`likelihood`]: Prewitt edges (no linking) → distance transform D → ∮ D ds (eq. 4.2).
//! - [`classes`]: optional, for photographs (departure from §4.2): D and seeds from the ch. 3
//!   window class instead of the image edges.
//! - [`detect`]: seeds at peaks of D, conjugate-gradient MLE ([`optimise`], `argmin`),
//!   significance test, duplicate suppression.
//! - [`corrections`]: the user's deleted, moved and added elements (issue 22), applied between
//!   detection and grouping ([`estimate_corrected`]).
//! - [`group`]: clusters by (h, w, v) and joint re-estimation (shared shape, own positions);
//!   [`repeat`]: clusters split by their spacing, members proposed where it repeats;
//!   [`sliver`]: thin ungrouped contours beside a group or a jamb dropped.
//! - [`hierarchy`]: enclosing-arch proposals over groups, iterated (figure 4.4), and parents;
//!   [`enclose`]: the grid search for arches whose inside is the wall (issue 23).
//! - [`masonry`] with [`watershed`]: element pixels removed, watershed on the rest, regions
//!   merged by colour into stones and mortar.
//! - [`program`]: [`to_vsg`](program::to_vsg), the estimate (+ stones, + a depth) as a VSG
//!   program: a wall block, each element cut from it with the spandrel/opening construction of
//!   `library/gothic_window.vsg` (same x0, y0, h, w, v), stones extruded as blocks.
//! - [`draw`]: the overlay figure (mortar tinted, contours by nesting depth).
//! - [`synth`], [`synth_lancet`]: synthetic façades with known arches for tests and
//!   benchmarks; [`score`]: how an estimate compares with their answers (issue 23).
//!
//! ```
//! use facade::gothic::{estimate, GothicParams, masonry, to_vsg, VsgOptions};
//! use facade::gothic::synth::{synthetic_facade, SynthSpec};
//!
//! let synth = synthetic_facade(&SynthSpec::small(), 1);
//! let est = estimate(&synth.image, &GothicParams::default()).unwrap();
//! assert!(est.elements.len() >= 3);
//! let stones = masonry::segment(&synth.image, &est, &masonry::MasonryParams::default());
//! let program = to_vsg(&est, Some(&stones), &VsgOptions::default());
//! assert!(program.contains("Axiom ::"));
//! ```
//!
//! GOTHIC.json is [`GothicEstimate`] serialised (ARCHITECTURE.md contract).

pub mod classes;
pub mod corrections;
pub mod detect;
pub mod draw;
pub mod dual;
pub mod element;
pub mod enclose;
pub mod group;
pub mod hatching_tone;
pub mod hierarchy;
pub mod likelihood;
pub mod masonry;
mod model;
pub mod optimise;
mod params;
pub mod program;
pub mod repeat;
pub mod score;
pub mod sliver;
pub mod synth;
pub mod synth_engraving;
pub mod synth_lancet;
pub mod verify;
pub mod watershed;

use image::RgbImage;

// GOTHIC.json's types and the pipeline's settings, in files of their own.
pub use model::{Element, GothicEstimate, Group};
pub use params::{GothicParams, Progress};

pub use corrections::{Applied, CorrectionError, ElementCorrection};
pub use element::{ArchKind, Theta};
pub use program::{VsgOptions, to_vsg};

use crate::{FacadeError, Result};
use corrections::Corrected;
use detect::Candidate;
use likelihood::{DistanceMap, fit};
use optimise::maximise_group;

/// Smallest image side the pipeline accepts: an element needs a few pixels around it.
pub const MIN_SIDE: u32 = 16;

/// Edges and distance transform of §4.2 for an image.
pub fn distance_map(img: &RgbImage, params: &GothicParams) -> DistanceMap {
    DistanceMap::of_edges(&image_edges(img, params))
}

/// The Prewitt edge map of §4.2 (after hatching suppression when asked).
pub fn image_edges(img: &RgbImage, params: &GothicParams) -> image::GrayImage {
    let mut gray = image::imageops::grayscale(img);
    if let Some(h) = &params.hatching {
        gray = hatching_tone::suppress(&gray, params.edge_threshold, h).0;
    }
    raster::edges::prewitt_edges(&gray, &likelihood::edge_rule(params.edge_threshold)).mask
}

/// Refuses images too small for an element (both entry points).
pub(crate) fn check_size(img: &RgbImage) -> Result<()> {
    let (w, h) = img.dimensions();
    if w < MIN_SIDE || h < MIN_SIDE {
        return Err(FacadeError::ImageTooSmall {
            width: w,
            height: h,
            need: format!("Gothic element detection needs at least {MIN_SIDE}x{MIN_SIDE} pixels"),
        });
    }
    Ok(())
}

/// The whole element pipeline of §4.2: detection, grouping, nesting.
pub fn estimate(img: &RgbImage, params: &GothicParams) -> Result<GothicEstimate> {
    estimate_with_progress(img, params, &|_| {})
}

/// [`estimate`], telling `progress` how far it has got (called from several threads).
pub fn estimate_with_progress(
    img: &RgbImage,
    params: &GothicParams,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<GothicEstimate> {
    let detection = detect_elements(img, params, progress)?;
    let est = organise_plain(&detection.dt, detection.found, params, progress);
    Ok(verify::checked(img, est, &[], params.verify).0)
}

/// The slow half of §4.2 (edges, distance transform, every seed maximised), kept so the
/// user's corrections can be applied and the elements organised again without it.
#[derive(Debug, Clone)]
pub struct Detection {
    pub dt: DistanceMap,
    pub found: Vec<Candidate>,
    /// The image detected on, for the learned check of the organised elements (issue 23).
    pub image: RgbImage,
}

/// Edges, distance transform and detection (§4.2) of an image.
pub fn detect_elements(
    img: &RgbImage,
    params: &GothicParams,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<Detection> {
    check_size(img)?;
    progress(Progress::Edges);
    let dt = distance_map(img, params);
    let found = detect::detect_with(&dt, params, progress);
    Ok(Detection {
        dt,
        found,
        image: img.clone(),
    })
}

/// What [`estimate_corrected`] gives.
#[derive(Debug, Clone)]
pub struct CorrectedEstimate {
    pub estimate: GothicEstimate,
    /// What each correction did, with the element ids of `estimate`.
    pub applied: Vec<Applied>,
    /// Elements the learned check took out (issue 23; 0 when `params.verify` is off).
    pub dropped: usize,
}

/// The estimate with the user's corrections (issue 22): applied to the detected elements,
/// then grouping, enclosing arches, nesting and the learned check as [`estimate`] does them.
pub fn estimate_corrected(
    detection: &Detection,
    corrections: &[ElementCorrection],
    params: &GothicParams,
    progress: &(dyn Fn(Progress) + Sync),
) -> std::result::Result<CorrectedEstimate, CorrectionError> {
    let corrected =
        corrections::apply(&detection.dt, detection.found.clone(), corrections, params)?;
    // Organising keeps the indices of the items it was given and appends enclosing arches;
    // `resolve` keeps the ids of what it applies in step with its deletions.
    let (est, mut applied) = organise_with_progress(&detection.dt, corrected, params, progress)?;
    let users: Vec<usize> = applied.iter().filter_map(|a| a.element).collect();
    let found = est.elements.len();
    let (est, new_id) = verify::checked(&detection.image, est, &users, params.verify);
    // The user's elements all stay, so each applied correction keeps an element.
    for a in &mut applied {
        a.element = a.element.and_then(|id| new_id.get(id).copied().flatten());
    }
    Ok(CorrectedEstimate {
        dropped: found - est.elements.len(),
        estimate: est,
        applied,
    })
}

/// Grouping, joint re-estimation and enclosing arches over detected elements, up to
/// `max_levels` rounds; then parents, depths and groups as GOTHIC.json has them.
pub fn organise(dt: &DistanceMap, found: Vec<Candidate>, params: &GothicParams) -> GothicEstimate {
    organise_plain(dt, found, params, &|_| {})
}

/// [`organise`] without corrections: nothing can fail.
fn organise_plain(
    dt: &DistanceMap,
    found: Vec<Candidate>,
    params: &GothicParams,
    progress: &(dyn Fn(Progress) + Sync),
) -> GothicEstimate {
    match organise_with_progress(dt, Corrected::none(found), params, progress) {
        Ok((est, _)) => est,
        // Only a correction can fail, and there is none.
        Err(_) => finish(dt, Vec::new(), Vec::new(), Vec::new(), params),
    }
}

/// Issue 22: elements the user set are `pinned` — left out of the groups (a group's shared
/// shape would move them off the user's handles), never snapped to a round arch nor replaced by
/// an enclosing arch — and an enclosing arch over a deleted element's box is not made again.
fn organise_with_progress(
    dt: &DistanceMap,
    corrected: Corrected,
    params: &GothicParams,
    progress: &(dyn Fn(Progress) + Sync),
) -> std::result::Result<(GothicEstimate, Vec<Applied>), CorrectionError> {
    let Corrected {
        mut items,
        mut pinned,
        deleted,
        mut applied,
        deferred,
    } = corrected;
    let mut group_of: Vec<Option<usize>> = vec![None; items.len()];
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut rejected: Vec<Vec<usize>> = Vec::new();
    // Each group's members and the item enclosing it, for twin arches (repeat::twin_arches).
    let mut arches: Vec<(Vec<Theta>, usize)> = Vec::new();
    for level in 0..params.max_levels {
        // Departure from §4.2: repeated elements proposed by copying (repeat.rs, issue 23).
        if params.repetition {
            add_copies(dt, &mut items, &mut group_of, &mut pinned, &deleted, params);
        }
        let free: Vec<usize> = (0..items.len())
            .filter(|&i| group_of[i].is_none() && !pinned[i])
            .collect();
        // Departure from §4.2: groups by box and rise, or by head, split by spacing (issue 23).
        let likeness = likeness(params);
        let mut clusters = cluster_items(&items, &free, likeness, params);
        if params.repetition {
            clusters = by_spacing(
                dt,
                clusters,
                (&mut items, &mut group_of, &mut pinned),
                &deleted,
                params,
            );
        }
        clusters.retain(|c| !rejected.contains(c));
        if clusters.is_empty() {
            break;
        }
        let mut queue: std::collections::VecDeque<Vec<usize>> = clusters.into();
        let mut done = 0;
        while let Some(members) = queue.pop_front() {
            progress(Progress::Organising {
                level: level + 1,
                of: params.max_levels,
                done,
                total: done + queue.len() + 1,
            });
            done += 1;
            // Departure from §4.2: also from the best member's shape (issue 23, `joint_fit`).
            let (joint, fits) = joint_fit(dt, &items, &members, params);
            // Self-similar only if every member stays significant with the shared shape and
            // fits it nearly as well as its own: otherwise no group.
            let similar = fits.iter().zip(&members).all(|(f, &i)| {
                let own = items[i].fit.mean_distance;
                detect::significant(f, params) && f.mean_distance <= (1.5 * own).max(own + 0.2)
            });
            if !similar {
                // A loose cluster that is not self-similar may still hold twins by their
                // boxes: they are tried on their own.
                if let group::Likeness::Loose { rise_factor } = likeness {
                    let boxes = group::Likeness::Box { rise_factor };
                    for c in cluster_items(&items, &members, boxes, params) {
                        if c != members && !rejected.contains(&c) {
                            queue.push_back(c);
                        }
                    }
                }
                rejected.push(members);
                continue;
            }
            for ((&i, t), f) in members.iter().zip(&joint).zip(&fits) {
                items[i] = Candidate { theta: *t, fit: *f };
            }
            for &i in &members {
                group_of[i] = Some(groups.len());
            }
            let thetas: Vec<Theta> = members.iter().map(|&i| items[i].theta).collect();
            groups.push(members);
            // An element found from the seeds may already enclose the group; the proposals
            // of §4.2 start from the group itself and replace it when they fit better.
            let Some(mut enc) = hierarchy::enclosing(dt, &thetas, params) else {
                continue;
            };
            if corrections::is_deleted(&deleted, &enc.theta, params) {
                continue;
            }
            // Departure from §4.2: twin groups get twin arches (issue 23).
            if params.repetition {
                let twin = arches.iter().find(|(m, _)| {
                    repeat::twins(m, &thetas, params.spacing_tolerance, RISE_FACTOR, params)
                });
                if let Some((m, a)) = twin.filter(|(_, a)| !pinned[*a]) {
                    let pair = repeat::twin_arches(
                        dt,
                        (m.as_slice(), &items[*a]),
                        (&thetas, &enc),
                        params,
                    );
                    if let Some((a2, b2)) = pair {
                        items[*a] = a2;
                        enc = b2;
                    }
                }
            }
            let same = (0..items.len())
                .find(|&i| detect::iou(&items[i].theta, &enc.theta) >= params.duplicate_iou);
            let at = match same {
                Some(i) if !pinned[i] && items[i].fit.mean_distance > enc.fit.mean_distance => {
                    items[i] = enc;
                    i
                }
                Some(i) => i,
                None => {
                    items.push(enc);
                    group_of.push(None);
                    pinned.push(false);
                    items.len() - 1
                }
            };
            arches.push((thetas, at));
        }
    }
    if !deferred.is_empty() {
        corrections::resolve(
            dt,
            corrections::Organised {
                items: &mut items,
                pinned: &mut pinned,
                group_of: &mut group_of,
                groups: &mut groups,
            },
            &deferred,
            &mut applied,
            params,
        )?;
    }
    for (c, &user) in items.iter_mut().zip(&pinned) {
        if !user {
            *c = snap_round(dt, *c, params);
        }
    }
    let shapes: Vec<Theta> = items.iter().map(|c| c.theta).collect();
    // Departure from §4.2: slivers beside a group or a jamb are not elements (issue 23).
    let keep = sliver::keep(&shapes, &group_of, &pinned, params);
    if keep.iter().any(|k| !k) {
        // Ids shift down past each dropped item: groups and corrections follow.
        let mut new_id = vec![None; items.len()];
        let mut next = 0;
        for (i, &k) in keep.iter().enumerate() {
            if k {
                new_id[i] = Some(next);
                next += 1;
            }
        }
        items = kept(items, &keep);
        group_of = kept(group_of, &keep);
        for g in &mut groups {
            for m in g.iter_mut() {
                *m = new_id[*m].unwrap_or(*m);
            }
        }
        for a in &mut applied {
            a.element = a.element.and_then(|e| new_id[e]);
        }
    }
    Ok((finish(dt, items, group_of, groups, params), applied))
}

/// With `repetition`, a rise may differ by this many times the grouping tolerance (see
/// [`group::cluster_with`]).
pub const RISE_FACTOR: f64 = 1.5;

/// Issue 23 (see [`repeat`]): each ungrouped element is tried at every shift along its sill
/// line, and the significant copies join the items (none where the user deleted one).
fn add_copies(
    dt: &DistanceMap,
    items: &mut Vec<Candidate>,
    group_of: &mut Vec<Option<usize>>,
    pinned: &mut Vec<bool>,
    deleted: &[Theta],
    params: &GothicParams,
) {
    let free: Vec<usize> = (0..items.len())
        .filter(|&i| group_of[i].is_none() && !pinned[i])
        .collect();
    // Every ungrouped element, not only those without a similar one: two lancets found in two
    // bays are similar, yet each bay's other lancets are still missing. A copy where an
    // element of its size already stands is refused, so found members are not found twice.
    let shapes: Vec<Theta> = items.iter().map(|c| c.theta).collect();
    // A sliver is not an element, so it is not repeated either (its copies would form a
    // group and escape the sliver test).
    let not_sliver = sliver::keep(&shapes, group_of, pinned, params);
    for &i in free.iter().filter(|&&i| not_sliver[i]) {
        // Only elements enclosing nothing: an arch is found over its own group, and a copy
        // of one (a large contour) lands too easily on the long lines of a ruled drawing.
        let encloses = shapes
            .iter()
            .any(|o| hierarchy::contains(&shapes[i], o, params.nesting_tolerance));
        // Nor one pressed against the size bounds: CG stopped at the penalty there, not at
        // an opening (a 16-px contour between two rulings of the synthetic engraving).
        let t = &shapes[i];
        let at_bound = t.w < 1.1 * params.min_width || t.h + t.v < 1.1 * params.min_height;
        if encloses || at_bound {
            continue;
        }
        let others: Vec<Theta> = items.iter().map(|c| c.theta).collect();
        for c in repeat::copies(dt, &items[i].theta, &others, params) {
            if corrections::is_deleted(deleted, &c.theta, params) {
                continue;
            }
            items.push(c);
            group_of.push(None);
            pinned.push(false);
        }
    }
}

/// Issue 23 (see [`repeat`]): clusters split where their spacing jumps, and members proposed
/// in whole-spacing gaps and one spacing beyond each end (new items; none where the user
/// deleted one).
fn by_spacing(
    dt: &DistanceMap,
    clusters: Vec<Vec<usize>>,
    (items, group_of, pinned): (&mut Vec<Candidate>, &mut Vec<Option<usize>>, &mut Vec<bool>),
    deleted: &[Theta],
    params: &GothicParams,
) -> Vec<Vec<usize>> {
    let tol = params.spacing_tolerance;
    let in_cluster: std::collections::BTreeSet<usize> =
        clusters.iter().flatten().copied().collect();
    let loose: Vec<usize> = (0..items.len())
        .filter(|&i| group_of[i].is_none() && !pinned[i] && !in_cluster.contains(&i))
        .collect();
    let mut taken: Vec<usize> = Vec::new();
    let mut out = Vec::new();
    for c in clusters {
        let shapes: Vec<Theta> = items.iter().map(|c| c.theta).collect();
        for mut piece in repeat::split_by_spacing(&shapes, &c, tol) {
            let members: Vec<Theta> = piece.iter().map(|&i| items[i].theta).collect();
            let all: Vec<Theta> = items.iter().map(|c| c.theta).collect();
            let free: Vec<usize> = loose
                .iter()
                .copied()
                .filter(|j| !taken.contains(j))
                .collect();
            for (found, replaced) in repeat::fill_gaps(dt, &members, &all, &free, tol, params) {
                if corrections::is_deleted(deleted, &found.theta, params) {
                    continue;
                }
                if let Some(j) = replaced {
                    items[j] = found;
                    taken.push(j);
                    piece.push(j);
                    continue;
                }
                piece.push(items.len());
                items.push(found);
                group_of.push(None);
                pinned.push(false);
            }
            piece.sort_by(|&a, &b| items[a].theta.x0.total_cmp(&items[b].theta.x0));
            out.push(piece);
        }
    }
    out
}

/// The entries of `v` whose `keep` is true.
fn kept<T>(v: Vec<T>, keep: &[bool]) -> Vec<T> {
    v.into_iter()
        .zip(keep)
        .filter(|(_, k)| **k)
        .map(|(x, _)| x)
        .collect()
}

/// How the clusters of §4.2 are formed under `params` ([`group::Likeness`]): by shape as the
/// text does, or (issue 23) by box and rise with `repetition`, and also by head with
/// `group_by_heads`.
fn likeness(params: &GothicParams) -> group::Likeness {
    match (params.repetition, params.group_by_heads) {
        (false, _) => group::Likeness::Shape,
        (true, false) => group::Likeness::Box {
            rise_factor: RISE_FACTOR,
        },
        (true, true) => group::Likeness::Loose {
            rise_factor: RISE_FACTOR,
        },
    }
}

/// The clusters ([`group::cluster_with`]) among the items at `indices`, as item indices.
fn cluster_items(
    items: &[Candidate],
    indices: &[usize],
    likeness: group::Likeness,
    params: &GothicParams,
) -> Vec<Vec<usize>> {
    let shapes: Vec<Theta> = indices.iter().map(|&i| items[i].theta).collect();
    group::cluster_with(
        &shapes,
        params.group_relative,
        params.group_absolute,
        likeness,
    )
    .into_iter()
    .map(|c| c.iter().map(|&k| indices[k]).collect())
    .collect()
}

/// §4.2's joint re-estimation of a group: one shared shape (h, w, v) and one position per
/// member, by CG from the members' mean shape; returns the shapes and their fits.
///
/// Departure from §4.2 (issue 23, `GothicParams::joint_from_best`): a member fitted wrong
/// (a sill caught 5 px low on a mortar joint, a lancet fitted 30 px wide beside its 23-px
/// twin) pulls the mean shape away, and CG from there stays in the wrong optimum: the
/// group is refused, or accepted with every member wrong. So the fit is also started from
/// the best-fitting member's shape and sill line, each member about its own centre, and
/// whichever start fits the members better in all (summed mean distance) is kept.
fn joint_fit(
    dt: &DistanceMap,
    items: &[Candidate],
    members: &[usize],
    params: &GothicParams,
) -> (Vec<Theta>, Vec<likelihood::Fit>) {
    let from = |start: &[Theta]| {
        let joint = maximise_group(dt, start, params.step, params.bounds(), params.max_iters);
        let fits: Vec<likelihood::Fit> = joint.iter().map(|t| fit(dt, t, params.step)).collect();
        (joint, fits)
    };
    let thetas: Vec<Theta> = members.iter().map(|&i| items[i].theta).collect();
    let mean_start = from(&thetas);
    if !params.joint_from_best {
        return mean_start;
    }
    let Some(best) = members
        .iter()
        .min_by(|&&a, &&b| {
            items[a]
                .fit
                .mean_distance
                .total_cmp(&items[b].fit.mean_distance)
        })
        .map(|&i| items[i].theta)
    else {
        return mean_start;
    };
    let start: Vec<Theta> = thetas
        .iter()
        .map(|t| Theta {
            x0: t.x0 + (t.w - best.w) / 2.0,
            ..best
        })
        .collect();
    let best_start = from(&start);
    let total = |fits: &[likelihood::Fit]| fits.iter().map(|f| f.mean_distance).sum::<f64>();
    if total(&best_start.1) < total(&mean_start.1) {
        best_start
    } else {
        mean_start
    }
}

/// Where an arc meets its jambs tangentially the springing line barely moves the contour, so
/// a round arch comes out as a segmental or slightly pointed one with h and v off by several
/// pixels at the same apex. Not in §4.2: the round arch with the same apex replaces the
/// estimate when v is within 10% of w/2 and the fit is worse by at most 0.05 px.
fn snap_round(dt: &DistanceMap, c: Candidate, params: &GothicParams) -> Candidate {
    let t = c.theta;
    let half = t.w / 2.0;
    if (t.v - half).abs() > 0.1 * t.w || t.h + t.v < half {
        return c;
    }
    let round = Theta {
        h: t.h + t.v - half,
        v: half,
        ..t
    };
    let f = fit(dt, &round, params.step);
    if f.mean_distance <= c.fit.mean_distance + 0.05 {
        Candidate {
            theta: round,
            fit: f,
        }
    } else {
        c
    }
}

fn finish(
    dt: &DistanceMap,
    items: Vec<Candidate>,
    group_of: Vec<Option<usize>>,
    groups: Vec<Vec<usize>>,
    params: &GothicParams,
) -> GothicEstimate {
    let shapes: Vec<Theta> = items.iter().map(|c| c.theta).collect();
    let parents = hierarchy::parents(&shapes, params.nesting_tolerance);
    let depth = |mut i: usize| {
        let mut d = 0;
        while let Some(p) = parents[i] {
            d += 1;
            i = p;
            if d > items.len() {
                break;
            }
        }
        d
    };
    let elements = items
        .iter()
        .enumerate()
        .map(|(i, c)| Element {
            id: i,
            x0: c.theta.x0,
            y0: c.theta.y0,
            h: c.theta.h,
            w: c.theta.w,
            v: c.theta.v,
            group: group_of[i],
            parent: parents[i],
            kind: c.theta.kind(1.0),
            depth: depth(i),
            mean_distance: c.fit.mean_distance,
            support: c.fit.support,
        })
        .collect();
    let groups = groups
        .into_iter()
        .enumerate()
        .map(|(id, members)| {
            let t = shapes[members[0]];
            let first_parent = parents[members[0]];
            let enclosing =
                first_parent.filter(|_| members.iter().all(|&m| parents[m] == first_parent));
            Group {
                id,
                members,
                h: t.h,
                w: t.w,
                v: t.v,
                enclosing,
            }
        })
        .collect();
    GothicEstimate {
        width: dt.width as u32,
        height: dt.height as u32,
        elements,
        groups,
    }
}
