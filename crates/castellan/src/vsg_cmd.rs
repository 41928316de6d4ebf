//! `castellan vsg run`: read a program, produce the model, write glb / obj+mtl / STATS.json and
//! the heritage formats (CityJSON, IFC; issue 24), the root's children as the building's parts.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, anyhow};

use crate::output::Outputs;
use clap::Args;

pub fn run(args: &VsgRunArgs) -> Result<()> {
    let file = args.program.display().to_string();
    // Bounded, UTF-8 errors at line:col, a byte-order mark dropped (text.rs).
    let src = crate::text::read_text(&args.program)?;
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
    // The program's own parts: the root's children, in its units taken as metres.
    let heritage = vsg::export::semantics::Heritage {
        name: args
            .program
            .file_stem()
            .map_or_else(|| "model".into(), |s| s.to_string_lossy().into_owned()),
        ..Default::default()
    };
    let glb = vsg::export::to_glb_with_metadata(&model, &export, &textures, &heritage)
        .with_context(|| format!("cannot export {}", args.output.display()))?;
    outputs.add(&args.output, glb);
    if let Some(path) = &args.cityjson {
        let text = vsg::export::to_cityjson(&model, &heritage, &export)
            .with_context(|| format!("cannot export {}", path.display()))?;
        outputs.add(path, text.into_bytes());
    }
    if let Some(path) = &args.ifc {
        let text = vsg::export::to_ifc(&model, &heritage, &export)
            .with_context(|| format!("cannot export {}", path.display()))?;
        outputs.add(path, text.into_bytes());
    }
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
    let bytes = crate::images::read_file(path)?;
    let (decoded, format) = crate::images::decode(&bytes, &path.display().to_string())?;
    let (bytes, mime_type) = match format {
        image::ImageFormat::Png => (bytes, "image/png"),
        image::ImageFormat::Jpeg => (bytes, "image/jpeg"),
        _ => (crate::images::png(&decoded.to_rgba8(), path)?, "image/png"),
    };
    Ok(vsg::export::TextureImage {
        bytes,
        mime_type: mime_type.into(),
        // A file named on the command line has no known real size: it repeats every unit.
        size: None,
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
        let Some(found) = candidates.iter().find(|c| c.exists()) else {
            let looked: Vec<String> = candidates.iter().map(|c| c.display().to_string()).collect();
            return Err(format!(
                "no such file (looked in {}; add directories with --lib)",
                looked.join(", ")
            ));
        };
        // A folder, a device such as /dev/zero or a pipe exists but is no program text.
        if !found.is_file() {
            let what = match std::fs::metadata(found) {
                Ok(m) if m.is_dir() => "a folder",
                _ => "a device or other special file",
            };
            return Err(format!(
                "{} is {what}, not a regular file; import a .vsg program",
                found.display()
            ));
        }
        let text = crate::text::read_text(found).map_err(|e| format!("{e:#}"))?;
        Ok((found.display().to_string(), text))
    }
}

/// `castellan vsg run` flags.
#[derive(Debug, Args)]
pub struct VsgRunArgs {
    /// The VSG program.
    pub program: PathBuf,
    /// Binary glTF output (.glb); its node tree is the semantic tree.
    #[arg(short = 'o', long = "output", value_name = "MODEL.glb")]
    pub output: PathBuf,
    /// Also write Wavefront OBJ (with an .mtl beside it), one group per terminal.
    #[arg(long, value_name = "MODEL.obj")]
    pub obj: Option<PathBuf>,
    /// Also write CityJSON 2.0 (QGIS, cjio, 3D city viewers): a Building whose parts are the
    /// root's children, LoD 2 solids with semantic surfaces, LoD 3 where there are windows or
    /// doors; the program's units are taken as metres.
    #[arg(long, value_name = "MODEL.city.json")]
    pub cityjson: Option<PathBuf>,
    /// Also write IFC4 (Bonsai, IfcOpenShell, BIM tools): the root's children as element
    /// assemblies of walls, roofs, slabs, windows and doors, void shapes as spaces, volumes and
    /// masses as quantities.
    #[arg(long, value_name = "MODEL.ifc")]
    pub ifc: Option<PathBuf>,
    /// Write counts and exact volumes as JSON.
    #[arg(long, value_name = "STATS.json")]
    pub stats: Option<PathBuf>,
    /// Also render a quick preview picture (PNG): visible terminals in their colours, from a
    /// 3/4 view fitted to the model.
    #[arg(long, value_name = "PREVIEW.png")]
    pub preview: Option<PathBuf>,
    /// Size of the preview picture in pixels.
    #[arg(long, value_name = "WxH", default_value = "800x600", value_parser = parse_size)]
    pub preview_size: (u32, u32),
    /// Override a declared float: `--set height=12.5` (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE", value_parser = parse_assignment)]
    pub set: Vec<(String, f64)>,
    /// Seed of every random choice; the same program and seed give the same model.
    #[arg(long, default_value_t = vsg::DEFAULT_SEED)]
    pub seed: u64,
    /// Segments around a full circle when meshing curved shapes.
    #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u32).range(3..=4096))]
    pub segments: u32,
    /// Where `import "file.vsg"` looks after the importing file's own directory (repeatable),
    /// e.g. `--lib library` for the medieval library.
    #[arg(long = "lib", value_name = "DIR")]
    pub lib: Vec<PathBuf>,
    /// Stop with an error when production nests deeper than this.
    #[arg(long, default_value_t = vsg::Limits::default().max_depth)]
    pub max_depth: u32,
    /// Stop with an error when production creates more shapes than this.
    #[arg(long, default_value_t = vsg::Limits::default().max_shapes)]
    pub max_shapes: usize,
}

fn parse_assignment(s: &str) -> Result<(String, f64), String> {
    let (name, value) = s
        .split_once('=')
        .ok_or_else(|| format!("expected NAME=VALUE, found '{s}'"))?;
    let name = name.trim();
    // Imported floats are named `alias.name`.
    if name.is_empty()
        || name.starts_with('.')
        || name.ends_with('.')
        || !name
            .chars()
            .all(|c| c.is_alphanumeric() || c == '_' || c == '.')
    {
        return Err(format!("'{name}' is not a variable name"));
    }
    Ok((name.to_string(), crate::flags::finite(value)?))
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("expected WIDTHxHEIGHT such as 800x600 (each 16 to 8192), found '{s}'");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if !(16..=8192).contains(&w) || !(16..=8192).contains(&h) {
        return Err(bad());
    }
    Ok((w, h))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flags::testing::parse;
    fn run_args(extra: &[&str]) -> Result<VsgRunArgs, clap::Error> {
        let mut argv = vec!["castellan", "vsg", "run", "p.vsg", "-o", "m.glb"];
        argv.extend_from_slice(extra);
        parse::<VsgRunArgs>(&argv[3..])
    }

    #[test]
    fn output_is_required() {
        assert!(parse::<VsgRunArgs>(&["p.vsg"]).is_err());
        assert_eq!(run_args(&[]).unwrap().output, PathBuf::from("m.glb"));
    }

    #[test]
    fn obj_flag() {
        assert_eq!(
            run_args(&["--obj", "m.obj"]).unwrap().obj,
            Some(PathBuf::from("m.obj"))
        );
    }

    #[test]
    fn heritage_format_flags() {
        let a = run_args(&[]).unwrap();
        assert_eq!((a.cityjson, a.ifc), (None, None));
        let a = run_args(&["--cityjson", "m.city.json", "--ifc", "m.ifc"]).unwrap();
        assert_eq!(a.cityjson, Some(PathBuf::from("m.city.json")));
        assert_eq!(a.ifc, Some(PathBuf::from("m.ifc")));
    }

    #[test]
    fn stats_flag() {
        assert_eq!(
            run_args(&["--stats", "s.json"]).unwrap().stats,
            Some(PathBuf::from("s.json"))
        );
    }

    #[test]
    fn set_flag_repeats_and_checks_its_value() {
        let a = run_args(&["--set", "h=2.5", "--set", "n = 3"]).unwrap();
        assert_eq!(a.set, vec![("h".to_string(), 2.5), ("n".to_string(), 3.0)]);
        assert!(run_args(&["--set", "h"]).is_err());
        assert!(run_args(&["--set", "h=tall"]).is_err());
        assert!(run_args(&["--set", "h=inf"]).is_err());
        let a = run_args(&["--set", "tower.radius=4"]).unwrap();
        assert_eq!(a.set, vec![("tower.radius".to_string(), 4.0)]);
        assert!(run_args(&["--set", "tower.=4"]).is_err());
    }

    #[test]
    fn preview_flags() {
        let a = run_args(&[]).unwrap();
        assert_eq!((a.preview, a.preview_size), (None, (800, 600)));
        let a = run_args(&["--preview", "p.png", "--preview-size", "320x200"]).unwrap();
        assert_eq!(a.preview, Some(PathBuf::from("p.png")));
        assert_eq!(a.preview_size, (320, 200));
        assert!(run_args(&["--preview-size", "320"]).is_err());
        assert!(run_args(&["--preview-size", "0x200"]).is_err());
        assert!(run_args(&["--preview-size", "99999x200"]).is_err());
    }

    #[test]
    fn lib_flag_repeats() {
        assert!(run_args(&[]).unwrap().lib.is_empty());
        let a = run_args(&["--lib", "library", "--lib", "/x"]).unwrap();
        assert_eq!(a.lib, [PathBuf::from("library"), PathBuf::from("/x")]);
    }

    #[test]
    fn seed_flag_defaults_to_the_library_default() {
        assert_eq!(run_args(&[]).unwrap().seed, vsg::DEFAULT_SEED);
        assert_eq!(run_args(&["--seed", "42"]).unwrap().seed, 42);
        assert!(run_args(&["--seed", "-1"]).is_err());
    }

    #[test]
    fn segments_flag_is_bounded() {
        assert_eq!(run_args(&[]).unwrap().segments, 32);
        assert!(run_args(&["--segments", "2"]).is_err());
        assert!(run_args(&["--segments", "100000"]).is_err());
    }

    #[test]
    fn limit_flags() {
        let a = run_args(&["--max-depth", "7", "--max-shapes", "1000"]).unwrap();
        assert_eq!((a.max_depth, a.max_shapes), (7, 1000));
    }
}
