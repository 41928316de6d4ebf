//! Drawings parsed enlarged (departure from §5.1.2, see [`crate::parse`]): every result of a
//! parse at `k` times the drawing's size mapped back to the drawing's own pixels.

use crate::bulges;
use crate::graph::Vertex;
use crate::measure::{PlanFace, Spur};
use crate::parsed::{ParsedPlan, PlanEdge};
use crate::thin::Mask;

/// Maps a plan parsed at `k` times the size back to the `w` × `h` input.
pub(crate) fn shrink(p: ParsedPlan, k: u32, w: u32, h: u32) -> ParsedPlan {
    let kf = f64::from(k);
    let inv = 1.0 / kf;
    let at = |x: u32, y: u32| ((y * k + k / 2) * p.width + x * k + k / 2) as usize;
    let mut labels = Vec::with_capacity((w * h) as usize);
    let mut walls = Mask::new(w, h);
    for y in 0..h {
        for x in 0..w {
            labels.push(p.labels[at(x, y)]);
            walls.data[(y * w + x) as usize] = p.walls.data[at(x, y)];
        }
    }
    let small = |v: f64| (v + 0.5) * inv - 0.5;
    // A chain's pixels on the drawing: each enlarged pixel's, neighbours that fall on one
    // pixel kept once.
    let shrink_chain = |chain: &[(u32, u32)]| {
        let mut points: Vec<(u32, u32)> = chain.iter().map(|&(x, y)| (x / k, y / k)).collect();
        points.dedup();
        points
    };
    let edges = p
        .edges
        .into_iter()
        .map(|e| PlanEdge {
            points: shrink_chain(&e.points),
            fit: e.fit.map(|f| f.scaled(inv)),
            thickness: e.thickness * inv,
            ..e
        })
        .collect();
    let spurs = p
        .spurs
        .into_iter()
        .map(|s| Spur {
            points: shrink_chain(&s.points),
            thickness: s.thickness * inv,
        })
        .collect();
    let faces = p
        .faces
        .into_iter()
        .map(|f| PlanFace {
            // The enlarged drawing's rows through each small pixel's centre.
            runs: f
                .runs
                .iter()
                .filter(|r| r[0] % k == k / 2)
                .map(|r| [r[0] / k, r[1].div_ceil(k), (r[2] + 1) / k])
                .filter(|r| r[2] >= r[1] && r[2] > 0)
                .map(|r| [r[0], r[1], r[2] - 1])
                .filter(|r| r[2] >= r[1])
                .collect(),
            area: (f.area as f64 / (kf * kf)).round() as usize,
            centroid: [small(f.centroid[0]), small(f.centroid[1])],
            shape: f.shape.map(|s| s.scaled(inv)),
            ..f
        })
        .collect();
    ParsedPlan {
        width: w,
        height: h,
        vertices: p
            .vertices
            .into_iter()
            .map(|v| Vertex {
                x: small(v.x),
                y: small(v.y),
            })
            .collect(),
        edges,
        faces,
        labels,
        walls,
        towers: p.towers,
        bulge_towers: p
            .bulge_towers
            .into_iter()
            .map(|t| bulges::BulgeTower {
                // Clamped to the drawing: a tower on the sheet's edge (thick ink cut off by
                // it) has its centre on the enlarged edge pixel, a quarter pixel outside.
                center: [
                    small(t.center[0]).clamp(0.0, f64::from(w - 1)),
                    small(t.center[1]).clamp(0.0, f64::from(h - 1)),
                ],
                radius: t.radius * inv,
            })
            .collect(),
        spurs,
        pre: p.pre,
        warnings: p.warnings,
        scale_bar: p.scale_bar,
    }
}
