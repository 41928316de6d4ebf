//! Semantic labels (§5.1.6): the ten ordered heuristics over the simplified graph — castle
//! surroundings, outer walls, courtyard, tower walls by the convexity (Jensen) test, tower
//! rooms, great hall and its walls, chapel and its walls, unknown — then every pixel's label.

use serde::{Deserialize, Serialize};

use crate::graph::Graph;
use crate::thin::Mask;

/// The label names of the PLAN.json / LABELS.png contract, in legend order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Label {
    CastleSurroundings = 0,
    CastleOuterWall = 1,
    Courtyard = 2,
    TowerWall = 3,
    TowerRoom = 4,
    GreatHall = 5,
    GreatHallWall = 6,
    Chapel = 7,
    ChapelWall = 8,
    UnknownRoom = 9,
    UnknownWall = 10,
}

impl Label {
    pub const ALL: [Label; 11] = [
        Label::CastleSurroundings,
        Label::CastleOuterWall,
        Label::Courtyard,
        Label::TowerWall,
        Label::TowerRoom,
        Label::GreatHall,
        Label::GreatHallWall,
        Label::Chapel,
        Label::ChapelWall,
        Label::UnknownRoom,
        Label::UnknownWall,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Label::CastleSurroundings => "castle_surroundings",
            Label::CastleOuterWall => "castle_outer_wall",
            Label::Courtyard => "courtyard",
            Label::TowerWall => "tower_wall",
            Label::TowerRoom => "tower_room",
            Label::GreatHall => "great_hall",
            Label::GreatHallWall => "great_hall_wall",
            Label::Chapel => "chapel",
            Label::ChapelWall => "chapel_wall",
            Label::UnknownRoom => "unknown_room",
            Label::UnknownWall => "unknown_wall",
        }
    }

    /// The colours of the dissertation's figures (§5.1.6 lists them by name).
    pub fn color(self) -> [u8; 3] {
        match self {
            Label::CastleSurroundings => [20, 30, 120],
            Label::CastleOuterWall => [240, 220, 30],
            Label::Courtyard => [50, 110, 230],
            Label::TowerWall => [250, 140, 20],
            Label::TowerRoom => [30, 170, 60],
            Label::GreatHall => [150, 200, 250],
            Label::GreatHallWall => [250, 140, 140],
            Label::Chapel => [40, 220, 220],
            Label::ChapelWall => [210, 30, 30],
            Label::UnknownRoom => [160, 230, 140],
            Label::UnknownWall => [255, 255, 255],
        }
    }

    pub fn is_wall(self) -> bool {
        matches!(
            self,
            Label::CastleOuterWall
                | Label::TowerWall
                | Label::GreatHallWall
                | Label::ChapelWall
                | Label::UnknownWall
        )
    }
}

/// Per-face measurements the heuristics use.
#[derive(Debug, Clone, Default)]
pub struct FaceInfo {
    /// White (open) pixels the face owns.
    pub area: usize,
    pub sum: [f64; 2],
    pub touches_border: bool,
    /// Largest distance from a white pixel to a wall (half the widest width).
    pub max_inset: f64,
}

/// Inputs of the heuristics: the simplified graph and the pixel maps behind it.
pub struct Scene<'a> {
    pub walls: &'a Mask,
    pub skel: &'a Mask,
    pub graph: &'a Graph,
    pub face_of: &'a [u32],
    pub faces: &'a [FaceInfo],
    /// Faces on either side of each edge.
    pub edge_faces: &'a [Vec<usize>],
    /// Wall thickness at each edge, pixels.
    pub thickness: &'a [f64],
    /// Also test walls inside the enceinte as towers of an inner ward ((4') in [`heuristics`]).
    pub inner_ward_towers: bool,
    /// Faces on the outer wall at least this fraction of the courtyard's area are further
    /// wards ((5') in [`heuristics`]); 0 keeps one courtyard as §5.1.6 does.
    pub ward_ratio: f64,
}

