//! Towers of an inner ward ((4') of `label::heuristics`; issue 11, several enclosures): walls
//! inside the enceinte that bulge into a courtyard around a small room. §5.1.6 (4)'s
//! convexity test, run towards the courtyard instead of the surroundings.
//!
//! Departure from §5.1.6 (4), which tests only the walls bounding the surroundings, so the
//! towers of an inner ward (Chambord's keep, Bonaguil) were never towers. Turned towards the
//! courtyard, the same test also takes every small building standing in it (Montargis), so a
//! candidate must further stand on a ward's wall — its building reaches the surroundings or
//! holds a ward-sized face —, project from it (the bulging wall makes most of the room's
//! walls) and have a tower's thick wall: at least 0.3 of the curtain's thickness, around a
//! room no wider than 1.5 times that wall (docs/plan.md, "Inner-ward towers").

use crate::legend::Label;
use crate::scene::{Apex, Reached, Scene, beyond_apex, bulge_apex};

/// An inner ward's tower must bulge this fraction of its chord into the courtyard (an outer
/// tower 0.25): walls inside the enceinte bend round stairs and halls more often than the
/// curtain does.
const INNER_BULGE: f64 = 0.4;
/// Area over inset squared below which a face is round or square enough to be a tower room.
const ROUND_ROOM: f64 = 5.0;
/// A building holding a face this fraction of the courtyard's area holds a ward: the towers
/// on its wall stand on the ward's wall.
const WARD_FACE: f64 = 0.1;
/// The bulging wall is at least this fraction of the curtain's thickness: a thinner one is a
/// building's wall (Coucy's porch, Old Sarum's bank).
const APEX_WALL: f64 = 0.3;
/// A tower's room is at most this many times as wide (inset) as its bulging wall is thick;
/// rooms of buildings with thin walls are wider.
const ROOM_OVER_WALL: f64 = 1.5;
/// The bulging wall makes at least this share of the room's walls (by skeleton length): a
/// tower projects from the ward's wall, its room at least a half-disc in front of it (arc over
/// perimeter π / (π + 2) = 0.61). A room between hachures on a motte or a closet behind a
/// range has a bulging side among several (0.42–0.57 on the drawings, towers 0.71–0.83).
const PROJECTION: f64 = 0.6;
/// Points of the bulging chain at which its wall thickness is measured.
const WALL_SAMPLES: usize = 12;

/// Edges that are tower walls of an inner ward, given the face and edge labels after §5.1.6
/// (4) (`fl`, `el`) and the castle's extent.
pub(crate) fn find(
    s: &Scene,
    fl: &[Option<Label>],
    el: &[Option<Label>],
    extent: f64,
) -> Vec<usize> {
    let Some(court) = s.courtyard_area(fl) else {
        return Vec::new();
    };
    let curtain = curtain_thickness(s, el);
    let mut neighbours = vec![Vec::new(); fl.len()];
    // Skeleton length of the walls round each face.
    let mut perimeter = vec![0usize; fl.len()];
    for (e, fs) in s.edge_faces.iter().enumerate() {
        for &f in fs {
            neighbours[f].extend(fs.iter().copied().filter(|&g| g != f));
            perimeter[f] += s.graph.edges[e].points.len();
        }
    }
    let mut found = Vec::new();
    for (e, _) in el.iter().enumerate().filter(|(_, l)| l.is_none()) {
        let Some(apex) = bulge_apex(s, e, extent, INNER_BULGE) else {
            continue;
        };
        let into_courtyard = |f: usize| fl.get(f) == Some(&Some(Label::Courtyard));
        if !matches!(beyond_apex(s, e, apex), Reached::Face(f, _) if into_courtyard(f)) {
            continue;
        }
        let wall = bulge_wall_thickness(s, e, apex);
        if wall < APEX_WALL * curtain {
            continue;
        }
        let bulge = s.graph.edges[e].points.len() as f64;
        let tower_room = |f: usize| {
            let info = &s.faces[f];
            fl[f].is_none()
                && is_small_room(s, f, court)
                && bulge >= PROJECTION * perimeter[f] as f64
                && info.max_inset <= ROOM_OVER_WALL * wall
                && on_a_ward_wall(s, &neighbours, f, fl, court)
        };
        if s.edge_faces[e].iter().any(|&f| tower_room(f)) {
            found.push(e);
        }
    }
    found
}

