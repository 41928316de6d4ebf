//! What chapter 5 measures on the vectorised walls around the labelling (§5.1.4–§5.1.6): the
//! open area, centroid and inset of every face, the faces beside every edge, the drawn
//! thickness of a skeleton chain, the spurs §5.1.4's simplification set aside, the rows of
//! open pixels of every face, the faces with their §5.1.5 shapes, and the warnings of §5.2
//! item 1 read from the walls' extent. Split out of `parse_grey` so that the pipeline reads as
//! its steps.

use crate::binarize;
use crate::fit::{self, Fit};
use crate::graph::Graph;
use crate::label::{FaceInfo, Label, Labelling};
use crate::pixels::EuclideanAt;
use crate::thin::Mask;

/// A wall chain the §5.1.6 simplification prunes (a leaf of the skeleton's graph: a wall
/// running out into the field, a solid mass drawn hatched, a stub): chapter 5 neither labels
/// nor fits it, but the model builds the thick ones (issue 25).
#[derive(Debug, Clone)]
pub struct Spur {
    /// Skeleton pixels, in order.
    pub points: Vec<(u32, u32)>,
    /// Wall thickness, pixels, measured as an edge's is.
    pub thickness: f64,
}

/// An open space bounded by walls.
#[derive(Debug, Clone)]
pub struct PlanFace {
    pub label: Label,
    /// Open pixels the face owns.
    pub area: usize,
    pub centroid: [f64; 2],
    pub shape: Option<Fit>,
    /// Indices of the bounding edges.
    pub edges: Vec<usize>,
    /// Its open pixels as row runs `[y, x0, x1]` (x1 inclusive), top to bottom; empty for the
    /// surroundings. The model builds a room §5.1.5 could not fit from them (issue 25).
    pub runs: Vec<[u32; 3]>,
}

/// Share of the sheet in diagonal hatch patterns above which a drawing parsed without the
/// hatching step is warned that its walls may be hatched: Loftie's White Tower has 6.8 %, the
/// other 235 castle plans at most 3.3 % (`hatched_walls::hatch_share`).
const HATCHED_SHARE: f64 = 0.05;

/// Per face: the open pixels it owns (area, centroid sums, largest distance to a wall) and
/// whether it reaches the image border. `face_of` gives each pixel's face (`u32::MAX`: none);
/// `in_open` is the distance from each open pixel to the nearest wall.
pub(crate) fn face_infos(
    face_of: &[u32],
    faces: usize,
    walls: &Mask,
    in_open: &image::GrayImage,
) -> Vec<FaceInfo> {
    let (wu, h) = (walls.width as usize, walls.height as usize);
    let mut infos = vec![FaceInfo::default(); faces];
    for (y, row) in face_of.chunks(wu).enumerate() {
        let i0 = y * wu;
        for (x, &f) in row.iter().enumerate() {
            if f == u32::MAX {
                continue;
            }
            let info = &mut infos[f as usize];
            if x == 0 || y == 0 || x == wu - 1 || y == h - 1 {
                info.touches_border = true;
            }
            if walls.data[i0 + x] == 0 {
                info.area += 1;
                info.sum[0] += x as f64;
                info.sum[1] += y as f64;
                info.max_inset = info.max_inset.max(f64::from(in_open.as_raw()[i0 + x]));
            }
        }
    }
    infos
}

/// The drawn thickness of a skeleton chain: twice the mean distance from its pixels to the
/// wall's edge (`in_wall`), less the centre pixel; at least 1.
pub(crate) fn chain_thickness(in_wall: &EuclideanAt, points: &[(u32, u32)]) -> f64 {
    let sum: f64 = points
        .iter()
        .map(|&(x, y)| f64::from(in_wall.at(x, y)))
        .sum();
    (2.0 * sum / points.len().max(1) as f64 - 1.0).max(1.0)
}

/// The edges of the full graph that §5.1.4's simplification dropped (`parts` lists the full
/// edges each kept edge is made of), with their drawn thickness.
pub(crate) fn spurs(full: &Graph, parts: &[Vec<usize>], in_wall: &EuclideanAt) -> Vec<Spur> {
    let mut kept = vec![false; full.edges.len()];
    for &k in parts.iter().flatten() {
        kept[k] = true;
    }
    full.edges
        .iter()
        .zip(&kept)
        .filter(|(e, k)| !**k && e.points.len() > 1)
        .map(|(e, _)| Spur {
            points: e.points.clone(),
            thickness: chain_thickness(in_wall, &e.points),
        })
        .collect()
}

