//! Towers drawn as thick ink (issue 26): solid or vaulted towers, drum towers studding a
//! curtain, and keeps whose walls the drawing fills, found where the wall ink is much thicker
//! than the curtain and compact (round or square, not a long thick wall).
//!
//! Departure from §5.1.6 (4), which finds a tower only as a wall edge bulging out of the castle
//! round a tower room. Many draughtsmen draw towers solid, or with vault ribs the wall ink
//! takes for wall, so they have no room, and a curtain studded with them is one edge whose
//! chord the towers barely leave; the development set's counts were exact on 2 of 31 plans,
//! with Montargis' 22 towers read as 5 and the Louvre's 20 as 1 (docs/plan.md, "Towers drawn
//! as thick ink"). Here the distance from each wall pixel to the open space gives the wall's
//! half-thickness; the pixels deeper than [`CORE`] curtains form each thick mass's core, and a
//! core that is compact is a tower of the inscribed radius, centred on its deepest pixel.
//!
//! Departure from §5.1.6 (5), whose tower rooms are faces the drawing leaves open: a thick
//! tower at least two curtains across has a room inside its wall ring ([`rooms`]).

use raster::components::{Connectivity, components_where};

use crate::bulges::BulgeTower;
use crate::legend::Label;
use crate::pixels;
use crate::thin::Mask;

/// A tower's core: wall pixels this many curtain thicknesses from the open space. The
/// curtain's own middle is half a thickness in, so a core holds only ink at least 1.4 curtains
/// thick. Swept on both annotated sets (0.7, 0.8, 0.9; docs/plan.md).
const CORE: f64 = 0.7;
/// Cores smaller than this many squared curtain thicknesses are blots, dots or letters.
const MIN_CORE_AREA: f64 = 0.3;
/// A core larger than this many times the disc of its inscribed radius is a long thick wall
/// (a bastion's face, a range drawn solid), not a tower: a square tower's core is 1.27 discs.
const MAX_CORE_DISCS: f64 = 4.0;

/// Towers drawn as thick ink. `walls` is the cleaned drawing (1 = wall); `curtain` the outer
/// wall's thickness in pixels; `labels` the pixel labels, where a tower already found (a tower
/// wall) keeps the thick ink round it from being counted again. A tower stands out of the
/// enceinte: its disc reaches the surroundings. Thick ink inside the castle is a range's
/// junction, a room's corner or a building the ink filled (Montargis' inner buildings). Each
/// tower's centre is its deepest pixel and its radius the ink's half-thickness there.
pub fn find(walls: &Mask, labels: &[u8], curtain: f64) -> Vec<BulgeTower> {
    let (w, h) = (walls.width as usize, walls.height as usize);
    if w == 0 || h == 0 || curtain <= 0.0 {
        return Vec::new();
    }
    let open: Vec<bool> = walls.data.iter().map(|&p| p == 0).collect();
    let depth = pixels::euclidean(&open, w, h);
    let depth = depth.as_raw();
    let core_depth = CORE * curtain;
    let cores = components_where(w, h, Connectivity::Eight, |i| {
        f64::from(depth[i]) >= core_depth
    });
    // Per core: its deepest pixel (depth, x, y), searched in its box.
    let n = cores.sizes.len() - 1;
    let area = &cores.sizes;
    let mut deepest = vec![(0u8, 0u32, 0u32); n + 1];
    for (l, b) in cores.bbox.iter().enumerate().skip(1) {
        for y in b[1]..=b[3] {
            for x in b[0]..=b[2] {
                let i = y as usize * w + x as usize;
                if cores.labels[i] as usize == l && depth[i] > deepest[l].0 {
                    deepest[l] = (depth[i], x, y);
                }
            }
        }
    }
    let c2 = curtain * curtain;
    (1..=n)
        .filter_map(|l| {
            let (d, x, y) = deepest[l];
            let radius = f64::from(d);
            let core_radius = (radius - core_depth).max(0.7);
            let disc = std::f64::consts::PI * core_radius * core_radius;
            let a = area[l] as f64;
            (a >= MIN_CORE_AREA * c2 && a <= MAX_CORE_DISCS * disc).then_some(BulgeTower {
                center: [f64::from(x), f64::from(y)],
                radius,
            })
        })
        .filter(|t| !touches(t, labels, walls.width, Label::TowerWall))
        .filter(|t| touches(t, labels, walls.width, Label::CastleSurroundings))
        .collect()
}

