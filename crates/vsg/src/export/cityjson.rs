//! CityJSON 2.0 export of a produced model (issue 24): the castle as one `Building` whose
//! `children` are `BuildingPart`s, one per part of [`Heritage::parts_or_default`] (a tower,
//! the keep, a range, a curtain run). Sui 2011 §7.1.3 keeps the semantic tree of a production;
//! CityJSON keeps two levels of it (building, part) as city objects, and the rest as the
//! *semantic surfaces* of the parts' geometry: every face names its terminal's symbol
//! (`vsg_symbol`) and class (`castellan_class`, [`class_of`]) besides its CityJSON type.
//!
//! What is written:
//! - `transform` (scale 0.001: integer millimetres; translate: the minimum corner of the
//!   geometry) and `vertices` on that grid, each grid point once and every one used
//!   (`cityjson_geometry`): cjval warns of duplicate and unused vertices.
//! - `metadata`: `title` (the heritage's name), `geographicalExtent`, and `referenceSystem`
//!   (`https://www.opengis.net/def/crs/EPSG/0/<code>`) when the frame has a placement.
//! - The `Building` with the heritage's attributes; each `BuildingPart` with its `parents`,
//!   the part's attributes, `castellan_kind`, `volume_m3` and `mass_kg` ([`part_totals`], in
//!   m³ and kg whatever the model's unit) and `terminals` (its visible terminals), which
//!   replace a part's own attribute of the same name.
//! - Geometry: LoD 2, the part's drawn wall, roof and floor terminals, one solid each (one
//!   outer shell, coplanar triangles merged into polygons), and, for parts with window or door
//!   terminals only, LoD 3: the same solids and those terminals' solids. CityJSON 2.0 allows a
//!   building (part) `Solid`, `CompositeSolid`, `MultiSurface` or `CompositeSurface`, not the
//!   `MultiSolid` that would say "solids, unrelated": the solids are a `CompositeSolid`, which
//!   the terminals of a split are (they meet at shared faces), though a rule may also place
//!   overlapping ones — the schema validators check no such topology. Void terminals (rooms,
//!   openings) have no surface and are not written; parts without a drawn terminal get no
//!   geometry, and terminals outside every part are left out.
//!
//! The semantic type of a face, from its terminal's class and its unit normal's height `n_z`
//! in the file's frame (z up): "up" is `n_z ≥ sin 10°`, "down" `n_z ≤ −sin 10°`, else the face
//! is "vertical" (within 10° of it, as façades and gable ends are):
//!
//! | class  | up                                     | vertical           | down                                        |
//! |--------|----------------------------------------|--------------------|---------------------------------------------|
//! | roof   | `RoofSurface`                          | `WallSurface`      | `OuterCeilingSurface` (eaves)               |
//! | wall   | `RoofSurface` if the part has no roof, else `OuterFloorSurface` (a ledge, a sill, a wall top under the roof) | `WallSurface` | `OuterCeilingSurface` (a lintel's underside) |
//! | floor  | `FloorSurface` if the part has a roof, else `OuterFloorSurface` (a wall walk) | `ClosureSurface` (where a slab meets the walls) | `CeilingSurface` if roofed, else `OuterCeilingSurface` |
//! | window | `Window` (every face)                  |                    |                                             |
//! | door   | `Door` (every face)                    |                    |                                             |
//!
//! and, before the table, a downward face lying at the part's lowest level (all its vertices
//! within 1 cm of the lowest vertex of the part's geometry) is its `GroundSurface`. "The part
//! has a roof" means one of its drawn terminals is of class roof. No visibility is computed:
//! a face that another terminal covers gets the type its orientation gives.
//!
//! Rings keep the meshes' winding: counter-clockwise seen from outside (§7.1.2), and
//! [`Frame::to_world`](super::semantics::Frame::to_world) is a rotation (right-handed to
//! right-handed), so shells stay oriented outwards, as CityJSON wants them.

use serde_json::{Map, Value, json};

use super::cityjson_geometry::{Face, FileMesh, MAX_INTEGER, Pool, SCALE, Vertices, faces};
use super::common::check_model;
use super::error::ExportError;
use super::options::ExportOptions;
use super::semantics::{
    Attribute, Class, Heritage, Part, Totals, class_of, part_totals, world_mesh,
};
use crate::tree::{Model, NodeId, NodeState};

/// sin 10°: faces whose normal rises less than this out of the horizontal are vertical.
const STEEP: f64 = 0.173_648_177_666_930_33;
/// How far above the part's lowest vertex a downward face may lie and still be its ground
/// (grid units: 10 mm).
const GROUND_TOLERANCE: i64 = 10;

/// A drawn terminal of a part in the file's frame, then its faces on the grid.
struct Terminal<'a> {
    symbol: &'a str,
    class: Class,
    faces: Vec<Face>,
}

