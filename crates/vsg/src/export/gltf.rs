//! Binary glTF 2.0 export. The glTF node tree is the semantic tree of §7.1.3 (one node per
//! model node, local transforms, shape data in `extras`); only visible terminals carry meshes
//! (§7.1.2), shared by all terminals with the same primitive and appearance (and, with
//! structural metadata, the same part and symbol: `metadata`).

use std::collections::HashMap;

use gltf_json as json;
use json::validation::{Checked::Valid, USize64};
use serde::Serialize;

use super::common::{
    Geometry, Palette, ShapeKey, check_model, finite_f32, solid_mesh, solid_volume, unit,
};
use super::error::ExportError;
use super::metadata::{FeatureIds, Features};
use super::options::{ExportOptions, TextureImage, Textures};
use super::semantics::Heritage;
use super::shading::{ShadedMesh, shade};
use crate::tree::{Appearance, Model, NodeState};

const GLB_MAGIC: u32 = 0x4654_6C67; // "glTF"
const CHUNK_JSON: u32 = 0x4E4F_534A; // "JSON"
const CHUNK_BIN: u32 = 0x004E_4942; // "BIN\0"

/// The `extras` of every node.
#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct NodeExtras<'a> {
    #[serde(skip_serializing_if = "Option::is_none")]
    shape_type: Option<&'a str>,
    params: &'a [f64],
    #[serde(skip_serializing_if = "Option::is_none")]
    volume: Option<f64>,
    rule_line: u32,
    state: NodeState,
}

#[derive(Serialize)]
struct MaterialExtras<'a> {
    texture: &'a str,
}

/// Accessors of one shaded primitive, shared by all meshes (materials) that draw it.
#[derive(Clone, Copy)]
struct Attributes {
    position: json::Index<json::Accessor>,
    normal: json::Index<json::Accessor>,
    uv: Option<json::Index<json::Accessor>>,
    indices: json::Index<json::Accessor>,
    vertices: usize,
}

#[derive(Default)]
struct Builder {
    root: json::Root,
    bin: Vec<u8>,
    /// Accessors per distinct primitive and texture repeat size (the bits of its two
    /// numbers: a primitive drawn with textures of different real sizes needs different
    /// texture coordinates); `None`: no triangles.
    attributes: HashMap<(ShapeKey, [u64; 2]), Option<Attributes>>,
    /// Meshes per distinct primitive, material slot and feature IDs.
    meshes: HashMap<(ShapeKey, u32, Option<FeatureIds>), Option<json::Index<json::Mesh>>>,
    /// Constant feature-ID accessors by vertex count and value.
    feature_ids: HashMap<(usize, u32), json::Index<json::Accessor>>,
    /// Texture coordinates on every mesh, when some material is textured.
    textured: bool,
    /// While adding a mesh: the real-world size [u, v] of one repeat of its material's texture
    /// (box projection), in model units.
    uv_size: [f64; 2],
    /// Embedded textures by name.
    textures: HashMap<String, json::Index<json::Texture>>,
    /// While adding a mesh under a photo: node frame → photo frame, and the photo box's size.
    uv_frame: Option<(nalgebra::Isometry3<f64>, [f64; 3])>,
}

