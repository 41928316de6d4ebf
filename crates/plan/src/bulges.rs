//! Towers drawn as bulges of the curtain with no room of their own (issue 11: small solid or
//! ring towers along a wall, as at Montargis or the Louvre). §5.1.6 (4)'s convexity test, run
//! on stretches of the castle's outline instead of on whole wall edges.
//!
//! Departure from §5.1.6 (4), which tests whole graph edges: a curtain studded with small
//! towers is one long edge whose chord the bulges barely leave, so none of them was a tower.
//! Here every stretch of the outline is compared with its chord; a stretch is a tower when it
//! leaves the chord far (Jensen's test, as there) and the outline runs straight along the
//! chord on both sides — a bare corner of the enceinte fails that, and so, as a limitation, does
//! a tower standing on a corner (those usually have rooms and the edge test finds them).

use image::{GrayImage, Luma};
use imageproc::contours::{BorderType, find_contours};
use serde::Serialize;

use crate::legend::Label;

/// A tower found on the pixels rather than as tower-wall edges (pixels): a bulge of the
/// castle's outline, thick ink (`thick_towers`), or a ring round rooms on the curtain
/// (`ring_towers`, whose rooms are tower rooms).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BulgeTower {
    pub center: [f64; 2],
    pub radius: f64,
}

impl BulgeTower {
    /// The thickness of the tower's wall ring: the curtain's it studs (pixels; a third of the
    /// radius without one), at most half the radius. One home for the plan's thick towers'
    /// rooms ([`crate::thick_towers::rooms`]) and the model's towers (`integrate`).
    pub fn wall_width(&self, curtain: Option<f64>) -> f64 {
        curtain.unwrap_or(self.radius / 3.0).min(self.radius / 2.0)
    }

    /// Row-major indices of the pixels of the tower's disc grown by a pixel, clipped to the
    /// `width` × `height` image: the pixels a tower marks as its walls.
    pub fn pixels(&self, width: u32, height: u32) -> impl Iterator<Item = usize> + use<> {
        let r = self.radius + 1.0;
        let (w, h) = (i64::from(width), i64::from(height));
        let [cx, cy] = self.center;
        let (x0, x1) = (
            ((cx - r).floor() as i64).max(0),
            ((cx + r).ceil() as i64).min(w - 1),
        );
        let (y0, y1) = (
            ((cy - r).floor() as i64).max(0),
            ((cy + r).ceil() as i64).min(h - 1),
        );
        (y0..=y1).flat_map(move |y| {
            (x0..=x1).filter_map(move |x| {
                ((x as f64 - cx).hypot(y as f64 - cy) <= r).then_some((y * w + x) as usize)
            })
        })
    }
}

/// Leaves out every tower whose centre lies inside the disc of a larger one: two finders saw
/// the same tower (a ring's room inside a bulge of the outline, Chambord's north tower).
pub(crate) fn drop_nested(towers: &mut Vec<BulgeTower>) {
    let all = towers.clone();
    let key = |t: &BulgeTower| (t.radius, t.center[0], t.center[1]);
    towers.retain(|t| {
        !all.iter().any(|u| {
            key(u) > key(t)
                && (t.center[0] - u.center[0]).hypot(t.center[1] - u.center[1]) <= u.radius
        })
    });
}

/// A bulge must leave its chord by this many curtain thicknesses. Departure from §5.1.6 (4),
/// which asks 1.5: the drum towers that stud a curtain at Montargis, Vincennes, Langres or
/// Roche-Pont stand out of it by about one thickness. Swept on both annotated sets
/// (docs/plan.md, "Shallower bulges"): 1.5, 1.2, 1.0, 0.8, 0.7 give 4, 5, 5, 6, 6 exact
/// tower counts of 31 and 6, 6, 6, 7, 7 of 20, with the points level.
const MIN_DEPTH: f64 = 0.8;
/// … over a chord at least this many curtain thicknesses long (§5.1.6 (4)'s 1.5).
const MIN_CHORD: f64 = 1.5;
/// … and by this fraction of the chord (a semicircle leaves it by one half).
const MIN_DEPTH_OVER_CHORD: f64 = 0.3;
/// Deeper than this many chords it is a spur (a wall or a causeway running out), not a tower.
const MAX_DEPTH_OVER_CHORD: f64 = 1.5;
/// The widest tower looked for, in curtain thicknesses (wider ones have rooms of their own).
const MAX_CHORD: f64 = 10.0;
/// The outline beside a bulge may stray from the chord's line by this fraction of its depth.
const FLANK_TOLERANCE: f64 = 0.2;

