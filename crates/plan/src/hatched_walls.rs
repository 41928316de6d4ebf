//! Hatched walls made solid: an addition to §5.1.2, which assumes walls drawn solid (or as
//! outlines whose small inner specks step (2) fills). Engraved plans draw walls as two
//! outlines with parallel hatch strokes between them (Loftie's White Tower); step (4)'s
//! opening then erases the thin strokes and outlines, and the wall is lost.
//!
//! A hatch pattern is recognised along image rows and columns: a run of at least
//! [`HatchParams::min_gaps`] paper gaps of nearly equal length, each between thin ink runs.
//! Rooms break such a run (their width is far above the pattern's gaps), and so do thick
//! walls; a corridor is two walls, not a pattern. A paper pixel is filled when it lies in a
//! pattern along its row *and* its column, with gaps of similar length: the strokes run
//! diagonally, the engravers' convention for cut walls. Viollet-le-Duc shades water, ground
//! and roofs with horizontal lines and draws stairs as lines square to the sheet (Provins,
//! Carcassonne, Narbonne): one direction sees those, not both.

use image::GrayImage;

/// How a hatch pattern looks along a row or column, in pixels of the thresholded drawing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HatchParams {
    /// Widest ink run that is a hatch stroke (wider ink is a wall or an outline).
    pub max_stroke: usize,
    /// Longest paper gap between two strokes of a pattern.
    pub max_gap: usize,
    /// Gaps needed in one run of the pattern.
    pub min_gaps: usize,
    /// A gap belongs to its run's pattern when its length is within this factor of the
    /// run's median gap (broken strokes make double gaps; letters make uneven ones).
    pub regularity: f64,
    /// Largest ratio of a pixel's row gap to its column gap (either way round): 1 for
    /// strokes at 45°, 2 for strokes at about 27° or 63° to the rows.
    pub max_skew: f64,
}

impl HatchParams {
    /// The pattern's size follows the drawing's: engraved hatching is a few tenths of a
    /// millimetre apart whatever the building, so its gaps scale with the sheet, not with
    /// the walls (which the hatching hides from `wall_thickness`). Chosen on Loftie's White
    /// Tower enlarged to 1300 px (strokes 2–4 px, gaps 8–14 px along rows) and measured on
    /// the development set (docs/plan.md).
    pub fn for_sheet(long_side: u32) -> Self {
        let long = long_side as usize;
        HatchParams {
            max_stroke: (long / 260).clamp(2, 10),
            max_gap: (long / 80).clamp(6, 32),
            min_gaps: 3,
            regularity: 1.8,
            max_skew: 2.0,
        }
    }
}

/// Fills the paper gaps of hatch patterns (ink = 255) along every row and column, so that a
/// hatched wall becomes solid before §5.1.2's steps. Returns the pixels filled.
pub fn fill_hatching(img: &mut GrayImage, params: &HatchParams) -> usize {
    let gaps = hatch_gaps(img, params);
    for (p, &g) in img.pixels_mut().zip(&gaps) {
        if g {
            p[0] = 255;
        }
    }
    gaps.iter().filter(|&&g| g).count()
}

/// The share of the sheet that [`fill_hatching`] would fill, without filling it: drawings
/// whose walls are hatched stand out (Loftie's White Tower 6.8 %; among the other 235
/// castle plans the most is 3.3 %, contour lines of a Roche-Pont map).
pub fn hatch_share(img: &GrayImage, params: &HatchParams) -> f64 {
    let n = hatch_gaps(img, params).iter().filter(|&&g| g).count();
    n as f64 / (img.width() as f64 * img.height() as f64).max(1.0)
}

