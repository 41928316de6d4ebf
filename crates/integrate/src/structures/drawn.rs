//! Each straight piece of a wall run laid on the wall as drawn (issue 25: "the thickness
//! measured from the drawing"). A run's centreline joins its edges' fits, and one thickness —
//! the median of its edges' — stood for all of it; but a curtain thickens by a tower and
//! thins along a range, and the fitted line between two vertices need not run down the
//! middle of the ink. Here each piece is measured on the plan's wall mask across its length:
//! how far the ink reaches on either side of it. The piece is moved to the middle of the drawn
//! wall and takes the drawn width; neighbouring pieces meet where their moved lines cross.
//!
//! Departure from §5.3 (which extrudes the labelled pixels as they are): the wall stays one
//! straight box per piece, so the model is still read from the fits, only measured piece by
//! piece.

use plan::thin::Mask;

/// Cross-sections are taken this far apart along a piece (pixels), and not within this share
/// of its length of either end, where the neighbouring piece's ink (a corner, a tower) widens
/// the wall.
const STEP: f64 = 1.0;
const END_SHARE: f64 = 0.15;
/// A cross-section that runs on beyond this many of the run's thicknesses on one side has
/// left along another wall (a junction), and says nothing of this one's width. Over the 34
/// shared plans (median plan–model IoU): 0.8, 0.787; 1.0, 0.802; 1.2, 0.794; 1.5, 0.783.
const REACH: f64 = 1.0;
/// A piece is measured when at least this share of its cross-sections found both faces.
const MEASURED_SHARE: f64 = 0.4;
/// A piece's drawn width is kept within these multiples of its run's thickness, and its
/// centreline moves by at most this share of it: the run's fits still place the wall.
const WIDTH_WITHIN: [f64; 2] = [0.5, 2.0];
const MOVE_WITHIN: f64 = 0.5;

/// How far the drawn wall reaches on the left and on the right of the piece `a`–`b` (as the
/// drawing is seen, y down), the medians over its cross-sections; `None` when too few
/// cross-sections cross it cleanly.
pub(super) fn sides(walls: &Mask, a: [f64; 2], b: [f64; 2], thickness: f64) -> Option<[f64; 2]> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy);
    if len < 2.0 * STEP {
        return None;
    }
    let (ux, uy) = (dx / len, dy / len);
    let left = [uy, -ux];
    let inked = |p: [f64; 2]| walls.get(p[0].round() as i32, p[1].round() as i32) > 0;
    let limit = REACH * thickness.max(1.0) + 2.0;
    // Distance along `dir` from `p` to the ink's edge: sampled every half pixel, a quarter off
    // the pixel grid, so that an edge between pixel centres is found exactly along an axis.
    let reach = |p: [f64; 2], dir: [f64; 2]| -> Option<f64> {
        let mut d = 0.25;
        while d <= limit {
            if !inked([p[0] + dir[0] * d, p[1] + dir[1] * d]) {
                return Some(d - 0.25);
            }
            d += 0.5;
        }
        None
    };
    let start = END_SHARE * len;
    let count = (((1.0 - 2.0 * END_SHARE) * len) / STEP).floor() as usize + 1;
    let (mut l, mut r) = (Vec::new(), Vec::new());
    for k in 0..count {
        let t = start + k as f64 * STEP;
        let p = [a[0] + ux * t, a[1] + uy * t];
        if !inked(p) {
            continue;
        }
        if let (Some(dl), Some(dr)) = (reach(p, left), reach(p, [-left[0], -left[1]])) {
            l.push(dl);
            r.push(dr);
        }
    }
    if (l.len() as f64) < MEASURED_SHARE * count as f64 {
        return None;
    }
    Some([median(&mut l), median(&mut r)])
}

/// The median, halfway between the middle two of an even count (the cross-sections' widths
/// are in half pixels: `roles::median`'s upper one moves the docs' figures, 0.801 → 0.800).
fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

