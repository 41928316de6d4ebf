//! `castellan reconstruct PROJECT.toml -o OUTDIR` (issue 9, dissertation ch. 6 and §7.2.2–7.2.3):
//! plan drawing and façade photos → estimates → integrated hierarchy → VSG program → model,
//! with the overlays of every step and an HTML report. Everything is written at the end, each
//! file atomically, so a failed run leaves OUTDIR as it was.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, anyhow};
use clap::Args;
use image::GrayImage;
use integrate::gothic::{GothicFacadeEstimate, GothicPhoto, estimate_gothic};
use integrate::photo::{FacadeEstimate, FacadePhoto, estimate_facade};
use integrate::project::{Project, TrainingSource};
use rayon::prelude::*;

use crate::images::{png, read_image};
use crate::output::Outputs;

/// `castellan reconstruct` flags.
#[derive(Debug, Args)]
pub struct ReconstructArgs {
    /// The project file (PROJECT.toml contract).
    pub project: PathBuf,
    /// Output folder: model.vsg, model.glb, model.obj, stats.json, estimate.json, index.html.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Seed for the classifier's sampling and the program's randomness (overrides the project's).
    #[arg(long)]
    pub seed: Option<u64>,
}

/// What a reconstruction produced, for the commands' closing lines.
pub struct Summary {
    pub estimate: integrate::estimate::Estimate,
    pub stages: Vec<(String, f64)>,
    pub terminals: usize,
    pub report: PathBuf,
    pub model: PathBuf,
}

pub fn run(args: &ReconstructArgs) -> Result<()> {
    let s = reconstruct(&args.project, &args.output, args.seed)?;
    print_summary(&s);
    Ok(())
}

pub fn print_summary(s: &Summary) {
    let times: Vec<String> = s
        .stages
        .iter()
        .map(|(k, v)| format!("{k} {v:.0} ms"))
        .collect();
    eprintln!(
        "{} structures, {} façade(s) mapped, {} terminals; {}",
        s.estimate.structures.len(),
        s.estimate
            .structures
            .iter()
            .map(|x| x.facades.len())
            .sum::<usize>(),
        s.terminals,
        times.join(", ")
    );
    eprintln!(
        "report: {}\nmodel:  {}",
        s.report.display(),
        s.model.display()
    );
}

