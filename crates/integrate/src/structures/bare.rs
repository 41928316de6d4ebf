//! Round towers the structures leave bare (issue 25: "every tower … of the plan present"). A
//! half-round tower drawn as a small arc on a thin curtain is labelled wall by chapter 5 but
//! has no room of its own, and §5.1.6 (4)'s bulge test (`plan::bulges`) misses it when the
//! wall ink is read thicker than drawn (Falaise: 3 of 10 towers). After every structure is
//! built, the outer wall's pixels that none covers are grouped; a group whose edge towards the
//! surroundings is an arc of a circle about as large as a tower becomes a tower on that circle.
//!
//! Departure from §5.3, which extrudes every labelled pixel as it is: only groups a circle fits
//! are built, so the model is still read from fits.

use plan::ParsedPlan;
use plan::bulges::BulgeTower;
use plan::fit::{fit_circle, segment_distance};
use plan::label::Label;
use raster::components::{Connectivity, components_where};

use crate::correspond::contains;
use crate::estimate::{Footprint, Structure};

/// A group is looked at from this many square curtain thicknesses of bare pixels …
const MIN_AREA: f64 = 1.0;
/// … and its circle's radius must lie within these multiples of the curtain's thickness.
const RADIUS_WITHIN: [f64; 2] = [0.75, 4.0];
/// The arc's mean distance from its circle, over the radius.
const MAX_ERROR: f64 = 0.15;
/// The share of the group inside its circle, and of the circle's area the group fills (a
/// half-round tower's part outside the curtain is about half of its disc).
const MIN_INSIDE: f64 = 0.8;
const MIN_FILL: f64 = 0.25;
/// An arc needs at least this many pixels.
const MIN_ARC: usize = 8;

/// The plan pixels (row-major) that `built`'s footprints cover; `s` model units per pixel.
fn covered(plan: &ParsedPlan, built: &[Structure], s: f64) -> Vec<bool> {
    let (w, h) = (plan.width as usize, plan.height as usize);
    let mut out = vec![false; w * h];
    let mut mark = |lo: [f64; 2], hi: [f64; 2], inside: &dyn Fn([f64; 2]) -> bool| {
        let x0 = lo[0].floor().max(0.0) as usize;
        let y0 = lo[1].floor().max(0.0) as usize;
        let x1 = (hi[0].ceil().max(0.0) as usize).min(w.saturating_sub(1));
        let y1 = (hi[1].ceil().max(0.0) as usize).min(h.saturating_sub(1));
        for y in y0..=y1 {
            for x in x0..=x1 {
                if !out[y * w + x] && inside([x as f64, y as f64]) {
                    out[y * w + x] = true;
                }
            }
        }
    };
    for st in built {
        let f = &st.footprint;
        let inside = |p: [f64; 2]| contains(f, [p[0] * s, p[1] * s]);
        // Each footprint's box in plan pixels, `lo` to `hi`.
        let square = |c: &[f64; 2], reach: f64| {
            let c = [c[0] / s, c[1] / s];
            ([c[0] - reach, c[1] - reach], [c[0] + reach, c[1] + reach])
        };
        match f {
            Footprint::Wall { .. } => {
                // Piece by piece: a run's box can hold the whole castle.
                for ([a, b], width) in f.pieces_with_widths() {
                    let (a, b, r) = ([a[0] / s, a[1] / s], [b[0] / s, b[1] / s], width / s / 2.0);
                    let lo = [a[0].min(b[0]) - r, a[1].min(b[1]) - r];
                    let hi = [a[0].max(b[0]) + r, a[1].max(b[1]) + r];
                    mark(lo, hi, &|p| segment_distance(p, a, b) <= r);
                }
            }
            Footprint::Circle { center, radius } => {
                let (lo, hi) = square(center, radius / s);
                mark(lo, hi, &inside);
            }
            Footprint::Rectangle { center, size, .. } => {
                let (lo, hi) = square(center, size[0].hypot(size[1]) / s / 2.0);
                mark(lo, hi, &inside);
            }
            Footprint::Blocks { blocks, .. } => {
                for b in blocks {
                    let (lo, hi) = square(&b.center, b.size[0].hypot(b.size[1]) / s / 2.0);
                    mark(lo, hi, &inside);
                }
            }
        }
    }
    out
}

