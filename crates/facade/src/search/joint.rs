//! Joint floor and window search over several façades of one building (§6.1.2): each façade's
//! height H_n is scaled by s_yn = H̄ / H_n to the mean height H̄, the vertical parameters
//! {h_1, h, h_NL, N_L, w_h, w_grd, w'_h, w'_grd, w''_h, w''_grd} are searched once over the
//! summed row profiles (so they are equal in all façades), the horizontal ones per façade.
//! With one façade this is exactly the single-façade search of §3.1.7.

use super::floors::{Horizontal, Vertical, search_horizontal, search_vertical};
use super::gradients::{Gradients, Integral};
use super::params::SearchParams;
use crate::model::FacadeParams;

/// One façade taking part in a joint search: its rectangle [x0, y0, x1, y1] in its own image,
/// the integral of that image's window-minus-wall log-likelihood, and its gradients.
pub struct JointFacade<'a> {
    pub rect: [usize; 4],
    pub window_minus_wall: &'a Integral,
    pub gradients: &'a Gradients,
}

/// Rows of façade `n` (own pixels, relative to its top) that common row `t` stands for, when
/// the façade's `fh` rows are stretched to `common` rows.
fn own_row(t: usize, fh: usize, common: usize) -> usize {
    (((t as f64 + 0.5) * fh as f64 / common as f64) as usize).min(fh - 1)
}

fn to_common(y: usize, fh: usize, common: usize) -> usize {
    ((y as f64 * common as f64 / fh as f64).round() as usize).min(common)
}

/// Jointly fits floors and windows of `facades` (§6.1.2). The returned parameters are in each
/// façade's own pixels: the vertical ones are the shared values scaled by 1 / s_yn.
pub fn fit_floors_joint(facades: &[JointFacade], p: &SearchParams) -> Vec<FacadeParams> {
    if facades.is_empty() {
        return Vec::new();
    }
    let heights: Vec<usize> = facades
        .iter()
        .map(|f| f.rect[3].saturating_sub(f.rect[1]).max(1))
        .collect();
    let common = (heights.iter().sum::<usize>() as f64 / heights.len() as f64)
        .round()
        .max(1.0) as usize;
    let x_cands: Vec<Vec<usize>> = facades
        .iter()
        .map(|f| {
            f.gradients
                .x_peaks(f.rect, p)
                .into_iter()
                .map(|x| x - f.rect[0])
                .collect()
        })
        .collect();
    let mut y_cands: Vec<usize> = facades
        .iter()
        .zip(&heights)
        .flat_map(|(f, &fh)| {
            f.gradients
                .y_peaks(f.rect, p)
                .into_iter()
                .map(move |y| to_common(y - f.rect[1], fh, common))
        })
        .collect();
    y_cands.sort_unstable();
    y_cands.dedup();

    // Σ over one façade's columns `cols` of row `y` (own pixels, relative).
    let row_sum = |f: &JointFacade, y: usize, cols: &[(usize, usize)]| -> f64 {
        let [x0, y0, ..] = f.rect;
        cols.iter()
            .map(|&(a, b)| f.window_minus_wall.sum(x0 + a, y0 + y, x0 + b, y0 + y + 1))
            .sum()
    };
    // The summed row profile in common rows; each façade's rows weighted by s_yn⁻¹ so that
    // every façade contributes its whole pixel mass.
    let joint_rows = |cols: &[Vec<(usize, usize)>]| -> Vec<f64> {
        (0..common)
            .map(|t| {
                facades
                    .iter()
                    .zip(&heights)
                    .zip(cols)
                    .map(|((f, &fh), c)| {
                        row_sum(f, own_row(t, fh, common), c) * fh as f64 / common as f64
                    })
                    .sum()
            })
            .collect()
    };
    let col_profile = |f: &JointFacade, fh: usize, rows: &[(usize, usize)]| -> Vec<f64> {
        let [x0, y0, x1, _] = f.rect;
        (0..x1 - x0)
            .map(|x| {
                rows.iter()
                    .map(|&(a, b)| {
                        let (a, b) = (own_row(a, fh, common), own_row(b.max(1) - 1, fh, common));
                        f.window_minus_wall
                            .sum(x0 + x, y0 + a, x0 + x + 1, y0 + b + 1)
                    })
                    .sum()
            })
            .collect()
    };

    // Start: rows whose window-minus-wall sum over the whole width is above the median row's.
    let full: Vec<Vec<(usize, usize)>> = facades
        .iter()
        .map(|f| vec![(0, f.rect[2] - f.rect[0])])
        .collect();
    let all = joint_rows(&full);
    let mut sorted = all.clone();
    sorted.sort_by(|a, b| a.total_cmp(b));
    let median = sorted.get(common / 2).copied().unwrap_or(0.0);
    // Departure: when half the rows or more are window rows, no row is strictly above the
    // median; then rows at the median count too (otherwise the search starts from nothing).
    let above = |strict: bool| -> Vec<(usize, usize)> {
        (0..common)
            .filter(|&y| all[y] > median || (!strict && all[y] >= median))
            .map(|y| (y, y + 1))
            .collect()
    };
    let mut rows = above(true);
    if rows.is_empty() {
        rows = above(false);
    }
    let mut hors = vec![Horizontal::default(); facades.len()];
    let mut ver = Vertical::default();
    for _ in 0..p.rounds.max(1) {
        let new_hors: Vec<Horizontal> = facades
            .iter()
            .zip(&heights)
            .zip(&x_cands)
            .map(|((f, &fh), xc)| search_horizontal(&col_profile(f, fh, &rows), xc))
            .collect();
        let cols: Vec<Vec<(usize, usize)>> = new_hors
            .iter()
            .map(|h| {
                (0..h.n)
                    .map(|k| {
                        let a = h.off + k * (h.w + h.gap);
                        (a, a + h.w)
                    })
                    .collect()
            })
            .collect();
        let new_ver = if cols.iter().all(|c| c.is_empty()) {
            Vertical {
                n_l: 1,
                h_1: common,
                ..Default::default()
            }
        } else {
            search_vertical(&joint_rows(&cols), &y_cands)
        };
        let same = new_hors == hors && new_ver == ver;
        hors = new_hors;
        ver = new_ver;
        rows = ver.rows(common);
        if same || cols.iter().all(|c| c.is_empty()) || rows.is_empty() {
            break;
        }
    }
    let shared = ver.params_stub(common);
    facades
        .iter()
        .zip(&heights)
        .zip(&hors)
        .map(|((f, &fh), hor)| {
            let k = fh as f64 / common as f64;
            let [x0, y0, x1, y1] = f.rect;
            FacadeParams {
                x_fl: x0 as f64,
                x_fr: x1 as f64,
                y_ft: y0 as f64,
                y_fb: y1 as f64,
                h_1: shared.h_1 * k,
                h: shared.h * k,
                h_nl: shared.h_nl * k,
                n_l: shared.n_l,
                w_h: shared.w_h * k,
                w_grd: shared.w_grd * k,
                w_h_ground: shared.w_h_ground * k,
                w_grd_ground: shared.w_grd_ground * k,
                w_h_top: shared.w_h_top * k,
                w_grd_top: shared.w_grd_top * k,
                w_off: hor.off as f64,
                w_w: hor.w as f64,
                w_gap: hor.gap as f64,
                n_w: if rows.is_empty() { 0 } else { hor.n as u32 },
            }
        })
        .collect()
}

