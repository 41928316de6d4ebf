//! The photo stages of a reconstruction: chapter 3 on a façade photo and chapter 4 on a Gothic
//! photo, each with the overlays a user judges it by (the rectification's line families, the
//! classifier's probabilities, the façade tree, the arches and stones). `serve` runs them one
//! by one; [`super::reconstruct`] runs them all.

use facade::classify::Training;
use facade::rectify::ManualLines;
use image::{GrayImage, RgbImage};

use super::interface::{Files, Options, Overlay, Picture, PipelineError, at};
use crate::IntegrateError;
use crate::gothic::{GothicFacadeEstimate, GothicPhoto, estimate_gothic};
use crate::photo::{FacadeEstimate, FacadePhoto, estimate_facade};
use crate::project::{FacadeEntry, GothicEntry, Project, TrainingSource, gothic_element_entry};
use crate::textures::safe_stem;

/// A façade's training boxes (photo pixels): inline in PROJECT.toml or its TRAINING.json; a
/// TRAINING.json that is named but missing is an error naming the entry, in every command.
pub fn training(entry: &FacadeEntry, files: &impl Files) -> Result<Training, String> {
    match &entry.training {
        TrainingSource::Inline(t) => Ok(t.clone()),
        TrainingSource::File(name) => files.json(name, "a TRAINING.json"),
    }
}

/// A photo and its optional rectification segments (LINES.json).
fn photo_and_lines(
    image: &str,
    lines: Option<&str>,
    files: &impl Files,
) -> Result<(RgbImage, Option<ManualLines>), String> {
    let photo = files.image(image)?.to_rgb8();
    let lines = match lines {
        Some(name) => Some(files.json(name, "a LINES.json")?),
        None => None,
    };
    Ok((photo, lines))
}

fn facade_entry(i: usize, f: &FacadeEntry) -> String {
    format!("[[facade]] #{} (image = \"{}\")", i + 1, f.image)
}

fn gothic_entry(i: usize, g: &GothicEntry) -> String {
    format!("[[gothic]] #{} (image = \"{}\")", i + 1, g.image)
}

/// Chapter 3 on the project's façade photo `index` (§3.1.1–3.1.7), with its overlays.
pub fn estimate_photo(
    project: &Project,
    index: usize,
    files: &impl Files,
    options: &Options,
) -> Result<(FacadeEstimate, Vec<Overlay>), PipelineError> {
    let seed = options.seed_for(project);
    let f = &project.facades[index];
    let entry = facade_entry(index, f);
    let (image, lines) =
        photo_and_lines(&f.image, f.lines.as_deref(), files).map_err(at(entry.clone()))?;
    let training = training(f, files).map_err(at(entry.clone()))?;
    let estimate = estimate_facade(&FacadePhoto {
        name: &f.image,
        image: &image,
        training: &training,
        lines: lines.as_ref(),
        rectified: f.rectified,
        bbox: f.bbox,
        metres_per_pixel: f.metres_per_pixel,
        seed,
        classifier: options.classifier,
        fixes: &f.fix,
    })
    .map_err(|e| at(entry)(e.to_string()))?;
    let overlays = facade_overlays(&estimate, &image);
    Ok((estimate, overlays))
}

/// §3.1.1's line families, the classifier's probabilities and the façade tree over the
/// rectified photo, and its label image.
fn facade_overlays(e: &FacadeEstimate, photo: &RgbImage) -> Vec<Overlay> {
    let stem = safe_stem(&e.name);
    let labels = e.model.labels();
    let mut out = lines_overlay(&e.name, &stem, photo, e.rectification.as_ref());
    out.push(Overlay {
        name: format!("overlays/{stem}_pixels.png"),
        caption: Some(format!(
            "{}: the pixel classifier's class probabilities before the façade search (§3.1.4; \
             {}, blended where unsure)",
            e.name,
            facade::draw::LEGEND
        )),
        picture: Picture::Rgb(facade::draw::probability_overlay(
            &e.rectified,
            &e.log_likelihoods,
        )),
    });
    out.push(Overlay {
        name: format!("overlays/{stem}_facade.png"),
        caption: Some(format!(
            "{}: the façade tree over the rectified photo (§3.1.7; {})",
            e.name,
            facade::draw::LEGEND
        )),
        picture: Picture::Rgb(facade::draw::label_overlay(&e.rectified, &labels)),
    });
    // Issue 22: the index image a program reads, and its view a person reads.
    let view = facade::draw::labels_view(e.model.width, e.model.height, &labels);
    if let Some(grey) = GrayImage::from_raw(e.model.width, e.model.height, labels) {
        out.push(Overlay {
            name: format!("overlays/{stem}_labels.png"),
            caption: None,
            picture: Picture::Grey(grey),
        });
        out.push(Overlay {
            name: format!("overlays/{stem}_labels.view.png"),
            caption: None,
            picture: Picture::Rgb(view),
        });
    }
    out
}

/// Chapter 4 on the project's Gothic photo `index`, with its overlays.
pub fn estimate_gothic_photo(
    project: &Project,
    index: usize,
    files: &impl Files,
) -> Result<(GothicFacadeEstimate, Vec<Overlay>), PipelineError> {
    let g = &project.gothics[index];
    let entry = gothic_entry(index, g);
    let (image, lines) =
        photo_and_lines(&g.image, g.lines.as_deref(), files).map_err(at(entry.clone()))?;
    let estimate = estimate_gothic(&GothicPhoto {
        name: &g.image,
        image: &image,
        bbox: g.bbox,
        lines: lines.as_ref(),
        rectified: g.rectified,
        corrections: &g.elements,
    })
    .map_err(|e| match e {
        // Named by the correction itself: `[[gothic]] #1 element #2 (image = …): …`.
        IntegrateError::GothicCorrection { error, .. } => PipelineError::Entry {
            entry: gothic_element_entry(index, error.index, &g.image),
            message: error.problem,
        },
        e => at(entry)(e.to_string()),
    })?;
    let stem = safe_stem(&estimate.name);
    let mut overlays = lines_overlay(
        &estimate.name,
        &stem,
        &image,
        estimate.rectification.as_ref(),
    );
    overlays.push(Overlay {
        name: format!("overlays/{stem}_gothic.png"),
        caption: Some(format!(
            "{}: arches, groups, nesting and stones (ch. 4){} — {}",
            estimate.name,
            if estimate.dropped > 0 {
                format!(
                    "; the learned check dropped {} element(s) the fit found, not drawn",
                    estimate.dropped
                )
            } else {
                String::new()
            },
            facade::gothic::draw::LEGEND
        )),
        picture: Picture::Rgb(facade::gothic::draw::overlay(
            &estimate.facade,
            &estimate.estimate,
            Some(&estimate.masonry),
        )),
    });
    Ok((estimate, overlays))
}

/// The line families and vanishing points of a rectified photo (§3.1.1), if it was rectified.
fn lines_overlay(
    image: &str,
    stem: &str,
    photo: &RgbImage,
    rectification: Option<&facade::rectify::Rectification>,
) -> Vec<Overlay> {
    rectification
        .map(|r| Overlay {
            name: format!("overlays/{stem}_lines.png"),
            caption: Some(format!(
                "{image}: line families and vanishing points (§3.1.1) — {}",
                facade::rectify::OVERLAY_LEGEND
            )),
            picture: Picture::Rgb(facade::rectify::draw_overlay(photo, r)),
        })
        .into_iter()
        .collect()
}
