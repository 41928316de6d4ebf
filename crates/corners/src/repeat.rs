//! The evaluation of §2.2: the modified repeatability rate (eq. 2.10 with 1-to-1 mutual
//! nearest neighbours under the forward and inverse homography, r₀ = 5), counted over the
//! region both images see, and the Oxford `H1toNp` homography format.

use std::collections::HashMap;

use nalgebra::Matrix3;

use crate::error::Error;

/// A plane homography x₂ ~ H x₁ in homogeneous pixel coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Homography(pub [[f64; 3]; 3]);

impl Homography {
    pub const IDENTITY: Homography =
        Homography([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);

    /// Parses the Oxford text format: nine numbers, row by row, separated by white space
    /// (`8.7976964e-01` and `-1.14E-4` styles both occur).
    pub fn parse(text: &str) -> Result<Self, Error> {
        let nums: Vec<f64> = text
            .split_whitespace()
            .map(|t| {
                t.parse::<f64>()
                    .map_err(|_| Error::BadHomography(format!("'{t}' is not a number")))
            })
            .collect::<Result<_, _>>()?;
        if nums.len() != 9 {
            return Err(Error::BadHomography(format!(
                "expected 9 numbers, found {}",
                nums.len()
            )));
        }
        if nums.iter().any(|v| !v.is_finite()) {
            return Err(Error::BadHomography("numbers must be finite".into()));
        }
        let h = Homography([
            [nums[0], nums[1], nums[2]],
            [nums[3], nums[4], nums[5]],
            [nums[6], nums[7], nums[8]],
        ]);
        h.inverse()
            .ok_or_else(|| Error::BadHomography("the matrix is singular".into()))?;
        Ok(h)
    }

    /// Maps a point; None when it goes to infinity.
    pub fn apply(&self, p: [f64; 2]) -> Option<[f64; 2]> {
        let m = &self.0;
        let w = m[2][0] * p[0] + m[2][1] * p[1] + m[2][2];
        if w.abs() < 1e-12 {
            return None;
        }
        Some([
            (m[0][0] * p[0] + m[0][1] * p[1] + m[0][2]) / w,
            (m[1][0] * p[0] + m[1][1] * p[1] + m[1][2]) / w,
        ])
    }

    pub fn inverse(&self) -> Option<Homography> {
        let m = Matrix3::from_fn(|i, j| self.0[i][j]);
        if m.determinant().abs() < 1e-300 {
            return None;
        }
        let inv = m.try_inverse()?;
        Some(Homography(std::array::from_fn(|i| {
            std::array::from_fn(|j| inv[(i, j)])
        })))
    }
}

/// The result for one image pair.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Repeatability {
    /// 1-to-1 correspondences (§2.2).
    pub correspondences: usize,
    /// Points of image 1 that map into image 2, and of image 2 that map back into image 1.
    pub n1: usize,
    pub n2: usize,
    /// correspondences / min(n1, n2) (eq. 2.10); 0 when either is empty.
    pub rate: f64,
}

/// Grid of points for fixed-radius nearest-neighbour queries.
struct Grid<'a> {
    cell: f64,
    pts: &'a [[f64; 2]],
    map: HashMap<(i64, i64), Vec<usize>>,
}

impl<'a> Grid<'a> {
    fn new(pts: &'a [[f64; 2]], cell: f64) -> Self {
        let mut map: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        for (i, p) in pts.iter().enumerate() {
            map.entry(Self::key(p, cell)).or_default().push(i);
        }
        Self { cell, pts, map }
    }

    fn key(p: &[f64; 2], cell: f64) -> (i64, i64) {
        ((p[0] / cell).floor() as i64, (p[1] / cell).floor() as i64)
    }

    /// The nearest point strictly closer than `cell` (ties go to the lower index).
    fn nearest(&self, q: [f64; 2]) -> Option<(usize, f64)> {
        let (kx, ky) = Self::key(&q, self.cell);
        let mut best: Option<(usize, f64)> = None;
        for dy in -1..=1 {
            for dx in -1..=1 {
                for &i in self.map.get(&(kx + dx, ky + dy)).into_iter().flatten() {
                    let p = self.pts[i];
                    let d = (p[0] - q[0]).hypot(p[1] - q[1]);
                    if d < self.cell && best.is_none_or(|(j, bd)| d < bd || (d == bd && i < j)) {
                        best = Some((i, d));
                    }
                }
            }
        }
        best
    }
}

fn inside(p: [f64; 2], size: (usize, usize)) -> bool {
    p[0] >= 0.0 && p[1] >= 0.0 && p[0] <= size.0 as f64 - 1.0 && p[1] <= size.1 as f64 - 1.0
}