/// Paper pixels in a diagonal hatch pattern: in a pattern along their row and their column,
/// with gap lengths within [`HatchParams::max_skew`] of each other.
fn hatch_gaps(img: &GrayImage, params: &HatchParams) -> Vec<bool> {
    let (w, h) = (img.width() as usize, img.height() as usize);
    let ink: Vec<bool> = img.pixels().map(|p| p[0] == 255).collect();
    // Length of the pattern gap each pixel lies in along its row and its column (0: none).
    let mut row_gap = vec![0u32; w * h];
    let mut col_gap = vec![0u32; w * h];
    let mut line = Vec::with_capacity(w.max(h));
    let mut gaps = Vec::with_capacity(w.max(h));
    for y in 0..h {
        line.clear();
        line.extend_from_slice(&ink[y * w..(y + 1) * w]);
        pattern_gaps(&line, params, &mut gaps);
        row_gap[y * w..(y + 1) * w].copy_from_slice(&gaps);
    }
    for x in 0..w {
        line.clear();
        line.extend((0..h).map(|y| ink[y * w + x]));
        pattern_gaps(&line, params, &mut gaps);
        for (y, &g) in gaps.iter().enumerate() {
            col_gap[y * w + x] = g;
        }
    }
    row_gap
        .iter()
        .zip(&col_gap)
        .map(|(&r, &c)| {
            let (r, c) = (f64::from(r), f64::from(c));
            r > 0.0 && c > 0.0 && r.max(c) <= params.max_skew * r.min(c)
        })
        .collect()
}

/// A maximal stretch of one value along a line.
#[derive(Debug, Clone, Copy)]
struct Run {
    ink: bool,
    start: usize,
    len: usize,
}

fn runs(line: &[bool]) -> Vec<Run> {
    let mut out: Vec<Run> = Vec::new();
    for (i, &v) in line.iter().enumerate() {
        match out.last_mut() {
            Some(r) if r.ink == v => r.len += 1,
            _ => out.push(Run {
                ink: v,
                start: i,
                len: 1,
            }),
        }
    }
    out
}

