//! IFC4 export (issue 24): a produced model as a BIM file that heritage and building tools
//! open, written by castellan itself as a STEP physical file (`ifc_step.rs`), with no native
//! dependency.
//!
//! Sui 2011 §7.1.3 keeps the semantic tree of a production: the model is an aggregation of
//! labelled shapes whose leaves are the solids. IFC says the same with `IfcRelAggregates`, so
//! the tree survives at the level a BIM tool understands: the project aggregates a site, a
//! building and one storey; every part of the building ([`Heritage::parts_or_default`], a
//! structure of the castle) is an `IfcElementAssembly` contained in the storey, which
//! aggregates the part's drawn terminals as elements of their class ([`class_of`]): `IfcWall`,
//! `IfcRoof`, `IfcSlab` (floor), `IfcWindow`, `IfcDoor`. The inner non-terminals (a tower's
//! shaft, a wall's band of slits) are not written: IFC has no element for "a group of stones
//! that was split further", and assemblies of assemblies make viewers' trees deep without
//! saying more than the element names (the vsg symbols) already do.
//!
//! Void terminals are `IfcSpace`s, as the issue asks ("IfcSpace for rooms and void shapes"),
//! aggregated by the storey (IFC puts spaces in the spatial tree, not under an element) and
//! named after their part: rooms (class `Space`) `INTERNAL`, the other voids (arrow slits,
//! crenels, window openings) `USERDEFINED` with the object type `opening`. Not
//! `IfcOpeningElement`: one must void an element (`IfcRelVoidsElement`) that it overlaps, but a
//! vsg opening does not cut a wall, it takes the place of the masonry beside it (the split
//! already left the gap), so there is no host to name and nothing to subtract.
//!
//! Geometry: each element's mesh ([`world_mesh`]) as an `IfcTriangulatedFaceSet` (IFC4's
//! tessellated solid) in the file frame (metres, x east, y north, z up; [`Frame::to_world`]
//! without the map placement), every element placed at the origin. The map placement, when
//! there is one, is the context's `IfcMapConversion` to an `IfcProjectedCRS` (EPSG code)
//! rather than baked in: map coordinates of 6–7 digits would cost viewers that draw in single
//! precision their centimetres. Colours are surface styles of the appearances.
//!
//! Quantities: `NetVolume` (the exact volume of the primitive, Table 7.1, not the mesh's) and,
//! where the appearance has a density, `NetWeight` per element and per assembly; the part's
//! attributes (label, role, height, provenance of each parameter) are the property set
//! `Castellan_Attributes`. GlobalIds hash the building, part and node, and the header's time stamp
//! comes from the heritage attribute `timestamp` (else the epoch), so writing the same model
//! twice gives the same file.

use std::collections::BTreeMap;

use super::common::{Palette, check_model, unit};
use super::error::ExportError;
use super::ifc_step::{Id, Step, list, real, string};
use super::options::ExportOptions;
use super::semantics::{
    Attribute, Class, Frame, Heritage, Part, class_of, part_totals, world_mesh,
};
use crate::tree::{Appearance, Model, NodeId, NodeState};

/// The time stamp of files whose heritage gives none: files must not depend on the clock.
const EPOCH: &str = "1970-01-01T00:00:00";

/// IfcLabel and IfcIdentifier are STRING(255): longer texts are cut (names) or become IfcText
/// (property values).
const LABEL_MAX: usize = 255;