/// Labels of faces and edges, and what the heuristics could not find.
#[derive(Debug, Clone)]
pub struct Labelling {
    pub faces: Vec<Label>,
    pub edges: Vec<Label>,
    pub warnings: Vec<String>,
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
    }
}

/// Largest side of the bounding box of the walls.
fn castle_extent(walls: &Mask) -> f64 {
    let w = walls.width as usize;
    let mut bb = [usize::MAX, usize::MAX, 0, 0];
    for (i, &v) in walls.data.iter().enumerate() {
        if v == 1 {
            let (x, y) = (i % w, i / w);
            bb = [bb[0].min(x), bb[1].min(y), bb[2].max(x), bb[3].max(y)];
        }
    }
    if bb[0] == usize::MAX {
        0.0
    } else {
        (bb[2] - bb[0]).max(bb[3] - bb[1]) as f64 + 1.0
    }
}

/// The farthest point of an edge's chain from its chord, as §5.1.6 (4)'s convexity test sees it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Apex {
    pub point: (f64, f64),
    /// Unit vector from the chord to the apex.
    pub normal: (f64, f64),
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
        Beyond::Off => outside == Label::CastleSurroundings,
        Beyond::Face(f) => fl.get(f).copied().flatten() == Some(outside),
        Beyond::Wall => false,
    })
}

/// The apex of the edge when its chain bulges at least `bulge` of its chord (and 1.5 wall
/// thicknesses) away from it, and chord and bulge are small against the castle's `extent`.
pub(crate) fn bulge_apex(s: &Scene, e: usize, extent: f64, bulge: f64) -> Option<Apex> {
    let edge = &s.graph.edges[e];
    let a = &s.graph.vertices[edge.from];
    let b = &s.graph.vertices[edge.to];
    let (ax, ay) = (a.x, a.y);
    let (dx, dy) = (b.x - ax, b.y - ay);
    let len = dx.hypot(dy);
    let mut best = (0.0f64, (ax, ay), (0.0, 0.0));
    for &(px, py) in &edge.points {
        let (px, py) = (px as f64, py as f64);
        let (foot, dist) = if len < 2.0 {
            ((ax, ay), (px - ax).hypot(py - ay))
        } else {
            let t = ((px - ax) * dx + (py - ay) * dy) / (len * len);
            let f = (ax + t * dx, ay + t * dy);
            (f, (px - f.0).hypot(py - f.1))
        };
        if dist > best.0 {
            best = (dist, (px, py), foot);
        }
    }
    let (dev, p, foot) = best;
    let t = s.thickness[e];
    if dev < (bulge * len).max(1.5 * t).max(3.0) || len > 0.45 * extent || dev > 0.45 * extent {
        return None;
    }
    Some(Apex {
        point: p,
        normal: ((p.0 - foot.0) / dev, (p.1 - foot.1) / dev),
    })
}

/// What lies just beyond an apex, outwards through its wall.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Beyond {
    /// Off the image: the surroundings.
    Off,
    Face(usize),
    /// Wall further than the edge's thickness and 8 px.
    Wall,
}

/// The face just beyond the apex, outwards through the wall.
pub(crate) fn beyond_apex(s: &Scene, e: usize, apex: Apex) -> Beyond {
    let (p, (nx, ny)) = (apex.point, apex.normal);
    let w = s.walls.width as i32;
    let h = s.walls.height as i32;
    let reach = (s.thickness[e] + 8.0).ceil() as i32;
    for k in 1..=reach {
        let (qx, qy) = (
            (p.0 + nx * k as f64).round() as i32,
            (p.1 + ny * k as f64).round() as i32,
        );
        if qx < 0 || qy < 0 || qx >= w || qy >= h {
            return Beyond::Off;
        }
        let i = (qy * w + qx) as usize;
        if s.skel.data[i] == 1 || s.walls.data[i] == 1 {
            continue;
        }
        return Beyond::Face(s.face_of[i] as usize);
    }
    Beyond::Wall
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
