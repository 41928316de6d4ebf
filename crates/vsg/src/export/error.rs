//! Why a model could not be exported as glTF or OBJ (§7.1.3): [`ExportError`], re-exported as
//! `vsg::export::ExportError` and returned by the writers (`gltf`, `obj`), the mesh shading
//! (`shading`) and the checks they share (`common`).

use crate::tree::NodeId;

/// Why a model could not be exported.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error("node {node} refers to {what} {index}, but the model has only {len}")]
    BadReference {
        node: NodeId,
        what: &'static str,
        index: u32,
        len: usize,
    },
    #[error("node {node} is not a well-formed tree node: {why}")]
    BadTree { node: NodeId, why: &'static str },
    #[error("the {kind} mesh is malformed: {why}")]
    BadMesh { kind: &'static str, why: String },
    #[error(
        "{what} is not a finite number the file can store (32-bit floats in glTF and OBJ, millimetres within 2^53 in CityJSON): {value:?} (is the model out of bounds?)"
    )]
    NotFinite { what: String, value: Vec<f64> },
    #[error("the GLB would be {bytes} bytes, more than the 4 GiB the format allows")]
    TooLarge { bytes: u64 },
    #[error("cannot serialize the glTF JSON: {0}")]
    Json(#[from] serde_json::Error),
}
