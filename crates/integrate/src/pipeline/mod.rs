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

use image::RgbImage;
use plan::ParsedPlan;
use plan::scale::ScaleNote;
use rayon::prelude::*;

use crate::estimate::Estimate;
use crate::gothic::GothicFacadeEstimate;
use crate::photo::{FacadeEstimate, crop};
use crate::project::Project;
use crate::textures::{MAX_SAMPLE_SIDE, Texture, box_size, power_of_two, wall_samples};
use crate::{Inputs, integrate};

mod interface;
mod photos;

use interface::at;
pub use interface::{Files, InMemory, Options, Overlay, Picture, PipelineError, encode_png};
pub use photos::{estimate_gothic_photo, estimate_photo, training};

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
        plan::ink::InkMethod::Network => "wall-ink network",
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
    warnings.extend(crate::plausibility::facade_warnings(&estimates));
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