pub(super) fn write_ifc(
    model: &Model,
    heritage: &Heritage,
    options: &ExportOptions,
) -> Result<String, ExportError> {
    check_model(model)?;
    let mpu = heritage.frame.metres_per_unit;
    if !(mpu.is_finite() && mpu > 0.0) {
        return Err(ExportError::NotFinite {
            what: "the frame's metres per unit (a positive number)".into(),
            value: vec![mpu],
        });
    }
    let parts = heritage.parts_or_default(model);
    let part_of = Heritage::part_of(model, &parts);
    let totals = part_totals(model, &parts, &part_of);
    let mut w = Writer {
        step: Step::new(),
        key: heritage.name.clone(),
        // Local engineering coordinates; the placement goes to the map conversion.
        frame: Frame {
            placement: None,
            ..heritage.frame
        },
        palette: Palette::new(model),
        styles: Vec::new(),
        body: Id(0),
    };
    let (project, axes) = w.context_and_project(heritage)?;
    let place = |w: &mut Writer, rel: Option<Id>| {
        let rel = rel.map_or("$".to_string(), |r| r.to_string());
        w.step.add("IFCLOCALPLACEMENT", &format!("{rel},{axes}"))
    };
    let site_at = place(&mut w, None);
    let building_at = place(&mut w, Some(site_at));
    let storey_at = place(&mut w, Some(building_at));
    let name = label(&heritage.name);
    let site = w.root(
        "IFCSITE",
        "site",
        "'Site'",
        site_at,
        "$,.ELEMENT.,$,$,$,$,$",
    );
    let building = w.root(
        "IFCBUILDING",
        "building",
        &name,
        building_at,
        "$,.ELEMENT.,$,$,$",
    );
    let storey = w.root(
        "IFCBUILDINGSTOREY",
        "storey",
        "'Ground'",
        storey_at,
        "$,.ELEMENT.,0.",
    );
    w.aggregate("project", project, &[site]);
    w.aggregate("site", site, &[building]);
    w.aggregate("building", building, &[storey]);
    w.properties("building", building, &heritage.attributes)?;

    // One assembly per part, its elements placed relative to it.
    let mut assemblies = Vec::with_capacity(parts.len());
    let mut element_at = Vec::with_capacity(parts.len());
    for part in &parts {
        let at = place(&mut w, Some(storey_at));
        let guid = w.guid(&format!("part/{}", part.name));
        // USERDEFINED requires the ObjectType that says what the part is.
        let (kind, predefined) = if part.kind.is_empty() {
            ("$".to_string(), ".NOTDEFINED.")
        } else {
            (label(&part.kind), ".USERDEFINED.")
        };
        let args = format!(
            "{guid},$,{},$,{kind},{at},$,$,.SITE.,{predefined}",
            label(&part.name)
        );
        assemblies.push(w.step.add("IFCELEMENTASSEMBLY", &args));
        element_at.push(place(&mut w, Some(at)));
    }

    let mut members: Vec<Vec<Id>> = vec![Vec::new(); parts.len()];
    let mut loose = Vec::new();
    let mut spaces = Vec::new();
    let mut has_mass = vec![false; parts.len()];
    for (i, node) in model.nodes.iter().enumerate() {
        let id = i as NodeId;
        let (Some(solid), true) = (model.solid(id), node.is_leaf()) else {
            continue;
        };
        let part = part_of[i];
        let symbol = model.symbol(node);
        let class = class_of(symbol, node.state);
        let volume = solid.volume() * mpu.powi(3);
        let appearance = model.appearance(node);
        let style = match node.state {
            NodeState::Terminal => Some(w.style(node.appearance, appearance)?),
            _ => None,
        };
        let shape = w.body(model, id, style, options)?;
        let guid = w.guid(&format!("node/{i}"));
        let name = label(symbol);
        // Elements sit in their assembly's frame, spaces (spatial, aggregated by the storey)
        // in the storey's; every frame is the identity, the meshes are in the file frame.
        let placement = match (class, part) {
            (Class::Space | Class::Opening, _) | (_, None) => storey_at,
            (_, Some(p)) => element_at[p],
        };
        let head =
            |object_type: &str| format!("{guid},$,{name},$,{object_type},{placement},{shape}");
        let element = match class {
            Class::Space | Class::Opening => {
                let of = part.map_or(String::new(), |p| format!(" of {}", parts[p].name));
                let long = label(&format!("{symbol}{of}"));
                let (object_type, kind) = match class {
                    Class::Space => ("$", ".INTERNAL."),
                    _ => ("'opening'", ".USERDEFINED."),
                };
                let head = head(object_type);
                let args = format!("{head},{long},.ELEMENT.,{kind},$");
                let space = w.step.add("IFCSPACE", &args);
                spaces.push(space);
                space
            }
            class => {
                let (entity, rest) = match class {
                    Class::Roof => ("IFCROOF", ".NOTDEFINED."),
                    Class::Floor => ("IFCSLAB", ".FLOOR."),
                    Class::Window => ("IFCWINDOW", "$,$,.WINDOW.,.NOTDEFINED.,$"),
                    Class::Door => ("IFCDOOR", "$,$,.DOOR.,.NOTDEFINED.,$"),
                    _ => ("IFCWALL", ".SOLIDWALL."),
                };
                let head = head("$");
                let element = w
                    .step
                    .add(entity, &format!("{head},{},{rest}", string(&i.to_string())));
                match part {
                    Some(p) => members[p].push(element),
                    None => loose.push(element),
                }
                element
            }
        };
        let mass = match (node.state, appearance.density) {
            (NodeState::Terminal, Some(density)) => {
                if let Some(p) = part {
                    has_mass[p] = true;
                }
                Some(density * volume)
            }
            _ => None,
        };
        w.quantities(&format!("node/{i}"), element, volume, mass)?;
    }

    let mut contained = assemblies.clone();
    contained.extend(loose);
    w.contain(storey, &contained);
    w.aggregate("storey", storey, &spaces);
    for (p, part) in parts.iter().enumerate() {
        let key = format!("part/{}", part.name);
        w.aggregate(&key, assemblies[p], &members[p]);
        let t = totals[p];
        let scale = mpu.powi(3);
        let mass = has_mass[p].then_some(t.mass * scale);
        w.quantities(&key, assemblies[p], t.volume * scale, mass)?;
        w.part_properties(part, assemblies[p])?;
    }
    let timestamp = match heritage.attributes.get("timestamp") {
        Some(Attribute::Text(t)) => t.as_str(),
        _ => EPOCH,
    };
    let file = if heritage.name.is_empty() {
        "model"
    } else {
        &heritage.name
    };
    Ok(w.step.finish(&format!("{file}.ifc"), timestamp))
}

