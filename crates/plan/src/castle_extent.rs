//! The castle kept alone (addition to §5.1.2, which left this to the user's clean-up, §5.1.1
//! and §5.2 item 2): which ink regions of a plan sheet are the castle, and which are legends,
//! scale bars, north arrows and the other figures of a book page.

use raster::components::Components;

/// How near the castle's ink, as a share of the drawing's long side, a region's ink must come
/// to join it ([`castle_regions`]).
const CASTLE_REACH: f64 = 0.03;

/// [`CASTLE_REACH`] in pixels on a `w` × `h` sheet (at most 254, the distances' range).
pub(crate) fn reach(w: usize, h: usize) -> u8 {
    (CASTLE_REACH * w.max(h) as f64).round().min(254.0) as u8
}

/// With one building on the sheet ([`crate::Options::one_building`]), how near the castle's
/// ink, in wall thicknesses, a region's ink must come to join it: far enough to cross a
/// modern survey's windows and doors (3–4 thicknesses on R3D plan 9). Measured with the
/// network on R3D's walls (docs/plan.md, "One building"): 2 → 0.543, 3 → 0.663,
/// 4 → 0.677, **6 → 0.703** (0.459 without).
pub(crate) const ONE_BUILDING_REACH: f64 = 6.0;

/// [`ONE_BUILDING_REACH`] in pixels for walls `thickness` pixels thick (1 to 254, the
/// distances' range).
pub(crate) fn building_reach(thickness: f64) -> u8 {
    (ONE_BUILDING_REACH * thickness).round().clamp(1.0, 254.0) as u8
}

/// The share of the sheet's width or height beyond which a region is a frame or a sheet edge
/// to [`castle_regions`].
const SHEET_SPAN: f64 = 0.9;

/// Which ink regions of `black` are the castle (index 0, the background, is never kept;
/// `sizes` of 0 are regions already removed): the largest region and those whose bounding box
/// lies within its box; and, with a `reach` in pixels, every region whose ink comes within
/// `reach` of the ink kept so far (chessboard distance), a region that joins counting as kept
/// ink at once ([`grow_by_ink`]). A region that spans [`SHEET_SPAN`] of the sheet's width or height (a frame, a sheet edge)
/// joins only from within the box. With `building` (one building on the sheet), the ink grows
/// by `building` pixels where that is farther than `reach`.
///
/// Issue 26: with the learned ink the castle grows by reach ([`CASTLE_REACH`]). Keeping only
/// what lay inside the largest region's box dropped every piece of a wall cut by windows and
/// doors that reached beyond it (a flat's walls, Bell's Udhruh), and outworks. Growing by
/// boxes instead of ink joined the next figure of a book page through boxes that overlap at
/// the corners (Pierrefonds: plan–model IoU 0.905 → 0.795). Measured with the learned ink in
/// docs/plan.md ("What the castle keeps"). The rules' threshold keeps letters, numerals and
/// hachure blobs near the castle, which then pass as towers (exact towers 6 → 2 of 31), so it
/// keeps the box.
pub(crate) fn castle_regions(
    black: &Components,
    w: usize,
    h: usize,
    reach: Option<u8>,
    building: Option<u8>,
) -> Vec<bool> {
    let (sizes, bbox) = (&black.sizes, &black.bbox);
    let mut keep = vec![false; sizes.len()];
    let Some((big, _)) = sizes.iter().enumerate().skip(1).max_by_key(|&(_, s)| *s) else {
        return keep;
    };
    let b = bbox[big];
    for (i, c) in bbox.iter().enumerate().skip(1) {
        keep[i] = i == big
            || (sizes[i] > 0 && c[0] >= b[0] && c[1] >= b[1] && c[2] <= b[2] && c[3] <= b[3]);
    }
    // Growing by the nearer reach and then by the farther one keeps what growing by the
    // farther one alone keeps (each joins every region within its reach, round after round),
    // so one search by the larger serves (`None` orders below every reach).
    let Some(reach) = reach.max(building) else {
        return keep;
    };
    // A frame or a sheet edge spans the sheet; a piece of a tightly cropped castle only
    // touches its border.
    let may_join: Vec<bool> = (0..sizes.len())
        .map(|i| {
            let c = bbox[i];
            i > 0
                && sizes[i] > 0
                && f64::from(c[2] + 1 - c[0]) < SHEET_SPAN * w as f64
                && f64::from(c[3] + 1 - c[1]) < SHEET_SPAN * h as f64
        })
        .collect();
    grow_by_ink(black, w, h, reach, &may_join, &mut keep);
    keep
}

