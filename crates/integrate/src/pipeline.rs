//! The whole reconstruction of a project, pure (Sui 2011, figure 1.2): the plan drawing
//! (ch. 5), the façade photos (ch. 3) and Gothic photos (ch. 4), integration (ch. 6), the VSG
//! program and its production (ch. 7), the exports. A [`Project`] and a [`Files`] (which reads
//! the files PROJECT.toml names) go in; the estimate, the program, the model, its exports, the
//! textures and the named overlays of every step come out, with per-stage timings.
//!
//! `castellan reconstruct`, `castellan demo` and `castellan serve` are adapters over this
//! module: they read files, show progress and write outputs. The stages a user runs one by one
//! in `serve` ([`parse_plan`], [`estimate_photo`]) are the ones [`reconstruct`] runs, so an
//! overlay in the browser is the overlay of the report.

use std::time::Instant;

use facade::classify::{Method, Training};
use facade::rectify::ManualLines;
use image::{DynamicImage, GrayImage, RgbImage};
use plan::ParsedPlan;
use plan::scale::ScaleNote;
use rayon::prelude::*;

use crate::estimate::Estimate;
use crate::gothic::{GothicFacadeEstimate, GothicPhoto, estimate_gothic};
use crate::photo::{FacadeEstimate, FacadePhoto, crop, estimate_facade};
use crate::project::{FacadeEntry, GothicEntry, Project, TrainingSource, gothic_element_entry};
use crate::textures::{MAX_SAMPLE_SIDE, Texture, box_size, power_of_two, safe_stem, wall_samples};
use crate::{Inputs, IntegrateError, integrate};

/// The files a project names (the plan, photos, TRAINING.json, LINES.json), read by the
/// caller: from a folder (`castellan reconstruct`), a confined project store (`serve`), or
/// memory (tests). Errors are the caller's message (the file, the pixel budget, …).
pub trait Files: Sync {
    /// The image `name` (a path relative to PROJECT.toml), decoded.
    fn image(&self, name: &str) -> Result<DynamicImage, String>;
    /// The JSON file `name`, parsed; errors name `name:line:column`.
    fn json<T: serde::de::DeserializeOwned>(&self, name: &str, what: &str) -> Result<T, String>;
}

/// The steps of [`reconstruct`], in order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    Plan,
    Facades,
    Gothic,
    Integrate,
    Vsg,
    Export,
}

impl Stage {
    /// The key of stats.json's `stages_ms`.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Plan => "plan",
            Stage::Facades => "facades",
            Stage::Gothic => "gothic",
            Stage::Integrate => "integrate",
            Stage::Vsg => "vsg",
            Stage::Export => "export",
        }
    }

    /// What the stage does, for progress messages.
    pub fn describe(self) -> &'static str {
        match self {
            Stage::Plan => "plan drawing (ch. 5)",
            Stage::Facades => "façade photos (ch. 3)",
            Stage::Gothic => "Gothic façades (ch. 4)",
            Stage::Integrate => "integration (ch. 6)",
            Stage::Vsg => "VSG production (ch. 7)",
            Stage::Export => "export",
        }
    }
}

/// What [`reconstruct`] reports while it works.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Progress {
    /// A stage begins.
    Started(Stage),
    /// One of [`steps`] is done (a stage, or one photo of the photo stages).
    Step,
}

/// How many [`Progress::Step`]s [`reconstruct`] reports for `project`.
pub fn steps(project: &Project) -> u64 {
    4 + (project.facades.len() + project.gothics.len()) as u64
}

/// Why a reconstruction failed: the PROJECT.toml entry at fault and what went wrong.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    #[error("{entry}: {message}")]
    Entry { entry: String, message: String },
    #[error(transparent)]
    Integrate(#[from] IntegrateError),
    /// A bug of castellan's, not of the input.
    #[error("internal error: {0}")]
    Internal(String),
}

fn at(entry: impl Into<String>) -> impl Fn(String) -> PipelineError {
    let entry = entry.into();
    move |message| PipelineError::Entry {
        entry: entry.clone(),
        message,
    }
}

/// An overlay picture and the file name it is written under (relative to the output folder).
pub struct Overlay {
    pub name: String,
    /// What it shows, for the report's legend; `None` for data pictures the report does not
    /// show (the label image).
    pub caption: Option<String>,
    pub picture: Picture,
}

