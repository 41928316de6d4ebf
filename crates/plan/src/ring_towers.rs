//! Towers drawn as a ring of wall round a room that stands on a long curtain ((5'') of
//! `label::heuristics`; issue 26).
//!
//! Departure from §5.1.6 (4)–(5), where a room is a tower room only when one of its walls is a
//! tower wall: an outer-wall edge bulging out of the castle. A round tower drawn on the
//! curtain (Bury, Sully, the Bastille, Chambord's corners) shares its outer half with the
//! curtain's edge, whose chord the half-ring barely leaves, and its inner half is an unknown
//! wall, so its room was an unknown room: the development set's most frequent error (13 of
//! its 169 points). Here a room is a tower room when it is a tower's: small against the
//! courtyard, round or square, not a speck, and wrapped by the surroundings — from its centre,
//! at least 0.4 of the directions cross only the room and a wall at least 0.7 curtains thick
//! before they reach the surroundings, nearby. A room against a straight curtain sees the
//! surroundings over at most about a quarter of the directions; a tower standing out of the
//! curtain over a half or more. Rooms that share a wall are one tower, and a room beside a
//! tower room already found is that tower's (docs/plan.md, "Towers drawn as a ring").
//!
//! A round tower standing free — a keep in its ward (Coucy's donjon), a tower inside the
//! enceinte (Bonaguil's, Pierrefonds') — is wrapped by no surroundings, and no wall of it
//! bulges out of the castle, so the same departure takes a second kind of room (session 26,
//! docs/plan.md, "Towers standing free"): a rounder one, from whose centre nearly every
//! direction crosses a wall of about equal thickness, at least most of a curtain, before it
//! reaches another face — a ring round the room, where a room of a range or of a block of
//! masonry has thin partitions on some side.

use crate::bulges::BulgeTower;
use crate::legend::Label;
use crate::scene::{FaceInfo, Reached, Scene, walk};
use crate::union_find::UnionFind;

/// A tower's room is at most this fraction of the courtyard's area.
const SMALL_ROOM: f64 = 0.15;
/// Area over π · inset² at most this: round (1), polygonal or square (1.27), not a 2:1 range.
const ROUND_ROOM: f64 = 1.5;
/// The room's inset is at least this many curtain thicknesses: narrower ones are specks left
/// between strokes (stairs, letters).
const MIN_INSET: f64 = 0.3;
/// Directions sampled round the room's centre.
const RAYS: usize = 72;
/// Share of the directions that must reach the surroundings.
const WRAP: f64 = 0.4;
/// … within the room's inset plus this many curtain thicknesses.
const REACH: f64 = 3.0;
/// The median of the wall crossed by those directions is at least this many curtain
/// thicknesses: a tower's ring, not the thin lines of a bank or a ditch (Borrans' rampart).
const RING_WALL: f64 = 0.7;
/// A free-standing tower's room is rounder than a ring tower's: area over π · inset² at most
/// this (a disc 1, an octagon 1.05, a drawn square with filled corners about 1.2, a sharp one
/// 1.27).
const KEEP_ROUND: f64 = 1.25;
/// Share of the directions from a free-standing tower's centre that must cross its wall into
/// another face …
const KEEP_WRAP: f64 = 0.9;
/// … within its inset plus this many curtain thicknesses;
const KEEP_REACH: f64 = 6.0;
/// the thinnest tenth of the wall crossed is at least this many curtains thick …
const KEEP_WALL: f64 = 0.8;
/// … and this share of the median: a ring of even thickness round the room, not a room in a
/// block of masonry or between a range's walls.
const KEEP_EVEN: f64 = 0.7;

/// Towers drawn as rings, given the face labels after §5.1.6 (5) (`fl`) and the curtain's
/// thickness: each a group of faces (rooms sharing a wall), to be labelled tower rooms. Rooms
/// beside a tower room of `fl` are returned in no group but in the second list: they are
/// tower rooms of a tower already counted.
pub(crate) fn find(s: &Scene, fl: &[Option<Label>], curtain: f64) -> (Vec<Vec<usize>>, Vec<usize>) {
    let Some(court) = s.courtyard_area(fl) else {
        return (Vec::new(), Vec::new());
    };
    let rooms: Vec<usize> = (0..fl.len())
        .filter(|&f| {
            fl[f].is_none()
                && (is_ring_room(s, fl, f, court, curtain) || is_keep_room(s, f, court, curtain))
        })
        .collect();
    let beside_tower = |f: usize| {
        s.edge_faces
            .iter()
            .any(|fs| fs.contains(&f) && fs.iter().any(|&g| fl[g] == Some(Label::TowerRoom)))
    };
    let (of_known, new): (Vec<usize>, Vec<usize>) =
        rooms.into_iter().partition(|&f| beside_tower(f));
    // Rooms sharing a wall (an edge with both on its sides) are one tower.
    let mut sets = UnionFind::new(new.len());
    for fs in s.edge_faces {
        let on: Vec<usize> = (0..new.len()).filter(|&k| fs.contains(&new[k])).collect();
        for pair in on.windows(2) {
            sets.union(pair[0], pair[1]);
        }
    }
    let mut groups: Vec<(usize, Vec<usize>)> = Vec::new();
    for (k, &f) in new.iter().enumerate() {
        let root = sets.root(k);
        match groups.iter_mut().find(|(r, _)| *r == root) {
            Some((_, rooms)) => rooms.push(f),
            None => groups.push((root, vec![f])),
        }
    }
    let groups = groups.into_iter().map(|(_, rooms)| rooms).collect();
    (groups, of_known)
}

