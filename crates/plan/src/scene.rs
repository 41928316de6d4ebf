//! What the §5.1.6 heuristics look at: the simplified graph, the wall and skeleton masks, the
//! faces with their measurements ([`Scene`]), and the geometry of §5.1.6 (4)'s convexity test
//! on it (an edge's apex, what lies beyond it), which `label`'s test (4) and `inner_towers`'
//! (4') share. `Scene` and `FaceInfo` are re-exported from `plan::label`.

use crate::graph::Graph;
use crate::legend::Label;
use crate::thin::Mask;

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
    /// Also test walls inside the enceinte as towers of an inner ward ((4') in [`heuristics`](crate::label::heuristics)).
    pub inner_ward_towers: bool,
    /// Also take rooms wrapped by the surroundings as rooms of towers drawn as rings ((5'') in
    /// [`heuristics`](crate::label::heuristics)).
    pub ring_towers: bool,
    /// Faces on the outer wall at least this fraction of the courtyard's area are further
    /// wards ((5') in [`heuristics`](crate::label::heuristics)); 0 keeps one courtyard as §5.1.6 does.
    pub ward_ratio: f64,
}

impl Scene<'_> {
    /// Area of the largest face labelled courtyard in `fl`; `None` without one.
    pub(crate) fn courtyard_area(&self, fl: &[Option<Label>]) -> Option<usize> {
        (0..fl.len())
            .filter(|&c| fl[c] == Some(Label::Courtyard))
            .map(|c| self.faces[c].area)
            .max()
    }
}

/// The farthest point of an edge's chain from its chord, as §5.1.6 (4)'s convexity test sees it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Apex {
    pub point: (f64, f64),
    /// Unit vector from the chord to the apex.
    pub normal: (f64, f64),
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

/// Where a walk through the walls ([`walk`]) first reaches open paper.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Reached {
    /// An open pixel of face `.0`, after `.1` pixels of wall.
    Face(usize, f64),
    /// The image's edge (the surroundings), after `.0` pixels of wall.
    Off(f64),
    /// Neither within the walk's steps: the walk ran along a wall or into solid masonry.
    Nothing,
}

/// Walks from `from` along the unit direction `dir`, at the whole steps `steps`, through wall
/// pixels (counted) and the open pixels of face `through`, until the first open pixel of
/// another face, the image's edge or the last step.
pub(crate) fn walk(
    s: &Scene,
    from: [f64; 2],
    dir: [f64; 2],
    steps: std::ops::RangeInclusive<usize>,
    through: Option<usize>,
) -> Reached {
    let (w, h) = (i64::from(s.walls.width), i64::from(s.walls.height));
    let mut wall = 0.0;
    for step in steps {
        let t = step as f64;
        let (x, y) = (
            (from[0] + dir[0] * t).round() as i64,
            (from[1] + dir[1] * t).round() as i64,
        );
        if x < 0 || y < 0 || x >= w || y >= h {
            return Reached::Off(wall);
        }
        let i = (y * w + x) as usize;
        let face = s.face_of[i] as usize;
        if s.walls.data[i] == 1 || s.skel.data[i] == 1 {
            wall += 1.0;
        } else if Some(face) != through {
            return Reached::Face(face, wall);
        }
    }
    Reached::Nothing
}

/// What lies just beyond the apex, outwards through the wall: `Nothing` when the wall goes on
/// further than the edge's thickness and 8 px.
pub(crate) fn beyond_apex(s: &Scene, e: usize, apex: Apex) -> Reached {
    let (p, (nx, ny)) = (apex.point, apex.normal);
    let reach = (s.thickness[e] + 8.0).ceil() as usize;
    walk(s, [p.0, p.1], [nx, ny], 1..=reach, None)
}
