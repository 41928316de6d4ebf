//! Semantic labels (§5.1.6): the ten ordered heuristics over the simplified graph — castle
//! surroundings, outer walls, courtyard, tower walls by the convexity (Jensen) test, tower
//! rooms, great hall and its walls, chapel and its walls, unknown — then every pixel's label.

pub use crate::legend::Label;
pub use crate::scene::{FaceInfo, Scene};
use crate::scene::{Reached, beyond_apex, bulge_apex};
use crate::thin::Mask;

/// Labels of faces and edges, and what the heuristics could not find.
#[derive(Debug, Clone)]
pub struct Labelling {
    pub faces: Vec<Label>,
    pub edges: Vec<Label>,
    pub warnings: Vec<String>,
    /// Towers drawn as rings round rooms on the curtain ((5''), `ring_towers`): the
    /// rooms of each, which are tower rooms with no tower wall, counted once each.
    pub ring_towers: Vec<Vec<usize>>,
}

/// A face is a passage when it is long and narrow: area over its width squared above this.
pub const PASSAGE_RATIO: f64 = 14.0;

/// The ten ordered heuristics of §5.1.6.
pub fn heuristics(s: &Scene) -> Labelling {
    let nf = s.faces.len();
    let ne = s.graph.edges.len();
    let mut fl: Vec<Option<Label>> = vec![None; nf];
    let mut el: Vec<Option<Label>> = vec![None; ne];
    let mut warnings = Vec::new();
    // Faces with no open pixel (loops of the skeleton inside solid masonry) are not rooms.
    for (f, info) in s.faces.iter().enumerate() {
        if info.area == 0 {
            fl[f] = Some(Label::UnknownRoom);
        }
    }
    // (1) surroundings: faces that include the image boundary.
    for (f, info) in s.faces.iter().enumerate() {
        if info.touches_border {
            fl[f] = Some(Label::CastleSurroundings);
        }
    }
    // End of §5.1.6: long thin passages are set aside as unknown.
    for (f, info) in s.faces.iter().enumerate() {
        let width = 2.0 * info.max_inset.max(0.5);
        if fl[f].is_none() && info.area as f64 / (width * width) > PASSAGE_RATIO {
            fl[f] = Some(Label::UnknownRoom);
        }
    }
    // (2) outer walls: edges bounding a surroundings face.
    for (e, fs) in s.edge_faces.iter().enumerate() {
        if fs.iter().any(|&f| fl[f] == Some(Label::CastleSurroundings)) {
            el[e] = Some(Label::CastleOuterWall);
        }
    }
    let largest = |fl: &[Option<Label>]| {
        (0..nf)
            .filter(|&f| fl[f].is_none())
            .max_by_key(|&f| (s.faces[f].area, std::cmp::Reverse(f)))
    };
    // (3) courtyard.
    match largest(&fl) {
        Some(f) => fl[f] = Some(Label::Courtyard),
        None => warnings.push(
            "no closed outer wall: the walls enclose no open space (§5.2 item 4)".to_string(),
        ),
    }
    // (4) tower walls: outer walls bulging out of the castle (convexity test).
    let extent = castle_extent(s.walls);
    for (e, l) in el.iter_mut().enumerate() {
        if *l == Some(Label::CastleOuterWall)
            && is_tower(s, e, &fl, extent, Label::CastleSurroundings, 0.25)
        {
            *l = Some(Label::TowerWall);
        }
    }
    // (4') towers of an inner ward (issue 11, several enclosures): thick walls inside the
    // enceinte bulging into the courtyard around a small room on a ward's wall. Departure from
    // §5.1.6 (4), which tests only the walls bounding the surroundings, so an inner ward's
    // towers (Chambord, Bonaguil) were never towers; the tests are in `inner_towers`.
    if s.inner_ward_towers {
        let found = crate::inner_towers::find(s, &fl, &el, extent);
        for e in found {
            el[e] = Some(Label::TowerWall);
        }
    }
    // (5) tower rooms.
    for (e, fs) in s.edge_faces.iter().enumerate() {
        if el[e] == Some(Label::TowerWall) {
            for &f in fs {
                if fl[f].is_none() {
                    fl[f] = Some(Label::TowerRoom);
                }
            }
        }
    }
    // (5'') towers drawn as a ring round a room on a long curtain, or standing free in a ward
    // (issue 26). Departure from §5.1.6 (4)-(5), whose tower rooms need a bulging tower wall;
    // see `ring_towers`.
    let mut ring_towers = Vec::new();
    if s.ring_towers {
        let curtain = crate::inner_towers::curtain_thickness(s, &el);
        let (towers, of_known) = crate::ring_towers::find(s, &fl, curtain);
        for &f in towers.iter().flatten().chain(&of_known) {
            fl[f] = Some(Label::TowerRoom);
        }
        ring_towers = towers;
    }
    // (5') further wards (issue 11, several enclosures): an unlabelled face on the outer wall
    // at least WARD_RATIO of the courtyard's area is a courtyard too. Departure from §5.1.6
    // (3), which takes one courtyard, so a second ward became the great hall or the chapel; run
    // after the tower rooms so that no tower room is taken for a ward.
    if s.ward_ratio > 0.0
        && let Some(c) = (0..nf).find(|&f| fl[f] == Some(Label::Courtyard))
    {
        let court = s.faces[c].area as f64;
        for (f, label) in fl.iter_mut().enumerate().take(nf) {
            let on_outer = || {
                s.edge_faces
                    .iter()
                    .enumerate()
                    .any(|(e, fs)| fs.contains(&f) && el[e] == Some(Label::CastleOuterWall))
            };
            if label.is_none() && s.faces[f].area as f64 >= s.ward_ratio * court && on_outer() {
                *label = Some(Label::Courtyard);
            }
        }
    }
    // (6)-(7) great hall and its walls.
    let bound = |f: usize, label: Label, el: &mut Vec<Option<Label>>| {
        for (e, fs) in s.edge_faces.iter().enumerate() {
            if el[e].is_none() && fs.contains(&f) {
                el[e] = Some(label);
            }
        }
    };
    if let Some(f) = largest(&fl) {
        fl[f] = Some(Label::GreatHall);
        bound(f, Label::GreatHallWall, &mut el);
    }
    // (8)-(9) a chapel when more than three faces remain.
    if (0..nf).filter(|&f| fl[f].is_none()).count() > 3
        && let Some(f) = largest(&fl)
    {
        fl[f] = Some(Label::Chapel);
        bound(f, Label::ChapelWall, &mut el);
    }
    // (10) the rest.
    Labelling {
        faces: fl
            .into_iter()
            .map(|l| l.unwrap_or(Label::UnknownRoom))
            .collect(),
        edges: el
            .into_iter()
            .map(|l| l.unwrap_or(Label::UnknownWall))
            .collect(),
        warnings,
        ring_towers,
    }
}