/// Runs the whole pipeline and writes OUTDIR.
pub fn reconstruct(project_path: &Path, outdir: &Path, seed: Option<u64>) -> Result<Summary> {
    let name = project_path.display().to_string();
    let text = crate::text::read_text(project_path)?;
    let project = Project::from_toml(&text).map_err(|e| anyhow!("{name}:{e}"))?;
    let dir = project_path.parent().unwrap_or(Path::new("")).to_path_buf();
    let seed = seed.or(project.seed).unwrap_or(0);
    let bar = crate::progress::bar(4 + (project.facades.len() + project.gothics.len()) as u64);
    let mut stages: Vec<(String, f64)> = Vec::new();
    let mut outputs = Outputs::folder(outdir);

    bar.set_message("plan drawing (ch. 5)");
    let t = Instant::now();
    let plan_path = dir.join(&project.plan);
    let plan_image =
        read_image(&plan_path).with_context(|| format!("{name}: plan = \"{}\"", project.plan))?;
    let parsed = plan::parse(&plan_image, &project.plan_options())
        .map_err(|e| anyhow!("{name}: plan = \"{}\": {e}", project.plan))?;
    stages.push(("plan".into(), ms(t)));
    let plan_scale = match project.scale_bar {
        None => project.scale,
        Some(metres) => Some(
            crate::plan_cmd::scale_from_bar(&parsed, metres, &format!("{name}: plan scale bar"))
                .ok_or_else(|| {
                    anyhow!(
                        "{name}: scale_bar = {metres}: no drawn scale bar found in plan = \"{}\" ({}); give scale = METRES_PER_PIXEL instead",
                        project.plan,
                        plan::scalebar::LOOKED_FOR
                    )
                })?,
        ),
    };
    outputs.add(
        &outdir.join("overlays/plan_labels.png"),
        png(
            &plan::output::overlay(&parsed, &plan_image.to_luma8()),
            Path::new("plan overlay"),
        )?,
    );
    outputs.add(
        &outdir.join("plan.svg"),
        plan::output::svg(&parsed).into_bytes(),
    );
    bar.inc(1);

    bar.set_message("façade photos (ch. 3)");
    let t = Instant::now();
    let inputs: Vec<_> = project
        .facades
        .iter()
        .enumerate()
        .map(|(i, f)| -> Result<_> {
            let at = format!("{name}: [[facade]] #{} (image = \"{}\")", i + 1, f.image);
            let (image, lines) = read_photo(&dir, &f.image, f.lines.as_deref(), &at)?;
            let training = match &f.training {
                TrainingSource::Inline(t) => t.clone(),
                TrainingSource::File(p) => crate::text::read_json(&dir.join(p), "a TRAINING.json")
                    .with_context(|| at.clone())?,
            };
            Ok((image, training, lines))
        })
        .collect::<Result<_>>()?;
    let estimates: Vec<FacadeEstimate> = project
        .facades
        .par_iter()
        .zip(&inputs)
        .map(|(f, (image, training, lines))| {
            let e = estimate_facade(&FacadePhoto {
                name: &f.image,
                image,
                training,
                lines: lines.as_ref(),
                rectified: f.rectified,
                bbox: f.bbox,
                scale: f.scale,
                seed,
            })
            .map_err(|e| anyhow!("{name}: [[facade]] image = \"{}\": {e}", f.image));
            bar.inc(1);
            e
        })
        .collect::<Result<_>>()?;
    stages.push(("facades".into(), ms(t)));

    if !project.gothics.is_empty() {
        bar.set_message("Gothic façades (ch. 4)");
    }
    let t = Instant::now();
    let gothic_inputs: Vec<_> = project
        .gothics
        .iter()
        .enumerate()
        .map(|(i, g)| -> Result<_> {
            let at = format!("{name}: [[gothic]] #{} (image = \"{}\")", i + 1, g.image);
            read_photo(&dir, &g.image, g.lines.as_deref(), &at)
        })
        .collect::<Result<_>>()?;
    let gothics: Vec<GothicFacadeEstimate> = project
        .gothics
        .par_iter()
        .zip(&gothic_inputs)
        .map(|(g, (image, lines))| {
            let e = estimate_gothic(&GothicPhoto {
                name: &g.image,
                image,
                bbox: g.bbox,
                lines: lines.as_ref(),
                rectified: g.rectified,
            })
            .map_err(|e| anyhow!("{name}: [[gothic]] image = \"{}\": {e}", g.image));
            bar.inc(1);
            e
        })
        .collect::<Result<_>>()?;
    if !gothics.is_empty() {
        stages.push(("gothic".into(), ms(t)));
    }
    // The inputs are in the order of the estimates (an indexed parallel collect keeps it).
    for (g, (photo, _)) in gothics.iter().zip(&gothic_inputs) {
        let stem = stem(&g.name);
        add_lines_overlay(&mut outputs, outdir, &stem, photo, g.rectification.as_ref())?;
        outputs.add(
            &outdir.join(format!("overlays/{stem}_gothic.png")),
            png(
                &facade::gothic::draw::overlay(&g.facade, &g.estimate, Some(&g.masonry)),
                Path::new("Gothic overlay"),
            )?,
        );
    }
    for (e, (photo, _, _)) in estimates.iter().zip(&inputs) {
        let stem = stem(&e.name);
        add_lines_overlay(&mut outputs, outdir, &stem, photo, e.rectification.as_ref())?;
        let labels = e.model.labels();
        outputs.add(
            &outdir.join(format!("overlays/{stem}_facade.png")),
            png(
                &facade::draw::label_overlay(&e.rectified, &labels),
                Path::new("façade overlay"),
            )?,
        );
        let lab = GrayImage::from_raw(e.model.width, e.model.height, labels)
            .ok_or_else(|| anyhow!("label image size"))?;
        outputs.add(
            &outdir.join(format!("overlays/{stem}_labels.png")),
            png(&lab, Path::new("labels"))?,
        );
    }

    bar.set_message("integration (ch. 6)");
    let t = Instant::now();
    let mut estimate = integrate::integrate(&integrate::Inputs {
        plan: &parsed,
        plan_image: &project.plan,
        scale: plan_scale,
        facades: &estimates,
        gothics: &gothics,
        correspondences: &project.correspondences,
    })
    .map_err(|e| anyhow!("{name}: {e}"))?;
    let mut textures = integrate::textures::facade_textures(&mut estimate, &estimates);
    let (mut samples, sample_width) = integrate::textures::wall_samples(&estimate, &estimates);
    for (i, t) in project.textures.iter().enumerate() {
        let image = read_image(&dir.join(&t.image))
            .with_context(|| format!("{name}: [[texture]] #{} (image = \"{}\")", i + 1, t.image))?
            .to_rgb8();
        for (k, b) in t.boxes.iter().enumerate() {
            let crop = integrate::textures::crop(&image, *b).ok_or_else(|| {
                anyhow!(
                    "{name}: [[texture]] #{} box {b:?} has no pixels inside {}",
                    i + 1,
                    t.image
                )
            })?;
            samples.push(integrate::textures::Texture {
                name: format!("textures/sample_{}_{}.png", i + 1, k + 1),
                image: crop,
            });
        }
    }
    let program_options = integrate::program::Options {
        wall_textures: samples.iter().map(|t| t.name.clone()).collect(),
        ..Default::default()
    };
    textures.extend(samples);
    let program = integrate::program::generate(&estimate, &program_options);
    stages.push(("integrate".into(), ms(t)));
    bar.inc(1);

    bar.set_message("VSG production (ch. 7)");
    let t = Instant::now();
    let options = vsg::RunOptions {
        seed,
        ..Default::default()
    };
    let generated = integrate::gothic_programs(&estimate, &gothics);
    for (file, text) in &generated {
        outputs.add(&outdir.join(file), text.clone().into_bytes());
    }
    let model = vsg::run_with(
        "model.vsg",
        &program,
        &options,
        &mut integrate::library::Library::with(generated),
    )
    .map_err(|e| {
        anyhow!(
            "internal error: the generated program does not run: {}",
            e.render("model.vsg", &program).trim_end()
        )
    })?;
    stages.push(("vsg".into(), ms(t)));
    bar.inc(1);

    bar.set_message("export");
    let t = Instant::now();
    let export = vsg::export::ExportOptions {
        texture_scale: sample_width.unwrap_or(1.0),
        ..Default::default()
    };
    let mut embedded = vsg::export::Textures::new();
    for t in &textures {
        let bytes = png(&t.image, Path::new(&t.name))?;
        outputs.add(&outdir.join(&t.name), bytes.clone());
        embedded.insert(
            t.name.clone(),
            vsg::export::TextureImage {
                bytes,
                mime_type: "image/png".into(),
            },
        );
    }
    let glb = vsg::export::to_glb_with_textures(&model, &export, &embedded)
        .context("cannot export model.glb")?;
    let (obj, mtl) =
        vsg::export::to_obj(&model, &export, "model.mtl").context("cannot export model.obj")?;
    let picture = vsg::render::render(
        &model,
        &vsg::render::RenderOptions {
            width: 960,
            height: 640,
            tessellation: export.tessellation,
            ..Default::default()
        },
    );
    let preview = image::RgbImage::from_raw(picture.width, picture.height, picture.rgb)
        .ok_or_else(|| anyhow!("preview size"))?;
    stages.push(("export".into(), ms(t)));
    bar.inc(1);
    bar.finish_and_clear();

    let stats = vsg::stats::Stats::of(&model, &export.tessellation);
    let mut stats_json = serde_json::to_value(&stats)?;
    stats_json["stages_ms"] = serde_json::Value::Object(
        stages
            .iter()
            .map(|(k, v)| (k.clone(), serde_json::json!((v * 10.0).round() / 10.0)))
            .collect(),
    );
    outputs.add(&outdir.join("model.vsg"), program.clone().into_bytes());
    for (file, text) in integrate::library::FILES {
        outputs.add(&outdir.join(file), text.as_bytes().to_vec());
    }
    let report = crate::report::html(&project, &estimate, &stats_json, &stages, &glb);
    outputs.add(&outdir.join("model.glb"), glb);
    outputs.add(&outdir.join("model.obj"), obj.into_bytes());
    outputs.add(&outdir.join("model.mtl"), mtl.into_bytes());
    outputs.add(
        &outdir.join("preview.png"),
        png(&preview, Path::new("preview"))?,
    );
    outputs.add(
        &outdir.join("stats.json"),
        serde_json::to_vec_pretty(&stats_json)?,
    );
    outputs.add(
        &outdir.join("estimate.json"),
        serde_json::to_vec_pretty(&estimate)?,
    );
    outputs.add(&outdir.join("index.html"), report.into_bytes());
    outputs.commit()?;
    Ok(Summary {
        estimate,
        stages,
        terminals: stats.terminals,
        report: outdir.join("index.html"),
        model: outdir.join("model.glb"),
    })
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// A file name without folders and extension, for output names.
pub fn stem(name: &str) -> String {
    Path::new(name)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| name.to_string())
}

