//! `castellan plan`: read a plan drawing, parse it (dissertation ch. 5), and write PLAN.json,
//! LABELS.png, the label overlay, the vector SVG and the extruded glTF model.

use std::io::Cursor;
use std::time::Instant;

use anyhow::{Context, Result, anyhow};

use crate::cli::PlanArgs;
use crate::output::Outputs;

fn png(img: &image::DynamicImage, what: &std::path::Path) -> Result<Vec<u8>> {
    let mut buf = Cursor::new(Vec::new());
    img.write_to(&mut buf, image::ImageFormat::Png)
        .with_context(|| format!("cannot encode {}", what.display()))?;
    Ok(buf.into_inner())
}

pub fn run(args: &PlanArgs) -> Result<()> {
    let file = args.image.display().to_string();
    let img = image::ImageReader::open(&args.image)
        .with_context(|| format!("cannot read {file}"))?
        .with_guessed_format()
        .with_context(|| format!("cannot read {file}"))?
        .decode()
        .with_context(|| format!("{file}: not a readable image"))?;
    let started = Instant::now();
    let parsed =
        plan::parse(&img, &plan::Options::default()).map_err(|e| anyhow!("{file}: {e}"))?;
    let elapsed = started.elapsed();

    let mut outputs = Outputs::default();
    let doc = plan::output::plan_json(&parsed, args.scale);
    outputs.add(&args.output, serde_json::to_vec_pretty(&doc)?);
    if let Some(path) = &args.labels {
        let labels = image::DynamicImage::ImageLuma8(plan::output::labels_image(&parsed));
        outputs.add(path, png(&labels, path)?);
    }
    if let Some(path) = &args.overlay {
        let over = plan::output::overlay(&parsed, &img.to_luma8());
        outputs.add(path, png(&image::DynamicImage::ImageRgb8(over), path)?);
    }
    if let Some(path) = &args.svg {
        outputs.add(path, plan::output::svg(&parsed).into_bytes());
    }
    if let Some(path) = &args.model {
        // Without a scale, heights are in pixels: 1 m taken as 1/100 of the castle's size.
        let (scale, heights) = match args.scale {
            Some(s) => (s, plan::extrude::Heights::metres()),
            None => {
                let size = f64::from(parsed.width.max(parsed.height));
                (1.0, plan::extrude::Heights::scaled(size / 100.0))
            }
        };
        let src = plan::extrude::to_vsg(&parsed, scale, &heights);
        let model = vsg::run(&src, &vsg::RunOptions::default()).map_err(|e| {
            anyhow!(
                "{}: internal error in the extrusion program: {}",
                path.display(),
                e.render("extrusion.vsg", &src).trim_end()
            )
        })?;
        let glb = vsg::export::to_glb(&model, &vsg::export::ExportOptions::default())
            .with_context(|| format!("cannot export {}", path.display()))?;
        outputs.add(path, glb);
    }
    outputs.commit()?;
    let count = |l: plan::label::Label| parsed.faces.iter().filter(|f| f.label == l).count();
    eprintln!(
        "{file}: {} x {} px, {} vertices, {} walls, {} faces ({} tower rooms), {} towers; parsed in {:.0} ms, written to {}",
        parsed.width,
        parsed.height,
        parsed.vertices.len(),
        parsed.edges.len(),
        parsed.faces.len(),
        count(plan::label::Label::TowerRoom),
        parsed.towers,
        elapsed.as_secs_f64() * 1e3,
        args.output.display()
    );
    for w in &parsed.warnings {
        eprintln!("{file}: warning: {w}");
    }
    Ok(())
}