/// The run's centreline moved piece by piece onto the middle of the drawn wall, and each
/// piece's drawn width (in `pieces` order: the closing piece of a ring last). A piece that
/// cannot be measured keeps its place and the run's thickness.
pub(super) fn onto_ink(
    walls: &Mask,
    points: &[[f64; 2]],
    closed: bool,
    thickness: f64,
) -> (Vec<[f64; 2]>, Vec<f64>) {
    let n = points.len();
    let closed = closed && n > 2;
    let pieces = if closed { n } else { n.saturating_sub(1) };
    if pieces == 0 {
        return (points.to_vec(), Vec::new());
    }
    let piece = |k: usize| (points[k], points[(k + 1) % n]);
    // Per piece: its left normal, its offset along it, its width.
    let mut shifts: Vec<([f64; 2], f64)> = Vec::with_capacity(pieces);
    let mut widths = Vec::with_capacity(pieces);
    for k in 0..pieces {
        let (a, b) = piece(k);
        let len = (b[0] - a[0]).hypot(b[1] - a[1]).max(1e-9);
        let normal = [(b[1] - a[1]) / len, -(b[0] - a[0]) / len];
        match sides(walls, a, b, thickness) {
            Some([l, r]) => {
                let width = (l + r).clamp(WIDTH_WITHIN[0] * thickness, WIDTH_WITHIN[1] * thickness);
                let move_by = MOVE_WITHIN * thickness;
                shifts.push((normal, ((l - r) / 2.0).clamp(-move_by, move_by)));
                widths.push(width);
            }
            None => {
                shifts.push((normal, 0.0));
                widths.push(thickness);
            }
        }
    }
    let moved = |k: usize, p: [f64; 2]| {
        let (nrm, o) = shifts[k];
        [p[0] + nrm[0] * o, p[1] + nrm[1] * o]
    };
    let mut out = Vec::with_capacity(n);
    for (i, &point) in points.iter().enumerate() {
        // The pieces that meet at point i: the one before (ending there) and the one after.
        let before = if i > 0 {
            Some(i - 1)
        } else if closed {
            Some(pieces - 1)
        } else {
            None
        };
        let after = (i < pieces).then_some(i);
        out.push(match (before, after) {
            (Some(kb), Some(ka)) => {
                let (a0, b0) = piece(kb);
                let (a1, b1) = piece(ka);
                meet(moved(kb, a0), moved(kb, b0), moved(ka, a1), moved(ka, b1))
                    .filter(|m| (m[0] - point[0]).hypot(m[1] - point[1]) <= thickness)
                    .unwrap_or_else(|| {
                        let (p, q) = (moved(kb, point), moved(ka, point));
                        [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0]
                    })
            }
            (Some(k), None) | (None, Some(k)) => moved(k, point),
            (None, None) => point,
        });
    }
    (out, widths)
}

