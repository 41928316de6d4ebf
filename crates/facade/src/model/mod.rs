//! The parametric façade hierarchy (§3.1.5) under the assumptions of §3.1.6: a façade rectangle,
//! floors (ground, equal middle floors, top), and aligned windows — 18 parameters per façade —
//! plus the label image it implies and its merit F (§3.1.7).

use serde::{Deserialize, Serialize};

use crate::classify::{Class, LogLikelihoods};

/// Most floors per façade and windows per floor (§3.1.6).
pub const MAX_FLOORS: u32 = 10;
pub const MAX_WINDOWS: u32 = 10;
/// Most window columns per floor kind under `search::Grammar::Columns` (a departure from
/// §3.1.6's N_w ≤ 10: wide CMP façades have more).
pub const MAX_COLUMNS: u32 = 40;

/// Ω of §3.1.6, in pixels of the image parsed (x right, y down). Floors are counted from the
/// ground: floor 1 (height `h_1`) at the bottom, floor N_L (height `h_nl`) at the top, the
/// middle floors of equal height `h`. In every floor a window spans, upwards from `w_grd`
/// above the floor's bottom edge, a height `w_h`; `*_ground` are w'_h, w'_grd (floor 1) and
/// `*_top` are w''_h, w''_grd (floor N_L). Windows start `w_off` right of the façade's left edge,
/// are `w_w` wide and `w_gap` apart, `n_w` of them, in every floor with a non-zero window height.
/// A single-floor façade uses the ground-floor values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FacadeParams {
    pub x_fl: f64,
    pub y_ft: f64,
    pub x_fr: f64,
    pub y_fb: f64,
    pub h_1: f64,
    pub h: f64,
    pub h_nl: f64,
    pub n_l: u32,
    pub w_off: f64,
    pub w_w: f64,
    pub w_gap: f64,
    pub w_h: f64,
    pub w_grd: f64,
    pub w_h_ground: f64,
    pub w_grd_ground: f64,
    pub w_h_top: f64,
    pub w_grd_top: f64,
    pub n_w: u32,
}

/// One floor: its vertical extent and window rectangles [x0, y0, x1, y1].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Floor {
    pub y0: f64,
    pub y1: f64,
    pub windows: Vec<[f64; 4]>,
}

/// One façade of FACADE.json.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Facade {
    pub bbox: [f64; 4],
    /// Top to bottom (image order).
    pub floors: Vec<Floor>,
    pub params: FacadeParams,
}

/// FACADE.json: every façade found in the image.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FacadeModel {
    pub width: u32,
    pub height: u32,
    pub facades: Vec<Facade>,
    /// The merit F(Ω) = Σ_j Σ_{k ∈ R_j} ln P_kj of the whole labelling (§3.1.7).
    pub merit: f64,
}

impl FacadeParams {
    /// Floor extents bottom-up: (y_top, y_bottom, window height, window-to-floor-bottom).
    pub fn floor_bands(&self) -> Vec<(f64, f64, f64, f64)> {
        let n = self.n_l.clamp(1, MAX_FLOORS);
        if n == 1 {
            return vec![(self.y_ft, self.y_fb, self.w_h_ground, self.w_grd_ground)];
        }
        let mut out = vec![(
            self.y_fb - self.h_1,
            self.y_fb,
            self.w_h_ground,
            self.w_grd_ground,
        )];
        let mut bottom = self.y_fb - self.h_1;
        for _ in 0..n.saturating_sub(2) {
            out.push((bottom - self.h, bottom, self.w_h, self.w_grd));
            bottom -= self.h;
        }
        out.push((self.y_ft, bottom, self.w_h_top, self.w_grd_top));
        out
    }

    /// Window x ranges.
    pub fn window_columns(&self) -> Vec<(f64, f64)> {
        (0..self.n_w.min(MAX_WINDOWS))
            .map(|i| {
                let x0 = self.x_fl + self.w_off + i as f64 * (self.w_w + self.w_gap);
                (x0, x0 + self.w_w)
            })
            .collect()
    }