/// The round towers of the outer wall that `built` leaves bare (plan pixels), for a curtain
/// `curtain_px` thick; `s` model units per pixel.
pub(super) fn towers(
    plan: &ParsedPlan,
    built: &[Structure],
    s: f64,
    curtain_px: f64,
) -> Vec<BulgeTower> {
    let (w, h) = (plan.width as usize, plan.height as usize);
    if plan.labels.len() != w * h || curtain_px <= 0.0 {
        return Vec::new();
    }
    let cover = covered(plan, built, s);
    let outer = Label::CastleOuterWall as u8;
    let outside = Label::CastleSurroundings as u8;
    let bare = |i: usize| plan.labels[i] == outer && !cover[i];
    let groups = components_where(w, h, Connectivity::Eight, bare);
    let min_area = MIN_AREA * curtain_px * curtain_px;
    // Each group's pixels, and its arc: its pixels beside the surroundings.
    let n = groups.sizes.len();
    let mut pixels: Vec<Vec<[f64; 2]>> = vec![Vec::new(); n];
    let mut arcs: Vec<Vec<[f64; 2]>> = vec![Vec::new(); n];
    for (i, &g) in groups.labels.iter().enumerate() {
        let g = g as usize;
        if g == 0 || (groups.sizes[g] as f64) < min_area {
            continue;
        }
        let (x, y) = (i % w, i / w);
        let p = [x as f64, y as f64];
        pixels[g].push(p);
        let beside = [
            (x > 0).then(|| i - 1),
            (x + 1 < w).then(|| i + 1),
            (y > 0).then(|| i - w),
            (y + 1 < h).then(|| i + w),
        ];
        if beside
            .into_iter()
            .flatten()
            .any(|j| plan.labels[j] == outside)
        {
            arcs[g].push(p);
        }
    }
    let mut found = Vec::new();
    for g in 1..n {
        if arcs[g].len() < MIN_ARC {
            continue;
        }
        let Some((cx, cy, r, error)) = fit_circle(&arcs[g]) else {
            continue;
        };
        let t = curtain_px;
        if !(RADIUS_WITHIN[0] * t..=RADIUS_WITHIN[1] * t).contains(&r) || error > MAX_ERROR * r {
            continue;
        }
        let count = pixels[g].len() as f64;
        let inside = pixels[g]
            .iter()
            .filter(|p| (p[0] - cx).hypot(p[1] - cy) <= r + 0.5)
            .count() as f64;
        if inside < MIN_INSIDE * count || count < MIN_FILL * std::f64::consts::PI * r * r {
            continue;
        }
        found.push(BulgeTower {
            center: [cx, cy],
            radius: r,
        });
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimate::{Kind, Role};

    const W: u32 = 120;
    const H: u32 = 80;

    /// A 120 × 80 plan, surroundings everywhere but the outer wall: a curtain 8 px thick along
    /// rows 36..=43 (x 10..=110), a half-round tower of radius 16 about (60, 36) on its north
    /// face, and a flat strip 28 × 6 against it (x 12..=39, rows 30..=35) that is no tower.
    fn plan() -> ParsedPlan {
        let outer = |x: u32, y: u32| {
            let curtain = (10..=110).contains(&x) && (36..=43).contains(&y);
            let tower = y < 36 && (f64::from(x) - 60.0).hypot(f64::from(y) - 36.0) <= 16.0;
            let strip = (12..=39).contains(&x) && (30..=35).contains(&y);
            curtain || tower || strip
        };
        let mut walls = plan::thin::Mask::new(W, H);
        let mut labels = vec![Label::CastleSurroundings as u8; (W * H) as usize];
        for y in 0..H {
            for x in 0..W {
                if outer(x, y) {
                    let i = (y * W + x) as usize;
                    labels[i] = Label::CastleOuterWall as u8;
                    walls.data[i] = 1;
                }
            }
        }
        ParsedPlan {
            labels,
            walls,
            ..ParsedPlan::empty(W, H)
        }
    }

    /// The curtain built along its centreline, `thickness` thick, at 2 model units a pixel.
    fn curtain(thickness: f64) -> Structure {
        Structure {
            id: "curtain1".into(),
            label: Label::CastleOuterWall,
            role: Role::Curtain,
            kind: Kind::Solid,
            footprint: Footprint::Wall {
                centerline: vec![[20.0, 79.0], [220.0, 79.0]],
                thickness: 2.0 * thickness,
                closed: false,
                widths: vec![],
            },
            height: 20.0,
            wall_thickness: 2.0 * thickness,
            facades: vec![],
            roof: None,
            crenellated: None,
            children: vec![],
            provenance: Default::default(),
        }
    }

    #[test]
    fn the_bare_half_round_tower_is_found_on_its_circle_and_the_strip_is_not() {
        let found = towers(&plan(), &[curtain(8.0)], 2.0, 8.0);
        assert_eq!(found.len(), 1, "{found:?}");
        let t = found[0];
        assert!((t.center[0] - 60.0).abs() < 1.5, "{t:?}");
        assert!((t.center[1] - 36.0).abs() < 2.5, "{t:?}");
        assert!((t.radius - 16.0).abs() < 1.5, "{t:?}");
    }

    #[test]
    fn nothing_is_found_where_the_structures_cover_the_wall() {
        // A curtain wide enough to take in the tower and the strip leaves nothing bare.
        assert!(towers(&plan(), &[curtain(44.0)], 2.0, 8.0).is_empty());
        // Against a curtain 22 px thick the tower (radius 16, about 400 px) is smaller than a
        // square of its thickness and than three quarters of it: no tower.
        assert!(towers(&plan(), &[curtain(8.0)], 2.0, 22.0).is_empty());
    }
}
