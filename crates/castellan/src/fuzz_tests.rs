//! Fuzzing on stable Rust (issue 19): mutated image files through every command that reads an
//! image, and mutated PROJECT.toml files through `reconstruct`, in-process. Each case must end
//! in `Ok` or a clear error, never a panic, and a failed run must write nothing.
//!
//! CI runs a few dozen cases per test; a longer run for developers:
//! `PROPTEST_CASES=5000 cargo test --release -p castellan --bin castellan fuzz_`.

use std::path::{Path, PathBuf};

use clap::Parser;
use proptest::prelude::*;

/// `default` cases (kept small for CI) unless `PROPTEST_CASES` says otherwise; failures are
/// reported, not saved into src/ (every fuzz test of the binary uses this).
pub(crate) fn config(default: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default);
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Runs `castellan ARGS…` in-process.
fn castellan(args: &[&str]) -> anyhow::Result<()> {
    let cli =
        crate::cli::Cli::try_parse_from(std::iter::once("castellan").chain(args.iter().copied()))
            .map_err(|e| anyhow::anyhow!("{e}"))?;
    crate::dispatch(cli.command)
}

/// Every file below `dir`, as paths relative to it.
fn files_below(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let p = entry.path();
        if p.is_dir() {
            out.extend(files_below(&p));
        } else {
            out.push(p);
        }
    }
    out
}

#[derive(Debug, Clone, Copy)]
enum Format {
    PngGrey,
    PngRgb,
    Png16,
    Jpeg,
    Pgm,
}

/// A small image with a dark rectangle on a light ground (so stages find something), encoded.
fn encode(format: Format, w: u32, h: u32, seed: u8) -> Vec<u8> {
    let px = |x: u32, y: u32| {
        let inside = x > w / 4 && x < 3 * w / 4 && y > h / 4 && y < 3 * h / 4;
        let base: u8 = if inside { 40 } else { 220 };
        base.wrapping_add(((x * 7 + y * 13) as u8 ^ seed) % 23)
    };
    let mut buf = std::io::Cursor::new(Vec::new());
    match format {
        Format::PngGrey | Format::Pgm => {
            let img = image::GrayImage::from_fn(w, h, |x, y| image::Luma([px(x, y)]));
            let f = match format {
                Format::Pgm => image::ImageFormat::Pnm,
                _ => image::ImageFormat::Png,
            };
            img.write_to(&mut buf, f).unwrap();
        }
        Format::PngRgb | Format::Jpeg => {
            let img = image::RgbImage::from_fn(w, h, |x, y| {
                let v = px(x, y);
                image::Rgb([v, v / 2 + 60, 255 - v])
            });
            let f = match format {
                Format::Jpeg => image::ImageFormat::Jpeg,
                _ => image::ImageFormat::Png,
            };
            img.write_to(&mut buf, f).unwrap();
        }
        Format::Png16 => {
            let img = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_fn(w, h, |x, y| {
                image::Luma([u16::from(px(x, y)) * 257])
            });
            img.write_to(&mut buf, image::ImageFormat::Png).unwrap();
        }
    }
    buf.into_inner()
}

#[derive(Debug, Clone)]
enum Mutation {
    None,
    /// Bytes set at positions given as fractions of the length.
    Flip(Vec<(f64, u8)>),
    /// The file cut at a fraction of its length.
    Truncate(f64),
    /// A 32-bit big-endian value written at a byte offset (PNG's IHDR width is at 16, height
    /// at 20): huge or zero sizes.
    Header(usize, u32),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        Just(Mutation::None),
        proptest::collection::vec((0.0..1.0f64, any::<u8>()), 1..8).prop_map(Mutation::Flip),
        (0.0..1.0f64).prop_map(Mutation::Truncate),
        (
            prop_oneof![Just(16usize), Just(20usize), 0usize..40],
            prop_oneof![
                Just(0u32),
                Just(1u32),
                Just(20_000u32),
                Just(u32::MAX),
                any::<u32>()
            ]
        )
            .prop_map(|(at, v)| Mutation::Header(at, v)),
    ]
}

fn mutate(mut bytes: Vec<u8>, m: &Mutation) -> Vec<u8> {
    let n = bytes.len();
    match m {
        Mutation::None => {}
        Mutation::Flip(flips) => {
            for &(at, v) in flips {
                bytes[((at * n as f64) as usize).min(n - 1)] = v;
            }
        }
        Mutation::Truncate(at) => bytes.truncate((at * n as f64) as usize),
        Mutation::Header(at, v) => {
            if at + 4 <= n {
                bytes[*at..at + 4].copy_from_slice(&v.to_be_bytes());
            }
        }
    }
    bytes
}

fn format() -> impl Strategy<Value = Format> {
    prop_oneof![
        Just(Format::PngGrey),
        Just(Format::PngRgb),
        Just(Format::Png16),
        Just(Format::Jpeg),
        Just(Format::Pgm),
    ]
}

