//! Exporters of a produced [`Model`]: binary glTF 2.0 (`.glb`, with structural metadata on
//! request), Wavefront OBJ + MTL, and the heritage formats IFC4 and CityJSON 2.0, whose shared
//! rules (parts, classes, frame) are in [`semantics`].
//! Following §7.1.2/§7.1.3 of Sui 2011, only terminals carry meshes, while the semantic
//! hierarchy (non-terminals and void terminals included) is kept as the glTF node tree.

mod cityjson;
mod cityjson_geometry;
mod common;
mod error;
mod gltf;
mod ifc;
mod ifc_step;
mod metadata;
mod obj;
mod options;
pub mod semantics;
mod shading;
#[cfg(test)]
mod tests;

// The public types, in files of their own (the writers import them, not this file).
pub use error::ExportError;
pub use options::{ExportOptions, TextureImage, Textures};

use crate::shape::Primitive;
use crate::tree::Model;
use common::Geometry;
use semantics::Heritage;

/// Writes `model` as a binary glTF 2.0 file: one node per model node (named by its symbol,
/// with its local transform and shape data in `extras`), meshes on visible terminals only,
/// shared between terminals with bit-identical primitives and equal appearances.
pub fn to_glb(model: &Model, options: &ExportOptions) -> Result<Vec<u8>, ExportError> {
    to_glb_with_textures(model, options, &Textures::new())
}

/// Like [`to_glb`], and embeds the image of every texture a visible terminal uses that
/// `textures` holds: materials get a `baseColorTexture` (tinted by their colour) and, when
/// any material is textured, all meshes get `TEXCOORD_0` by box projection at real scale
/// (each texture's [`TextureImage::size`], else [`ExportOptions::texture_scale`]), sampled
/// with mipmaps. Textures missing from `textures` stay names in the material `extras` only.
pub fn to_glb_with_textures(
    model: &Model,
    options: &ExportOptions,
    textures: &Textures,
) -> Result<Vec<u8>, ExportError> {
    glb_of_shapes(model, options, textures, None)
}

/// Like [`to_glb_with_textures`], and describes the building's parts and elements in property
/// tables (`EXT_structural_metadata`) that every drawn primitive points into by its feature IDs
/// (`EXT_mesh_features`), so that 3D Tiles viewers show a part's label, volume, mass and
/// provenance on click (issue 24; the tables in `metadata.rs`).
pub fn to_glb_with_metadata(
    model: &Model,
    options: &ExportOptions,
    textures: &Textures,
    heritage: &Heritage,
) -> Result<Vec<u8>, ExportError> {
    glb_of_shapes(model, options, textures, Some(heritage))
}

/// The binary glTF of the model's own primitives (tessellated by `options`, exact volumes),
/// with the property tables when `heritage` is given.
fn glb_of_shapes(
    model: &Model,
    options: &ExportOptions,
    textures: &Textures,
    heritage: Option<&Heritage>,
) -> Result<Vec<u8>, ExportError> {
    let mesh = |p: &Primitive| p.mesh(&options.tessellation);
    let volume = |p: &Primitive| p.volume();
    gltf::write_glb(
        model,
        options,
        textures,
        heritage,
        &Geometry {
            mesh: &mesh,
            volume: &volume,
        },
    )
}

/// Writes the visible terminals of `model` as OBJ (one group per terminal, world coordinates)
/// and the materials of their appearances as MTL; the OBJ refers to the MTL as
/// `mtl_file_name`. Returns `(obj, mtl)`.
pub fn to_obj(
    model: &Model,
    options: &ExportOptions,
    mtl_file_name: &str,
) -> Result<(String, String), ExportError> {
    let mesh = |p: &Primitive| p.mesh(&options.tessellation);
    let volume = |p: &Primitive| p.volume();
    obj::write_obj(
        model,
        options,
        mtl_file_name,
        &Geometry {
            mesh: &mesh,
            volume: &volume,
        },
    )
}

/// Writes `model` as an IFC4 STEP file (issue 24): the building's parts as element assemblies
/// of walls, roofs, slabs, windows and doors with tessellated bodies in metres (z up), rooms and
/// void shapes as spaces, volumes and masses as quantities, part attributes as `Castellan_Attributes`, and the map
/// placement of `heritage.frame` as a map conversion. Pure: the same input, the same text.
pub fn to_ifc(
    model: &Model,
    heritage: &Heritage,
    options: &ExportOptions,
) -> Result<String, ExportError> {
    ifc::write_ifc(model, heritage, options)
}

/// Writes `model` as a CityJSON 2.0 document: one `Building` for `heritage`, one
/// `BuildingPart` per part with LoD 2 (walls, roofs, floors) and, where it has windows or
/// doors, LoD 3 solids whose faces are semantic surfaces naming their terminals (issue 24; the
/// rules are in `cityjson.rs`). Coordinates are `heritage.frame`'s, in integer millimetres.
pub fn to_cityjson(
    model: &Model,
    heritage: &Heritage,
    options: &ExportOptions,
) -> Result<String, ExportError> {
    cityjson::write_cityjson(model, heritage, options)
}
