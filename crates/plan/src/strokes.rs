//! Shape of small regions (strokes of ink) from their second moments, and a grid to find
//! their neighbours: shared by the clean-up steps added to §5.1.2 that recognise patterns of
//! strokes ([`crate::hachure_bands`], [`crate::dashes`]).

use raster::components::Components;

/// A region seen as a bar: centroid, direction of its long axis, length and width.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stroke {
    /// Label of the region in the [`Components`] it came from.
    pub(crate) label: u32,
    pub(crate) centre: [f64; 2],
    /// Direction of the long axis, radians in [0, π).
    pub(crate) angle: f64,
    /// A uniform bar of length L has variance L² / 12 along its axis, so L = √(12 λ₁).
    pub(crate) length: f64,
    pub(crate) width: f64,
}

impl Stroke {
    pub(crate) fn elongation(&self) -> f64 {
        self.length / self.width.max(1.0)
    }

    /// Unit vector along the long axis.
    pub(crate) fn axis(&self) -> [f64; 2] {
        [self.angle.cos(), self.angle.sin()]
    }

    /// The offset to `other`'s centre split into (along this axis, across it), both ≥ 0.
    pub(crate) fn offset(&self, other: &Stroke) -> (f64, f64) {
        let d = [
            other.centre[0] - self.centre[0],
            other.centre[1] - self.centre[1],
        ];
        let a = self.axis();
        let along = d[0] * a[0] + d[1] * a[1];
        let across = -d[0] * a[1] + d[1] * a[0];
        (along.abs(), across.abs())
    }
}

/// Difference of two axis directions, in [0, π/2].
pub(crate) fn angle_between(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::PI);
    d.min(std::f64::consts::PI - d)
}

/// The bar shape of every region `wanted` selects (by label), from one pass over the labels.
pub(crate) fn strokes(c: &Components, width: usize, wanted: impl Fn(usize) -> bool) -> Vec<Stroke> {
    let n = c.sizes.len();
    let take: Vec<bool> = (0..n).map(|l| l > 0 && wanted(l)).collect();
    // Sums of x, y, x², y², xy relative to the bounding box corner (keeps the sums small).
    let mut m = vec![[0.0f64; 5]; n];
    for (i, &l) in c.labels.iter().enumerate() {
        let l = l as usize;
        if !take[l] {
            continue;
        }
        let x = (i % width) as f64 - f64::from(c.bbox[l][0]);
        let y = (i / width) as f64 - f64::from(c.bbox[l][1]);
        let s = &mut m[l];
        s[0] += x;
        s[1] += y;
        s[2] += x * x;
        s[3] += y * y;
        s[4] += x * y;
    }
    (1..n)
        .filter(|&l| take[l])
        .map(|l| {
            let a = c.sizes[l] as f64;
            let (mx, my) = (m[l][0] / a, m[l][1] / a);
            let sxx = m[l][2] / a - mx * mx + 1.0 / 12.0;
            let syy = m[l][3] / a - my * my + 1.0 / 12.0;
            let sxy = m[l][4] / a - mx * my;
            let half = (sxx + syy) / 2.0;
            let root = (((sxx - syy) / 2.0).powi(2) + sxy * sxy).sqrt();
            let (l1, l2) = (half + root, (half - root).max(1.0 / 12.0));
            Stroke {
                label: l as u32,
                centre: [mx + f64::from(c.bbox[l][0]), my + f64::from(c.bbox[l][1])],
                angle: (0.5 * (2.0 * sxy).atan2(sxx - syy)).rem_euclid(std::f64::consts::PI),
                length: (12.0 * l1).sqrt(),
                width: (12.0 * l2).sqrt(),
            }
        })
        .collect()
}

/// Buckets of stroke indices on a square grid, so a neighbour search looks at nine cells.
pub(crate) struct Grid {
    cell: f64,
    cols: usize,
    rows: usize,
    cells: Vec<Vec<usize>>,
}

impl Grid {
    pub(crate) fn new(strokes: &[Stroke], width: usize, height: usize, cell: f64) -> Grid {
        let cell = cell.max(1.0);
        let cols = (width as f64 / cell).ceil().max(1.0) as usize;
        let rows = (height as f64 / cell).ceil().max(1.0) as usize;
        let mut cells = vec![Vec::new(); cols * rows];
        for (i, s) in strokes.iter().enumerate() {
            let (cx, cy) = Self::cell_of(s.centre, cell, cols, rows);
            cells[cy * cols + cx].push(i);
        }
        Grid {
            cell,
            cols,
            rows,
            cells,
        }
    }

    fn cell_of(p: [f64; 2], cell: f64, cols: usize, rows: usize) -> (usize, usize) {
        let cx = ((p[0] / cell).max(0.0) as usize).min(cols - 1);
        let cy = ((p[1] / cell).max(0.0) as usize).min(rows - 1);
        (cx, cy)
    }

    /// Indices of the strokes within `radius` (at most the cell size) of `p`, `p`'s own included.
    pub(crate) fn near(&self, strokes: &[Stroke], p: [f64; 2], radius: f64) -> Vec<usize> {
        let (cx, cy) = Self::cell_of(p, self.cell, self.cols, self.rows);
        let mut out = Vec::new();
        for y in cy.saturating_sub(1)..=(cy + 1).min(self.rows - 1) {
            for x in cx.saturating_sub(1)..=(cx + 1).min(self.cols - 1) {
                for &i in &self.cells[y * self.cols + x] {
                    let c = strokes[i].centre;
                    if (c[0] - p[0]).hypot(c[1] - p[1]) <= radius {
                        out.push(i);
                    }
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{GrayImage, Luma};
    use raster::components::{Connectivity, components};

    #[test]
    fn a_diagonal_bar_has_its_length_width_and_direction() {
        // A 2-px wide bar of 20 px along the diagonal x = y.
        let img = GrayImage::from_fn(30, 30, |x, y| {
            Luma([if x < 22 && (x as i32 - y as i32).abs() <= 0 {
                255
            } else {
                0
            }])
        });
        let c = components(&img, 255, Connectivity::Eight);
        let s = strokes(&c, 30, |_| true);
        assert_eq!(s.len(), 1);
        assert!(
            (s[0].angle - std::f64::consts::FRAC_PI_4).abs() < 0.05,
            "{:?}",
            s[0]
        );
        assert!((s[0].length - 22.0 * 2f64.sqrt()).abs() < 3.0, "{:?}", s[0]);
        assert!(s[0].elongation() > 10.0);
        assert!(angle_between(0.1, std::f64::consts::PI - 0.1) < 0.21);
    }
}