/// Largest side of the bounding box of the walls.
fn castle_extent(walls: &Mask) -> f64 {
    walls
        .bounding_box()
        .map_or(0.0, |b| f64::from((b[2] - b[0]).max(b[3] - b[1])) + 1.0)
}

/// §5.1.6 (4): compares the edge's chain with the straight chord between its vertices. The
/// chain is a tower when it departs far from the chord (Jensen's inequality: a convex bulge),
/// towards the exterior: just beyond its farthest point lies the castle surroundings. Towers
/// are small against the castle: a chord longer than 45 % of its extent is a curtain wall
/// turning a corner, not a tower.
fn is_tower(
    s: &Scene,
    e: usize,
    fl: &[Option<Label>],
    extent: f64,
    outside: Label,
    bulge: f64,
) -> bool {
    bulge_apex(s, e, extent, bulge).is_some_and(|apex| match beyond_apex(s, e, apex) {
        Reached::Off(_) => outside == Label::CastleSurroundings,
        Reached::Face(f, _) => fl.get(f).copied().flatten() == Some(outside),
        Reached::Nothing => false,
    })
}

/// Label of every pixel (§5.1.6): open pixels take their face's label; wall pixels take the
/// label of the nearest remaining wall edge, reached through the wall (breadth-first from the
/// edges' skeleton pixels), so pruned buttresses join the wall they stand on. Walls no edge
/// reaches are unknown walls.
pub fn pixel_labels(s: &Scene, l: &Labelling) -> Vec<u8> {
    let w = s.walls.width as usize;
    let h = s.walls.height as usize;
    let n = w * h;
    let mut out = vec![u8::MAX; n];
    let mut queue = std::collections::VecDeque::new();
    for (e, edge) in s.graph.edges.iter().enumerate() {
        for &(x, y) in &edge.points {
            let i = y as usize * w + x as usize;
            if out[i] == u8::MAX {
                out[i] = l.edges[e] as u8;
                queue.push_back(i);
            }
        }
    }
    let on = |i: usize| s.walls.data[i] == 1 || s.skel.data[i] == 1;
    while let Some(i) = queue.pop_front() {
        let (x, y) = ((i % w) as i32, (i / w) as i32);
        for (dx, dy) in crate::thin::NEIGHBOURS {
            let (nx, ny) = (x + dx, y + dy);
            if nx < 0 || ny < 0 || nx >= w as i32 || ny >= h as i32 {
                continue;
            }
            let j = ny as usize * w + nx as usize;
            if out[j] == u8::MAX && on(j) {
                out[j] = out[i];
                queue.push_back(j);
            }
        }
    }
    for (i, o) in out.iter_mut().enumerate() {
        if *o != u8::MAX {
            continue;
        }
        *o = if on(i) {
            Label::UnknownWall as u8
        } else {
            let f = s.face_of[i] as usize;
            l.faces.get(f).map_or(Label::UnknownRoom, |&x| x) as u8
        };
    }
    out
}