/// The curtain's thickness from the outer walls' (thickness, skeleton length) pairs, which
/// it sorts by thickness: the lower quartile by length, since an edge's thickness is averaged
/// along its chain, towers included. `None` without outer walls. Shared by this finder, the
/// inner-ward towers' wall test (`inner_towers`) and the ring towers (`ring_towers`).
pub(crate) fn curtain_thickness(outer: &mut [(f64, usize)]) -> Option<f64> {
    outer.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: usize = outer.iter().map(|e| e.1).sum();
    let mut run = 0;
    outer.iter().find_map(|&(t, n)| {
        run += n;
        (4 * run >= total).then_some(t)
    })
}

/// Bulges of the castle's outline that are towers. `labels` holds a label index per pixel
/// (row-major, `width` wide); `curtain` is the outer wall's thickness in pixels. Bulges on
/// tower walls already labelled are left out, so nothing is counted twice.
pub fn find(labels: &[u8], width: u32, height: u32, curtain: f64) -> Vec<BulgeTower> {
    let outside = Label::CastleSurroundings as u8;
    // The contours are traced in the castle's bounding box grown by a pixel (clipped to the
    // image), which holds all of it: the same contours in the same order, shifted, at a
    // fraction of the cost of the whole sheet.
    let (w, h) = (width as usize, height as usize);
    let mut bb = [usize::MAX, usize::MAX, 0, 0];
    for (y, row) in labels.chunks(w).enumerate().take(h) {
        if let (Some(x0), Some(x1)) = (
            row.iter().position(|&l| l != outside),
            row.iter().rposition(|&l| l != outside),
        ) {
            bb = [bb[0].min(x0), bb[1].min(y), bb[2].max(x1), bb[3].max(y)];
        }
    }
    if bb[0] == usize::MAX {
        return Vec::new();
    }
    let (x0, y0) = (bb[0].saturating_sub(1), bb[1].saturating_sub(1));
    let (x1, y1) = ((bb[2] + 1).min(w - 1), (bb[3] + 1).min(h - 1));
    let castle = GrayImage::from_fn((x1 - x0 + 1) as u32, (y1 - y0 + 1) as u32, |x, y| {
        let i = (y as usize + y0) * w + x as usize + x0;
        Luma([if labels[i] == outside { 0 } else { 255 }])
    });
    let Some(mut outline) = find_contours::<i32>(&castle)
        .into_iter()
        .filter(|c| c.border_type == BorderType::Outer)
        .max_by_key(|c| c.points.len())
    else {
        return Vec::new();
    };
    for p in &mut outline.points {
        (p.x, p.y) = (p.x + x0 as i32, p.y + y0 as i32);
    }
    // Every few pixels of the outline are enough for bulges at least 0.8 walls deep, and the
    // search below costs the square of the points per wall thickness.
    let step = (curtain / 4.0).floor().max(1.0) as usize;
    let pts: Vec<[f64; 2]> = outline
        .points
        .iter()
        .step_by(step)
        .map(|p| [f64::from(p.x), f64::from(p.y)])
        .collect();
    let tower_wall = |p: [f64; 2]| {
        let (x, y) = (p[0] as i64, p[1] as i64);
        (-2..=2).any(|dy| {
            (-2..=2).any(|dx| {
                let (qx, qy) = (x + dx, y + dy);
                qx >= 0
                    && qy >= 0
                    && qx < i64::from(width)
                    && qy < i64::from(height)
                    && labels[(qy * i64::from(width) + qx) as usize] == Label::TowerWall as u8
            })
        })
    };
    let mut found = Vec::new();
    for b in select(candidates(&pts, curtain.max(1.0), step as f64)) {
        let apex = pts[b.apex];
        if tower_wall(apex) {
            continue;
        }
        found.push(b.tower(&pts));
    }
    found
}

/// A stretch `from ..= to` of the outline (indices taken modulo its length) that bulges.
#[derive(Debug, Clone, Copy)]
struct Bulge {
    from: usize,
    to: usize,
    apex: usize,
    depth: f64,
    chord: f64,
}

impl Bulge {
    /// Tight, deep bulges first: a chord spanning two towers has the same depth but is longer.
    fn rank(&self) -> f64 {
        self.depth * self.depth / self.chord
    }

    fn indices(&self, n: usize) -> impl Iterator<Item = usize> {
        let len = (self.to + n - self.from) % n;
        (0..=len).map(move |k| (self.from + k) % n)
    }