    /// The façade tree these parameters describe.
    pub fn to_facade(&self) -> Facade {
        let cols = self.window_columns();
        let mut floors: Vec<Floor> = self
            .floor_bands()
            .into_iter()
            .map(|(y0, y1, wh, wg)| Floor {
                y0,
                y1,
                windows: if wh > 0.0 {
                    cols.iter()
                        .map(|&(a, b)| [a, y1 - wg - wh, b, y1 - wg])
                        .collect()
                } else {
                    Vec::new()
                },
            })
            .collect();
        floors.reverse();
        Facade {
            bbox: [self.x_fl, self.y_ft, self.x_fr, self.y_fb],
            floors,
            params: *self,
        }
    }
}

impl FacadeModel {
    /// LABELS.png values, row-major: 0 background, 1 wall, 2 window. Rectangles cover pixel
    /// centres in [x0, x1) × [y0, y1).
    pub fn labels(&self) -> Vec<u8> {
        let (w, h) = (self.width as usize, self.height as usize);
        let mut out = vec![Class::Background as u8; w * h];
        let span = |a: f64, b: f64, n: usize| -> (usize, usize) {
            (
                a.max(0.0).round().min(n as f64) as usize,
                b.max(0.0).round().min(n as f64) as usize,
            )
        };
        let mut fill = |r: &[f64; 4], v: u8| {
            let (x0, x1) = span(r[0], r[2], w);
            let (y0, y1) = span(r[1], r[3], h);
            for y in y0..y1 {
                out[y * w + x0..y * w + x1].fill(v);
            }
        };
        for f in &self.facades {
            fill(&f.bbox, Class::Wall as u8);
            for fl in &f.floors {
                for win in &fl.windows {
                    fill(win, Class::Window as u8);
                }
            }
        }
        out
    }
}

/// F = Σ_k ln P_k,label(k) for a label image (§3.1.7). A class without a trained mixture
/// contributes the lowest log-likelihood of any class at that pixel.
pub fn merit(labels: &[u8], ll: &LogLikelihoods) -> f64 {
    let maps: Vec<Option<&[f32]>> = Class::ALL.iter().map(|c| ll.get(*c)).collect();
    labels
        .iter()
        .enumerate()
        .map(|(k, &l)| match maps[l as usize] {
            Some(m) => m[k] as f64,
            None => maps
                .iter()
                .flatten()
                .map(|m| m[k] as f64)
                .fold(f64::INFINITY, f64::min),
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params() -> FacadeParams {
        FacadeParams {
            x_fl: 10.0,
            y_ft: 20.0,
            x_fr: 110.0,
            y_fb: 120.0,
            h_1: 40.0,
            h: 20.0,
            h_nl: 20.0,
            n_l: 4,
            w_off: 10.0,
            w_w: 20.0,
            w_gap: 15.0,
            w_h: 10.0,
            w_grd: 5.0,
            w_h_ground: 25.0,
            w_grd_ground: 0.0,
            w_h_top: 0.0,
            w_grd_top: 0.0,
            n_w: 2,
        }
    }

    #[test]
    fn floors_stack_from_the_ground() {
        let f = params().to_facade();
        let ys: Vec<(f64, f64)> = f.floors.iter().map(|fl| (fl.y0, fl.y1)).collect();
        assert_eq!(
            ys,
            vec![(20.0, 40.0), (40.0, 60.0), (60.0, 80.0), (80.0, 120.0)]
        );
        assert!(f.floors[0].windows.is_empty(), "top floor has no windows");
        assert_eq!(
            f.floors[1].windows,
            vec![[20.0, 45.0, 40.0, 55.0], [55.0, 45.0, 75.0, 55.0]]
        );
        assert_eq!(f.floors[3].windows[0], [20.0, 95.0, 40.0, 120.0]);
    }

    #[test]
    fn labels_paint_wall_then_windows() {
        let m = FacadeModel {
            width: 130,
            height: 130,
            facades: vec![params().to_facade()],
            merit: 0.0,
        };
        let l = m.labels();
        assert_eq!(l[0], 0);
        assert_eq!(l[25 * 130 + 50], 1);
        assert_eq!(l[50 * 130 + 30], 2);
        assert_eq!(l[119 * 130 + 30], 2);
        assert_eq!(l[120 * 130 + 30], 0);
    }
}
