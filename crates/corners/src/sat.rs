//! Summed-area tables of the 15 scatter moments of eq. 2.3 (§2.1.2), one tile of window centres
//! at a time, so the first fit of every window costs four look-ups and one change of origin
//! instead of a pass over its edge points. Same sums as the direct pass, up to rounding.
//!
//! Precision: coordinates are taken from the tile's centre (at most TILE/2 + r pixels away) and
//! scaled like the fit's, so the x⁴ terms of the table stay within (TILE/2 + r)⁴ / r⁴ of a
//! window's own (TILE = 64, W = 13: (38/6)⁴ ≈ 1600); the four-corner difference and the
//! binomial shift to the window centre lose about seven of the sixteen digits of an `f64`,
//! far below the spread of real edge positions (the tests compare with a direct sum to 1e-10).

use crate::fit::Moments;

/// Side of a tile of window centres. Larger tiles amortise their margin of r pixels on each
/// side better (the table covers (TILE + 2r)² cells) but move the origin farther from the
/// windows; 64 keeps the table (76 × 76 cells of 128 bytes at W = 13) within a typical L2
/// cache and its build cost 1.4 × one pass over the pixels (32: 1.9 ×).
pub(crate) const TILE: usize = 64;

/// One point of the edge image Ê for the window fits: pixel column, sub-pixel position and
/// squared weight.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EdgePoint {
    pub col: isize,
    pub x: f64,
    pub y: f64,
    pub w2: f64,
}

/// Moments of one point (15 of them, and a count in the last lane).
#[inline(always)]
fn point_moments(x: f64, y: f64, w2: f64) -> [f64; 16] {
    let mut mo = Moments::default();
    mo.add(x, y, w2);
    let mut out = [0.0; 16];
    out[..15].copy_from_slice(&mo.m);
    out[15] = 1.0;
    out
}

/// The table of one tile, reused from tile to tile.
#[derive(Default)]
pub(crate) struct MomentTable {
    /// Image pixel of cell (0, 0) and the size of the covered region.
    x0: usize,
    y0: usize,
    width: usize,
    /// Coordinate origin (image pixels) and the fit's scale.
    origin: [f64; 2],
    inv_scale: f64,
    /// (height + 1) × (width + 1) prefix sums, the first row and column zero.
    table: Vec<[f64; 16]>,
}

impl MomentTable {
    /// Builds the table over pixels x0..x1, y0..y1 (exclusive) from the edge points of
    /// `rows` (one sorted vector per image row), coordinates taken from `origin` and divided
    /// by `scale`.
    pub fn build(
        &mut self,
        rows: &[Vec<EdgePoint>],
        (x0, x1): (usize, usize),
        (y0, y1): (usize, usize),
        origin: [f64; 2],
        scale: f64,
    ) {
        let width = x1 - x0;
        let stride = width + 1;
        self.x0 = x0;
        self.y0 = y0;
        self.width = width;
        self.origin = origin;
        self.inv_scale = 1.0 / scale;
        self.table.clear();
        self.table.resize(stride * (y1 - y0 + 1), [0.0; 16]);
        let s = self.inv_scale;
        for (j, row) in rows[y0..y1].iter().enumerate() {
            let start = row.partition_point(|p| (p.col as usize) < x0);
            let mut pts = row[start..].iter().peekable();
            let mut acc = [0.0f64; 16];
            let (above, here) = self.table[j * stride..(j + 2) * stride].split_at_mut(stride);
            for i in 0..width {
                // Ê is thinned: at most one point per pixel.
                if let Some(p) = pts.next_if(|p| p.col as usize == x0 + i) {
                    let m = point_moments((p.x - origin[0]) * s, (p.y - origin[1]) * s, p.w2);
                    for (a, v) in acc.iter_mut().zip(m) {
                        *a += v;
                    }
                }
                for ((o, a), b) in here[i + 1].iter_mut().zip(&acc).zip(&above[i + 1]) {
                    *o = a + b;
                }
            }
        }
    }

    /// Moments of the points in pixels x0..=x1, y0..=y1 (inside the built region), about
    /// `centre` (image pixels), coordinates divided by the scale.
    pub fn window(
        &self,
        (x0, x1): (usize, usize),
        (y0, y1): (usize, usize),
        centre: [f64; 2],
    ) -> Moments {
        let stride = self.width + 1;
        let at = |x: usize, y: usize| &self.table[(y - self.y0) * stride + (x - self.x0)];
        let (a, b, c, d) = (
            at(x1 + 1, y1 + 1),
            at(x0, y1 + 1),
            at(x1 + 1, y0),
            at(x0, y0),
        );
        let sum: [f64; 16] = std::array::from_fn(|k| (a[k] - b[k]) - (c[k] - d[k]));
        let dx = (centre[0] - self.origin[0]) * self.inv_scale;
        let dy = (centre[1] - self.origin[1]) * self.inv_scale;
        let mut m = [0.0; 15];
        m.copy_from_slice(&sum[..15]);
        Moments {
            n: sum[15].round() as usize,
            m: shifted(&m, dx, dy),
        }
    }
}

