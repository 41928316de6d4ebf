//! The rectifying homography of §3.1.1, H = [V_h V_v 0; 1 1 1]⁻¹, normalised so the output keeps
//! the input's scale at its centre, and the bilinear warp.

use image::RgbImage;
use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;

use super::vp::Vp;
use crate::error::{FacadeError, Result};

/// Applies a homography to a pixel; `None` when the point maps to infinity.
pub fn apply(h: &Matrix3<f64>, x: f64, y: f64) -> Option<(f64, f64)> {
    let p = h * Vector3::new(x, y, 1.0);
    if p[2].abs() < 1e-12 {
        None
    } else {
        Some((p[0] / p[2], p[1] / p[2]))
    }
}

/// The rectifying homography from the horizontal and vertical vanishing points.
///
/// Steps: (1) the matrix of §3.1.1 in coordinates centred on the image and scaled by its half
/// size (the text's formula with the image centre in place of the origin, for conditioning);
/// (2) per-axis scale and sign so that at the image centre a step along the horizontal
/// (vertical) line family keeps its length and points right (down) — the similarity S, with the
/// aspect ratio taken from the centre of the photo since A = I cannot fix it; (3) a uniform
/// shrink when the output would exceed `max_area_factor` times the input area, and a translation
/// so the warped image starts at (0, 0). Returns H and the output size.
pub fn rectifying_homography(
    vh: &Vp,
    vv: &Vp,
    width: u32,
    height: u32,
    max_area_factor: f64,
) -> Result<(Matrix3<f64>, u32, u32)> {
    let (cx, cy) = ((width as f64 - 1.0) / 2.0, (height as f64 - 1.0) / 2.0);
    let s = (width.max(height) as f64 / 2.0).max(1.0);
    let t = Matrix3::new(1.0 / s, 0.0, -cx / s, 0.0, 1.0 / s, -cy / s, 0.0, 0.0, 1.0);
    let vh_n = t * Vector3::from(*vh);
    let vv_n = t * Vector3::from(*vv);
    let m = Matrix3::from_columns(&[vh_n, vv_n, Vector3::new(0.0, 0.0, 1.0)]);
    let h0 = m.try_inverse().ok_or_else(|| {
        FacadeError::NoVanishingPoints("the two vanishing points coincide".into())
    })? * t;
    // Where the vanishing line crosses the image, only the side holding the image centre can
    // be rectified (the other side is "beyond the horizon"). Departure from §3.1.1, which
    // assumes the line is outside: the image is clipped to the part where w keeps the centre's
    // sign and is at least half the centre's |w| (past that, the local magnification grows as
    // (w_c / w)³ and the output would be all stretch); the warp leaves the rest black.
    let corners = [
        (0.0, 0.0),
        (width as f64 - 1.0, 0.0),
        (width as f64 - 1.0, height as f64 - 1.0),
        (0.0, height as f64 - 1.0),
    ];
    let w_at = |x: f64, y: f64| (h0 * Vector3::new(x, y, 1.0))[2];
    let wc = w_at(cx, cy);
    if wc.abs() < 1e-12 {
        return Err(FacadeError::NoVanishingPoints(
            "the vanishing line passes through the image centre (the two line families are not a plane's horizontals and verticals)".into(),
        ));
    }
    let same_side = corners
        .iter()
        .all(|&(x, y)| w_at(x, y) * wc.signum() > 1e-12);
    let region: Vec<(f64, f64)> = if same_side {
        corners.to_vec()
    } else {
        let keep = |p: (f64, f64)| w_at(p.0, p.1) * wc.signum() - 0.5 * wc.abs();
        clip_polygon(&corners, keep)
    };
    if region.len() < 3 {
        return Err(FacadeError::NoVanishingPoints(
            "the vanishing line leaves too little of the image to rectify".into(),
        ));
    }
    // Local scale at the centre along each family.
    let dir_to = |vp: &Vp| -> (f64, f64) {
        let (tx, ty) = (vp[0] - vp[2] * cx, vp[1] - vp[2] * cy);
        let n = tx.hypot(ty).max(1e-12);
        (tx / n, ty / n)
    };
    let (mut hx, mut hy) = dir_to(vh);
    if hx < 0.0 {
        (hx, hy) = (-hx, -hy);
    }
    let (mut vx, mut vy) = dir_to(vv);
    if vy < 0.0 {
        (vx, vy) = (-vx, -vy);
    }
    let c0 =
        apply(&h0, cx, cy).ok_or_else(|| FacadeError::Numerical("centre at infinity".into()))?;
    let ch =
        apply(&h0, cx + hx, cy + hy).ok_or_else(|| FacadeError::Numerical("degenerate".into()))?;
    let cv =
        apply(&h0, cx + vx, cy + vy).ok_or_else(|| FacadeError::Numerical("degenerate".into()))?;
    let (ax, ay) = (ch.0 - c0.0, cv.1 - c0.1);
    if ax.abs() < 1e-15 || ay.abs() < 1e-15 {
        return Err(FacadeError::Numerical("degenerate rectification".into()));
    }
    let sc = Matrix3::new(1.0 / ax, 0.0, 0.0, 0.0, 1.0 / ay, 0.0, 0.0, 0.0, 1.0);
    let mut h1 = sc * h0;
    let bbox = |h: &Matrix3<f64>| -> Option<(f64, f64, f64, f64)> {
        let mut b = (
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        );
        for &(x, y) in &region {
            let (u, v) = apply(h, x, y)?;
            b = (b.0.min(u), b.1.min(v), b.2.max(u), b.3.max(v));
        }
        Some(b)
    };
    let b = bbox(&h1).ok_or_else(|| FacadeError::Numerical("corner at infinity".into()))?;
    let area = (b.2 - b.0 + 1.0) * (b.3 - b.1 + 1.0);
    let limit = max_area_factor * width as f64 * height as f64;
    if !area.is_finite() {
        return Err(FacadeError::Numerical("unbounded rectified image".into()));
    }
    if area > limit {
        let k = (limit / area).sqrt();
        h1 = Matrix3::new(k, 0.0, 0.0, 0.0, k, 0.0, 0.0, 0.0, 1.0) * h1;
    }
    let b = bbox(&h1).ok_or_else(|| FacadeError::Numerical("corner at infinity".into()))?;
    let shift = Matrix3::new(1.0, 0.0, -b.0, 0.0, 1.0, -b.1, 0.0, 0.0, 1.0);
    let h = shift * h1;
    let h = h / h[(2, 2)];
    let ow = ((b.2 - b.0).ceil() as u32 + 1).max(1);
    let oh = ((b.3 - b.1).ceil() as u32 + 1).max(1);
    Ok((h, ow, oh))
}

