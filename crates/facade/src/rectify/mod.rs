//! Façade rectification (§3.1.1): straight edges → horizontal and vertical groups → two vanishing
//! points by RANSAC → the homography sending them to infinity along x and y → a bilinear warp.
//! Manual segment groups ([`ManualLines`], the LINES.json contract, checked by
//! [`ManualLines::validate`]) replace the automatic ones.

pub mod homography;
pub mod lines;
pub mod vp;

use image::{Rgb, RgbImage};
use nalgebra::Matrix3;
use serde::{Deserialize, Serialize};

use crate::error::{FacadeError, Result};
pub use homography::{apply, rectifying_homography, warp};
pub use lines::{LineParams, Segment, detect_segments};
pub use vp::{RansacParams, Vp, angle_error, ransac_vp, weighted_lsq};

/// LINES.json: user-chosen segments, `{"horizontal": [[x0, y0, x1, y1], ...], "vertical": [...]}`
/// in input pixels, at least two of each (§3.1.1, the manual override).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ManualLines {
    pub horizontal: Vec<[f64; 4]>,
    pub vertical: Vec<[f64; 4]>,
}

/// Most segments per family one LINES.json may hold.
pub const MAX_SEGMENTS: usize = 2000;

impl ManualLines {
    /// Segment families as LINES.json writes them, `[x0, y0, x1, y1]` to a hundredth of a pixel
    /// (the detected segments, offered to the user as a starting point).
    pub fn from_segments(horizontal: &[Segment], vertical: &[Segment]) -> ManualLines {
        ManualLines {
            horizontal: as_json(horizontal),
            vertical: as_json(vertical),
        }
    }

    /// Refuses segments the rectification cannot use, with its own message, before they are
    /// saved: more than [`MAX_SEGMENTS`] in a family, or what [`rectify_with_lines`] refuses
    /// for a `width` × `height` photo.
    pub fn validate(&self, width: u32, height: u32) -> std::result::Result<(), String> {
        for (name, family) in [
            ("horizontal", &self.horizontal),
            ("vertical", &self.vertical),
        ] {
            if family.len() > MAX_SEGMENTS {
                return Err(format!(
                    "{} {name} segments, more than the limit of {MAX_SEGMENTS}",
                    family.len()
                ));
            }
        }
        rectify_with_lines(width, height, self, &RectifyParams::default())
            .map(|_| ())
            .map_err(|e| e.to_string())
    }
}

/// Segments as LINES.json writes them, `[x0, y0, x1, y1]`.
fn as_json(segments: &[Segment]) -> Vec<[f64; 4]> {
    let round = |v: f64| (v * 100.0).round() / 100.0;
    segments
        .iter()
        .map(|s| [round(s.x0), round(s.y0), round(s.x1), round(s.y1)])
        .collect()
}

/// Rectification settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RectifyParams {
    pub lines: LineParams,
    pub ransac: RansacParams,
    /// Segments tilted less than this from the x axis are horizontal candidates (degrees).
    pub max_horizontal_tilt: f64,
    /// Segments tilted less than this from the y axis are vertical candidates (degrees).
    pub max_vertical_tilt: f64,
    /// The output may have at most this many times the input's pixels.
    pub max_area_factor: f64,
}

impl Default for RectifyParams {
    fn default() -> Self {
        RectifyParams {
            lines: LineParams::default(),
            ransac: RansacParams::default(),
            max_horizontal_tilt: 40.0,
            max_vertical_tilt: 30.0,
            max_area_factor: 4.0,
        }
    }
}

/// The outcome of rectification.
#[derive(Debug, Clone)]
pub struct Rectification {
    /// Input pixels → output pixels.
    pub h: Matrix3<f64>,
    pub width: u32,
    pub height: u32,
    pub horizontal_vp: Vp,
    pub vertical_vp: Vp,
    /// Segments of the horizontal family (inliers of its vanishing point).
    pub horizontal: Vec<Segment>,
    /// Segments of the vertical family.
    pub vertical: Vec<Segment>,
    /// Detected segments belonging to neither family.
    pub others: Vec<Segment>,
}

impl Rectification {
    /// The warped (rectified) image.
    pub fn warp(&self, img: &RgbImage) -> Result<RgbImage> {
        warp(img, &self.h, self.width, self.height)
    }
}

fn check_size(w: u32, h: u32) -> Result<()> {
    if w < 16 || h < 16 {
        return Err(FacadeError::ImageTooSmall {
            width: w,
            height: h,
            need: "rectification needs at least 16x16 pixels".into(),
        });
    }
    Ok(())
}

fn norm_frame(w: u32, h: u32) -> ((f64, f64), f64) {
    (
        ((w as f64 - 1.0) / 2.0, (h as f64 - 1.0) / 2.0),
        (w.max(h) as f64 / 2.0).max(1.0),
    )
}