/// Moments about (dx, dy) from moments about the origin: Σ w (x − dx)ᵃ (y − dy)ᵇ expanded by
/// the binomial theorem, first along x, then along y (written out: this runs once per window).
fn shifted(m: &[f64; 15], dx: f64, dy: f64) -> [f64; 15] {
    // Positions of Σ xᵃ yᵇ by b (rows) and a (columns), see `moment_index`.
    const BY_B: [[usize; 5]; 5] = [
        [0, 1, 3, 6, 10],
        [2, 4, 7, 11, 0],
        [5, 8, 12, 0, 0],
        [9, 13, 0, 0, 0],
        [14, 0, 0, 0, 0],
    ];
    // Taylor shift of s₀ … s₄ (sₖ = Σ w tᵏ) to t − d, with u = −d.
    let taylor = |s: [f64; 5], u: f64| {
        let (u2, u3) = (u * u, u * u * u);
        [
            s[0],
            s[1] + u * s[0],
            s[2] + 2.0 * u * s[1] + u2 * s[0],
            s[3] + 3.0 * u * s[2] + 3.0 * u2 * s[1] + u3 * s[0],
            s[4] + 4.0 * u * s[3] + 6.0 * u2 * s[2] + 4.0 * u3 * s[1] + u2 * u2 * s[0],
        ]
    };
    let mut t = [0.0; 15];
    for (b, idx) in BY_B.iter().enumerate() {
        let n = 5 - b;
        let s: [f64; 5] = std::array::from_fn(|a| if a < n { m[idx[a]] } else { 0.0 });
        let r = taylor(s, -dx);
        for a in 0..n {
            t[idx[a]] = r[a];
        }
    }
    let mut out = [0.0; 15];
    for a in 0..5 {
        let n = 5 - a;
        let s: [f64; 5] = std::array::from_fn(|b| if b < n { t[BY_B[b][a]] } else { 0.0 });
        let r = taylor(s, -dy);
        for b in 0..n {
            out[BY_B[b][a]] = r[b];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn direct(points: &[EdgePoint], centre: [f64; 2], scale: f64) -> Moments {
        let mut mo = Moments::default();
        for p in points {
            mo.add((p.x - centre[0]) / scale, (p.y - centre[1]) / scale, p.w2);
        }
        mo
    }

    #[test]
    fn window_moments_match_a_direct_sum() {
        // A scattered set of sub-pixel points with uneven weights on a 50 × 40 image.
        let (w, h) = (50usize, 40usize);
        let mut rows: Vec<Vec<EdgePoint>> = vec![Vec::new(); h];
        for (y, row) in rows.iter_mut().enumerate() {
            for x in 0..w {
                if (x * 7 + y * 13) % 5 < 2 {
                    row.push(EdgePoint {
                        col: x as isize,
                        x: x as f64 + 0.3 * ((x + y) as f64).sin(),
                        y: y as f64 - 0.2 * ((x * y) as f64).cos(),
                        w2: 1.0 + (x % 9) as f64 * 3.7,
                    });
                }
            }
        }
        let scale = 6.0;
        let mut t = MomentTable::default();
        t.build(&rows, (3, 47), (2, 38), [25.0, 20.0], scale);
        for (x0, x1, y0, y1) in [
            (3, 15, 2, 14),
            (30, 46, 20, 37),
            (10, 10, 5, 5),
            (3, 46, 2, 37),
        ] {
            let centre = [(x0 + x1) as f64 / 2.0, (y0 + y1) as f64 / 2.0];
            let inside: Vec<EdgePoint> = rows[y0..=y1]
                .iter()
                .flatten()
                .filter(|p| (x0..=x1).contains(&(p.col as usize)))
                .copied()
                .collect();
            let want = direct(&inside, centre, scale);
            let got = t.window((x0, x1), (y0, y1), centre);
            assert_eq!(got.n, want.n);
            for k in 0..15 {
                let tol = 1e-10 * want.m[0].abs().max(1.0);
                assert!(
                    (got.m[k] - want.m[k]).abs() < tol,
                    "moment {k}: {} vs {}",
                    got.m[k],
                    want.m[k]
                );
            }
        }
    }

    #[test]
    fn shifting_moves_the_origin() {
        let pts = [[0.5, -1.0, 2.0], [1.5, 0.25, 1.0], [-2.0, 3.0, 0.5]];
        let mut about0 = Moments::default();
        let mut about_d = Moments::default();
        let (dx, dy) = (0.7, -1.3);
        for p in pts {
            about0.add(p[0], p[1], p[2]);
            about_d.add(p[0] - dx, p[1] - dy, p[2]);
        }
        let got = shifted(&about0.m, dx, dy);
        for (k, (g, d)) in got.iter().zip(&about_d.m).enumerate() {
            assert!((g - d).abs() < 1e-12, "{k}");
        }
    }
}