/// The part of a convex polygon where `f ≥ 0` (`f` affine along edges), by Sutherland–Hodgman.
fn clip_polygon(poly: &[(f64, f64)], f: impl Fn((f64, f64)) -> f64) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for (i, &a) in poly.iter().enumerate() {
        let b = poly[(i + 1) % poly.len()];
        let (fa, fb) = (f(a), f(b));
        if fa >= 0.0 {
            out.push(a);
        }
        if (fa >= 0.0) != (fb >= 0.0) {
            let t = fa / (fa - fb);
            out.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
        }
    }
    out
}

/// Bilinear warp: each output pixel samples the input at H⁻¹ p; outside pixels are black, and
/// so are pixels whose source lies beyond the vanishing line (on the other side of it from the
/// image centre), which a projective map would otherwise fold back into the output.
pub fn warp(img: &RgbImage, h: &Matrix3<f64>, out_w: u32, out_h: u32) -> Result<RgbImage> {
    let hi = h
        .try_inverse()
        .ok_or_else(|| FacadeError::Numerical("singular homography".into()))?;
    let (w, hgt) = img.dimensions();
    if w == 0 || hgt == 0 {
        return Err(FacadeError::ImageTooSmall {
            width: w,
            height: hgt,
            need: "the image to warp is empty".into(),
        });
    }
    let centre_side = (h * Vector3::new((w as f64 - 1.0) / 2.0, (hgt as f64 - 1.0) / 2.0, 1.0))[2];
    let mut buf = vec![0u8; out_w as usize * out_h as usize * 3];
    buf.par_chunks_mut(out_w as usize * 3)
        .enumerate()
        .for_each(|(y, row)| {
            for x in 0..out_w as usize {
                // For q = H⁻¹ (x, y, 1), H (q / q₂) = (x, y, 1) / q₂: the source's w is 1 / q₂.
                let q = hi * Vector3::new(x as f64, y as f64, 1.0);
                if q[2] * centre_side <= 0.0 {
                    continue;
                }
                let (u, v) = (q[0] / q[2], q[1] / q[2]);
                if !(u >= 0.0 && v >= 0.0 && u <= (w - 1) as f64 && v <= (hgt - 1) as f64) {
                    continue;
                }
                let (x0, y0) = (u.floor() as u32, v.floor() as u32);
                let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(hgt - 1));
                let (fx, fy) = (u - x0 as f64, v - y0 as f64);
                let (p00, p10) = (img.get_pixel(x0, y0), img.get_pixel(x1, y0));
                let (p01, p11) = (img.get_pixel(x0, y1), img.get_pixel(x1, y1));
                for c in 0..3 {
                    let top = p00[c] as f64 * (1.0 - fx) + p10[c] as f64 * fx;
                    let bot = p01[c] as f64 * (1.0 - fx) + p11[c] as f64 * fx;
                    row[x * 3 + c] = (top * (1.0 - fy) + bot * fy).round().clamp(0.0, 255.0) as u8;
                }
            }
        });
    RgbImage::from_raw(out_w, out_h, buf)
        .ok_or_else(|| FacadeError::Numerical("output buffer".into()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vanishing_points_go_to_infinity_along_the_axes() {
        let vh = [2000.0, 120.0, 1.0];
        let vv = [150.0, -3000.0, 1.0];
        let (h, w, hh) = rectifying_homography(&vh, &vv, 300, 200, 4.0).unwrap();
        let p = h * Vector3::from(vh);
        assert!(p[2].abs() < 1e-9 * p.norm() && p[1].abs() < 1e-9 * p.norm());
        let q = h * Vector3::from(vv);
        assert!(q[2].abs() < 1e-9 * q.norm() && q[0].abs() < 1e-9 * q.norm());
        assert!(w > 100 && hh > 100 && (w as f64) * (hh as f64) <= 4.0 * 300.0 * 200.0 + 1e3);
    }

    #[test]
    fn identity_for_points_at_infinity_on_the_axes() {
        let (h, w, hh) =
            rectifying_homography(&[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0], 64, 48, 4.0).unwrap();
        assert!((h - Matrix3::identity()).norm() < 1e-9, "{h}");
        assert_eq!((w, hh), (64, 48));
    }

    #[test]
    fn vanishing_line_through_the_centre_is_an_error() {
        // Both vanishing points on the line y = x·(23.5/31.5) through the centre (31.5, 23.5).
        let r = rectifying_homography(&[63.0, 47.0, 1.0], &[-63.0, -47.0, 1.0], 64, 48, 4.0);
        assert!(matches!(r, Err(FacadeError::NoVanishingPoints(_))), "{r:?}");
    }

    #[test]
    fn vanishing_line_through_the_image_keeps_the_centres_side() {
        // Looking steeply up a tower: the verticals meet at (32, 5), inside the image, and the
        // horizontals far right on the same row, so the vanishing line y = 5 crosses the image
        // near its top. The rows below it are rectified, the rows above it are not.
        let (vh, vv) = ([2000.0, 5.0, 1.0], [32.0, 5.0, 1.0]);
        let (h, w, hh) = rectifying_homography(&vh, &vv, 64, 48, 4.0).unwrap();
        assert!(w > 4 && hh > 4);
        let img = RgbImage::from_pixel(64, 48, image::Rgb([200, 100, 50]));
        let out = warp(&img, &h, w, hh).unwrap();
        let lit = out.pixels().filter(|p| p[0] > 0).count();
        assert!(lit > 0, "the centre's side is warped");
        // Every lit output pixel comes from below the line.
        let hi = h.try_inverse().unwrap();
        for (x, y, p) in out.enumerate_pixels() {
            if p[0] > 0 {
                let (_, v) = apply(&hi, x as f64, y as f64).unwrap();
                assert!(v > 5.0, "({x}, {y}) samples row {v}");
            }
        }
    }

    #[test]
    fn clipping_keeps_the_positive_side() {
        let square = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)];
        let half = clip_polygon(&square, |p| p.1 - 1.0);
        assert_eq!(half, vec![(2.0, 1.0), (2.0, 2.0), (0.0, 2.0), (0.0, 1.0)]);
        assert!(clip_polygon(&square, |p| -p.0 - 1.0).is_empty());
    }
}