/// The two vanishing points of a photo and the segment families behind them.
#[derive(Debug, Clone)]
pub struct VanishingPoints {
    pub horizontal_vp: Vp,
    pub vertical_vp: Vp,
    pub horizontal: Vec<Segment>,
    pub vertical: Vec<Segment>,
    pub others: Vec<Segment>,
}

/// Automatic rectification of a façade photo (§3.1.1).
pub fn rectify(img: &RgbImage, params: &RectifyParams) -> Result<Rectification> {
    let (w, h) = img.dimensions();
    let v = find_vanishing_points(img, params)?;
    let (hm, ow, oh) = rectifying_homography(
        &v.horizontal_vp,
        &v.vertical_vp,
        w,
        h,
        params.max_area_factor,
    )?;
    Ok(Rectification {
        h: hm,
        width: ow,
        height: oh,
        horizontal_vp: v.horizontal_vp,
        vertical_vp: v.vertical_vp,
        horizontal: v.horizontal,
        vertical: v.vertical,
        others: v.others,
    })
}

/// Edge segments → near-horizontal and near-vertical groups → one vanishing point per group by
/// RANSAC (§3.1.1).
pub fn find_vanishing_points(img: &RgbImage, params: &RectifyParams) -> Result<VanishingPoints> {
    let (w, h) = img.dimensions();
    check_size(w, h)?;
    let gray = image::imageops::grayscale(img);
    let segs = detect_segments(&gray, &params.lines);
    let (hor, rest): (Vec<Segment>, Vec<Segment>) = segs
        .into_iter()
        .partition(|s| s.tilt_degrees() < params.max_horizontal_tilt);
    let (ver, mut others): (Vec<Segment>, Vec<Segment>) = rest
        .into_iter()
        .partition(|s| s.tilt_degrees() > 90.0 - params.max_vertical_tilt);
    let (centre, scale) = norm_frame(w, h);
    let fit = |group: &[Segment],
               name: &str,
               seed: u64|
     -> Result<(Vp, Vec<Segment>, Vec<Segment>)> {
        let p = RansacParams {
            seed,
            ..params.ransac
        };
        let f = ransac_vp(group, centre, scale, &p).ok_or_else(|| {
            FacadeError::NoVanishingPoints(format!(
                "found {} {name} edge segment(s) and no two that converge; give the segments with --lines",
                group.len()
            ))
        })?;
        let (mut inl, mut out) = (Vec::new(), Vec::new());
        for (i, s) in group.iter().enumerate() {
            if f.inliers.contains(&i) {
                inl.push(*s);
            } else {
                out.push(*s);
            }
        }
        Ok((f.vp, inl, out))
    };
    let (vh, hin, hout) = fit(&hor, "near-horizontal", params.ransac.seed)?;
    let (vv, vin, vout) = fit(&ver, "near-vertical", params.ransac.seed.wrapping_add(1))?;
    others.extend(hout);
    others.extend(vout);
    Ok(VanishingPoints {
        horizontal_vp: vh,
        vertical_vp: vv,
        horizontal: hin,
        vertical: vin,
        others,
    })
}

/// Rectification from user-given segment groups (the manual override of §3.1.1): the vanishing
/// points are the weighted least squares intersections of each group.
pub fn rectify_with_lines(
    width: u32,
    height: u32,
    lines: &ManualLines,
    params: &RectifyParams,
) -> Result<Rectification> {
    check_size(width, height)?;
    let to_segs = |v: &[[f64; 4]], name: &str| -> Result<Vec<Segment>> {
        if v.len() < 2 {
            return Err(FacadeError::BadLines(format!(
                "need at least two {name} segments, found {}",
                v.len()
            )));
        }
        v.iter()
            .map(|a| {
                let s = Segment::new(a[0], a[1], a[2], a[3]);
                if a.iter().all(|c| c.is_finite()) && s.length() > 1e-6 {
                    Ok(s)
                } else {
                    Err(FacadeError::BadLines(format!(
                        "{name} segment {a:?} is not a segment of finite, non-zero length"
                    )))
                }
            })
            .collect()
    };
    let hor = to_segs(&lines.horizontal, "horizontal")?;
    let ver = to_segs(&lines.vertical, "vertical")?;
    let (centre, scale) = norm_frame(width, height);
    let vh = weighted_lsq(&hor.iter().collect::<Vec<_>>(), centre, scale)
        .ok_or_else(|| FacadeError::BadLines("horizontal segments have no intersection".into()))?;
    let vv = weighted_lsq(&ver.iter().collect::<Vec<_>>(), centre, scale)
        .ok_or_else(|| FacadeError::BadLines("vertical segments have no intersection".into()))?;
    let (hm, ow, oh) = rectifying_homography(&vh, &vv, width, height, params.max_area_factor)?;
    Ok(Rectification {
        h: hm,
        width: ow,
        height: oh,
        horizontal_vp: vh,
        vertical_vp: vv,
        horizontal: hor,
        vertical: ver,
        others: Vec::new(),
    })
}