proptest! {
    #![proptest_config(config(24))]

    /// Every image-reading command on a mutated small image: a result or an error, and after an
    /// error no output file.
    #[test]
    fn fuzz_mutated_images_through_every_command(
        format in format(),
        w in 1u32..48,
        h in 1u32..48,
        seed in any::<u8>(),
        m in mutation(),
    ) {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let ext = match format {
            Format::Jpeg => "jpg",
            Format::Pgm => "pgm",
            _ => "png",
        };
        let img = d.join(format!("in.{ext}"));
        std::fs::write(&img, mutate(encode(format, w, h, seed), &m)).unwrap();
        let training = d.join("t.json");
        let (x1, y1) = (f64::from(w.max(2)), f64::from(h.max(2)));
        std::fs::write(
            &training,
            format!(r#"{{"classes":{{"wall":[[0,0,{},{}]],"window":[[{},{},{x1},{y1}]]}}}}"#,
                x1 / 2.0, y1 / 2.0, x1 / 2.0, y1 / 2.0),
        ).unwrap();
        let out = d.join("out");
        std::fs::create_dir(&out).unwrap();
        let i = img.to_str().unwrap();
        let t = training.to_str().unwrap();
        let o = |name: &str| out.join(name).to_str().unwrap().to_string();
        let runs: Vec<Vec<String>> = vec![
            vec!["plan".into(), i.into(), "-o".into(), o("p.json"), "--overlay".into(), o("p.png")],
            vec!["corners".into(), i.into(), "-o".into(), o("c.json"), "--overlay".into(), o("c.png")],
            vec!["rectify".into(), i.into(), "-o".into(), o("r.png")],
            vec!["facade".into(), i.into(), "--training".into(), t.into(), "-o".into(), o("f.json")],
            vec!["gothic".into(), i.into(), "-o".into(), o("g.json"), "--overlay".into(), o("g.png")],
        ];
        for args in runs {
            let argv: Vec<&str> = args.iter().map(String::as_str).collect();
            let before = files_below(&out).len();
            if let Err(e) = castellan(&argv) {
                let msg = format!("{e:#}");
                prop_assert!(!msg.contains("panic"), "{argv:?}: {msg}");
                prop_assert_eq!(files_below(&out).len(), before, "{:?} failed ({}) but wrote", argv, msg);
            }
        }
    }
}

/// The shipped demo project with one edit of its PROJECT.toml.
#[derive(Debug, Clone)]
enum TomlEdit {
    /// A line replaced by `key = value`.
    Replace(usize, String, String),
    /// A line deleted.
    Delete(usize),
    /// A byte changed.
    Byte(f64, u8),
}

fn toml_edit() -> impl Strategy<Value = TomlEdit> {
    let key = prop_oneof![
        Just("scale"),
        Just("scale_bar"),
        Just("plan"),
        Just("seed"),
        Just("image"),
        Just("training"),
        Just("facade_point"),
        Just("plan_points"),
        Just("thin_lines"),
        Just("hatching"),
        Just("one_building"),
        Just("trim_ink"),
        Just("bbox"),
        Just("lines"),
        Just("[[facade]]"),
        Just("[[gothic]]"),
    ];
    let value = prop_oneof![
        Just("1e300".to_string()),
        Just("-1".to_string()),
        Just("0".to_string()),
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("\"\"".to_string()),
        Just("\"/dev/zero\"".to_string()),
        Just("\"../../etc/passwd\"".to_string()),
        Just("[1e308, -1e308]".to_string()),
        Just("[[1, 2], [3]]".to_string()),
        Just("[0, 0, -5, 1e9]".to_string()),
        Just("true".to_string()),
        Just("\"keep_south_near.png\"".to_string()),
        Just("18446744073709551615".to_string()),
        "[a-z0-9 .\\[\\]\"=,-]{0,16}",
    ];
    prop_oneof![
        (0usize..30, key, value).prop_map(|(l, k, v)| TomlEdit::Replace(l, k.to_string(), v)),
        (0usize..30).prop_map(TomlEdit::Delete),
        (0.0..1.0f64, any::<u8>()).prop_map(|(a, b)| TomlEdit::Byte(a, b)),
    ]
}

fn edit(text: &str, e: &TomlEdit) -> Vec<u8> {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    match e {
        TomlEdit::Replace(l, k, v) => {
            let at = l % lines.len();
            lines[at] = if k.starts_with('[') {
                k.clone()
            } else {
                format!("{k} = {v}")
            };
            lines.join("\n").into_bytes()
        }
        TomlEdit::Delete(l) => {
            let at = l % lines.len();
            lines.remove(at);
            lines.join("\n").into_bytes()
        }
        TomlEdit::Byte(at, b) => {
            let mut bytes = text.as_bytes().to_vec();
            let n = bytes.len();
            bytes[((at * n as f64) as usize).min(n - 1)] = *b;
            bytes
        }
    }
}

proptest! {
    #![proptest_config(config(12))]

    /// `reconstruct` on the demo project with a mutated PROJECT.toml: a model or an error that
    /// names the file, and after an error no OUTDIR.
    #[test]
    fn fuzz_mutated_project_files_through_reconstruct(e in toml_edit()) {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/demo");
        let dir = tempfile::tempdir().unwrap();
        for f in std::fs::read_dir(&root).unwrap().flatten() {
            std::fs::copy(f.path(), dir.path().join(f.file_name())).unwrap();
        }
        let text = std::fs::read_to_string(root.join("PROJECT.toml")).unwrap();
        let project = dir.path().join("PROJECT.toml");
        std::fs::write(&project, edit(&text, &e)).unwrap();
        let out = dir.path().join("out");
        let r = castellan(&["reconstruct", project.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        if let Err(err) = r {
            let msg = format!("{err:#}");
            prop_assert!(msg.contains("PROJECT.toml") || msg.contains(".json") || msg.contains(".png"),
                "the error names no file: {msg}");
            prop_assert!(!out.exists(), "failed ({msg}) but wrote {}", out.display());
        }
    }
}