/// Whether face `f` is a room of a tower standing out of the curtain (module header).
fn is_ring_room(s: &Scene, fl: &[Option<Label>], f: usize, court: usize, curtain: f64) -> bool {
    let Some((centre, r)) = tower_room_shape(s, f, court, curtain, ROUND_ROOM) else {
        return false;
    };
    let mut walls = walls_round(s, f, centre, r + REACH * curtain, |reached| match reached {
        Reached::Off(wall) => Some(wall),
        Reached::Face(g, wall) => {
            (fl.get(g).copied().flatten() == Some(Label::CastleSurroundings)).then_some(wall)
        }
        Reached::Nothing => None,
    });
    if (walls.len() as f64) < WRAP * RAYS as f64 {
        return false;
    }
    walls.sort_by(f64::total_cmp);
    walls[walls.len() / 2] >= RING_WALL * curtain
}

/// Whether face `f` is the room of a round tower standing free (a keep in its ward, a tower
/// inside the enceinte; module header): round, and from its centre nearly every direction
/// crosses a wall, about equally thick all round and at least most of a curtain, before it
/// reaches another face.
fn is_keep_room(s: &Scene, f: usize, court: usize, curtain: f64) -> bool {
    let Some((centre, r)) = tower_room_shape(s, f, court, curtain, KEEP_ROUND) else {
        return false;
    };
    let mut walls = walls_round(
        s,
        f,
        centre,
        r + KEEP_REACH * curtain,
        |reached| match reached {
            Reached::Face(_, wall) => Some(wall),
            Reached::Off(_) | Reached::Nothing => None,
        },
    );
    if (walls.len() as f64) < KEEP_WRAP * RAYS as f64 {
        return false;
    }
    walls.sort_by(f64::total_cmp);
    let (low, median) = (walls[walls.len() / 10], walls[walls.len() / 2]);
    low >= KEEP_WALL * curtain && low >= KEEP_EVEN * median
}

/// The centre of area and inset of face `f` when it is shaped like a tower's room: small
/// against the courtyard, not a speck, and area over π · inset² at most `round`.
fn tower_room_shape(
    s: &Scene,
    f: usize,
    court: usize,
    curtain: f64,
    round: f64,
) -> Option<([f64; 2], f64)> {
    let info = &s.faces[f];
    let r = info.max_inset;
    let area = info.area as f64;
    let shaped = info.area > 0
        && r >= MIN_INSET * curtain
        && area <= SMALL_ROOM * court as f64
        && area / (std::f64::consts::PI * r * r) <= round;
    shaped.then(|| ([info.sum[0] / area, info.sum[1] / area], r))
}

/// The walls crossed in each of the `RAYS` directions from `centre` out of face `f`, within
/// `reach`, as `keep` reads each walk's end (`None`: the direction does not count).
fn walls_round(
    s: &Scene,
    f: usize,
    centre: [f64; 2],
    reach: f64,
    keep: impl Fn(Reached) -> Option<f64>,
) -> Vec<f64> {
    (0..RAYS)
        .filter_map(|k| {
            let angle = k as f64 * std::f64::consts::TAU / RAYS as f64;
            let dir = [angle.cos(), angle.sin()];
            keep(walk(s, centre, dir, 0..=reach.floor() as usize, Some(f)))
        })
        .collect()
}

/// A ring tower's disc, as the towers found on the pixels are kept ([`BulgeTower`]): round the
/// rooms' centre of area, reaching the farthest room's far side and a curtain beyond.
pub(crate) fn disc(faces: &[FaceInfo], rooms: &[usize], curtain: f64) -> BulgeTower {
    let area: f64 = rooms.iter().map(|&f| faces[f].area as f64).sum();
    let centre = [0, 1].map(|k| rooms.iter().map(|&f| faces[f].sum[k]).sum::<f64>() / area);
    let reach = rooms
        .iter()
        .map(|&f| {
            let i = &faces[f];
            let a = i.area as f64;
            (i.sum[0] / a - centre[0]).hypot(i.sum[1] / a - centre[1]) + i.max_inset
        })
        .fold(0.0, f64::max);
    BulgeTower {
        center: centre,
        radius: reach + curtain,
    }
}