/// Modified repeatability rate of §2.2 between points `p1` of an image of `size1` (width,
/// height) and `p2` of an image of `size2`, with x₂ ~ H x₁. s₁ and s₂ correspond iff s₂ is the
/// nearest point of image 2 to Hs₁, s₁ the nearest point of image 1 to H⁻¹s₂, and both distances
/// are below `r0`. Only points seen by both images count (s₁ with Hs₁ inside image 2, s₂ with
/// H⁻¹s₂ inside image 1).
pub fn repeatability(
    p1: &[[f64; 2]],
    size1: (usize, usize),
    p2: &[[f64; 2]],
    size2: (usize, usize),
    h: &Homography,
    r0: f64,
) -> Repeatability {
    let hinv = h.inverse().unwrap_or(Homography::IDENTITY);
    // Keep the common region: (original point, mapped point).
    let a: Vec<([f64; 2], [f64; 2])> = p1
        .iter()
        .filter_map(|&p| h.apply(p).filter(|&q| inside(q, size2)).map(|q| (p, q)))
        .collect();
    let b: Vec<([f64; 2], [f64; 2])> = p2
        .iter()
        .filter_map(|&p| hinv.apply(p).filter(|&q| inside(q, size1)).map(|q| (p, q)))
        .collect();
    let (n1, n2) = (a.len(), b.len());
    let r0 = r0.max(1e-9);
    let a_orig: Vec<[f64; 2]> = a.iter().map(|x| x.0).collect();
    let b_orig: Vec<[f64; 2]> = b.iter().map(|x| x.0).collect();
    let grid1 = Grid::new(&a_orig, r0);
    let grid2 = Grid::new(&b_orig, r0);
    let correspondences = a
        .iter()
        .enumerate()
        .filter(|(i, (_, hs1))| {
            grid2
                .nearest(*hs1)
                .and_then(|(j, _)| grid1.nearest(b[j].1))
                .is_some_and(|(k, _)| k == *i)
        })
        .count();
    let m = n1.min(n2);
    Repeatability {
        correspondences,
        n1,
        n2,
        rate: if m == 0 {
            0.0
        } else {
            correspondences as f64 / m as f64
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_both_oxford_styles() {
        let a = Homography::parse(
            "   8.7976964e-01   3.1245438e-01  -3.9430589e+01\n -1.8389418e-01 9.3847198e-01 1.5315784e+02\n 1.9641425e-04 -1.6015275e-05 1.0000000e+00\n",
        )
        .unwrap();
        assert!((a.0[0][2] + 39.430589).abs() < 1e-9);
        let b = Homography::parse(
            "0.78 0.01 28.1  \n-0.02 0.92 44.2  \n-1.1457814415224265E-4 1.28E-5 1.0  \n",
        )
        .unwrap();
        assert!((b.0[2][0] + 1.1457814415224265e-4).abs() < 1e-15);
        assert!(Homography::parse("1 2 3").is_err());
        assert!(Homography::parse("1 0 0 0 1 0 0 0 x").is_err());
        assert!(Homography::parse("0 0 0 0 0 0 0 0 0").is_err());
    }

    #[test]
    fn inverse_round_trips() {
        let h = Homography([[0.9, 0.1, 5.0], [-0.2, 1.1, 3.0], [1e-4, 2e-5, 1.0]]);
        let p = [123.0, 45.0];
        let q = h.inverse().unwrap().apply(h.apply(p).unwrap()).unwrap();
        assert!((q[0] - p[0]).abs() < 1e-9 && (q[1] - p[1]).abs() < 1e-9);
    }

    #[test]
    fn mutual_nearest_neighbours_are_one_to_one() {
        let size = (100, 100);
        // Two points of image 1 near one point of image 2: only one may match.
        let p1 = [[10.0, 10.0], [12.0, 10.0], [50.0, 50.0], [80.0, 80.0]];
        let p2 = [[11.5, 10.0], [50.0, 53.0], [20.0, 90.0]];
        let r = repeatability(&p1, size, &p2, size, &Homography::IDENTITY, 5.0);
        assert_eq!((r.correspondences, r.n1, r.n2), (2, 4, 3));
        assert!((r.rate - 2.0 / 3.0).abs() < 1e-12);
        // r0 is strict and a shift of 5 px is out of reach.
        let r = repeatability(
            &[[10.0, 10.0]],
            size,
            &[[15.0, 10.0]],
            size,
            &Homography::IDENTITY,
            5.0,
        );
        assert_eq!(r.correspondences, 0);
    }

    #[test]
    fn only_the_common_region_counts() {
        // Image 2 is image 1 shifted left by 50 px: points with x < 50 leave the frame.
        let h = Homography([[1.0, 0.0, -50.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        let p1 = [[10.0, 10.0], [60.0, 10.0], [70.0, 40.0]];
        let p2 = [[10.0, 10.0], [20.0, 40.0], [60.0, 60.0]];
        let r = repeatability(&p1, (100, 100), &p2, (100, 100), &h, 5.0);
        assert_eq!((r.n1, r.n2, r.correspondences), (2, 2, 2));
        assert_eq!(r.rate, 1.0);
        let empty = repeatability(&[], (10, 10), &p2, (100, 100), &h, 5.0);
        assert_eq!(empty.rate, 0.0);
    }
}