struct Writer {
    step: Step,
    /// Prefix of every GlobalId's key: the building's name.
    key: String,
    frame: Frame,
    palette: Palette,
    /// Surface style per palette slot, written on first use.
    styles: Vec<Option<Id>>,
    /// The body subcontext, set by [`Writer::context_and_project`] before any body is written.
    body: Id,
}

impl Writer {
    fn guid(&mut self, what: &str) -> String {
        let key = format!("{}/{what}", self.key);
        self.step.guid(&key)
    }

    /// Units (metre, m², m³, kg, radian), the 3D model context with its body subcontext and,
    /// with a map placement, the map conversion; then the project. Returns the project and
    /// the identity axes, which every placement shares.
    fn context_and_project(&mut self, heritage: &Heritage) -> Result<(Id, Id), ExportError> {
        let s = &mut self.step;
        let metre = s.add("IFCSIUNIT", "*,.LENGTHUNIT.,$,.METRE.");
        let units = [
            metre,
            s.add("IFCSIUNIT", "*,.AREAUNIT.,$,.SQUARE_METRE."),
            s.add("IFCSIUNIT", "*,.VOLUMEUNIT.,$,.CUBIC_METRE."),
            s.add("IFCSIUNIT", "*,.MASSUNIT.,.KILO.,.GRAM."),
            s.add("IFCSIUNIT", "*,.PLANEANGLEUNIT.,$,.RADIAN."),
        ];
        let units = s.add("IFCUNITASSIGNMENT", &list(units));
        let origin = s.add("IFCCARTESIANPOINT", "(0.,0.,0.)");
        let wcs = s.add("IFCAXIS2PLACEMENT3D", &format!("{origin},$,$"));
        let north = s.add("IFCDIRECTION", "(0.,1.)");
        let model = s.add(
            "IFCGEOMETRICREPRESENTATIONCONTEXT",
            &format!("$,'Model',3,1.E-05,{wcs},{north}"),
        );
        let body = s.add(
            "IFCGEOMETRICREPRESENTATIONSUBCONTEXT",
            &format!("'Body','Model',*,*,*,*,{model},$,.MODEL_VIEW.,$"),
        );
        self.body = body;
        if let Some(p) = heritage.frame.placement {
            let crs = s.add(
                "IFCPROJECTEDCRS",
                &format!("{},$,$,$,$,$,{metre}", string(&format!("EPSG:{}", p.epsg))),
            );
            // Frame::to_world turns (x, y) to (x cos + y sin, −x sin + y cos): the local x axis
            // points along (cos, −sin) of the map grid.
            let (sin, cos) = p.rotation_deg.to_radians().sin_cos();
            let what = || "the map placement".to_string();
            let [e, n, h] = p.origin;
            let args = [e, n, h, cos, -sin]
                .into_iter()
                .map(|v| real(v, what))
                .collect::<Result<Vec<_>, _>>()?;
            s.add(
                "IFCMAPCONVERSION",
                &format!("{model},{crs},{},1.", args.join(",")),
            );
        }
        let guid = self.guid("project");
        let project = self.step.add(
            "IFCPROJECT",
            &format!(
                "{guid},$,{},$,$,$,$,({model}),{units}",
                label(&heritage.name)
            ),
        );
        Ok((project, wcs))
    }