pub(super) fn write_glb(
    model: &Model,
    options: &ExportOptions,
    textures: &Textures,
    heritage: Option<&Heritage>,
    geometry: &Geometry,
) -> Result<Vec<u8>, ExportError> {
    check_model(model)?;
    let mut b = Builder::default();
    let mut features = heritage.map(|h| Features::new(model, h));
    let textured = model.nodes.iter().enumerate().any(|(i, n)| {
        n.state == NodeState::Terminal
            && model.solid(i as u32).is_some()
            && model.appearances[n.appearance as usize]
                .texture
                .as_ref()
                .is_some_and(|t| textures.contains_key(t))
    });
    b.textured = textured;
    b.root.asset = json::Asset {
        generator: Some(concat!("castellan vsg ", env!("CARGO_PKG_VERSION")).into()),
        version: "2.0".into(),
        ..Default::default()
    };
    let mut palette = Palette::new(model);
    b.root.nodes.reserve_exact(model.nodes.len());
    let mut roots = Vec::new();

    for (i, node) in model.nodes.iter().enumerate() {
        let mut mesh = None;
        let solid = model.solid(i as u32);
        if let (NodeState::Terminal, Some(p)) = (node.state, &solid) {
            let appearance = &model.appearances[node.appearance as usize];
            let frame = appearance.texture_frame.filter(|_| {
                b.textured
                    && appearance
                        .texture
                        .as_ref()
                        .is_some_and(|t| textures.contains_key(t))
            });
            let key = match frame {
                Some(_) => ShapeKey::Framed(i as u32),
                None => ShapeKey::of(p),
            };
            b.uv_frame = frame.map(|f| (f.world.inverse() * node.world, f.size));
            b.uv_size = appearance
                .texture
                .as_ref()
                .and_then(|t| textures.get(t))
                .map_or([options.texture_scale; 2], |t| {
                    t.repeat_size(options.texture_scale)
                });
            let slot = palette.slot(node.appearance);
            if slot as usize == b.root.materials.len() {
                let index = palette.used[slot as usize];
                let appearance = &model.appearances[index as usize];
                let mut m = material(appearance, index)?;
                if let Some((name, image)) = appearance
                    .texture
                    .as_ref()
                    .and_then(|t| textures.get_key_value(t))
                {
                    let texture = b.add_texture(name, image);
                    m.pbr_metallic_roughness.base_color_texture = Some(json::texture::Info {
                        index: texture,
                        tex_coord: 0,
                        extensions: None,
                        extras: None,
                    });
                }
                b.root.materials.push(m);
            }
            let ids = features
                .as_mut()
                .and_then(|f| f.of(model, i as u32, solid_volume(p, geometry)));
            mesh = match b.meshes.get(&(key, slot, ids)) {
                Some(&m) => m,
                None => {
                    let crease = options.crease_angle_deg;
                    let shade = || shade(p.name(), &solid_mesh(p, geometry), crease);
                    b.add_mesh(key, p.name(), slot, ids, shade)?
                }
            };
            b.uv_frame = None;
        }
        let shape = node.shape.as_ref();
        let what = |field: &'static str| {
            move || format!("the {field} of node {i} ({})", model.symbol(node))
        };
        let volume = solid.map(|s| solid_volume(&s, geometry));
        if let Some(v) = volume {
            finite_f32([v], what("volume"))?;
        }
        let extras = NodeExtras {
            shape_type: solid.map(|s| s.name()),
            params: shape.map_or(&[], |p| p.params()),
            volume,
            rule_line: node.rule_line,
            state: node.state,
        };
        let t = node.local.translation.vector;
        let q = node.local.rotation.coords; // i, j, k, w
        let translation = finite_f32([t.x, t.y, t.z], what("translation"))?;
        let mut rotation = finite_f32([q.x, q.y, q.z, q.w], what("rotation"))?;
        let norm = rotation.iter().map(|c| c * c).sum::<f32>().sqrt();
        rotation = rotation.map(|c| c / norm);
        let identity = rotation == [0.0, 0.0, 0.0, 1.0] || !norm.is_normal();
        b.root.nodes.push(json::Node {
            children: (node.child_count > 0)
                .then(|| node.children().map(json::Index::new).collect()),
            extras: Some(serde_json::value::to_raw_value(&extras)?),
            mesh,
            name: Some(model.symbol(node).to_owned()),
            rotation: (!identity).then_some(json::scene::UnitQuaternion(rotation)),
            translation: (translation != [0.0; 3]).then_some(translation),
            ..Default::default()
        });
        if node.parent.is_none() {
            roots.push(json::Index::new(i as u32));
        }
    }
    let scene = json::Scene {
        extensions: None,
        extras: None,
        name: None,
        nodes: roots,
    };
    b.root.scene = Some(b.root.push(scene));
    if let Some(f) = features.filter(|f| f.has_rows()) {
        let metadata = f.extension(model, &mut |bytes| b.metadata_view(bytes));
        let others = &mut b
            .root
            .extensions
            .get_or_insert_with(Default::default)
            .others;
        others.insert("EXT_structural_metadata".into(), metadata);
        b.root
            .extensions_used
            .extend(["EXT_mesh_features", "EXT_structural_metadata"].map(String::from));
    }
    b.finish()
}

/// A metallic-roughness material for appearance `index`.
fn material(a: &Appearance, index: u32) -> Result<json::Material, ExportError> {
    let [r, g, b] = a.color.map(|c| unit(c) as f32);
    let alpha = unit(1.0 - a.transparency) as f32;
    let texture = a
        .texture
        .as_deref()
        .map(|texture| MaterialExtras { texture });
    Ok(json::Material {
        alpha_mode: Valid(if alpha < 1.0 {
            json::material::AlphaMode::Blend
        } else {
            json::material::AlphaMode::Opaque
        }),
        name: Some(format!("appearance_{index}")),
        pbr_metallic_roughness: json::material::PbrMetallicRoughness {
            base_color_factor: json::material::PbrBaseColorFactor([r, g, b, alpha]),
            metallic_factor: json::material::StrengthFactor(0.0),
            roughness_factor: json::material::StrengthFactor(unit(1.0 - a.shine) as f32),
            ..Default::default()
        },
        emissive_factor: json::material::EmissiveFactor(a.emissive.map(|c| unit(c) as f32)),
        extras: texture
            .map(|t| serde_json::value::to_raw_value(&t))
            .transpose()?,
        ..Default::default()
    })
}

