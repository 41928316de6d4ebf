//! What the stages of a reconstruction share: the files a project names ([`Files`]), the
//! settings beyond the project's ([`Options`]), the error naming the entry at fault
//! ([`PipelineError`]) and the overlays every stage returns ([`Overlay`], [`Picture`]).

use std::collections::BTreeMap;

use facade::classify::Method;
use image::{DynamicImage, GrayImage, RgbImage};

use crate::IntegrateError;
use crate::project::Project;

/// The files a project names (the plan, photos, TRAINING.json, LINES.json), read by the
/// caller: from a folder (`castellan reconstruct`), a confined project store (`serve`), or
/// memory ([`InMemory`]: tests). Errors are the caller's message (the file, the pixel budget, …).
pub trait Files: Sync {
    /// The image `name` (a path relative to PROJECT.toml), decoded.
    fn image(&self, name: &str) -> Result<DynamicImage, String>;
    /// The JSON file `name`, parsed; errors name `name:line:column`.
    fn json<T: serde::de::DeserializeOwned>(&self, name: &str, what: &str) -> Result<T, String>;
}

/// A project's files held in memory by name: for a caller that has the bytes already (the
/// tests; a project received whole). JSON errors name `name:line:column`, as a folder's do.
#[derive(Debug, Clone, Default)]
pub struct InMemory(pub BTreeMap<String, Vec<u8>>);

impl InMemory {
    fn bytes(&self, name: &str) -> Result<&[u8], String> {
        self.0
            .get(name)
            .map(Vec::as_slice)
            .ok_or_else(|| format!("{name}: no such file"))
    }
}

impl Files for InMemory {
    fn image(&self, name: &str) -> Result<DynamicImage, String> {
        image::load_from_memory(self.bytes(name)?).map_err(|e| format!("{name}: {e}"))
    }

    fn json<T: serde::de::DeserializeOwned>(&self, name: &str, what: &str) -> Result<T, String> {
        serde_json::from_slice(self.bytes(name)?)
            .map_err(|e| format!("{name}:{}:{}: not {what}: {e}", e.line(), e.column()))
    }
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

pub(super) fn at(entry: impl Into<String>) -> impl Fn(String) -> PipelineError {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn in_memory_files_name_the_file_and_the_json_error_at_line_and_column() {
        let files = InMemory(BTreeMap::from([
            (
                "a.json".to_string(),
                b"{\n  \"x\": [1,\n  oops]\n}".to_vec(),
            ),
            ("b.json".to_string(), b"[1, 2]".to_vec()),
        ]));
        let err = files
            .json::<serde_json::Value>("a.json", "a list")
            .unwrap_err();
        assert!(err.starts_with("a.json:3:3: not a list: "), "{err}");
        assert_eq!(
            files.json::<Vec<u8>>("b.json", "a list").unwrap(),
            vec![1, 2]
        );
        assert_eq!(
            files.image("c.png").unwrap_err(),
            "c.png: no such file".to_string()
        );
        assert!(files.image("b.json").unwrap_err().starts_with("b.json: "));
    }
}