    /// A spatial element (site, building, storey): GlobalId, name, placement, then `rest`.
    fn root(&mut self, entity: &str, what: &str, name: &str, at: Id, rest: &str) -> Id {
        let guid = self.guid(what);
        self.step
            .add(entity, &format!("{guid},$,{name},$,$,{at},$,{rest}"))
    }

    /// `whole` aggregates `parts` (nothing is written for no parts: the set may not be empty).
    fn aggregate(&mut self, key: &str, whole: Id, parts: &[Id]) {
        if !parts.is_empty() {
            let guid = self.guid(&format!("{key}/aggregates"));
            self.step.add(
                "IFCRELAGGREGATES",
                &format!("{guid},$,$,$,{whole},{}", list(parts)),
            );
        }
    }

    fn contain(&mut self, storey: Id, elements: &[Id]) {
        if !elements.is_empty() {
            let guid = self.guid("storey/contains");
            let args = format!("{guid},$,$,$,{},{storey}", list(elements));
            self.step.add("IFCRELCONTAINEDINSPATIALSTRUCTURE", &args);
        }
    }

    /// The surface style of a model appearance, shared by equal appearances.
    fn style(&mut self, index: u32, a: &Appearance) -> Result<Id, ExportError> {
        let slot = self.palette.slot(index) as usize;
        if slot >= self.styles.len() {
            self.styles.resize(slot + 1, None);
        }
        if let Some(style) = self.styles[slot] {
            return Ok(style);
        }
        let what = || format!("the colour of appearance {index}");
        let [r, g, b] = a.color.map(unit);
        let rgb = format!("$,{},{},{}", real(r, what)?, real(g, what)?, real(b, what)?);
        let colour = self.step.add("IFCCOLOURRGB", &rgb);
        let t = real(unit(a.transparency), what)?;
        let rendering = self.step.add(
            "IFCSURFACESTYLERENDERING",
            &format!("{colour},{t},$,$,$,$,$,$,.NOTDEFINED."),
        );
        let name = string(&format!("appearance_{}", self.palette.used[slot]));
        let style = self
            .step
            .add("IFCSURFACESTYLE", &format!("{name},.BOTH.,({rendering})"));
        self.styles[slot] = Some(style);
        Ok(style)
    }

    /// The body of node `id` as a product shape (`$` when its mesh is empty).
    fn body(
        &mut self,
        model: &Model,
        id: NodeId,
        style: Option<Id>,
        options: &ExportOptions,
    ) -> Result<String, ExportError> {
        let Some((points, triangles)) = world_mesh(model, id, &options.tessellation) else {
            return Ok("$".into());
        };
        if triangles.is_empty() {
            return Ok("$".into());
        }
        let mut coords = String::with_capacity(points.len() * 40);
        for (k, p) in points.iter().enumerate() {
            let w = self.frame.to_world(*p);
            let what = || format!("a vertex of node {id}");
            let [x, y, z] = [real(w[0], what)?, real(w[1], what)?, real(w[2], what)?];
            coords.push_str(if k == 0 { "(" } else { ",(" });
            coords.push_str(&format!("{x},{y},{z})"));
        }
        let list_of_points = self
            .step
            .add("IFCCARTESIANPOINTLIST3D", &format!("({coords})"));
        let indices = list(triangles.iter().map(|t| list(t.map(|v| v + 1))));
        // Closed: the terminals are solids (§7.1.2), their meshes closed.
        let faces = self.step.add(
            "IFCTRIANGULATEDFACESET",
            &format!("{list_of_points},$,.T.,{indices},$"),
        );
        if let Some(style) = style {
            self.step
                .add("IFCSTYLEDITEM", &format!("{faces},({style}),$"));
        }
        let body = self.body;
        let rep = self.step.add(
            "IFCSHAPEREPRESENTATION",
            &format!("{body},'Body','Tessellation',({faces})"),
        );
        Ok(self
            .step
            .add("IFCPRODUCTDEFINITIONSHAPE", &format!("$,$,({rep})"))
            .to_string())
    }