/// An overlay's pixels.
pub enum Picture {
    Rgb(RgbImage),
    Grey(GrayImage),
}

/// The plan stage: the parsed drawing and its pictures.
pub struct PlanStage {
    pub parsed: ParsedPlan,
    /// The drawing coloured by label (`overlays/plan_labels.png`).
    pub overlay: Overlay,
    /// The walls as read, over the drawing (`overlays/plan_walls.png`).
    pub walls: Overlay,
    /// The vectorised walls (`plan.svg`).
    pub svg: String,
}

/// Chapter 5 on the project's plan drawing, with the project's plan options.
pub fn parse_plan(project: &Project, files: &impl Files) -> Result<PlanStage, PipelineError> {
    let entry = format!("plan = \"{}\"", project.plan);
    let image = files.image(&project.plan).map_err(at(entry.clone()))?;
    let options = project.plan_options();
    let parsed = plan::parse(&image, &options).map_err(|e| PipelineError::Entry {
        entry,
        message: e.to_string(),
    })?;
    let grey = image.to_luma8();
    corrected_stage(project, parsed, &grey, options.ink)
}

/// The plan stage from a parsed drawing: the user's corrections applied (issue 22), then its
/// pictures. `serve` keeps the parse and calls this alone when only corrections changed.
pub fn corrected_stage(
    project: &Project,
    mut parsed: ParsedPlan,
    grey: &image::GrayImage,
    ink: plan::ink::InkMethod,
) -> Result<PlanStage, PipelineError> {
    let notes = plan::corrections::apply(&mut parsed, project.plan_fixes()).map_err(|e| {
        PipelineError::Entry {
            entry: format!("{} #{}", e.table.name(), e.index),
            message: e.why,
        }
    })?;
    parsed.warnings.extend(notes);
    let overlay = Overlay {
        name: "overlays/plan_labels.png".into(),
        caption: Some(format!(
            "Plan labels (ch. 5) — {}",
            plan::output::label_key_words(&parsed)
        )),
        picture: Picture::Rgb(plan::output::overlay(&parsed, grey)),
    };
    let how = match ink {
        plan::ink::InkMethod::Learned => "learned wall ink",
        plan::ink::InkMethod::Rules => "threshold and clean-up rules",
    };
    let walls = Overlay {
        name: "overlays/plan_walls.png".into(),
        caption: Some(format!(
            "Plan walls ({how}, §5.1.2) — {}",
            plan::output::WALLS_LEGEND
        )),
        picture: Picture::Rgb(plan::output::walls_overlay(&parsed, grey)),
    };
    let svg = plan::output::svg(&parsed);
    Ok(PlanStage {
        parsed,
        overlay,
        walls,
        svg,
    })
}

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
            "{}: arches, groups, nesting and stones (ch. 4) — {}",
            estimate.name,
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

/// Settings of a reconstruction beyond the project's.
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// Overrides the project's seed (the classifier's sampling, the program's randomness).
    pub seed: Option<u64>,
    /// The per-pixel classifier of the façade and Gothic photos (§3.1.3–3.1.4).
    pub classifier: Method,
}

impl Options {
    /// The seed of a run on `project`: this override, else the project's, else 0.
    pub fn seed_for(&self, project: &Project) -> u64 {
        self.seed.or(project.seed).unwrap_or(0)
    }
}

/// Everything a reconstruction produced.
pub struct Reconstruction {
    /// estimate.json.
    pub estimate: Estimate,
    /// How the plan's scale was decided (the bar read, or the assumption made).
    pub scale_note: ScaleNote,
    /// model.vsg, the generated program.
    pub program: String,
    /// The Gothic block programs model.vsg imports (file name, text).
    pub gothic_programs: Vec<(String, String)>,
    pub model: vsg::Model,
    /// Façade crops and wall samples, named as the program names them.
    pub textures: Vec<Texture>,
    pub plan_svg: String,
    /// Every step's overlay: the plan's, then each façade photo's, then each Gothic photo's.
    pub overlays: Vec<Overlay>,
    pub exports: Exports,
    /// The model seen from above against the plan's built area (issue 25; stats.json's
    /// `agreement`).
    pub agreement: crate::agreement::Agreement,
    /// What looks implausible, with the fix (issue 22): the commands print it, the report shows it.
    pub warnings: Vec<crate::plausibility::Warning>,
    /// Milliseconds per stage, in order (Gothic only when the project has Gothic photos).
    pub stages: Vec<(Stage, f64)>,
}