pub(super) fn write_cityjson(
    model: &Model,
    heritage: &Heritage,
    options: &ExportOptions,
) -> Result<String, ExportError> {
    check_model(model)?;
    let parts = heritage.parts_or_default(model);
    let part_of = Heritage::part_of(model, &parts);
    let totals = part_totals(model, &parts, &part_of);

    let (meshes, lo, hi) = drawn_meshes(model, heritage, &part_of, parts.len(), options)?;
    let translate = if lo[0] <= hi[0] { lo } else { [0.0; 3] };
    // Integer millimetres must stay exact in a JSON reader's doubles.
    if (0..3).any(|k| (hi[k] - lo[k]) / SCALE > MAX_INTEGER) {
        return Err(ExportError::NotFinite {
            what: "the model's extent in CityJSON's integer millimetres".into(),
            value: [lo, hi].concat(),
        });
    }

    let mut pool = Pool::new(translate);
    let drawn: Vec<Vec<Terminal>> = meshes
        .into_iter()
        .map(|list| {
            list.into_iter()
                .map(|(node, mesh)| {
                    let symbol = model.symbol(&model.nodes[node as usize]);
                    Terminal {
                        symbol,
                        class: class_of(symbol, NodeState::Terminal),
                        faces: faces(&mesh, &mut pool),
                    }
                })
                // Fewer than four faces enclose nothing: a terminal thinner than the grid.
                .filter(|t| t.faces.len() >= 4)
                .collect()
        })
        .collect();

    let mut out = Vertices::new(&pool);
    let building = sanitize(&heritage.name, "building");
    let mut taken = vec![building.clone()];
    let mut objects = Map::new();
    let mut children = Vec::new();
    let mpu3 = heritage.frame.metres_per_unit.powi(3);
    for (i, part) in parts.iter().enumerate() {
        let id = unique_id(
            &format!("{building}-{}", sanitize(&part.name, "part")),
            &mut taken,
        );
        let mut object = part_object(part, &totals[i], mpu3, &building);
        let geometry = part_geometry(&drawn[i], &pool, &mut out);
        if !geometry.is_empty() {
            object["geometry"] = Value::Array(geometry);
        }
        objects.insert(id.clone(), object);
        children.push(Value::String(id));
    }
    let mut root = json!({ "type": "Building" });
    if !heritage.attributes.is_empty() {
        let attributes: Map<String, Value> = heritage
            .attributes
            .iter()
            .map(|(k, v)| (k.clone(), attribute(v)))
            .collect();
        root["attributes"] = Value::Object(attributes);
    }
    if !children.is_empty() {
        root["children"] = Value::Array(children);
    }
    objects.insert(building, root);

    let mut metadata = Map::new();
    if !heritage.name.is_empty() {
        metadata.insert("title".into(), heritage.name.clone().into());
    }
    if let Some(extent) = out.extent(translate) {
        metadata.insert("geographicalExtent".into(), json!(extent));
    }
    if let Some(placement) = heritage.frame.placement {
        let crs = format!("https://www.opengis.net/def/crs/EPSG/0/{}", placement.epsg);
        metadata.insert("referenceSystem".into(), crs.into());
    }
    let document = json!({
        "type": "CityJSON",
        "version": "2.0",
        "transform": { "scale": [SCALE, SCALE, SCALE], "translate": translate },
        "metadata": metadata,
        "CityObjects": objects,
        "vertices": out.keys,
    });
    Ok(serde_json::to_string(&document)?)
}

/// The drawn terminals' meshes of each part in the file's frame (metres), and the bounds of
/// the points their triangles use (the grid's translate is the minimum), or the first point
/// that is not finite there.
fn drawn_meshes(
    model: &Model,
    heritage: &Heritage,
    part_of: &[Option<usize>],
    parts: usize,
    options: &ExportOptions,
) -> Result<(PartMeshes, [f64; 3], [f64; 3]), ExportError> {
    let mut meshes: PartMeshes = (0..parts).map(|_| Vec::new()).collect();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for (id, node) in model.nodes.iter().enumerate() {
        let id = id as NodeId;
        let Some(&Some(part)) = part_of.get(id as usize) else {
            continue;
        };
        if node.state != NodeState::Terminal {
            continue;
        }
        let Some((points, triangles)) = world_mesh(model, id, &options.tessellation) else {
            continue;
        };
        let mut world = Vec::with_capacity(points.len());
        for (v, p) in points.into_iter().enumerate() {
            let w = heritage.frame.to_world(p);
            if !w.iter().all(|c| c.is_finite()) {
                return Err(ExportError::NotFinite {
                    what: format!(
                        "vertex {v} of {} (node {id}) in CityJSON's frame",
                        model.symbol(node)
                    ),
                    value: w.to_vec(),
                });
            }
            world.push(w);
        }
        for &i in triangles.iter().flatten() {
            if let Some(w) = world.get(i as usize) {
                for k in 0..3 {
                    lo[k] = lo[k].min(w[k]);
                    hi[k] = hi[k].max(w[k]);
                }
            }
        }
        let mesh = FileMesh {
            points: world,
            triangles,
        };
        meshes[part].push((id, mesh));
    }
    Ok((meshes, lo, hi))
}

