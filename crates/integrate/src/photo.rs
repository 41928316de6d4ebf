//! One façade photo through chapter 3: rectification (§3.1.1, automatic or from the user's
//! segments), the pixel classifier trained from the user's boxes (§3.1.2–3.1.4) and the façade
//! search (§3.1.5–3.1.7). Boxes and points are given in the photo's pixels and mapped through
//! the rectifying homography, so a project stays valid if rectification is re-run.

use facade::classify::{Class, ClassifyParams, LogLikelihoods, Method, Training};
use facade::fixes::FacadeFixes;
use facade::model::FacadeModel;
use facade::rectify::{ManualLines, Rectification, RectifyParams, rectify, rectify_with_lines};
use facade::repeat::RepeatParams;
use facade::search::SearchParams;
use image::RgbImage;
use image::imageops::crop_imm;
use nalgebra::Matrix3;

use crate::error::IntegrateError;

/// A façade photo with what the user gave for it.
pub struct FacadePhoto<'a> {
    /// The name in PROJECT.toml.
    pub name: &'a str,
    pub image: &'a RgbImage,
    /// Boxes in the photo's pixels.
    pub training: &'a Training,
    pub lines: Option<&'a ManualLines>,
    /// The photo is already rectified.
    pub rectified: bool,
    /// The user's outline of the façade in the photo's pixels (replaces §3.1.5).
    pub bbox: Option<[f64; 4]>,
    /// Metres per pixel when the photo is a measured elevation (rectified photos only).
    pub metres_per_pixel: Option<f64>,
    pub seed: u64,
    /// The per-pixel classifier of §3.1.3–3.1.4 (the text's GMM or the forest).
    pub classifier: Method,
    /// The user's corrections of the façade estimate (issue 22), in rectified pixels (of the
    /// cut-out when `bbox` is given).
    pub fixes: &'a FacadeFixes,
}

/// The chapter 3 estimate of one photo.
pub struct FacadeEstimate {
    pub name: String,
    /// Photo pixels → rectified pixels.
    pub homography: Matrix3<f64>,
    pub rectification: Option<Rectification>,
    pub rectified: RgbImage,
    pub training: Training,
    pub log_likelihoods: LogLikelihoods,
    pub model: FacadeModel,
    /// Metres per rectified pixel, when the user measured it on the drawing.
    pub metres_per_pixel: Option<f64>,
    /// The user's corrections the search honoured (issue 22): integration reads the model's
    /// floors and windows whole where they are set, and names the user as their source.
    pub fixes: FacadeFixes,
}

impl FacadeEstimate {
    /// A photo point in rectified pixels.
    pub fn to_rectified(&self, p: [f64; 2]) -> Option<[f64; 2]> {
        facade::rectify::apply(&self.homography, p[0], p[1]).map(|(x, y)| [x, y])
    }

