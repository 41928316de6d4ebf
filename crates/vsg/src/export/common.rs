//! What the glTF and OBJ writers of §7.1.3 share: the primitive meshing and volumes they are
//! given ([`Geometry`], injectable by tests), the model check before writing ([`check_model`]),
//! the mesh-sharing key of a terminal's solid ([`ShapeKey`]) with its mesh and volume
//! ([`solid_mesh`], [`solid_volume`]), the materials of the appearances in use ([`Palette`]),
//! and the conversions to the numbers the files store ([`finite_f32`], [`unit`]).

use super::error::ExportError;
use crate::mesh::TriMesh;
use crate::shape::{Primitive, ShapeType};
use crate::tree::{Model, NodeId, Solid};

/// Meshing and volume of primitives: the public functions pass [`Primitive::mesh`] and
/// [`Primitive::volume`], tests inject their own.
pub(crate) struct Geometry<'a> {
    pub mesh: &'a dyn Fn(&Primitive) -> TriMesh,
    pub volume: &'a dyn Fn(&Primitive) -> f64,
}

/// Checks the references the exporters follow: symbols, appearances and a consistent,
/// acyclic parent/child structure (children come after their parent, in creation order).
pub(crate) fn check_model(model: &Model) -> Result<(), ExportError> {
    let len = model.nodes.len();
    for (i, node) in model.nodes.iter().enumerate() {
        let id = i as NodeId;
        if node.symbol as usize >= model.symbols.len() {
            let len = model.symbols.len();
            let index = node.symbol;
            return Err(ExportError::BadReference {
                node: id,
                what: "symbol",
                index,
                len,
            });
        }
        if node.appearance as usize >= model.appearances.len() {
            let (index, len) = (node.appearance, model.appearances.len());
            return Err(ExportError::BadReference {
                node: id,
                what: "appearance",
                index,
                len,
            });
        }
        let end = node.first_child as u64 + node.child_count as u64;
        if node.child_count > 0 && (node.first_child <= id || end > len as u64) {
            return Err(ExportError::BadTree {
                node: id,
                why: "children out of range",
            });
        }
        if node
            .children()
            .any(|c| model.nodes[c as usize].parent != Some(id))
        {
            return Err(ExportError::BadTree {
                node: id,
                why: "a child names another parent",
            });
        }
        if let Some(p) = node.parent {
            let parent = model.nodes.get(p as usize);
            if p >= id || !parent.is_some_and(|n| n.children().contains(&id)) {
                return Err(ExportError::BadTree {
                    node: id,
                    why: "not a child of its parent",
                });
            }
        }
    }
    Ok(())
}

/// Bit pattern of a primitive (terminals with equal keys share one mesh), or the node of a
/// unique shape (each has its own mesh).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum ShapeKey {
    Primitive {
        kind: ShapeType,
        params: [u64; 6],
    },
    Unique(NodeId),
    /// A terminal under a photo (`appearance("photo", …)`): its texture coordinates depend on
    /// where it lies in the photo's frame, so its mesh is its own.
    Framed(NodeId),
}

impl ShapeKey {
    pub fn of(s: &Solid) -> ShapeKey {
        let p = match s {
            Solid::Primitive(p) => p,
            Solid::Unique(id, _) => return ShapeKey::Unique(*id),
        };
        let mut params = [0; 6];
        for (slot, v) in params.iter_mut().zip(p.params()) {
            *slot = v.to_bits();
        }
        ShapeKey::Primitive {
            kind: p.kind,
            params,
        }
    }
}

/// The mesh of a solid in its node's frame: primitives through `geometry` (so tests can inject
/// meshes), unique shapes as produced.
pub(crate) fn solid_mesh(s: &Solid, geometry: &Geometry) -> TriMesh {
    match s {
        Solid::Primitive(p) => (geometry.mesh)(p),
        Solid::Unique(_, u) => u.mesh.clone(),
    }
}

/// The volume of a solid: primitives through `geometry`, unique shapes' mesh volume.
pub(crate) fn solid_volume(s: &Solid, geometry: &Geometry) -> f64 {
    match s {
        Solid::Primitive(p) => (geometry.volume)(p),
        Solid::Unique(_, u) => u.volume,
    }
}

/// Materials of the appearances that visible terminals use; equal appearances share one,
/// named after the smallest of their indices.
pub(crate) struct Palette {
    /// Per model appearance: the smallest index of an equal appearance.
    canonical: Vec<u32>,
    /// Material slot per canonical appearance (`u32::MAX` until used).
    slot_of: Vec<u32>,
    /// For each material slot, the canonical model appearance index.
    pub used: Vec<u32>,
}

#[derive(PartialEq, Eq, Hash)]
struct AppearanceKey<'a>([u64; 15], Option<&'a str>);

impl Palette {
    pub fn new(model: &Model) -> Palette {
        let mut first = std::collections::HashMap::with_capacity(model.appearances.len());
        let canonical = (0..model.appearances.len() as u32)
            .map(|i| {
                let a = &model.appearances[i as usize];
                let [r, g, b] = a.color;
                let ([dr, dg, db], [sr, sg, sb]) = (a.diffuse, a.specular);
                let ([er, eg, eb], (t, am, sh)) =
                    (a.emissive, (a.transparency, a.ambient, a.shine));
                let values = [r, g, b, t, am, dr, dg, db, sr, sg, sb, er, eg, eb, sh];
                let key = AppearanceKey(values.map(f64::to_bits), a.texture.as_deref());
                *first.entry(key).or_insert(i)
            })
            .collect();
        let slot_of = vec![u32::MAX; model.appearances.len()];
        Palette {
            canonical,
            slot_of,
            used: Vec::new(),
        }
    }

    /// Material slot of model appearance `index` (checked by [`check_model`]); slots are
    /// numbered in order of first use.
    pub fn slot(&mut self, index: u32) -> u32 {
        let canonical = self.canonical[index as usize];
        let slot = &mut self.slot_of[canonical as usize];
        if *slot == u32::MAX {
            *slot = self.used.len() as u32;
            self.used.push(canonical);
        }
        *slot
    }
}

/// `v` as the 32-bit floats the files store, or an error naming `what` if any is not finite
/// there. The second line of defence behind production's bounds (`shape::MAX_COORDINATE`):
/// a model built by hand must not become `null` in a glTF accessor or `inf` in an OBJ.
pub(crate) fn finite_f32<const N: usize>(
    v: [f64; N],
    what: impl FnOnce() -> String,
) -> Result<[f32; N], ExportError> {
    let f = v.map(|c| c as f32);
    if f.iter().all(|c| c.is_finite()) {
        Ok(f)
    } else {
        Err(ExportError::NotFinite {
            what: what(),
            value: v.to_vec(),
        })
    }
}

/// Clamps to 0..1, mapping NaN to 0.
pub(crate) fn unit(v: f64) -> f64 {
    if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) }
}