    /// The circle of the tower: fitted to the stretch beyond half the depth (the tower's own
    /// outline), or a half-disc on the chord when the fit is off.
    fn tower(&self, pts: &[[f64; 2]]) -> BulgeTower {
        let n = pts.len();
        let (a, b) = (pts[self.from], pts[self.to]);
        let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        let own: Vec<[f64; 2]> = self
            .indices(n)
            .map(|i| pts[i])
            .filter(|p| distance_to_line(*p, a, b).abs() >= self.depth / 2.0)
            .collect();
        let fallback = BulgeTower {
            center: mid,
            radius: (self.chord / 2.0).max(self.depth / 2.0),
        };
        match crate::fit::fit_circle(&own) {
            Some((cx, cy, r, _))
                if r.is_finite()
                    && r >= 0.3 * self.depth
                    && r <= self.chord.max(self.depth)
                    && (cx - mid[0]).hypot(cy - mid[1]) <= self.chord + self.depth =>
            {
                BulgeTower {
                    center: [cx, cy],
                    radius: r,
                }
            }
            _ => fallback,
        }
    }
}

/// Signed distance of `p` from the line through `a` and `b` (positive on the left of a → b,
/// with left the rotation of the direction by +90° in the image's coordinates).
fn distance_to_line(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy).max(1e-9);
    ((p[0] - a[0]) * -dy + (p[1] - a[1]) * dx) / len
}