/// Where the line through `a`–`b` crosses the line through `c`–`d`; `None` when they are
/// nearly parallel.
fn meet(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> Option<[f64; 2]> {
    let (r, s) = ([b[0] - a[0], b[1] - a[1]], [d[0] - c[0], d[1] - c[1]]);
    let cross = r[0] * s[1] - r[1] * s[0];
    let scale = r[0].hypot(r[1]) * s[0].hypot(s[1]);
    if cross.abs() <= 0.05 * scale {
        return None;
    }
    let t = ((c[0] - a[0]) * s[1] - (c[1] - a[1]) * s[0]) / cross;
    Some([a[0] + r[0] * t, a[1] + r[1] * t])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A mask from rows of `#` (wall) and `.` (paper).
    fn mask(rows: &[&str]) -> Mask {
        let mut m = Mask::new(rows[0].len() as u32, rows.len() as u32);
        for (y, row) in rows.iter().enumerate() {
            for (x, c) in row.chars().enumerate() {
                m.data[y * rows[0].len() + x] = u8::from(c == '#');
            }
        }
        m
    }

    /// A wall 6 px thick (rows 4–9) across a 40 × 14 sheet, with a cross wall from row 0 to
    /// the wall at x = 20..24.
    fn sheet() -> Mask {
        let mut rows: Vec<String> = Vec::new();
        for y in 0..14 {
            let row: String = (0..40)
                .map(|x| {
                    let wall = (4..10).contains(&y) || (y < 4 && (20..24).contains(&x));
                    if wall { '#' } else { '.' }
                })
                .collect();
            rows.push(row);
        }
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        mask(&refs)
    }

    #[test]
    fn a_piece_off_the_middle_of_its_wall_reads_both_faces() {
        // Pixel rows 4..=9 are ink, the wall's faces at y = 3.5 and 9.5: from y = 5 it reaches
        // 1.5 px up (the left of a piece drawn rightwards) and 4.5 down.
        let [left, right] = sides(&sheet(), [2.0, 5.0], [38.0, 5.0], 4.0).unwrap();
        assert_eq!((left, right), (1.5, 4.5));
        // The 4 of its 26 cross-sections through the cross wall (x = 20..=23) reach 5.5 up,
        // to the sheet's edge: the medians are the plain wall's.
    }

    #[test]
    fn a_piece_on_paper_is_not_measured() {
        assert_eq!(sides(&sheet(), [2.0, 12.0], [38.0, 12.0], 4.0), None);
        // Too short to cross.
        assert_eq!(sides(&sheet(), [2.0, 6.0], [3.0, 6.0], 4.0), None);
    }

    #[test]
    fn a_run_moves_onto_the_middle_of_the_ink_and_takes_its_width() {
        let (points, widths) = onto_ink(&sheet(), &[[2.0, 5.0], [38.0, 5.0]], false, 4.0);
        // Moved by (1.5 − 4.5) / 2 = −1.5 along the left normal (0, −1): down to y = 6.5, the
        // middle of the faces at 3.5 and 9.5; 6 px wide.
        assert_eq!(points, vec![[2.0, 6.5], [38.0, 6.5]]);
        assert_eq!(widths, vec![6.0]);
    }

    #[test]
    fn moves_and_widths_stay_within_the_runs_thickness() {
        // A run said to be 2.8 px thick on the 6 px wall: at most 2 × 2.8 wide, moved down by at
        // most half of 2.8.
        let (points, widths) = onto_ink(&sheet(), &[[2.0, 5.0], [38.0, 5.0]], false, 2.8);
        assert_eq!(widths, vec![2.0 * 2.8]);
        assert_eq!(points[0], [2.0, 5.0 + 0.5 * 2.8]);
        // Said to be 2 px thick, the 4.5 px down are beyond the reach (1 × 2 + 2): not measured,
        // it keeps its place and thickness.
        let (points, widths) = onto_ink(&sheet(), &[[2.0, 5.0], [38.0, 5.0]], false, 2.0);
        assert_eq!((points[0], widths), ([2.0, 5.0], vec![2.0]));
    }

    #[test]
    fn neighbouring_pieces_meet_where_their_moved_lines_cross() {
        // An L of two walls 5 px thick: rows 2..7 from x = 2 to 21, and columns 17..22 from
        // y = 2 to 29. The run's centreline is drawn a pixel outside both.
        let rows: Vec<String> = (0..32)
            .map(|y| {
                (0..26)
                    .map(|x| {
                        let top = (2..7).contains(&y) && (2..22).contains(&x);
                        let side = (17..22).contains(&x) && (2..30).contains(&y);
                        if top || side { '#' } else { '.' }
                    })
                    .collect()
            })
            .collect();
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        let (points, widths) = onto_ink(
            &mask(&refs),
            &[[2.0, 3.0], [20.0, 3.0], [20.0, 29.0]],
            false,
            5.0,
        );
        assert_eq!(widths, vec![5.0, 5.0]);
        // The top piece moves to y = 4 (pixel rows 2..=6), the side one to x = 19 (17..=21):
        // the corner is where those lines cross.
        assert_eq!(points, vec![[2.0, 4.0], [19.0, 4.0], [19.0, 29.0]]);
    }

    #[test]
    fn a_ring_moves_every_corner() {
        // A square ring 4 px thick (pixels 2..=5 and 22..=25 on each side) whose centreline
        // is drawn on its inner face: every corner moves out to the wall's middle.
        let rows: Vec<String> = (0..28)
            .map(|y| {
                (0..28)
                    .map(|x| {
                        let band = |v: i32| (2..6).contains(&v) || (22..26).contains(&v);
                        let inside = (2..26).contains(&x) && (2..26).contains(&y);
                        if inside && (band(x) || band(y)) {
                            '#'
                        } else {
                            '.'
                        }
                    })
                    .collect()
            })
            .collect();
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        let square = [[5.0, 5.0], [22.0, 5.0], [22.0, 22.0], [5.0, 22.0]];
        let (points, widths) = onto_ink(&mask(&refs), &square, true, 4.0);
        assert_eq!(widths, vec![4.0; 4]);
        assert_eq!(
            points,
            vec![[3.5, 3.5], [23.5, 3.5], [23.5, 23.5], [3.5, 23.5]]
        );
    }
}