/// A photo of PROJECT.toml and its optional rectification segments (LINES.json); `at` names
/// the entry in errors.
fn read_photo(
    dir: &Path,
    image: &str,
    lines: Option<&str>,
    at: &str,
) -> Result<(image::RgbImage, Option<facade::rectify::ManualLines>)> {
    let photo = read_image(&dir.join(image)).with_context(|| at.to_string())?;
    let lines = match lines {
        Some(p) => Some(
            crate::text::read_json(&dir.join(p), "a LINES.json").with_context(|| at.to_string())?,
        ),
        None => None,
    };
    Ok((photo.to_rgb8(), lines))
}

/// The line families and vanishing points of a rectified photo (§3.1.1).
fn add_lines_overlay(
    outputs: &mut Outputs,
    outdir: &Path,
    stem: &str,
    photo: &image::RgbImage,
    rectification: Option<&facade::rectify::Rectification>,
) -> Result<()> {
    if let Some(r) = rectification {
        outputs.add(
            &outdir.join(format!("overlays/{stem}_lines.png")),
            png(
                &facade::rectify::draw_overlay(photo, r),
                Path::new("lines overlay"),
            )?,
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: ReconstructArgs,
    }

    #[test]
    fn reconstruct_needs_a_project_and_an_output_folder() {
        assert!(Cli::try_parse_from(["x", "p.toml"]).is_err());
        let c = Cli::try_parse_from(["x", "p.toml", "-o", "out", "--seed", "3"]).unwrap();
        assert_eq!(c.args.output, PathBuf::from("out"));
        assert_eq!(c.args.seed, Some(3));
    }

    #[test]
    fn stems_drop_folders_and_extensions() {
        assert_eq!(stem("photos/keep south.jpg"), "keep south");
    }
}