/// The model in the formats users open.
pub struct Exports {
    /// Binary glTF with the semantic node tree and the textures embedded.
    pub glb: Vec<u8>,
    pub obj: String,
    pub mtl: String,
    /// CityJSON 2.0: the building, a part per structure, semantic surfaces (issue 24).
    pub cityjson: String,
    /// IFC4: the structures as assemblies of walls, roofs, slabs, windows, doors; spaces.
    pub ifc: String,
    /// A 960 × 640 picture of the model (3/4 view).
    pub preview: RgbImage,
    /// stats.json: the model's statistics and the stage timings.
    pub stats: serde_json::Value,
    pub terminals: usize,
    /// The textures as PNG (name, bytes), as embedded in the glTF.
    pub textures: Vec<(String, Vec<u8>)>,
}

/// The whole pipeline on `project` (ch. 5 → 3–4 → 6 → 7 → exports). `progress` hears of each
/// stage and step; photos are estimated in parallel.
pub fn reconstruct(
    project: &Project,
    files: &impl Files,
    options: &Options,
    progress: &(dyn Fn(Progress) + Sync),
) -> Result<Reconstruction, PipelineError> {
    let seed = options.seed_for(project);
    let mut stages: Vec<(Stage, f64)> = Vec::new();
    let mut overlays = Vec::new();

    progress(Progress::Started(Stage::Plan));
    let t = Instant::now();
    let plan_stage = parse_plan(project, files)?;
    stages.push((Stage::Plan, ms(t)));
    overlays.push(plan_stage.walls);
    overlays.push(plan_stage.overlay);
    progress(Progress::Step);

    progress(Progress::Started(Stage::Facades));
    let t = Instant::now();
    let photos: Vec<(FacadeEstimate, Vec<Overlay>)> = (0..project.facades.len())
        .into_par_iter()
        .map(|i| {
            let r = estimate_photo(project, i, files, options);
            progress(Progress::Step);
            r
        })
        .collect::<Result<_, _>>()?;
    stages.push((Stage::Facades, ms(t)));

    if !project.gothics.is_empty() {
        progress(Progress::Started(Stage::Gothic));
    }
    let t = Instant::now();
    let gothic_photos: Vec<(GothicFacadeEstimate, Vec<Overlay>)> = (0..project.gothics.len())
        .into_par_iter()
        .map(|i| {
            let r = estimate_gothic_photo(project, i, files);
            progress(Progress::Step);
            r
        })
        .collect::<Result<_, _>>()?;
    if !gothic_photos.is_empty() {
        stages.push((Stage::Gothic, ms(t)));
    }
    let (estimates, facade_overlays): (Vec<_>, Vec<_>) = photos.into_iter().unzip();
    overlays.extend(facade_overlays.into_iter().flatten());
    let (gothics, gothic_overlays): (Vec<_>, Vec<_>) = gothic_photos.into_iter().unzip();
    overlays.extend(gothic_overlays.into_iter().flatten());

    progress(Progress::Started(Stage::Integrate));
    let t = Instant::now();
    let integrated = integrate(&Inputs {
        plan: &plan_stage.parsed,
        plan_image: &project.plan,
        scale: project.given_scale(),
        structure_fixes: &project.structure_fixes,
        facades: &estimates,
        gothics: &gothics,
        correspondences: &project.correspondences,
    })?;
    let estimate = integrated.estimate;
    let mut textures = integrated.textures;
    let mut samples = wall_samples(&estimate, &estimates);
    samples.extend(texture_samples(project, files, &estimate, &estimates)?);
    let program_options = crate::program::Options {
        wall_textures: samples.iter().map(|t| t.name.clone()).collect(),
        ..Default::default()
    };
    textures.extend(samples);
    let program = crate::program::generate(&estimate, &program_options);
    stages.push((Stage::Integrate, ms(t)));
    progress(Progress::Step);

    progress(Progress::Started(Stage::Vsg));
    let t = Instant::now();
    let model = vsg::run_with(
        "model.vsg",
        &program,
        &vsg::RunOptions {
            seed,
            ..Default::default()
        },
        &mut crate::library::Library::with(integrated.gothic_programs.clone()),
    )
    .map_err(|e| {
        PipelineError::Internal(format!(
            "the generated program does not run: {}",
            e.render("model.vsg", &program).trim_end()
        ))
    })?;
    stages.push((Stage::Vsg, ms(t)));
    progress(Progress::Step);

    progress(Progress::Started(Stage::Export));
    let t = Instant::now();
    let heritage = crate::heritage::heritage(&estimate, &model, project.site.as_ref());
    // Textures of unknown real size repeat once a metre.
    let mut exports = export(&model, &heritage, &textures, estimate.scale.units_per_metre)?;
    // Issue 25: how well the model covers the plan it was built from, at the preview's detail.
    let view = crate::agreement::top_view(
        &plan_stage.parsed,
        &estimate,
        &model,
        &vsg::export::ExportOptions::default().tessellation,
    );
    let ids: Vec<String> = estimate.structures.iter().map(|s| s.id.clone()).collect();
    let parsed = &plan_stage.parsed;
    let agreement = crate::agreement::compare(&parsed.labels, &parsed.bulge_towers, &view, &ids);
    exports.stats["agreement"] = agreement.summary();
    let (units, per_pixel) = (estimate.scale.units, estimate.scale.units_per_pixel);
    let mut warnings = crate::plausibility::plan_warnings(
        parsed,
        &project.plan,
        &integrated.scale_note,
        units,
        per_pixel,
    );
    warnings.extend(crate::plausibility::model_warnings(
        parsed, &estimate, &agreement,
    ));
    overlays.push(Overlay {
        name: "overlays/plan_model.png".into(),
        caption: Some(format!(
            "The model from above against the plan's built area (issue 25): IoU {:.3}, {} of {} rooms and {} of {} towers built — {}",
            agreement.iou,
            agreement.rooms_present(),
            agreement.rooms.len(),
            agreement.towers_present(),
            agreement.towers.len(),
            crate::agreement::OVERLAY_LEGEND
        )),
        picture: Picture::Rgb(crate::agreement::overlay(&parsed.labels, &view)),
    });
    stages.push((Stage::Export, ms(t)));
    progress(Progress::Step);
    exports.stats["stages_ms"] = serde_json::Value::Object(
        stages
            .iter()
            .map(|(k, v)| {
                (
                    k.name().to_string(),
                    serde_json::json!((v * 10.0).round() / 10.0),
                )
            })
            .collect(),
    );
    Ok(Reconstruction {
        estimate,
        scale_note: integrated.scale_note,
        program,
        gothic_programs: integrated.gothic_programs,
        model,
        textures,
        plan_svg: plan_stage.svg,
        overlays,
        exports,
        agreement,
        warnings,
        stages,
    })
}