/// A thick tower at least this many curtain thicknesses in radius (two curtains across) has a
/// room: the drawing fills it (vaulted towers drawn black with white ribs, Villandraut;
/// solid-drawn drum towers), but a tower that wide is rarely solid masonry. Swept on both
/// annotated sets with 0.8, 1, 1.15, 1.3, 1.5 and 2 (docs/plan.md, "A room inside thick
/// towers").
const ROOM_FROM: f64 = 1.0;

/// The room of each thick tower at least [`ROOM_FROM`] curtains in radius: the pixels of its
/// disc inside its wall ring ([`BulgeTower::wall_width`], the ring the model builds) that are
/// tower wall become tower room. `curtain`: the outer walls' median thickness
/// ([`crate::scale::outer_wall_thickness_of`]), as the model takes it. Issue 26, departure
/// from §5.1.6 (5), whose tower rooms are faces the drawing leaves open: the development set
/// annotates a room at the heart of such towers (Villandraut's, drawn black with white vault
/// ribs).
pub fn rooms(labels: &mut [u8], width: u32, height: u32, towers: &[BulgeTower], curtain: f64) {
    let wide = towers.iter().filter(|t| wide_enough(t, curtain));
    carve_rooms(labels, width, height, wide, curtain);
}

/// Whether a tower is wide enough for a room: at least [`ROOM_FROM`] times `curtain` in radius.
fn wide_enough(t: &BulgeTower, curtain: f64) -> bool {
    t.radius >= ROOM_FROM * curtain
}

/// The tower-wall pixels of each tower's room ([`room`]) become tower room.
fn carve_rooms<'a>(
    labels: &mut [u8],
    width: u32,
    height: u32,
    towers: impl IntoIterator<Item = &'a BulgeTower>,
    curtain: f64,
) {
    for t in towers {
        for i in room(t, curtain).pixels(width, height) {
            if labels[i] == Label::TowerWall as u8 {
                labels[i] = Label::TowerRoom as u8;
            }
        }
    }
}

/// The disc of a tower's room: inside its wall ring ([`BulgeTower::wall_width`] of the
/// curtain `curtain`), less the pixel that [`BulgeTower::pixels`] grows a disc by.
fn room(t: &BulgeTower, curtain: f64) -> BulgeTower {
    BulgeTower {
        center: t.center,
        radius: t.radius - t.wall_width(Some(curtain)) - 1.0,
    }
}

/// A bulge's heart holds a room only where the drawing leaves at least this fraction of it
/// paper (vault ribs, a stair, a room the ink filled); a heart drawn solid is a solid tower.
const OPEN_HEART: f64 = 0.2;

/// The rooms of the outline's bulges ([`crate::bulges`]), as [`rooms`] gives thick towers
/// theirs, for the bulges whose heart the drawing `grey` leaves open: at least [`OPEN_HEART`]
/// of it paper by §5.1.2's threshold ([`crate::binarize::threshold_level`], taken only when a
/// bulge is wide enough to have a room). A bulge is wide enough against `curtain`, the
/// thickness it was measured against ([`crate::bulges::curtain_thickness`]); its ring is as
/// thick as the model builds it, from `median` (as for [`rooms`]). Issue 26: with bulges 0.8
/// curtains deep the outline finds Pierrefonds' east tower before the thick-tower finder
/// does, and its vault ribs, which the ink reads as wall, lost it its room (docs/plan.md,
/// "Shallower bulges").
pub fn bulge_rooms(
    labels: &mut [u8],
    grey: &image::GrayImage,
    towers: &[BulgeTower],
    curtain: f64,
    median: f64,
) {
    if !towers.iter().any(|t| wide_enough(t, curtain)) {
        return;
    }
    let (w, h) = grey.dimensions();
    let paper_from = crate::binarize::threshold_level(grey);
    let open = towers.iter().filter(|t| {
        wide_enough(t, curtain) && {
            let (mut n, mut paper) = (0usize, 0usize);
            for i in room(t, median).pixels(w, h) {
                n += 1;
                paper += usize::from(grey.as_raw()[i] >= paper_from);
            }
            n > 0 && paper as f64 >= OPEN_HEART * n as f64
        }
    });
    carve_rooms(labels, w, h, open, median);
}