impl Builder {
    /// Pads the binary chunk to 4 bytes and returns the offset of what comes next.
    fn align(&mut self) -> usize {
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        self.bin.len()
    }

    fn view(
        &mut self,
        start: usize,
        stride: Option<usize>,
        target: Option<json::buffer::Target>,
    ) -> json::Index<json::buffer::View> {
        let view = json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64(self.bin.len() as u64 - start as u64),
            byte_offset: Some(USize64(start as u64)),
            byte_stride: stride.map(json::buffer::Stride),
            name: None,
            target: target.map(Valid),
            extensions: None,
            extras: None,
        };
        self.root.push(view)
    }

    fn accessor(
        &mut self,
        view: json::Index<json::buffer::View>,
        offset: u64,
        count: usize,
        component: json::accessor::ComponentType,
        type_: json::accessor::Type,
        bounds: Option<([f32; 3], [f32; 3])>,
    ) -> json::Index<json::Accessor> {
        let (min, max) = match bounds {
            Some((lo, hi)) => (Some(lo.to_vec().into()), Some(hi.to_vec().into())),
            None => (None, None),
        };
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: (offset > 0).then_some(USize64(offset)),
            count: USize64(count as u64),
            component_type: Valid(json::accessor::GenericComponentType(component)),
            extensions: None,
            extras: None,
            type_: Valid(type_),
            min,
            max,
            name: None,
            normalized: false,
            sparse: None,
        })
    }

    /// Embeds texture `name` (once) as an image in the binary chunk, drawn with the one
    /// repeating, trilinearly filtered sampler: walls seen at a grazing angle or from far
    /// away cover many texels per pixel, and without mipmaps (`LINEAR` minification) a
    /// viewer samples them sparsely, which shows as moiré and static.
    fn add_texture(&mut self, name: &str, image: &TextureImage) -> json::Index<json::Texture> {
        if let Some(&t) = self.textures.get(name) {
            return t;
        }
        let sampler = match self.root.samplers.len() {
            0 => self.root.push(json::texture::Sampler {
                mag_filter: Some(Valid(json::texture::MagFilter::Linear)),
                min_filter: Some(Valid(json::texture::MinFilter::LinearMipmapLinear)),
                name: None,
                wrap_s: Valid(json::texture::WrappingMode::Repeat),
                wrap_t: Valid(json::texture::WrappingMode::Repeat),
                extensions: None,
                extras: None,
            }),
            _ => json::Index::new(0),
        };
        let start = self.align();
        self.bin.extend_from_slice(&image.bytes);
        let view = self.view(start, None, None);
        let source = self.root.push(json::Image {
            buffer_view: Some(view),
            mime_type: Some(json::image::MimeType(image.mime_type.clone())),
            name: Some(name.to_owned()),
            uri: None,
            extensions: None,
            extras: None,
        });
        let texture = self.root.push(json::Texture {
            name: Some(name.to_owned()),
            sampler: Some(sampler),
            source,
            extensions: None,
            extras: None,
        });
        self.textures.insert(name.to_owned(), texture);
        texture
    }

    /// Writes interleaved positions, normals and, when textured, texture coordinates (f32,
    /// stride 24 or 32) and indices (u16 when they fit, else u32); `None` for a mesh without
    /// triangles.
    fn add_attributes(&mut self, name: &str, mesh: &ShadedMesh) -> Option<Attributes> {
        use json::accessor::{ComponentType, Type};
        if mesh.triangles.is_empty() {
            return None;
        }
        let start = self.align();
        let stride = if self.textured { 32 } else { 24 };
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        self.bin
            .reserve(mesh.positions.len() * stride + mesh.triangles.len() * 12 + 4);
        for (&local, &normal) in mesh.positions.iter().zip(&mesh.normals) {
            let p = local.map(|c| c as f32);
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
            // Renormalise in f32 so the validator's unit-length check holds exactly enough.
            let n = normal.map(|c| c as f32);
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            for c in p.into_iter().chain(n.map(|c| c / len)) {
                self.bin.extend_from_slice(&c.to_le_bytes());
            }
            if self.textured {
                let uv = match &self.uv_frame {
                    Some((to_frame, size)) => {
                        let p = to_frame * nalgebra::Point3::from(local);
                        let n = to_frame.rotation * nalgebra::Vector3::from(normal);
                        photo_uv([p.x, p.y, p.z], [n.x, n.y, n.z], *size)
                    }
                    None => box_uv(local, normal, self.uv_size),
                };
                for c in uv {
                    self.bin.extend_from_slice(&(c as f32).to_le_bytes());
                }
            }
        }
        let target = Some(json::buffer::Target::ArrayBuffer);
        let vertices = self.view(start, Some(stride), target);
        let count = mesh.positions.len();
        let position = self.accessor(
            vertices,
            0,
            count,
            ComponentType::F32,
            Type::Vec3,
            Some((lo, hi)),
        );
        let normal = self.accessor(vertices, 12, count, ComponentType::F32, Type::Vec3, None);
        let uv = self
            .textured
            .then(|| self.accessor(vertices, 24, count, ComponentType::F32, Type::Vec2, None));

        let start = self.align();
        // u16 indices must stay below 65535 (the primitive-restart value).
        let component = if count < 0xFFFF {
            for &i in mesh.triangles.iter().flatten() {
                self.bin.extend_from_slice(&(i as u16).to_le_bytes());
            }
            ComponentType::U16
        } else {
            for &i in mesh.triangles.iter().flatten() {
                self.bin.extend_from_slice(&i.to_le_bytes());
            }
            ComponentType::U32
        };
        let view = self.view(start, None, Some(json::buffer::Target::ElementArrayBuffer));
        let indices = self.accessor(
            view,
            0,
            mesh.triangles.len() * 3,
            component,
            Type::Scalar,
            None,
        );
        let views = self.root.buffer_views.len();
        self.root.buffer_views[views - 2].name = Some(format!("{name}_vertices"));
        self.root.buffer_views[views - 1].name = Some(format!("{name}_indices"));
        Some(Attributes {
            position,
            normal,
            uv,
            indices,
            vertices: count,
        })
    }

    /// Adds the mesh of primitive `key` drawn with material `material`, shading the primitive
    /// (`shade`) only if no other material has drawn it yet; `None` when it has no triangles.
    fn add_mesh(
        &mut self,
        key: ShapeKey,
        name: &str,
        material: u32,
        ids: Option<FeatureIds>,
        shade: impl FnOnce() -> Result<ShadedMesh, ExportError>,
    ) -> Result<Option<json::Index<json::Mesh>>, ExportError> {
        // Without texture coordinates the repeat size changes nothing: one set of accessors.
        let size = if self.textured {
            self.uv_size.map(f64::to_bits)
        } else {
            [0; 2]
        };
        let attributes = match self.attributes.get(&(key, size)) {
            Some(&a) => a,
            None => {
                let view_name = format!("{name}_{}", self.attributes.len());
                let a = self.add_attributes(&view_name, &shade()?);
                self.attributes.insert((key, size), a);
                a
            }
        };
        let Some(a) = attributes else {
            self.meshes.insert((key, material, ids), None);
            return Ok(None);
        };
        let attributes = [
            (Valid(json::mesh::Semantic::Positions), a.position),
            (Valid(json::mesh::Semantic::Normals), a.normal),
        ];
        let uv =
            a.uv.map(|uv| (Valid(json::mesh::Semantic::TexCoords(0)), uv));
        let feature_ids = ids.map(|ids| {
            let part = self.feature_id(a.vertices, ids.part);
            let element = self.feature_id(a.vertices, ids.element);
            [("FEATURE_ID_0", part), ("FEATURE_ID_1", element)].map(|(name, accessor)| {
                (Valid(json::mesh::Semantic::Extras(name.into())), accessor)
            })
        });
        let extensions = ids.map(|_| json::extensions::mesh::Primitive {
            others: [("EXT_mesh_features".to_string(), Features::mesh_features())]
                .into_iter()
                .collect(),
        });
        let primitive = json::mesh::Primitive {
            attributes: attributes
                .into_iter()
                .chain(uv)
                .chain(feature_ids.into_iter().flatten())
                .collect(),
            extensions,
            extras: None,
            indices: Some(a.indices),
            material: Some(json::Index::new(material)),
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        };
        let mesh = self.root.push(json::Mesh {
            extensions: None,
            extras: None,
            name: Some(format!("{name}_{}", self.root.meshes.len())),
            primitives: vec![primitive],
            weights: None,
        });
        self.meshes.insert((key, material, ids), Some(mesh));
        Ok(Some(mesh))
    }

    /// A `vertices`-long float accessor holding `value` (exact below 2²⁴): a feature ID of
    /// `EXT_mesh_features`, constant over a primitive.
    fn feature_id(&mut self, vertices: usize, value: u32) -> json::Index<json::Accessor> {
        use json::accessor::{ComponentType, Type};
        if let Some(&a) = self.feature_ids.get(&(vertices, value)) {
            return a;
        }
        let start = self.align();
        for _ in 0..vertices {
            self.bin.extend_from_slice(&(value as f32).to_le_bytes());
        }
        let view = self.view(start, None, Some(json::buffer::Target::ArrayBuffer));
        let a = self.accessor(view, 0, vertices, ComponentType::F32, Type::Scalar, None);
        self.feature_ids.insert((vertices, value), a);
        a
    }

    /// Stores one column of a property table in a buffer view of its own, 8-byte aligned as
    /// `EXT_structural_metadata` asks, and returns the view's index.
    fn metadata_view(&mut self, bytes: &[u8]) -> u32 {
        self.bin.resize(self.bin.len().next_multiple_of(8), 0);
        let start = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.view(start, None, None).value() as u32
    }

    /// Serialises the JSON and wraps it and the binary data in a GLB container.
    fn finish(mut self) -> Result<Vec<u8>, ExportError> {
        self.align();
        if !self.bin.is_empty() {
            self.root.buffers.push(json::Buffer {
                byte_length: USize64(self.bin.len() as u64),
                name: None,
                uri: None,
                extensions: None,
                extras: None,
            });
        }
        let mut text = self.root.to_vec()?;
        text.resize(text.len().next_multiple_of(4), b' ');
        let bin_chunk = if self.bin.is_empty() {
            0
        } else {
            8 + self.bin.len()
        };
        let total = 12 + 8 + text.len() + bin_chunk;
        if total > u32::MAX as usize {
            return Err(ExportError::TooLarge {
                bytes: total as u64,
            });
        }
        let mut out = Vec::with_capacity(total);
        for word in [GLB_MAGIC, 2, total as u32, text.len() as u32, CHUNK_JSON] {
            out.extend_from_slice(&word.to_le_bytes());
        }
        out.extend_from_slice(&text);
        if !self.bin.is_empty() {
            out.extend_from_slice(&(self.bin.len() as u32).to_le_bytes());
            out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
            out.extend_from_slice(&self.bin);
        }
        Ok(out)
    }
}

