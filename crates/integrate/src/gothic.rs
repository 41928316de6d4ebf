//! A Gothic façade photo through chapter 4 for integration: rectification (§3.1.1), the façade
//! cut out of the rectified photo, its arches, groups and nesting (§4.1–4.2) and its masonry;
//! then, once its scale on the plan is known, the block-level VSG program that replaces the
//! wall it maps to (§6.1.3), imported by the generated model. The user's element corrections
//! (issue 22, PROJECT.toml `[[gothic.element]]`, in rectified photo pixels) are applied between
//! detection and grouping (`facade::gothic::corrections`).

use facade::gothic::masonry::{self, Masonry, MasonryParams};
use facade::gothic::{
    Applied, CorrectedEstimate, CorrectionError, Detection, ElementCorrection, GothicEstimate,
    GothicParams, VsgOptions, detect_elements, estimate_corrected, to_vsg,
};
use facade::rectify::{ManualLines, Rectification};
use image::RgbImage;
use nalgebra::Matrix3;

use crate::error::IntegrateError;
use crate::photo::{Rectified, cut_outline, rectify_photo};

/// A Gothic façade photo with what the user gave for it.
pub struct GothicPhoto<'a> {
    pub name: &'a str,
    pub image: &'a RgbImage,
    /// The façade's extent in the photo's pixels (all of it when `None`).
    pub bbox: Option<[f64; 4]>,
    pub lines: Option<&'a ManualLines>,
    pub rectified: bool,
    /// The user's element corrections, in rectified photo pixels.
    pub corrections: &'a [ElementCorrection],
}

/// The rectified photo cut to its façade: the picture chapter 4 runs on.
pub struct GothicCutout {
    pub homography: Matrix3<f64>,
    pub rectification: Option<Rectification>,
    /// The façade's box in the rectified photo [x0, y0, x1, y1]; its corner is the cut-out's
    /// origin.
    pub bbox: [f64; 4],
    pub facade: RgbImage,
}

/// The chapter 4 estimate of one photo, in the pixels of the façade cut-out.
pub struct GothicFacadeEstimate {
    pub name: String,
    /// Photo pixels → rectified pixels.
    pub homography: Matrix3<f64>,
    pub rectification: Option<Rectification>,
    /// The façade's box in the rectified photo [x0, y0, x1, y1].
    pub bbox: [f64; 4],
    /// The rectified façade cut-out the estimate is in.
    pub facade: RgbImage,
    pub estimate: GothicEstimate,
    pub masonry: Masonry,
    /// What each of the user's corrections did (element ids of `estimate`).
    pub applied: Vec<Applied>,
    /// Elements the fit found that the learned check took out as unlike openings (issue 23).
    pub dropped: usize,
}

/// §3.1.1 on one photo and the façade cut out of it.
pub fn cut_out(photo: &GothicPhoto) -> Result<GothicCutout, IntegrateError> {
    let Rectified {
        rectification,
        homography,
        image: rectified,
    } = rectify_photo(photo.name, photo.image, photo.lines, photo.rectified)?;
    let (bbox, facade) = match photo.bbox {
        Some(b) => cut_outline(photo.name, b, &homography, &rectified)?,
        None => {
            let (w, h) = rectified.dimensions();
            ([0.0, 0.0, f64::from(w), f64::from(h)], rectified)
        }
    };
    Ok(GothicCutout {
        homography,
        rectification,
        bbox,
        facade,
    })
}

/// §4.2's detection on a cut-out (the slow half; `serve` keeps it between corrections).
pub fn detect(name: &str, cutout: &GothicCutout) -> Result<Detection, IntegrateError> {
    detect_elements(&cutout.facade, &GothicParams::default(), &|_| {})
        .map_err(|e| IntegrateError::facade(name, "arches (§4.1–4.2)", e))
}

/// The elements with the user's corrections (rectified photo pixels, moved into the cut-out
/// whose corner is `origin`), grouped, nested and checked.
pub fn organise(
    detection: &Detection,
    corrections: &[ElementCorrection],
    origin: [f64; 2],
) -> Result<CorrectedEstimate, CorrectionError> {
    let moved: Vec<ElementCorrection> = corrections
        .iter()
        .map(|c| c.shifted(-origin[0], -origin[1]))
        .collect();
    estimate_corrected(detection, &moved, &GothicParams::default(), &|_| {})
}

/// Runs §3.1.1 and §4.1–4.2 on one photo, with the user's corrections.
pub fn estimate_gothic(photo: &GothicPhoto) -> Result<GothicFacadeEstimate, IntegrateError> {
    let cutout = cut_out(photo)?;
    let detection = detect(photo.name, &cutout)?;
    let CorrectedEstimate {
        estimate,
        applied,
        dropped,
    } = organise(
        &detection,
        photo.corrections,
        [cutout.bbox[0], cutout.bbox[1]],
    )
    .map_err(|error| IntegrateError::GothicCorrection {
        image: photo.name.to_string(),
        error,
    })?;
    let masonry = masonry::segment(&cutout.facade, &estimate, &MasonryParams::default());
    Ok(GothicFacadeEstimate {
        name: photo.name.to_string(),
        homography: cutout.homography,
        rectification: cutout.rectification,
        bbox: cutout.bbox,
        facade: cutout.facade,
        estimate,
        masonry,
        applied,
        dropped,
    })
}

impl GothicFacadeEstimate {
    /// A photo point in rectified pixels.
    pub fn to_rectified(&self, p: [f64; 2]) -> Option<[f64; 2]> {
        facade::rectify::apply(&self.homography, p[0], p[1]).map(|(x, y)| [x, y])
    }

    /// The façade as a VSG program in model units (`scale` units per façade pixel), its wall
    /// `wall_depth` thick: x along the wall from its left end as seen from outside, y up from
    /// the foot, z out of the wall (facade::gothic::to_vsg).
    pub fn program(&self, scale: f64, wall_depth: f64) -> String {
        to_vsg(
            &self.estimate,
            Some(&self.masonry),
            &VsgOptions {
                px_per_unit: 1.0 / scale.max(1e-12),
                wall_depth,
                stone_depth: (0.02 * wall_depth).max(1e-3),
            },
        )
    }
}