/// Whether any pixel of the tower's disc (its radius plus one) has the label.
fn touches(t: &BulgeTower, labels: &[u8], width: u32, label: Label) -> bool {
    let height = (labels.len() / width as usize) as u32;
    t.pixels(width, height).any(|i| labels[i] == label as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `w` × `h` mask with the given filled rectangles `[x0, y0, x1, y1]` (inclusive) and
    /// discs `[cx, cy, r]`.
    fn mask(w: u32, h: u32, rects: &[[u32; 4]], discs: &[[f64; 3]]) -> Mask {
        let mut m = Mask::new(w, h);
        for y in 0..h {
            for x in 0..w {
                let in_rect = rects
                    .iter()
                    .any(|r| x >= r[0] && x <= r[2] && y >= r[1] && y <= r[3]);
                let in_disc = discs
                    .iter()
                    .any(|d| (f64::from(x) - d[0]).hypot(f64::from(y) - d[1]) <= d[2]);
                if in_rect || in_disc {
                    m.data[(y * w + x) as usize] = 1;
                }
            }
        }
        m
    }

    fn surroundings(w: u32, h: u32) -> Vec<u8> {
        vec![Label::CastleSurroundings as u8; (w * h) as usize]
    }

    #[test]
    fn drum_towers_on_a_curtain_are_found_and_the_curtain_is_not() {
        // A curtain 8 px thick with three solid drum towers of radius 14 px on it.
        let m = mask(
            200,
            60,
            &[[10, 26, 189, 33]],
            &[[40.0, 30.0, 14.0], [100.0, 30.0, 14.0], [160.0, 30.0, 14.0]],
        );
        let towers = find(&m, &surroundings(200, 60), 8.0);
        assert_eq!(towers.len(), 3);
        for (t, cx) in towers.iter().zip([40.0, 100.0, 160.0]) {
            assert!((t.center[0] - cx).abs() <= 1.0 && (t.center[1] - 30.0).abs() <= 1.0);
            assert!((13.0..=15.0).contains(&t.radius), "radius {}", t.radius);
        }
    }

    #[test]
    fn a_long_thick_wall_is_no_tower_and_a_square_tower_is() {
        // A wall 24 px thick and 160 px long (a core 7 discs of its radius), and a square
        // tower 30 px a side standing on a curtain of 8 px.
        let m = mask(
            240,
            120,
            &[[10, 10, 169, 33], [10, 80, 229, 87], [190, 69, 219, 98]],
            &[],
        );
        let towers = find(&m, &surroundings(240, 120), 8.0);
        assert_eq!(towers.len(), 1, "{towers:?}");
        let t = towers[0];
        assert!((t.center[0] - 204.5).abs() <= 1.5 && (t.center[1] - 83.5).abs() <= 1.5);
    }

    #[test]
    fn dots_and_towers_already_found_are_not_counted() {
        // A blot of radius 7 on a curtain of 8 px (core 0.1 squared curtains), and a drum
        // tower whose ink is already a tower wall.
        let m = mask(
            160,
            60,
            &[[0, 26, 159, 33]],
            &[[40.0, 30.0, 7.0], [110.0, 30.0, 14.0]],
        );
        let mut labels = surroundings(160, 60);
        labels[30 * 160 + 110] = Label::TowerWall as u8;
        assert!(find(&m, &labels, 8.0).is_empty());
        let fresh = find(&m, &surroundings(160, 60), 8.0);
        assert_eq!(fresh.len(), 1);
    }

    #[test]
    fn thick_ink_inside_the_castle_is_no_tower() {
        // The drum of the first test, with the surroundings beyond the curtain's outer face
        // (y < 20) out of its reach: a junction or a filled room, not a tower.
        let m = mask(100, 60, &[[0, 26, 99, 33]], &[[50.0, 30.0, 14.0]]);
        let mut labels = vec![Label::Courtyard as u8; 100 * 60];
        labels[..100 * 10].fill(Label::CastleSurroundings as u8);
        assert!(find(&m, &labels, 8.0).is_empty());
        labels[..100 * 16].fill(Label::CastleSurroundings as u8);
        assert_eq!(find(&m, &labels, 8.0).len(), 1);
    }

    #[test]
    fn the_size_of_a_tower_is_read_against_the_curtain() {
        // The same drum of radius 14 reads as a tower on a curtain of 8 px, and as the wall
        // itself when the curtain is 20 px thick.
        let m = mask(100, 60, &[[0, 26, 99, 33]], &[[50.0, 30.0, 14.0]]);
        assert_eq!(find(&m, &surroundings(100, 60), 8.0).len(), 1);
        assert!(find(&m, &surroundings(100, 60), 20.0).is_empty());
    }

    /// Towers at (30, 20) and (75, 20) of the given radii, side by side in a 100 × 40 image.
    fn two_towers(left: f64, right: f64) -> [BulgeTower; 2] {
        [[30.0, left], [75.0, right]].map(|[x, radius]| BulgeTower {
            center: [x, 20.0],
            radius,
        })
    }

    fn room_pixels(labels: &[u8]) -> usize {
        labels
            .iter()
            .filter(|&&l| l == Label::TowerRoom as u8)
            .count()
    }

    #[test]
    fn a_wide_thick_tower_has_its_room_inside_its_ring_and_a_narrow_one_none() {
        // Curtain 8 px: a tower of radius 14 (≥ 8) gets a room inside a ring of
        // min(8, 14 / 2) = 7 px; one of radius 7 stays solid.
        let (w, h) = (100u32, 40u32);
        let mut labels = vec![Label::TowerWall as u8; (w * h) as usize];
        rooms(&mut labels, w, h, &two_towers(14.0, 7.0), 8.0);
        let at = |x: u32, y: u32| Label::ALL[labels[(y * w + x) as usize] as usize];
        assert_eq!(at(30, 20), Label::TowerRoom, "the wide tower's centre");
        assert_eq!(at(36, 20), Label::TowerRoom, "6 px out: inside the ring");
        assert_eq!(at(38, 20), Label::TowerWall, "8 px out: the ring");
        assert_eq!(at(75, 20), Label::TowerWall, "the narrow tower stays solid");
        // The disc of radius 7 (inclusive): 149 pixels.
        assert_eq!(room_pixels(&labels), 149);
    }

    #[test]
    fn a_bulge_has_a_room_only_where_the_drawing_leaves_its_heart_open() {
        // Two bulges of radius 14 on a curtain of 8 px, read as tower wall throughout. The
        // left one is drawn with its heart striped (every other column paper, half of it: a
        // vault's ribs), the right one solid black.
        let (w, h) = (100u32, 40u32);
        let towers = two_towers(14.0, 14.0);
        let grey = image::GrayImage::from_fn(w, h, |x, _| {
            image::Luma([if x < 50 && x % 2 == 0 { 250 } else { 10 }])
        });
        let mut labels = vec![Label::TowerWall as u8; (w * h) as usize];
        bulge_rooms(&mut labels, &grey, &towers, 8.0, 8.0);
        let at = |x: u32, y: u32| Label::ALL[labels[(y * w + x) as usize] as usize];
        assert_eq!(at(30, 20), Label::TowerRoom, "the striped heart");
        assert_eq!(at(75, 20), Label::TowerWall, "the solid heart");
        // As for a thick tower of the same size: the disc of radius 7, 149 pixels.
        assert_eq!(room_pixels(&labels), 149);
        // Paper on under a fifth of the heart is no room: one column in six.
        let sparse = image::GrayImage::from_fn(w, h, |x, _| {
            image::Luma([if x % 6 == 0 { 250 } else { 10 }])
        });
        let mut labels = vec![Label::TowerWall as u8; (w * h) as usize];
        bulge_rooms(&mut labels, &sparse, &towers, 8.0, 8.0);
        assert!(!labels.contains(&(Label::TowerRoom as u8)));
    }
}