/// Texture coordinates of a vertex at `p` with normal `n`, both in a photo's frame of box size
/// `size`: the photo covers each face of the box once, as seen from outside (so a façade photo
/// reads left to right on its wall whichever way the wall faces), up is +Y.
pub(super) fn photo_uv(p: [f64; 3], n: [f64; 3], size: [f64; 3]) -> [f64; 2] {
    let [sx, sy, sz] = size.map(|v| if v.abs() > 1e-12 { v } else { 1.0 });
    let a = n.map(f64::abs);
    let v = 0.5 - p[1] / sy;
    if a[1] > a[0] && a[1] > a[2] {
        [0.5 + p[0] / sx, 0.5 + p[2] / sz]
    } else if a[0] >= a[2] {
        let u = p[2] / sz;
        [if n[0] > 0.0 { 0.5 - u } else { 0.5 + u }, v]
    } else {
        let u = p[0] / sx;
        [if n[2] > 0.0 { 0.5 + u } else { 0.5 - u }, v]
    }
}

/// Texture coordinates of a vertex at local position `p` with normal `n` by box projection at
/// real scale: `p` projected onto the plane perpendicular to `n`'s dominant axis, seen from
/// outside (so textures are not mirrored, up is +Y on walls), divided by `size` (model units
/// per texture repeat across and up the texture); v grows downwards as glTF expects.
pub(super) fn box_uv(p: [f64; 3], n: [f64; 3], size: [f64; 2]) -> [f64; 2] {
    let [x, y, z] = p;
    let a = n.map(f64::abs);
    let sign = |c: f64| if c < 0.0 { -1.0 } else { 1.0 };
    let (u, v) = if a[1] > a[0] && a[1] > a[2] {
        (x, -z * sign(n[1]))
    } else if a[0] >= a[2] {
        (-z * sign(n[0]), y)
    } else {
        (x * sign(n[2]), y)
    };
    let [su, sv] = size.map(|s| if s.is_normal() { s.abs() } else { 1.0 });
    [u / su, -v / sv]
}
