//! Dotted and dashed lines joined into lines: an addition to §5.1.2, whose step (5) removes
//! black regions under 0.05 % of the image as specks, so walls and ward boundaries drawn
//! dotted or dashed (reconstructed or vanished walls) vanish and the wards they close stay
//! open (§5.2 item 4). Runs on the thresholded drawing before the specks are removed.

use image::GrayImage;

use crate::strokes::{Grid, Stroke, angle_between, strokes};
use raster::components::{Connectivity, components};

/// Directions that count as collinear differ by at most this (radians).
const ALIGNED: f64 = 0.26;
/// A dash is this many times longer than wide; a dot is less elongated than this.
const DASH: f64 = 2.0;

/// Links chains of three or more collinear, regularly spaced dashes or dots: an ink region
/// under `max_size` pixels, off the border, is a dash (elongated, at most `max_dash` long)
/// or a dot (at most `max_dot` across); two of the same kind and similar size (half to
/// twice) are neighbours in a line when the line between their centres runs along both
/// dashes (or, for dots, freely) and the gap is at most 1.5 dash lengths (4 dot sizes). A
/// neighbour pair is joined only when it is part of a chain of three — a middle stroke with
/// neighbours on opposite sides, the two steps collinear and of similar length (ratio
/// 2/3 – 3/2) — so letters of a word (not elongated along the word, or too large) and stray
/// pairs of specks are left alone. Each link is drawn as a bar `width` wide (at least the
/// strokes' own width), thick enough to survive step (4)'s 3 × 3 opening. Returns the
/// links drawn.
pub fn link_dashes(
    img: &mut GrayImage,
    max_size: usize,
    max_dash: f64,
    max_dot: f64,
    width: f64,
) -> usize {
    let (w, h) = (img.width() as usize, img.height() as usize);
    let ink = components(img, 255, Connectivity::Eight);
    let marks: Vec<Stroke> = strokes(&ink, w, |l| {
        (2..max_size).contains(&ink.sizes[l]) && !ink.touches_border(l, w, h)
    })
    .into_iter()
    .filter(|s| {
        if s.elongation() >= DASH {
            s.length <= max_dash
        } else {
            s.length <= max_dot
        }
    })
    .collect();
    if marks.len() < 3 {
        return 0;
    }
    let reach = (2.5 * max_dash).max(5.0 * max_dot);
    let grid = Grid::new(&marks, w, h, reach);
    let neighbours = |a: usize| -> Vec<usize> {
        let s = &marks[a];
        let dash = s.elongation() >= DASH;
        grid.near(&marks, s.centre, reach)
            .into_iter()
            .filter(|&b| {
                let o = &marks[b];
                if b == a || (o.elongation() >= DASH) != dash {
                    return false;
                }
                if o.length > 2.0 * s.length || s.length > 2.0 * o.length {
                    return false;
                }
                let d = [o.centre[0] - s.centre[0], o.centre[1] - s.centre[1]];
                let dist = d[0].hypot(d[1]);
                let dir = d[1].atan2(d[0]).rem_euclid(std::f64::consts::PI);
                if dash {
                    let gap = dist - (s.length + o.length) / 2.0;
                    gap <= 1.5 * s.length.max(o.length)
                        && angle_between(dir, s.angle) <= ALIGNED
                        && angle_between(dir, o.angle) <= ALIGNED
                } else {
                    dist <= 4.0 * s.length.max(o.length) + 2.0
                }
            })
            .collect()
    };
    let mut links: Vec<(usize, usize)> = Vec::new();
    for b in 0..marks.len() {
        let nb = neighbours(b);
        let c = marks[b].centre;
        let step = |a: usize| [marks[a].centre[0] - c[0], marks[a].centre[1] - c[1]];
        for (i, &a) in nb.iter().enumerate() {
            for &d in &nb[i + 1..] {
                let (u, v) = (step(a), step(d));
                let (lu, lv) = (u[0].hypot(u[1]), v[0].hypot(v[1]));
                let opposite = u[0] * v[0] + u[1] * v[1] < 0.0;
                let collinear = angle_between(u[1].atan2(u[0]), v[1].atan2(v[0])) <= ALIGNED;
                let even = lu <= 1.5 * lv && lv <= 1.5 * lu;
                if opposite && collinear && even {
                    links.push((a.min(b), a.max(b)));
                    links.push((d.min(b), d.max(b)));
                }
            }
        }
    }
    links.sort_unstable();
    links.dedup();
    for &(a, b) in &links {
        let r = (marks[a].width.max(marks[b].width).max(width) / 2.0).max(0.5);
        draw_bar(img, marks[a].centre, marks[b].centre, r);
    }
    links.len()
}

/// Sets every pixel within `r` of the segment from `p` to `q` to ink.
fn draw_bar(img: &mut GrayImage, p: [f64; 2], q: [f64; 2], r: f64) {
    let (w, h) = (img.width() as i64, img.height() as i64);
    let x0 = (p[0].min(q[0]) - r).floor().max(0.0) as i64;
    let x1 = ((p[0].max(q[0]) + r).ceil() as i64).min(w - 1);
    let y0 = (p[1].min(q[1]) - r).floor().max(0.0) as i64;
    let y1 = ((p[1].max(q[1]) + r).ceil() as i64).min(h - 1);
    let d = [q[0] - p[0], q[1] - p[1]];
    let len2 = (d[0] * d[0] + d[1] * d[1]).max(1e-9);
    for y in y0..=y1 {
        for x in x0..=x1 {
            let v = [x as f64 - p[0], y as f64 - p[1]];
            let t = ((v[0] * d[0] + v[1] * d[1]) / len2).clamp(0.0, 1.0);
            let e = [v[0] - t * d[0], v[1] - t * d[1]];
            if e[0].hypot(e[1]) <= r {
                img.put_pixel(x as u32, y as u32, image::Luma([255]));
            }
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use image::Luma;

    /// A 120 × 80 sheet: a dashed line (6 × 2 dashes every 10 px along row 20), a dotted one
    /// (2 × 2 dots every 6 px along column 100), a row of 12 × 12 "letters" every 16 px, and
    /// two stray dashes.
    pub(crate) fn sheet() -> GrayImage {
        GrayImage::from_fn(120, 80, |x, y| {
            let dashed = (20..22).contains(&y) && (10..90).contains(&x) && x % 10 < 6;
            let dotted = (100..102).contains(&x) && (10..70).contains(&y) && y % 6 < 2;
            let letters = (50..62).contains(&y) && (10..74).contains(&x) && (x - 10) % 16 < 12;
            let stray = (70..72).contains(&y) && ((20..26).contains(&x) || (30..36).contains(&x));
            Luma([if dashed || dotted || letters || stray {
                255
            } else {
                0
            }])
        })
    }

    #[test]
    fn dashes_and_dots_join_letters_and_stray_pairs_do_not() {
        let mut img = sheet();
        assert!(link_dashes(&mut img, 200, 20.0, 4.0, 3.0) >= 7 + 9);
        for x in 12..84 {
            assert_eq!(img.get_pixel(x, 21)[0], 255, "dashed line at x = {x}");
        }
        for y in 12..66 {
            assert_eq!(img.get_pixel(100, y)[0], 255, "dotted line at y = {y}");
        }
        assert_eq!(img.get_pixel(24, 55)[0], 0, "between letters");
        assert_eq!(img.get_pixel(28, 71)[0], 0, "between the stray dashes");
    }
}