/// The user's texture samples ([[texture]]): crops of boxes in photos, at power-of-two sizes,
/// with their real size when the photo is a façade of known scale.
fn texture_samples(
    project: &Project,
    files: &impl Files,
    estimate: &Estimate,
    photos: &[FacadeEstimate],
) -> Result<Vec<Texture>, PipelineError> {
    let mut out = Vec::new();
    for (i, t) in project.textures.iter().enumerate() {
        let entry = format!("[[texture]] #{} (image = \"{}\")", i + 1, t.image);
        let image = files.image(&t.image).map_err(at(entry.clone()))?.to_rgb8();
        for (k, b) in t.boxes.iter().enumerate() {
            let image = crop(&image, *b).ok_or_else(|| {
                at(entry.clone())(format!("box {b:?} has no pixels inside the image"))
            })?;
            out.push(Texture {
                name: format!("textures/sample_{}_{}.png", i + 1, k + 1),
                image: power_of_two(&image, MAX_SAMPLE_SIDE),
                size: box_size(estimate, photos, &t.image, *b),
            });
        }
    }
    Ok(out)
}

/// glTF (textures embedded, the structures in its metadata), OBJ + MTL, CityJSON, IFC, a
/// preview picture and statistics of `model`.
fn export(
    model: &vsg::Model,
    heritage: &vsg::export::semantics::Heritage,
    textures: &[Texture],
    texture_scale: f64,
) -> Result<Exports, PipelineError> {
    let options = vsg::export::ExportOptions {
        texture_scale,
        ..Default::default()
    };
    let mut embedded = vsg::export::Textures::new();
    let mut pngs = Vec::new();
    for t in textures {
        let bytes = encode_png(&t.image)
            .map_err(|e| PipelineError::Internal(format!("{}: {e}", t.name)))?;
        embedded.insert(
            t.name.clone(),
            vsg::export::TextureImage {
                bytes: bytes.clone(),
                mime_type: "image/png".into(),
                size: t.size,
            },
        );
        pngs.push((t.name.clone(), bytes));
    }
    let glb = vsg::export::to_glb_with_metadata(model, &options, &embedded, heritage)
        .map_err(|e| PipelineError::Internal(format!("cannot export model.glb: {e}")))?;
    let (obj, mtl) = vsg::export::to_obj(model, &options, "model.mtl")
        .map_err(|e| PipelineError::Internal(format!("cannot export model.obj: {e}")))?;
    let cityjson = vsg::export::to_cityjson(model, heritage, &options)
        .map_err(|e| PipelineError::Internal(format!("cannot export model.city.json: {e}")))?;
    let ifc = vsg::export::to_ifc(model, heritage, &options)
        .map_err(|e| PipelineError::Internal(format!("cannot export model.ifc: {e}")))?;
    let picture = vsg::render::render(
        model,
        &vsg::render::RenderOptions {
            width: 960,
            height: 640,
            tessellation: options.tessellation,
            ..Default::default()
        },
    );
    let preview = RgbImage::from_raw(picture.width, picture.height, picture.rgb)
        .ok_or_else(|| PipelineError::Internal("preview size".into()))?;
    let stats = vsg::stats::Stats::of(model, &options.tessellation);
    let stats_json = serde_json::to_value(&stats)
        .map_err(|e| PipelineError::Internal(format!("stats.json: {e}")))?;
    Ok(Exports {
        glb,
        obj,
        mtl,
        cityjson,
        ifc,
        preview,
        stats: stats_json,
        terminals: stats.terminals,
        textures: pngs,
    })
}