    /// `BaseQuantities` of `object`: its net volume (m³) and its mass (kg) when known.
    fn quantities(
        &mut self,
        key: &str,
        object: Id,
        volume: f64,
        mass: Option<f64>,
    ) -> Result<(), ExportError> {
        let what = || format!("the quantities of {key}");
        // Quantities may not be negative; a unique shape's mesh volume can be −0 or −ε.
        let v = real(volume.max(0.0), what)?;
        let mut q = vec![
            self.step
                .add("IFCQUANTITYVOLUME", &format!("'NetVolume',$,$,{v},$")),
        ];
        if let Some(m) = mass {
            let m = real(m.max(0.0), what)?;
            q.push(
                self.step
                    .add("IFCQUANTITYWEIGHT", &format!("'NetWeight',$,$,{m},$")),
            );
        }
        let guid = self.guid(&format!("{key}/quantities"));
        let method = "'castellan: exact volumes of the primitives (Sui 2011, Table 7.1)'";
        let set = self.step.add(
            "IFCELEMENTQUANTITY",
            &format!("{guid},$,'BaseQuantities',$,{method},{}", list(q)),
        );
        let guid = self.guid(&format!("{key}/quantities/rel"));
        self.step.add(
            "IFCRELDEFINESBYPROPERTIES",
            &format!("{guid},$,$,$,({object}),{set}"),
        );
        Ok(())
    }

    fn part_properties(&mut self, part: &Part, assembly: Id) -> Result<(), ExportError> {
        self.properties(&format!("part/{}", part.name), assembly, &part.attributes)
    }

    /// `attributes` as the property set `Castellan_Attributes` of `object` (none when empty).
    fn properties(
        &mut self,
        key: &str,
        object: Id,
        attributes: &BTreeMap<String, Attribute>,
    ) -> Result<(), ExportError> {
        if attributes.is_empty() {
            return Ok(());
        }
        let mut props = Vec::with_capacity(attributes.len());
        for (name, value) in attributes {
            let value = match value {
                Attribute::Text(t) if t.chars().count() <= LABEL_MAX => {
                    format!("IFCLABEL({})", string(t))
                }
                Attribute::Text(t) => format!("IFCTEXT({})", string(t)),
                Attribute::Number(v) => {
                    format!(
                        "IFCREAL({})",
                        real(*v, || format!("attribute {name} of {key}"))?
                    )
                }
                Attribute::Flag(b) => format!("IFCBOOLEAN(.{}.)", if *b { 'T' } else { 'F' }),
            };
            let args = format!("{},$,{value},$", label(name));
            props.push(self.step.add("IFCPROPERTYSINGLEVALUE", &args));
        }
        let guid = self.guid(&format!("{key}/properties"));
        let set = self.step.add(
            "IFCPROPERTYSET",
            &format!("{guid},$,'Castellan_Attributes',$,{}", list(props)),
        );
        let guid = self.guid(&format!("{key}/properties/rel"));
        self.step.add(
            "IFCRELDEFINESBYPROPERTIES",
            &format!("{guid},$,$,$,({object}),{set}"),
        );
        Ok(())
    }
}

/// An IfcLabel: at most 255 characters (longer names are cut), encoded.
fn label(s: &str) -> String {
    match s.char_indices().nth(LABEL_MAX) {
        Some((end, _)) => string(&s[..end]),
        None => string(s),
    }
}