/// Per part, its drawn terminals' node ids and meshes.
type PartMeshes = Vec<Vec<(NodeId, FileMesh)>>;

/// A `BuildingPart` without geometry: its parent and attributes, the computed ones
/// (`castellan_kind`, `volume_m3`, `mass_kg`, `terminals`) over any of the part's own of the
/// same name.
fn part_object(part: &Part, totals: &Totals, mpu3: f64, building: &str) -> Value {
    let mut attributes: Map<String, Value> = part
        .attributes
        .iter()
        .map(|(k, v)| (k.clone(), attribute(v)))
        .collect();
    attributes.insert("castellan_kind".into(), part.kind.clone().into());
    attributes.insert("volume_m3".into(), (totals.volume * mpu3).into());
    attributes.insert("mass_kg".into(), (totals.mass * mpu3).into());
    attributes.insert("terminals".into(), totals.terminals.into());
    json!({
        "type": "BuildingPart",
        "parents": [building],
        "attributes": attributes,
    })
}

/// The part's geometry objects: LoD 2 (walls, roofs, floors) if it has any, and LoD 3 (those
/// and its windows and doors) if it has windows or doors.
fn part_geometry(terminals: &[Terminal], pool: &Pool, out: &mut Vertices) -> Vec<Value> {
    let lod2 = |c: Class| matches!(c, Class::Wall | Class::Roof | Class::Floor);
    let openings = |c: Class| matches!(c, Class::Window | Class::Door);
    let context = Context {
        ground: terminals
            .iter()
            .flat_map(|t| t.faces.iter().map(|f| f.z_range[0]))
            .min()
            .unwrap_or(0),
        roofed: terminals.iter().any(|t| t.class == Class::Roof),
    };
    let mut geometry = Vec::new();
    if terminals.iter().any(|t| lod2(t.class)) {
        geometry.push(composite_solid("2", terminals, &lod2, context, pool, out));
    }
    if terminals.iter().any(|t| openings(t.class)) {
        let lod3 = |c: Class| lod2(c) || openings(c);
        geometry.push(composite_solid("3", terminals, &lod3, context, pool, out));
    }
    geometry
}

/// What the semantic type of a face depends on besides its terminal: the part's lowest grid
/// height and whether the part has a roof.
#[derive(Clone, Copy)]
struct Context {
    ground: i64,
    roofed: bool,
}

/// One `CompositeSolid` of the terminals whose class `keep` accepts, one solid each, with its
/// semantic surfaces (one per type, class and symbol).
fn composite_solid(
    lod: &str,
    terminals: &[Terminal],
    keep: &dyn Fn(Class) -> bool,
    context: Context,
    pool: &Pool,
    out: &mut Vertices,
) -> Value {
    let mut surfaces: Vec<Value> = Vec::new();
    let mut surface_of: std::collections::HashMap<(&str, Class, &str), usize> =
        std::collections::HashMap::new();
    let mut boundaries = Vec::new();
    let mut values = Vec::new();
    for t in terminals.iter().filter(|t| keep(t.class)) {
        let mut shell = Vec::with_capacity(t.faces.len());
        let mut shell_values = Vec::with_capacity(t.faces.len());
        for face in &t.faces {
            let kind = surface_type(t.class, face, context);
            let index = *surface_of
                .entry((kind, t.class, t.symbol))
                .or_insert_with(|| {
                    surfaces.push(json!({
                        "type": kind,
                        "castellan_class": t.class.name(),
                        "vsg_symbol": t.symbol,
                    }));
                    surfaces.len() - 1
                });
            let rings: Vec<Value> = face.rings.iter().map(|r| out.ring(r, pool)).collect();
            shell.push(Value::Array(rings));
            shell_values.push(index);
        }
        boundaries.push(json!([shell]));
        values.push(json!([shell_values]));
    }
    json!({
        "type": "CompositeSolid",
        "lod": lod,
        "boundaries": boundaries,
        "semantics": { "surfaces": surfaces, "values": values },
    })
}