/// PNG bytes of an image (the encoding every output of castellan uses, the binary's too).
pub fn encode_png<P, C>(image: &image::ImageBuffer<P, C>) -> Result<Vec<u8>, String>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    let mut bytes = Vec::new();
    image
        .write_with_encoder(image::codecs::png::PngEncoder::new(&mut bytes))
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}

impl Picture {
    /// The picture as PNG.
    pub fn png(&self) -> Result<Vec<u8>, String> {
        match self {
            Picture::Rgb(img) => encode_png(img),
            Picture::Grey(img) => encode_png(img),
        }
    }
}

impl Reconstruction {
    /// Every output file but the report (name relative to the output folder, bytes): the
    /// program and the library it imports, the model in each format, the preview, the
    /// estimate and statistics, the textures, the plan's SVG and every overlay.
    pub fn files(&self) -> Result<Vec<(String, Vec<u8>)>, PipelineError> {
        let mut out: Vec<(String, Vec<u8>)> = Vec::new();
        for o in &self.overlays {
            let bytes = o
                .picture
                .png()
                .map_err(|e| PipelineError::Internal(format!("{}: {e}", o.name)))?;
            out.push((o.name.clone(), bytes));
        }
        out.push(("plan.svg".into(), self.plan_svg.clone().into_bytes()));
        for (file, text) in &self.gothic_programs {
            out.push((file.clone(), text.clone().into_bytes()));
        }
        out.extend(self.exports.textures.iter().cloned());
        out.push(("model.vsg".into(), self.program.clone().into_bytes()));
        for (file, text) in crate::library::FILES {
            out.push((file.to_string(), text.as_bytes().to_vec()));
        }
        out.push(("model.glb".into(), self.exports.glb.clone()));
        out.push(("model.obj".into(), self.exports.obj.clone().into_bytes()));
        out.push(("model.mtl".into(), self.exports.mtl.clone().into_bytes()));
        out.push((
            "model.city.json".into(),
            self.exports.cityjson.clone().into_bytes(),
        ));
        out.push(("model.ifc".into(), self.exports.ifc.clone().into_bytes()));
        let preview = encode_png(&self.exports.preview)
            .map_err(|e| PipelineError::Internal(format!("preview.png: {e}")))?;
        out.push(("preview.png".into(), preview));
        out.push(("stats.json".into(), pretty(&self.exports.stats)?));
        out.push(("estimate.json".into(), pretty(&self.estimate)?));
        Ok(out)
    }
}

fn pretty<T: serde::Serialize>(value: &T) -> Result<Vec<u8>, PipelineError> {
    serde_json::to_vec_pretty(value).map_err(|e| PipelineError::Internal(e.to_string()))
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}