/// Per edge of `g`: the faces its skeleton pixels touch (4-neighbours), in the order met.
pub(crate) fn edge_faces(g: &Graph, face_of: &[u32], w: u32, h: u32) -> Vec<Vec<usize>> {
    g.edges
        .iter()
        .map(|e| {
            let mut fs: Vec<usize> = Vec::new();
            for &(x, y) in &e.points {
                for (dx, dy) in [(1i32, 0i32), (-1, 0), (0, 1), (0, -1)] {
                    let (nx, ny) = (x as i32 + dx, y as i32 + dy);
                    if nx < 0 || ny < 0 || nx >= w as i32 || ny >= h as i32 {
                        continue;
                    }
                    let f = face_of[ny as usize * w as usize + nx as usize];
                    if f != u32::MAX && !fs.contains(&(f as usize)) {
                        fs.push(f as usize);
                    }
                }
            }
            fs
        })
        .collect()
}

/// Per face, its open pixels as rows `[y, x0, x1]` (inclusive); none for the surroundings.
pub(crate) fn face_runs(
    face_of: &[u32],
    faces: usize,
    walls: &Mask,
    labels: &[Label],
) -> Vec<Vec<[u32; 3]>> {
    let wu = walls.width as usize;
    let mut runs: Vec<Vec<[u32; 3]>> = vec![Vec::new(); faces];
    for (y, row) in face_of.chunks(wu).enumerate() {
        let mut x = 0;
        while x < wu {
            let f = row[x];
            let open = |x: usize| row[x] == f && walls.data[y * wu + x] == 0;
            if f == u32::MAX || !open(x) || labels[f as usize] == Label::CastleSurroundings {
                x += 1;
                continue;
            }
            let start = x;
            while x < wu && open(x) {
                x += 1;
            }
            runs[f as usize].push([y as u32, start as u32, x as u32 - 1]);
        }
    }
    runs
}

/// The labelled faces with their bounding edges and §5.1.5's circle or rectangle, fitted to the
/// skeleton pixels of the edges around them (`edge_points`, per edge) within `tolerance` (none
/// for the surroundings).
pub(crate) fn plan_faces(
    infos: &[FaceInfo],
    runs: Vec<Vec<[u32; 3]>>,
    edge_points: &[&[(u32, u32)]],
    edge_faces: &[Vec<usize>],
    labelling: &Labelling,
    tolerance: f64,
) -> Vec<PlanFace> {
    let to_f = |p: &(u32, u32)| [p.0 as f64, p.1 as f64];
    infos
        .iter()
        .zip(runs)
        .enumerate()
        .map(|(f, (info, runs))| {
            let bounding: Vec<usize> = (0..edge_points.len())
                .filter(|&e| edge_faces[e].contains(&f))
                .collect();
            let label = labelling.faces[f];
            let shape = if label == Label::CastleSurroundings || bounding.is_empty() {
                None
            } else {
                let pts: Vec<[f64; 2]> = bounding
                    .iter()
                    .flat_map(|&e| edge_points[e].iter().map(to_f))
                    .collect();
                fit::fit_face(&pts, tolerance)
            };
            let a = info.area.max(1) as f64;
            PlanFace {
                label,
                area: info.area,
                centroid: [info.sum[0] / a, info.sum[1] / a],
                shape,
                edges: bounding,
                runs,
            }
        })
        .collect()
}

/// §5.2 item 1's warnings read from the walls' extent (reaching the image's edge, or too small
/// a part of it), and the hatching the clean-up measured (`pre`) when it is large.
pub(crate) fn sheet_warnings(walls: &Mask, pre: &binarize::PreStats) -> Vec<String> {
    let (w, h) = (walls.width, walls.height);
    let mut warnings = Vec::new();
    // parse_grey returns before this when no wall is left.
    if let Some(wall_bb) = walls.bounding_box() {
        if wall_bb[0] == 0 || wall_bb[1] == 0 || wall_bb[2] == w - 1 || wall_bb[3] == h - 1 {
            warnings.push(
                "the walls reach the edge of the image: the castle may extend off it (§5.2 item 1)"
                    .into(),
            );
        }
        let castle_area =
            f64::from(wall_bb[2] - wall_bb[0] + 1) * f64::from(wall_bb[3] - wall_bb[1] + 1);
        if castle_area < 0.01 * f64::from(w) * f64::from(h) {
            warnings.push(
                "the castle covers under 1 % of the image: too small to parse reliably (§5.2 item 1)"
                    .into(),
            );
        }
    }
    if pre.hatch_share >= HATCHED_SHARE {
        warnings.push(format!(
            "diagonal hatch patterns cover {:.1} % of the sheet: if the walls are drawn hatched, parse with hatching on (--hatching, or hatching = true in a project)",
            100.0 * pre.hatch_share
        ));
    }
    warnings
}