/// The curtain's thickness as [`crate::bulges::curtain_thickness`] takes it, from the edges
/// labelled outer wall so far; 0 without any.
pub(crate) fn curtain_thickness(s: &Scene, el: &[Option<Label>]) -> f64 {
    let mut outer: Vec<(f64, usize)> = (0..el.len())
        .filter(|&e| el[e] == Some(Label::CastleOuterWall))
        .map(|e| (s.thickness[e], s.graph.edges[e].points.len()))
        .collect();
    crate::bulges::curtain_thickness(&mut outer).unwrap_or(0.0)
}

/// Thickness of the bulging wall: the thinnest of the runs of wall pixels, along the apex's
/// normal, through points spread along the edge's chain. A ray crossing a ring or a straight
/// wall runs at least its thickness, so a thick tower keeps its thickness; a tower's thick
/// corner on a thin building wall does not make the wall thick.
fn bulge_wall_thickness(s: &Scene, e: usize, apex: Apex) -> f64 {
    let w = s.walls.width as i32;
    let h = s.walls.height as i32;
    let run = |from: (f64, f64), sign: f64| {
        let mut k = 1;
        loop {
            let (qx, qy) = (
                (from.0 + sign * apex.normal.0 * f64::from(k)).round() as i32,
                (from.1 + sign * apex.normal.1 * f64::from(k)).round() as i32,
            );
            if qx < 0 || qy < 0 || qx >= w || qy >= h || s.walls.data[(qy * w + qx) as usize] == 0 {
                return k - 1;
            }
            k += 1;
        }
    };
    let points = &s.graph.edges[e].points;
    let step = (points.len() / WALL_SAMPLES).max(1);
    points
        .iter()
        .step_by(step)
        .map(|&(x, y)| {
            let p = (f64::from(x), f64::from(y));
            f64::from(run(p, 1.0) + run(p, -1.0) + 1)
        })
        .fold(f64::INFINITY, f64::min)
}

/// A face small enough to be a tower room against the courtyard (under an eighth of its area)
/// and compact enough.
fn is_small_room(s: &Scene, f: usize, court: usize) -> bool {
    let info = &s.faces[f];
    // Round or square: a disc's area is π r², a square's 4 r², for the inset r; stair flights
    // and passages cut by hatching are long and narrow (Saint-Médard's stair P).
    let compact = info.area as f64 <= ROUND_ROOM * info.max_inset.max(1.0).powi(2);
    info.area > 0 && 8 * info.area < court && compact && info.max_inset >= 3.0
}

/// Whether the face stands on a ward's wall: the building it belongs to (the faces reached
/// from it across walls without entering a courtyard) reaches the surroundings or holds a
/// ward-sized face. A building standing free in the courtyard does neither.
fn on_a_ward_wall(
    s: &Scene,
    neighbours: &[Vec<usize>],
    f: usize,
    fl: &[Option<Label>],
    court: usize,
) -> bool {
    let mut seen = vec![false; fl.len()];
    let mut stack = vec![f];
    seen[f] = true;
    while let Some(g) = stack.pop() {
        if s.faces[g].area as f64 >= WARD_FACE * court as f64 {
            return true;
        }
        for &h in &neighbours[g] {
            if seen[h] {
                continue;
            }
            seen[h] = true;
            match fl[h] {
                Some(Label::Courtyard) => {}
                Some(Label::CastleSurroundings) => return true,
                _ => stack.push(h),
            }
        }
    }
    false
}