/// Overlay of figure 3.2: horizontal family red, vertical family blue, others grey, and each
/// vanishing point that falls within three image sizes of the image as a green cross (with lines
/// from the segments towards it); with its key ([`overlay_key`]).
pub fn draw_overlay(img: &RgbImage, r: &Rectification) -> RgbImage {
    use imageproc::drawing::{draw_cross_mut, draw_line_segment_mut};
    let mut out = img.clone();
    for p in out.pixels_mut() {
        for c in 0..3 {
            p[c] = (p[c] as u16 * 2 / 3) as u8;
        }
    }
    let (w, h) = (img.width() as f64, img.height() as f64);
    let draw = |out: &mut RgbImage, s: &Segment, col: Rgb<u8>| {
        draw_line_segment_mut(
            out,
            (s.x0 as f32, s.y0 as f32),
            (s.x1 as f32, s.y1 as f32),
            col,
        );
    };
    for s in &r.others {
        draw(&mut out, s, Rgb([150, 150, 150]));
    }
    for (segs, vp, col) in [
        (&r.horizontal, r.horizontal_vp, Rgb([255, 40, 40])),
        (&r.vertical, r.vertical_vp, Rgb([40, 120, 255])),
    ] {
        let near = vp[2].abs() > 1e-12 && {
            let (x, y) = (vp[0] / vp[2], vp[1] / vp[2]);
            x > -3.0 * w && x < 4.0 * w && y > -3.0 * h && y < 4.0 * h
        };
        for s in segs {
            if near {
                let (mx, my) = s.midpoint();
                let thin = Rgb([col[0] / 2, col[1] / 2, col[2] / 2]);
                draw_line_segment_mut(
                    &mut out,
                    (mx as f32, my as f32),
                    ((vp[0] / vp[2]) as f32, (vp[1] / vp[2]) as f32),
                    thin,
                );
            }
        }
        for s in segs {
            draw(&mut out, s, col);
        }
        if near {
            let (x, y) = ((vp[0] / vp[2]) as i32, (vp[1] / vp[2]) as i32);
            for d in -2..=2 {
                draw_cross_mut(&mut out, Rgb([0, 255, 0]), x + d, y);
                draw_cross_mut(&mut out, Rgb([0, 255, 0]), x, y + d);
            }
        }
    }
    raster::legend::draw(&mut out, &overlay_key(), &|_, _| false);
    out
}

/// The words of [`draw_overlay`]'s key, for captions.
pub const OVERLAY_LEGEND: &str = "red: the horizontal line family, blue: the vertical family, grey: other lines, green crosses: vanishing points";

/// The key of [`draw_overlay`] (issue 22: every overlay carries its key).
pub fn overlay_key() -> Vec<raster::legend::Entry> {
    use raster::legend::{Entry, Swatch};
    vec![
        Entry::new(Swatch::Line([255, 40, 40]), "horizontal lines"),
        Entry::new(Swatch::Line([40, 120, 255]), "vertical lines"),
        Entry::new(Swatch::Line([150, 150, 150]), "other lines"),
        Entry::new(Swatch::Fill([0, 255, 0]), "vanishing point"),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square_lines() -> ManualLines {
        ManualLines {
            horizontal: vec![[10.0, 10.0, 90.0, 10.0], [10.0, 90.0, 90.0, 90.0]],
            vertical: vec![[10.0, 10.0, 10.0, 90.0], [90.0, 10.0, 90.0, 90.0]],
        }
    }

    #[test]
    fn usable_segments_pass_and_the_rectification_says_why_others_fail() {
        assert_eq!(square_lines().validate(100, 100), Ok(()));
        let mut one = square_lines();
        one.vertical.pop();
        let e = one.validate(100, 100).unwrap_err();
        assert!(e.contains("two vertical"), "{e}");
        let mut dot = square_lines();
        dot.horizontal[0] = [5.0, 5.0, 5.0, 5.0];
        assert!(
            dot.validate(100, 100)
                .unwrap_err()
                .contains("non-zero length")
        );
        let mut many = square_lines();
        many.horizontal = vec![[0.0, 0.0, 10.0, 0.0]; MAX_SEGMENTS + 1];
        assert!(many.validate(100, 100).unwrap_err().contains("limit"));
    }

    #[test]
    fn segments_are_written_to_a_hundredth_of_a_pixel() {
        let s = Segment::new(1.234_56, 2.0, 3.005_1, 4.999_9);
        let lines = ManualLines::from_segments(&[s], &[]);
        assert_eq!(lines.horizontal, vec![[1.23, 2.0, 3.01, 5.0]]);
        assert!(lines.vertical.is_empty());
    }
}