/// Writes into `gaps`, for each pixel of `line`, the length of the hatch-pattern gap it lies
/// in (0 for none). A pattern is consecutive
/// gaps no longer than `max_gap`, each bounded by ink and separated by strokes no wider than
/// `max_stroke` (the pattern may end on a wide outline), at least `min_gaps` of them within
/// `regularity` of their median.
fn pattern_gaps(line: &[bool], p: &HatchParams, gaps: &mut Vec<u32>) {
    gaps.clear();
    gaps.resize(line.len(), 0);
    let rs = runs(line);
    let mut pattern: Vec<Run> = Vec::new();
    let flush = |pattern: &mut Vec<Run>, gaps: &mut Vec<u32>| {
        if pattern.len() >= p.min_gaps {
            let mut lens: Vec<usize> = pattern.iter().map(|r| r.len).collect();
            lens.sort_unstable();
            let median = lens[lens.len() / 2] as f64;
            let regular = |r: &Run| {
                let l = r.len as f64;
                l <= p.regularity * median && l * p.regularity >= median
            };
            if pattern.iter().filter(|r| regular(r)).count() >= p.min_gaps {
                for r in pattern.iter().filter(|r| regular(r)) {
                    gaps[r.start..r.start + r.len].fill(r.len as u32);
                }
            }
        }
        pattern.clear();
    };
    // The first and last runs touch the sheet's edge: no gap there is bounded by ink.
    for r in rs.iter().skip(1).take(rs.len().saturating_sub(2)) {
        if r.ink {
            if r.len > p.max_stroke {
                flush(&mut pattern, gaps);
            }
        } else if r.len <= p.max_gap {
            pattern.push(*r);
        } else {
            flush(&mut pattern, gaps);
        }
    }
    flush(&mut pattern, gaps);
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Luma;
    use raster::morphology::{Norm, open_close};

    fn params() -> HatchParams {
        HatchParams {
            max_stroke: 3,
            max_gap: 8,
            min_gaps: 3,
            regularity: 1.8,
            max_skew: 2.0,
        }
    }

    fn gaps(s: &str) -> String {
        let line: Vec<bool> = s.chars().map(|c| c == '#').collect();
        let mut g = Vec::new();
        pattern_gaps(&line, &params(), &mut g);
        g.iter()
            .map(|&n| char::from_digit(n, 10).unwrap_or('+'))
            .collect()
    }

    #[test]
    fn even_gaps_between_strokes_are_a_pattern() {
        assert_eq!(
            gaps("..#####....#....#...#....######.."),
            "000000044440444403330444400000000"
        );
    }

    #[test]
    fn two_gaps_a_room_or_a_thick_stroke_are_not() {
        assert_eq!(gaps("..####....#....####.."), "000000000000000000000");
        assert_eq!(
            gaps("..##..................##.."),
            "00000000000000000000000000"
        );
        // The strokes are as wide as walls: a row of small cells, not hatching.
        assert_eq!(
            gaps("..####....####....####....####.."),
            "00000000000000000000000000000000"
        );
    }

    #[test]
    fn an_uneven_gap_leaves_the_pattern_the_rest_stays() {
        // A 1-px gap (two strokes touching) is not within 1.8 of the median 4.
        assert_eq!(gaps("#....#....#.#....#"), "044440444400044440");
    }

    #[test]
    fn gaps_open_to_the_sheet_edge_are_not_bounded() {
        assert_eq!(gaps("....#....#....#....#...."), "000004444044440444400000");
    }

    /// A 120 × 80 sheet: a wall 24 px thick drawn as two 1-px outlines (rows 20 and 43)
    /// joined by 1-px hatch strokes every 6 px (diagonal, or `square`: vertical), and below
    /// it a 20-px room drawn with 1-px walls.
    fn hatched_wall_and_room(square: bool) -> GrayImage {
        GrayImage::from_fn(120, 80, |x, y| {
            let (x, y) = (x as i32, y as i32);
            let outline = (y == 20 || y == 43) && (10..110).contains(&x);
            let ends = (x == 10 || x == 109) && (20..=43).contains(&y);
            let phase = if square { x } else { x + y };
            let hatch = (21..43).contains(&y) && (10..110).contains(&x) && phase % 6 == 0;
            let room = ((y == 50 || y == 70) && (30..=60).contains(&x))
                || ((x == 30 || x == 60) && (50..=70).contains(&y));
            Luma([if outline || ends || hatch || room {
                255
            } else {
                0
            }])
        })
    }

    #[test]
    fn diagonal_hatching_becomes_solid_a_room_stays_open() {
        let mut img = hatched_wall_and_room(false);
        // Without the step the opening of §5.1.2 (4) erases the 1-px outlines and hatching.
        let opened = open_close(&img, Norm::LInf, 1);
        assert_eq!(opened.get_pixel(50, 30)[0], 0);
        let filled = fill_hatching(&mut img, &params());
        // The band's paper (less its strokes) is filled, but for gaps against the outlines
        // too short for the pattern's 5-px gaps; step (2) of §5.1.2 fills those as specks.
        let paper = (11..109)
            .flat_map(|x| (21..43).map(move |y| (x, y)))
            .filter(|&(x, y)| (x + y) % 6 != 0)
            .count();
        assert!(
            filled <= paper && 10 * filled >= 8 * paper,
            "{filled} of {paper}"
        );
        let opened = open_close(&img, Norm::LInf, 1);
        for x in 14..106 {
            for y in 23..41 {
                assert_eq!(opened.get_pixel(x, y)[0], 255, "wall at ({x}, {y})");
            }
        }
        for x in 31..60 {
            for y in 51..70 {
                assert_eq!(img.get_pixel(x, y)[0], 0, "the room at ({x}, {y})");
            }
        }
        assert_eq!(img.get_pixel(5, 5)[0], 0, "the paper around");
    }

    #[test]
    fn lines_square_to_the_sheet_stay_lines() {
        // Vertical strokes: a pattern along rows only (stairs, or water shaded in lines).
        let mut img = hatched_wall_and_room(true);
        assert_eq!(fill_hatching(&mut img, &params()), 0);
    }
}