    /// Each façade found, as the quadrilateral of the photo's pixels that rectifies to its box
    /// (corners clockwise from the top left): where a correspondence's `facade_point` may land
    /// (issue 22). `None` for a façade whose corner the rectification sends to infinity.
    pub fn outlines_in_photo(&self) -> Vec<Option<[[f64; 2]; 4]>> {
        let back = self.homography.try_inverse();
        self.model
            .facades
            .iter()
            .map(|f| {
                let back = back.as_ref()?;
                let [x0, y0, x1, y1] = f.bbox;
                let mut quad = [[0.0; 2]; 4];
                for (q, (x, y)) in quad
                    .iter_mut()
                    .zip([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
                {
                    let (u, v) = facade::rectify::apply(back, x, y)?;
                    *q = [u, v];
                }
                Some(quad)
            })
            .collect()
    }
}

/// A photo after §3.1.1.
pub struct Rectified {
    pub rectification: Option<Rectification>,
    /// Photo pixels → rectified pixels (identity for a photo given rectified).
    pub homography: Matrix3<f64>,
    pub image: RgbImage,
}

/// §3.1.1 on a photo: automatic, from the user's segments, or none when it is already an
/// elevation.
pub fn rectify_photo(
    name: &str,
    image: &RgbImage,
    lines: Option<&ManualLines>,
    already_rectified: bool,
) -> Result<Rectified, IntegrateError> {
    let err = |e| IntegrateError::facade(name, "rectification (§3.1.1)", e);
    if already_rectified {
        return Ok(Rectified {
            rectification: None,
            homography: Matrix3::identity(),
            image: image.clone(),
        });
    }
    let (w, h) = image.dimensions();
    let params = RectifyParams::default();
    let r = match lines {
        Some(lines) => rectify_with_lines(w, h, lines, &params),
        None => rectify(image, &params),
    }
    .map_err(err)?;
    Ok(Rectified {
        homography: r.h,
        image: r.warp(image).map_err(err)?,
        rectification: Some(r),
    })
}

/// Runs §3.1.1–3.1.7 on one photo.
pub fn estimate_facade(photo: &FacadePhoto) -> Result<FacadeEstimate, IntegrateError> {
    let err = |step, e| IntegrateError::facade(photo.name, step, e);
    // Checked in the photo's own pixels: mapping into the rectified façade orders each box's
    // corners, which would hide an inverted box (issue 19).
    let (w, h) = photo.image.dimensions();
    photo
        .training
        .validate(w as usize, h as usize)
        .map_err(|e| err("training boxes", e))?;
    let Rectified {
        rectification,
        homography,
        image: rectified,
    } = rectify_photo(photo.name, photo.image, photo.lines, photo.rectified)?;
    let mut training = map_training(photo.training, &homography);
    let (homography, rectified) = match photo.bbox {
        None => (homography, rectified),
        Some(b) => {
            // Departure from §3.1.5: the user's outline is the façade. The cut-out becomes the
            // rectified image (photo → cut-out = translation ∘ H), so everything downstream
            // (points, textures, overlays) stays in one frame; without a background class the
            // search takes the whole cut-out as one façade.
            let (r, cut) = cut_outline(photo.name, b, &homography, &rectified)?;
            let (x0, y0) = (r[0].max(0.0).round(), r[1].max(0.0).round());
            let shift = Matrix3::new(1.0, 0.0, -x0, 0.0, 1.0, -y0, 0.0, 0.0, 1.0);
            training = inside(&training, [x0, y0], cut.dimensions());
            (shift * homography, cut)
        }
    };
    // The corrections are in the frame the user saw them in, the rectified photo (cut out):
    // checked there before the classifier runs.
    let (rw, rh) = rectified.dimensions();
    photo
        .fixes
        .validate(rw, rh)
        .map_err(|e| IntegrateError::Facade {
            image: photo.name.to_string(),
            step: "fix".into(),
            message: e.to_string(),
        })?;
    let params = ClassifyParams::with(photo.classifier, photo.seed);
    // Classes, the drawn windows' repeats (when the window boxes are whole windows) and the
    // search, as `castellan facade` runs them.
    let (log_likelihoods, model, _) = facade::parse_photo_with(
        &rectified,
        &training,
        &params,
        &SearchParams::default(),
        &RepeatParams::default(),
        photo.fixes,
    )
    .map_err(|e| err("pixel classes and façade search (§3.1.2–3.1.7)", e))?;
    Ok(FacadeEstimate {
        name: photo.name.to_string(),
        homography,
        rectification,
        rectified,
        training,
        log_likelihoods,
        model,
        metres_per_pixel: photo.metres_per_pixel,
        fixes: photo.fixes.clone(),
    })
}

/// The user's façade outline `b` (photo pixels) cut out of the rectified photo: the rectangle
/// it maps to, in whole rectified pixels, and the cut-out. An outline that does not map into
/// the rectified photo is an error naming the photo, never a silent fall-back to the whole.
pub(crate) fn cut_outline(
    name: &str,
    b: [f64; 4],
    homography: &Matrix3<f64>,
    rectified: &RgbImage,
) -> Result<([f64; 4], RgbImage), IntegrateError> {
    let outline_error = |why: String| IntegrateError::Facade {
        image: name.to_string(),
        step: "façade outline (bbox)".into(),
        message: why,
    };
    let r = map_box(&b, homography)
        .map(|[x0, y0, x1, y1]| [x0.floor(), y0.floor(), x1.ceil(), y1.ceil()])
        .ok_or_else(|| {
            outline_error(format!("bbox {b:?} does not map into the rectified photo"))
        })?;
    let cut = crop(rectified, r).ok_or_else(|| {
        outline_error(format!(
            "bbox {b:?} has no pixels inside the rectified photo"
        ))
    })?;
    Ok((r, cut))
}

/// The window and wall boxes moved into a cut-out at `origin` of size `size`, clipped to it;
/// boxes left with no area are dropped, and so is the background class (the cut-out is the
/// façade).
fn inside(t: &Training, origin: [f64; 2], size: (u32, u32)) -> Training {
    let (w, h) = (f64::from(size.0), f64::from(size.1));
    let moved = |boxes: &[[f64; 4]]| -> Vec<[f64; 4]> {
        boxes
            .iter()
            .map(|b| {
                [
                    (b[0] - origin[0]).clamp(0.0, w),
                    (b[1] - origin[1]).clamp(0.0, h),
                    (b[2] - origin[0]).clamp(0.0, w),
                    (b[3] - origin[1]).clamp(0.0, h),
                ]
            })
            .filter(|b| b[2] > b[0] && b[3] > b[1])
            .collect()
    };
    let classes = t
        .classes
        .iter()
        .filter(|(class, _)| **class != Class::Background)
        .map(|(name, boxes)| (*name, moved(boxes)))
        .collect();
    Training {
        classes,
        whole_windows: moved(&t.whole_windows),
    }
}

/// Each box mapped through `h` and shrunk to the axis-aligned box inside the mapped
/// quadrilateral (so no pixel of another class creeps in).
pub fn map_training(t: &Training, h: &Matrix3<f64>) -> Training {
    let mapped = |boxes: &[[f64; 4]]| -> Vec<[f64; 4]> {
        boxes.iter().map(|b| map_box(b, h).unwrap_or(*b)).collect()
    };
    let classes = t
        .classes
        .iter()
        .map(|(name, boxes)| (*name, mapped(boxes)))
        .collect();
    Training {
        classes,
        whole_windows: mapped(&t.whole_windows),
    }
}

/// A box mapped through `h`, shrunk to the axis-aligned box inside the mapped quadrilateral.
pub fn map_box(b: &[f64; 4], h: &Matrix3<f64>) -> Option<[f64; 4]> {
    let (x0, x1) = (b[0].min(b[2]), b[0].max(b[2]));
    let (y0, y1) = (b[1].min(b[3]), b[1].max(b[3]));
    let p = |x: f64, y: f64| facade::rectify::apply(h, x, y);
    let (tl, tr, bl, br) = (p(x0, y0)?, p(x1, y0)?, p(x0, y1)?, p(x1, y1)?);
    let left = tl.0.max(bl.0);
    let right = tr.0.min(br.0);
    let top = tl.1.max(tr.1);
    let bottom = bl.1.min(br.1);
    (right > left && bottom > top).then_some([left, top, right, bottom])
}

/// The part of `img` inside box `b` = [x0, y0, x1, y1], clipped; `None` if nothing is left.
pub fn crop(img: &RgbImage, b: [f64; 4]) -> Option<RgbImage> {
    let (w, h) = img.dimensions();
    let x0 = b[0].max(0.0).round() as u32;
    let y0 = b[1].max(0.0).round() as u32;
    let x1 = (b[2].round().max(0.0) as u32).min(w);
    let y1 = (b[3].round().max(0.0) as u32).min(h);
    (x1 > x0 + 1 && y1 > y0 + 1).then(|| crop_imm(img, x0, y0, x1 - x0, y1 - y0).to_image())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_outline_is_cut_out_or_refused_by_name() {
        let img = RgbImage::from_fn(40, 30, |x, y| image::Rgb([x as u8, y as u8, 0]));
        let id = Matrix3::identity();
        let (r, cut) = cut_outline("tower.png", [5.0, 4.0, 25.0, 20.0], &id, &img).unwrap();
        assert_eq!((r, cut.dimensions()), ([5.0, 4.0, 25.0, 20.0], (20, 16)));
        assert_eq!(cut.get_pixel(0, 0), &image::Rgb([5, 4, 0]));
        let e = cut_outline("tower.png", [50.0, 40.0, 60.0, 50.0], &id, &img)
            .unwrap_err()
            .to_string();
        assert!(e.contains("tower.png") && e.contains("bbox"), "{e}");
    }

    #[test]
    fn boxes_shrink_inside_the_mapped_quadrilateral() {
        // A shear x' = x + 0.1 y: the box [10, 10, 20, 20] becomes a parallelogram whose
        // inscribed box spans x 12..21.
        let h = Matrix3::new(1.0, 0.1, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0);
        let b = map_box(&[10.0, 10.0, 20.0, 20.0], &h).unwrap();
        assert_eq!(b, [12.0, 10.0, 21.0, 20.0]);
        assert_eq!(
            map_box(&[1.0, 2.0, 3.0, 4.0], &Matrix3::identity()),
            Some([1.0, 2.0, 3.0, 4.0])
        );
    }
}
