//! `castellan vsg run`: read a program, produce the model, write glb / obj+mtl / STATS.json.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, anyhow};

use crate::cli::VsgRunArgs;
use crate::output::Outputs;

pub fn run(args: &VsgRunArgs) -> Result<()> {
    let file = args.program.display().to_string();
    let src =
        std::fs::read_to_string(&args.program).with_context(|| format!("cannot read {file}"))?;
    let options = vsg::RunOptions {
        seed: args.seed,
        overrides: args.set.clone(),
        limits: vsg::Limits {
            max_depth: args.max_depth,
            max_shapes: args.max_shapes,
            tessellation: vsg::shape::Tessellation {
                segments: args.segments,
            },
        },
    };
    let started = Instant::now();
    let mut resolver = FileResolver {
        lib: args.lib.clone(),
    };
    let model = vsg::run_with(&file, &src, &options, &mut resolver)
        .map_err(|e| anyhow!("{}", e.render(&file, &src).trim_end()))?;
    let produced = started.elapsed();
    let textures = read_textures(&model, &args.program)?;
    let export = vsg::export::ExportOptions {
        tessellation: vsg::shape::Tessellation {
            segments: args.segments,
        },
        ..Default::default()
    };
    let mut outputs = Outputs::default();
    let glb = vsg::export::to_glb_with_textures(&model, &export, &textures)
        .with_context(|| format!("cannot export {}", args.output.display()))?;
    outputs.add(&args.output, glb);
    if let Some(obj_path) = &args.obj {
        let mtl_path = obj_path.with_extension("mtl");
        let mtl_name = mtl_path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let (obj, mtl) = vsg::export::to_obj(&model, &export, &mtl_name)
            .with_context(|| format!("cannot export {}", obj_path.display()))?;
        outputs.add(obj_path, obj.into_bytes());
        outputs.add(&mtl_path, mtl.into_bytes());
    }
    if let Some(preview_path) = &args.preview {
        let (width, height) = args.preview_size;
        let picture = vsg::render::render(
            &model,
            &vsg::render::RenderOptions {
                width,
                height,
                tessellation: export.tessellation,
                ..Default::default()
            },
        );
        outputs.add(preview_path, png(&picture)?);
    }
    let stats = vsg::stats::Stats::of(&model, &export.tessellation);
    if let Some(stats_path) = &args.stats {
        outputs.add(stats_path, serde_json::to_vec_pretty(&stats)?);
    }
    outputs.commit()?;
    eprintln!(
        "{file}: {} terminals ({} visible, {} void), {} non-terminals, volume {:.6}, {} triangles; produced in {:.1} ms, written to {}",
        stats.terminals,
        stats.visible_terminals,
        stats.void_terminals,
        stats.nonterminals,
        stats.volume.total,
        stats.triangles,
        produced.as_secs_f64() * 1e3,
        args.output.display()
    );
    Ok(())
}

/// Every texture a visible terminal uses must be a readable image, looked up beside the
/// program; the error names the file and the rule that set it. Returns the images to embed:
/// PNG and JPEG files as they are, other formats re-encoded as PNG.
fn read_textures(model: &vsg::Model, program: &Path) -> Result<vsg::export::Textures> {
    let dir = program.parent().unwrap_or(Path::new(""));
    let mut textures = vsg::export::Textures::new();
    for node in model.terminals() {
        if node.state != vsg::tree::NodeState::Terminal {
            continue;
        }
        let appearance = model.appearance(node);
        let Some(texture) = &appearance.texture else {
            continue;
        };
        if textures.contains_key(texture) {
            continue;
        }
        let path = dir.join(texture);
        let image = read_texture(&path).map_err(|e| {
            anyhow!(
                "{}:{}: cannot read texture '{}' ({}) set for '{}': {e:#}",
                program.display(),
                appearance.texture_line,
                texture,
                path.display(),
                model.symbol(node)
            )
        })?;
        textures.insert(texture.clone(), image);
    }
    Ok(textures)
}

/// One texture file, checked to decode, as PNG or JPEG bytes.
fn read_texture(path: &Path) -> Result<vsg::export::TextureImage> {
    let decoded = crate::images::read_image(path)?;
    let bytes = std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
    let (bytes, mime_type) = match image::guess_format(&bytes) {
        Ok(image::ImageFormat::Png) => (bytes, "image/png"),
        Ok(image::ImageFormat::Jpeg) => (bytes, "image/jpeg"),
        _ => (crate::images::png(&decoded.to_rgba8(), path)?, "image/png"),
    };
    Ok(vsg::export::TextureImage {
        bytes,
        mime_type: mime_type.into(),
    })
}

/// Encodes a rendered picture as PNG.
fn png(picture: &vsg::render::Picture) -> Result<Vec<u8>> {
    let image = image::RgbImage::from_raw(picture.width, picture.height, picture.rgb.clone())
        .context("the preview picture has the wrong size")?;
    crate::images::png(&image, std::path::Path::new("the preview"))
}

/// Finds imported programs: beside the importing file first, then in each `--lib` directory.
pub struct FileResolver {
    pub lib: Vec<PathBuf>,
}

impl vsg::import::Resolver for FileResolver {
    fn load(&mut self, from: &str, path: &str) -> Result<(String, String), String> {
        let here = Path::new(from).parent().unwrap_or(Path::new(""));
        let candidates: Vec<PathBuf> = std::iter::once(here.join(path))
            .chain(self.lib.iter().map(|d| d.join(path)))
            .collect();
        let Some(found) = candidates.iter().find(|c| c.is_file()) else {
            let looked: Vec<String> = candidates.iter().map(|c| c.display().to_string()).collect();
            return Err(format!(
                "no such file (looked in {}; add directories with --lib)",
                looked.join(", ")
            ));
        };
        let text = std::fs::read_to_string(found)
            .map_err(|e| format!("cannot read {}: {e}", found.display()))?;
        Ok((found.display().to_string(), text))
    }
}