/// For every outline point, the tightest bulge centred on it, if any.
fn candidates(pts: &[[f64; 2]], curtain: f64, step: f64) -> Vec<Bulge> {
    let n = pts.len();
    // Shoelace: positive when the interior lies on the left of the direction of travel.
    let area2: f64 = (0..n)
        .map(|i| {
            let (p, q) = (pts[i], pts[(i + 1) % n]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum();
    let outward = if area2 > 0.0 { -1.0 } else { 1.0 };
    // Half-spans in outline points (`step` pixels of outline each).
    let min_half = ((MIN_DEPTH * curtain / step).ceil() as usize).max(3);
    let max_half = (MAX_CHORD * curtain / 2.0 / step).ceil() as usize + min_half;
    let mut out = Vec::new();
    if n < 4 * min_half {
        return out;
    }
    let at = |i: isize| pts[i.rem_euclid(n as isize) as usize];
    for i in 0..n as isize {
        for half in min_half..=max_half.min(n / 4) {
            let h = half as isize;
            let (a, b) = (at(i - h), at(i + h));
            let chord = (b[0] - a[0]).hypot(b[1] - a[1]);
            if chord < MIN_CHORD * curtain {
                continue;
            }
            let min_depth = (MIN_DEPTH * curtain)
                .max(3.0)
                .max(MIN_DEPTH_OVER_CHORD * chord);
            // Outline points are at most √2 `step` apart, so sampling every `stride`-th point
            // misses at most 0.75 stride steps of the depth: most stretches end here.
            let stride = (half / 6).max(1) as isize;
            let sampled = (i - h..=i + h)
                .step_by(stride as usize)
                .map(|j| outward * distance_to_line(at(j), a, b))
                .fold(0.0f64, f64::max);
            if sampled + 0.75 * (stride as f64) * step + 0.5 < min_depth {
                continue;
            }
            let (mut depth, mut apex, mut inward) = (0.0f64, i, 0.0f64);
            for j in i - h..=i + h {
                let d = outward * distance_to_line(at(j), a, b);
                if d > depth {
                    (depth, apex) = (d, j);
                }
                inward = inward.min(d);
            }
            let deep =
                depth >= min_depth && depth <= MAX_DEPTH_OVER_CHORD * chord && inward >= -curtain;
            if !deep {
                continue;
            }
            let tolerance = (FLANK_TOLERANCE * depth).max(1.5);
            let straight = (1..=h).all(|k| {
                distance_to_line(at(i - h - k), a, b).abs() <= tolerance
                    && distance_to_line(at(i + h + k), a, b).abs() <= tolerance
            });
            if straight {
                out.push(Bulge {
                    from: (i - h).rem_euclid(n as isize) as usize,
                    to: (i + h).rem_euclid(n as isize) as usize,
                    apex: apex.rem_euclid(n as isize) as usize,
                    depth,
                    chord,
                });
                break;
            }
        }
    }
    out
}

/// The best bulges that share no outline point.
fn select(mut cands: Vec<Bulge>) -> Vec<Bulge> {
    cands.sort_by(|a, b| b.rank().total_cmp(&a.rank()));
    let mut taken: Vec<Bulge> = Vec::new();
    let overlaps = |a: &Bulge, b: &Bulge| {
        let inside = |x: usize, s: &Bulge| {
            if s.from <= s.to {
                (s.from..=s.to).contains(&x)
            } else {
                x >= s.from || x <= s.to
            }
        };
        inside(a.from, b) || inside(a.to, b) || inside(b.from, a) || inside(b.to, a)
    };
    for c in cands {
        if !taken.iter().any(|t| overlaps(t, &c)) {
            taken.push(c);
        }
    }
    taken.sort_by_key(|b| b.from);
    taken
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Labels of a castle (courtyard) inside surroundings, drawn by `inside`.
    fn labels(w: u32, h: u32, inside: impl Fn(f64, f64) -> bool) -> Vec<u8> {
        (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                if inside(f64::from(x), f64::from(y)) {
                    Label::Courtyard as u8
                } else {
                    Label::CastleSurroundings as u8
                }
            })
            .collect()
    }

    fn in_disc(x: f64, y: f64, c: (f64, f64), r: f64) -> bool {
        (x - c.0).hypot(y - c.1) <= r
    }

    #[test]
    fn three_round_towers_on_a_straight_curtain_are_found_where_drawn() {
        let centres = [(60.0, 40.0), (120.0, 40.0), (180.0, 40.0)];
        let l = labels(240, 160, |x, y| {
            (20.0..=220.0).contains(&x) && (40.0..=140.0).contains(&y)
                || centres.iter().any(|&c| in_disc(x, y, c, 9.0))
        });
        let mut towers = find(&l, 240, 160, 4.0);
        assert_eq!(towers.len(), 3, "{towers:?}");
        towers.sort_by(|a, b| a.center[0].total_cmp(&b.center[0]));
        for (t, c) in towers.iter().zip(centres) {
            assert!(
                (t.center[0] - c.0).abs() < 2.5 && (t.center[1] - c.1).abs() < 2.5,
                "{t:?} vs {c:?}"
            );
            assert!((t.radius - 9.0).abs() < 2.5, "{t:?}");
        }
    }

    #[test]
    fn a_drum_standing_one_curtain_out_of_the_wall_is_a_tower() {
        // Discs of radius 4.5 on a curtain read as 4 px thick: they leave its face by 1.1
        // curtains, short of §5.1.6 (4)'s 1.5 and past this finder's 0.8.
        let centres = [(70.0, 40.0), (150.0, 40.0)];
        let l = labels(240, 160, |x, y| {
            (20.0..=220.0).contains(&x) && (40.0..=140.0).contains(&y)
                || centres.iter().any(|&c| in_disc(x, y, c, 4.5))
        });
        let towers = find(&l, 240, 160, 4.0);
        assert_eq!(towers.len(), 2, "{towers:?}");
        // On a curtain twice as thick they stand out by half a curtain: no towers.
        assert_eq!(find(&l, 240, 160, 8.0), vec![]);
    }

    #[test]
    fn a_plain_rectangle_has_no_tower_at_its_corners() {
        let l = labels(200, 150, |x, y| {
            (30.0..=170.0).contains(&x) && (30.0..=120.0).contains(&y)
        });
        assert_eq!(find(&l, 200, 150, 4.0), vec![]);
    }

    #[test]
    fn a_square_tower_mid_wall_counts_and_a_long_spur_does_not() {
        let l = labels(240, 200, |x, y| {
            let body = (40.0..=200.0).contains(&x) && (60.0..=180.0).contains(&y);
            let square = (70.0..=90.0).contains(&x) && (45.0..=60.0).contains(&y);
            let spur = (150.0..=154.0).contains(&x) && (5.0..=60.0).contains(&y);
            body || square || spur
        });
        let towers = find(&l, 240, 200, 4.0);
        assert_eq!(towers.len(), 1, "{towers:?}");
        assert!((towers[0].center[0] - 80.0).abs() < 4.0, "{towers:?}");
    }

    #[test]
    fn a_bulge_already_labelled_tower_wall_is_not_counted_again() {
        let w = 240;
        let mut l = labels(w, 160, |x, y| {
            (20.0..=220.0).contains(&x) && (40.0..=140.0).contains(&y)
                || in_disc(x, y, (120.0, 40.0), 9.0)
        });
        assert_eq!(find(&l, w, 160, 4.0).len(), 1);
        for y in 28..40u32 {
            for x in 110..131u32 {
                if in_disc(f64::from(x), f64::from(y), (120.0, 40.0), 9.0) {
                    l[(y * w + x) as usize] = Label::TowerWall as u8;
                }
            }
        }
        assert_eq!(find(&l, w, 160, 4.0), vec![]);
    }

    #[test]
    fn no_castle_means_no_towers() {
        let l = vec![Label::CastleSurroundings as u8; 50 * 40];
        assert_eq!(find(&l, 50, 40, 3.0), vec![]);
    }
}
