//! What a caller hands the exporters of §7.1.3 besides the model: [`ExportOptions`] (the
//! tessellation of Table 7.1's curved primitives, the crease angle, the texture scale) and the
//! texture images to embed ([`TextureImage`], [`Textures`]). Re-exported as `vsg::export::*`;
//! `gltf`, `obj` and `export/mod.rs` import them from here.

use crate::shape::Tessellation;

/// How a model is exported.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExportOptions {
    /// How finely curved primitives are meshed.
    pub tessellation: Tessellation,
    /// Faces of one mesh meeting at more than this angle (degrees) get separate vertices, so
    /// boxes look flat and cylinders smooth; normals are averaged across smaller angles.
    pub crease_angle_deg: f64,
    /// Real-world size of one texture repeat, in model units per texture width (and height),
    /// for textures that do not give their own ([`TextureImage::size`]): texture coordinates
    /// are box-projected local positions divided by the size, so a texture embedded with
    /// [`to_glb_with_textures`](super::to_glb_with_textures) keeps its scale on faces of any
    /// size.
    pub texture_scale: f64,
}

impl Default for ExportOptions {
    fn default() -> Self {
        ExportOptions {
            tessellation: Tessellation::default(),
            crease_angle_deg: 40.0,
            texture_scale: 1.0,
        }
    }
}

/// An encoded texture image to embed in a GLB.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureImage {
    /// The file's bytes, PNG or JPEG.
    pub bytes: Vec<u8>,
    /// `"image/png"` or `"image/jpeg"`, matching `bytes`.
    pub mime_type: String,
    /// Real-world size of one repeat of this texture, [width, height] in model units, when it
    /// is known (a wall sample cut from a photo of known scale): the texture then repeats at
    /// the size of what it shows rather than at [`ExportOptions::texture_scale`]. Photos
    /// stretched over their shape (`appearance("photo", ...)`) ignore it.
    pub size: Option<[f64; 2]>,
}

impl TextureImage {
    /// The image's repeat size in model units: its own [`size`](Self::size) when finite and
    /// positive, else `fallback` both ways.
    pub fn repeat_size(&self, fallback: f64) -> [f64; 2] {
        match self.size {
            Some(s) if s.iter().all(|v| v.is_normal() && *v > 0.0) => s,
            _ => [fallback; 2],
        }
    }
}

/// Texture images by the name an appearance gives (`appearance("texture", {...})`).
pub type Textures = std::collections::BTreeMap<String, TextureImage>;