/// The CityJSON semantic surface type of a face of a terminal of class `class`: the table in
/// the module's documentation.
fn surface_type(class: Class, face: &Face, context: Context) -> &'static str {
    let nz = face.normal[2];
    let (up, down) = (nz >= STEEP, nz <= -STEEP);
    match class {
        Class::Window => return "Window",
        Class::Door => return "Door",
        _ => {}
    }
    if down && face.z_range[1] <= context.ground + GROUND_TOLERANCE {
        return "GroundSurface";
    }
    match (class, up, down) {
        (Class::Roof, true, _) => "RoofSurface",
        (Class::Floor, true, _) if context.roofed => "FloorSurface",
        (Class::Floor, true, _) => "OuterFloorSurface",
        (Class::Floor, _, true) if context.roofed => "CeilingSurface",
        (Class::Floor, false, false) => "ClosureSurface",
        (_, true, _) if context.roofed => "OuterFloorSurface",
        (_, true, _) => "RoofSurface",
        (_, _, true) => "OuterCeilingSurface",
        _ => "WallSurface",
    }
}

/// An attribute value as JSON; a non-finite number becomes `null`, as JSON has none.
fn attribute(a: &Attribute) -> Value {
    match a {
        Attribute::Text(s) => Value::String(s.clone()),
        Attribute::Number(n) => Value::from(*n),
        Attribute::Flag(b) => Value::Bool(*b),
    }
}

/// A city object id from a name: letters, digits, `_`, `-` and `.` kept, anything else `_`
/// (ids end up in URLs and file names of tools that split CityJSON files).
fn sanitize(name: &str, fallback: &str) -> String {
    let id: String = name
        .trim()
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect();
    if id.is_empty() { fallback.into() } else { id }
}

/// `id`, or `id-2`, `id-3`, … if taken (two names may sanitise alike); records it as taken.
fn unique_id(id: &str, taken: &mut Vec<String>) -> String {
    let mut candidate = id.to_string();
    let mut n = 1;
    while taken.contains(&candidate) {
        n += 1;
        candidate = format!("{id}-{n}");
    }
    taken.push(candidate.clone());
    candidate
}

#[cfg(test)]
mod tests {
    use super::*;

    fn face(nz: f64, z_range: [i64; 2]) -> Face {
        let s = (1.0 - nz * nz).sqrt();
        Face {
            rings: Vec::new(),
            normal: [s, 0.0, nz],
            z_range,
        }
    }

    #[test]
    fn faces_get_the_types_of_the_table() {
        let roofed = Context {
            ground: 0,
            roofed: true,
        };
        let open = Context {
            roofed: false,
            ..roofed
        };
        let high = [5000, 5000];
        let (up, vertical, down, sloped) = (1.0, 0.0, -1.0, 0.5);
        assert_eq!(
            surface_type(Class::Roof, &face(sloped, high), roofed),
            "RoofSurface"
        );
        assert_eq!(
            surface_type(Class::Roof, &face(vertical, high), roofed),
            "WallSurface"
        );
        assert_eq!(
            surface_type(Class::Roof, &face(down, high), roofed),
            "OuterCeilingSurface"
        );
        assert_eq!(
            surface_type(Class::Wall, &face(0.1, high), roofed),
            "WallSurface"
        );
        assert_eq!(
            surface_type(Class::Wall, &face(up, high), open),
            "RoofSurface"
        );
        assert_eq!(
            surface_type(Class::Wall, &face(up, high), roofed),
            "OuterFloorSurface"
        );
        assert_eq!(
            surface_type(Class::Wall, &face(down, [0, 10]), roofed),
            "GroundSurface"
        );
        assert_eq!(
            surface_type(Class::Wall, &face(down, [0, 11]), roofed),
            "OuterCeilingSurface"
        );
        assert_eq!(
            surface_type(Class::Floor, &face(up, high), roofed),
            "FloorSurface"
        );
        assert_eq!(
            surface_type(Class::Floor, &face(up, high), open),
            "OuterFloorSurface"
        );
        assert_eq!(
            surface_type(Class::Floor, &face(down, high), roofed),
            "CeilingSurface"
        );
        assert_eq!(
            surface_type(Class::Floor, &face(down, high), open),
            "OuterCeilingSurface"
        );
        assert_eq!(
            surface_type(Class::Floor, &face(vertical, high), open),
            "ClosureSurface"
        );
        assert_eq!(
            surface_type(Class::Window, &face(down, [0, 0]), open),
            "Window"
        );
        assert_eq!(surface_type(Class::Door, &face(up, high), open), "Door");
    }

    #[test]
    fn ids_are_sanitised_and_unique() {
        assert_eq!(sanitize(" Château de Coucy ", "b"), "Ch_teau_de_Coucy");
        assert_eq!(sanitize("", "building"), "building");
        let mut taken = Vec::new();
        assert_eq!(unique_id("a_b", &mut taken), "a_b");
        assert_eq!(unique_id("a_b", &mut taken), "a_b-2");
        assert_eq!(unique_id("a_b", &mut taken), "a_b-3");
    }
}