/// Marks kept every region of `black` that `may_join` whose ink comes within `reach`
/// (chessboard) of kept ink, where a region that joins counts as kept ink at once: one search
/// by distance from the kept ink, in which the pixels of a region that joins start again at 0.
fn grow_by_ink(
    black: &Components,
    w: usize,
    h: usize,
    reach: u8,
    may_join: &[bool],
    keep: &mut [bool],
) {
    // Each region's pixels, by a counting sort on the labels.
    let mut start = vec![0usize; keep.len() + 1];
    for &l in &black.labels {
        start[l as usize + 1] += 1;
    }
    for l in 0..keep.len() {
        start[l + 1] += start[l];
    }
    let mut pixels = vec![0usize; black.labels.len()];
    let mut next = start.clone();
    for (i, &l) in black.labels.iter().enumerate() {
        pixels[next[l as usize]] = i;
        next[l as usize] += 1;
    }
    let region = |l: usize| &pixels[start[l]..start[l + 1]];
    let mut dist = vec![u8::MAX; w * h];
    let mut bucket: Vec<Vec<usize>> = vec![Vec::new(); usize::from(reach) + 1];
    for l in (1..keep.len()).filter(|&l| keep[l]) {
        for &i in region(l) {
            dist[i] = 0;
            bucket[0].push(i);
        }
    }
    // The nearest bucket not yet empty: pixels are only ever added at `d + 1`, or at 0 when a
    // region joins, which sends the search back to 0.
    let mut d = 0;
    loop {
        while d < bucket.len() && bucket[d].is_empty() {
            d += 1;
        }
        let Some(i) = bucket.get_mut(d).and_then(Vec::pop) else {
            return;
        };
        if usize::from(dist[i]) < d || d >= usize::from(reach) {
            continue; // reached nearer since, or at the reach
        }
        let (x, y) = (i % w, i / w);
        let mut joined = false;
        for ny in y.saturating_sub(1)..(y + 2).min(h) {
            for nx in x.saturating_sub(1)..(x + 2).min(w) {
                let j = ny * w + nx;
                let l = black.labels[j] as usize;
                if l > 0 && !keep[l] && may_join[l] {
                    keep[l] = true;
                    for &k in region(l) {
                        dist[k] = 0;
                        bucket[0].push(k);
                    }
                    joined = true;
                } else if usize::from(dist[j]) > d + 1 {
                    dist[j] = (d + 1) as u8;
                    bucket[d + 1].push(j);
                }
            }
        }
        if joined {
            d = 0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{GrayImage, Luma};
    use raster::components::{Connectivity, components};

    #[test]
    fn the_castle_keeps_its_box_or_grows_to_the_ink_that_comes_near() {
        // A 120 × 80 sheet. L: the castle, an L of 4-px bars (box 10..60); F: a block inside
        // its box; B: a block whose box overlaps L's at the corner, its ink 40 px from L's;
        // C: a bar 4 px right of L's top bar; D: a bar 4 px right of C; E: a line 4 px right
        // of D, as high as the sheet (a frame).
        let sheet = GrayImage::from_fn(120, 80, |x, y| {
            let l = ((10..60).contains(&x) && (10..14).contains(&y))
                || ((10..14).contains(&x) && (10..60).contains(&y));
            let f = (30..34).contains(&x) && (30..34).contains(&y);
            let b = (54..66).contains(&x) && (54..66).contains(&y);
            let c = (63..80).contains(&x) && (10..14).contains(&y);
            let d = (83..100).contains(&x) && (10..14).contains(&y);
            let e = (103..105).contains(&x);
            Luma([if l || f || b || c || d || e { 255 } else { 0 }])
        });
        let black = components(&sheet, 255, Connectivity::Eight);
        let kept_with = |reach: Option<u8>, building: Option<u8>| {
            let keep = castle_regions(&black, 120, 80, reach, building);
            // Which of L, F, B, C, D, E stay, by one pixel of each.
            [(20, 11), (31, 31), (60, 60), (70, 11), (90, 11), (104, 40)]
                .map(|(x, y)| keep[black.labels[y * 120 + x] as usize])
        };
        let kept = |reach: Option<u8>| kept_with(reach, None);
        assert_eq!(kept(None), [true, true, false, false, false, false]);
        assert_eq!(kept(Some(3)), [true, true, false, false, false, false]);
        assert_eq!(kept(Some(4)), [true, true, false, true, true, false]);
        // One building: the box, then the larger of the two reaches (B's ink is 21 px from
        // F's, chessboard); never the frame.
        assert_eq!(
            kept_with(None, Some(4)),
            [true, true, false, true, true, false]
        );
        assert_eq!(
            kept_with(Some(3), Some(20)),
            [true, true, false, true, true, false]
        );
        assert_eq!(
            kept_with(Some(3), Some(21)),
            [true, true, true, true, true, false]
        );
    }
}