/// Fits the floors and windows of the façade `r` = [x0, y0, x1, y1] given the integral of the
/// window-minus-wall log-likelihood (§3.1.7): the joint search of [`fit_floors_joint`] over
/// this one façade.
pub fn fit_floors(
    r: [usize; 4],
    d: &Integral,
    grads: &Gradients,
    p: &SearchParams,
) -> FacadeParams {
    let one = JointFacade {
        rect: r,
        window_minus_wall: d,
        gradients: grads,
    };
    fit_floors_joint(&[one], p)
        .pop()
        .expect("one façade in, one out")
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{Rgb, RgbImage};

    /// A façade of `floors` floors of `fh` px and `n` windows of `ww` px every `step` px, drawn
    /// dark on a light wall, with the matching window-minus-wall map (+1 window, −1 wall).
    fn facade(
        fw: usize,
        floors: usize,
        fh: usize,
        n: usize,
        ww: usize,
        step: usize,
    ) -> (RgbImage, Vec<f64>) {
        let h = floors * fh;
        let mut img = RgbImage::from_pixel(fw as u32, h as u32, Rgb([200, 190, 170]));
        let mut d = vec![-1.0; fw * h];
        for f in 0..floors {
            for k in 0..n {
                let x0 = step / 2 + k * step;
                for y in f * fh + fh / 4..f * fh + 3 * fh / 4 {
                    for x in x0..x0 + ww {
                        img.put_pixel(x as u32, y as u32, Rgb([30, 30, 40]));
                        d[y * fw + x] = 1.0;
                    }
                }
            }
        }
        (img, d)
    }

    #[test]
    fn two_facades_at_different_scales_share_their_vertical_parameters() {
        // The same building photographed at two scales: 4 floors of 30 px and of 45 px.
        let (a_img, a_d) = facade(120, 4, 30, 4, 10, 30);
        let (b_img, b_d) = facade(150, 4, 45, 3, 15, 50);
        let (a_int, b_int) = (Integral::new(&a_d, 120, 120), Integral::new(&b_d, 150, 180));
        let (a_g, b_g) = (Gradients::new(&a_img), Gradients::new(&b_img));
        let p = SearchParams::default();
        let both = fit_floors_joint(
            &[
                JointFacade {
                    rect: [0, 0, 120, 120],
                    window_minus_wall: &a_int,
                    gradients: &a_g,
                },
                JointFacade {
                    rect: [0, 0, 150, 180],
                    window_minus_wall: &b_int,
                    gradients: &b_g,
                },
            ],
            &p,
        );
        assert_eq!(both.len(), 2);
        assert_eq!(both[0].n_l, 4, "{:?}", both);
        assert_eq!(both[1].n_l, 4);
        // Shared vertical parameters, each in its façade's own pixels: ratio 120 : 180.
        let k = 180.0 / 120.0;
        assert!((both[1].h_1 - both[0].h_1 * k).abs() < 1e-9);
        assert!((both[1].w_h - both[0].w_h * k).abs() < 1e-9);
        assert!((both[0].w_h - 15.0).abs() <= 2.0, "{:?}", both[0]);
        // Horizontal parameters stay per façade.
        assert_eq!((both[0].n_w, both[1].n_w), (4, 3));
        assert!((both[0].w_w - 10.0).abs() <= 1.0 && (both[1].w_w - 15.0).abs() <= 1.0);
    }

    #[test]
    fn one_facade_joint_search_is_the_single_search() {
        let (img, d) = facade(120, 3, 40, 4, 10, 30);
        let int = Integral::new(&d, 120, 120);
        let g = Gradients::new(&img);
        let p = SearchParams::default();
        let joint = fit_floors_joint(
            &[JointFacade {
                rect: [0, 0, 120, 120],
                window_minus_wall: &int,
                gradients: &g,
            }],
            &p,
        );
        assert_eq!(joint[0].n_l, 3, "{:?}", joint[0]);
        assert_eq!(joint[0].n_w, 4);
        assert!(fit_floors_joint(&[], &p).is_empty());
    }
}
