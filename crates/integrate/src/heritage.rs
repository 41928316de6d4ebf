//! What the heritage and GIS files say of a reconstructed castle (issue 24): the estimate's
//! structures as the building's parts, each with its plan label, role, kind, measured sizes in
//! metres and the provenance of every parameter, and the site's map placement from PROJECT.toml
//! (`[site]`). The writers (`vsg::export`: CityJSON, IFC, glTF structural metadata) take the
//! [`Heritage`] this builds.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use vsg::export::semantics::{Attribute, Frame, Heritage, Part, Placement};

use crate::estimate::{Estimate, Provenance};

/// PROJECT.toml's `[site]`: where the drawing stands on a map, for CityJSON's reference system
/// and IFC's map conversion.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Site {
    /// The site's name (the building's name in the files); the plan's file name when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The EPSG code of a projected reference system in metres (e.g. 2154, Lambert-93).
    pub epsg: u32,
    /// Easting, northing and ground height (metres, in that system) of the plan point `at`.
    pub origin: [f64; 3],
    /// The plan pixel [x, y] that `origin` gives; the drawing's top-left corner when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<[f64; 2]>,
    /// The bearing of the drawing's up direction, degrees clockwise from grid north (0 when
    /// the drawing's up is north).
    #[serde(default)]
    pub north: f64,
}

/// EPSG's codes of reference systems lie in this range.
const EPSG_CODES: std::ops::RangeInclusive<u32> = 1024..=32767;

impl Site {
    /// Checks the values; the message names the key.
    pub fn check(&self) -> Result<(), String> {
        if !EPSG_CODES.contains(&self.epsg) {
            return Err(format!(
                "epsg = {}: not an EPSG code of a reference system (1024 to 32767)",
                self.epsg
            ));
        }
        if self.origin.iter().any(|v| !v.is_finite() || v.abs() > 1e8) {
            return Err(format!(
                "origin = {:?}: easting, northing and height in metres, each finite and within 10⁸",
                self.origin
            ));
        }
        if let Some(at) = self.at
            && at.iter().any(|v| !v.is_finite() || v.abs() > 1e6)
        {
            return Err(format!(
                "at = {at:?}: a plan pixel [x, y], finite and within 10⁶"
            ));
        }
        if !self.north.is_finite() || self.north.abs() > 360.0 {
            return Err(format!(
                "north = {}: degrees clockwise from grid north, from −360 to 360",
                self.north
            ));
        }
        Ok(())
    }
}

/// The parts, frame and attributes of the reconstructed castle: one part per structure of
/// `estimate` whose symbol names a node of `model`, the frame in metres, placed on the map
/// when `site` is given.
pub fn heritage(estimate: &Estimate, model: &vsg::Model, site: Option<&Site>) -> Heritage {
    let scale = &estimate.scale;
    let metres_per_unit = 1.0 / scale.units_per_metre;
    let placement = site.map(|s| {
        let (sin, cos) = s.north.to_radians().sin_cos();
        // The plan point `at` in metres, x east and y north before turning (the plan's y grows
        // down the page), turned as `Frame::to_world` turns: `origin` minus that.
        let [px, py] = s.at.unwrap_or([0.0, 0.0]);
        let metres_per_pixel = scale.units_per_pixel * metres_per_unit;
        let (x, y) = (px * metres_per_pixel, -py * metres_per_pixel);
        let (e, n) = (x * cos + y * sin, -x * sin + y * cos);
        Placement {
            origin: [s.origin[0] - e, s.origin[1] - n, s.origin[2]],
            epsg: s.epsg,
            rotation_deg: s.north,
        }
    });
    // The program's axiom places each structure as one or more children of the root, named
    // after it (`tower1Site`, `curtain2`, …: `agreement::structure_of`).
    let ids: Vec<String> = estimate.structures.iter().map(|s| s.id.clone()).collect();
    let mut nodes: Vec<Vec<u32>> = vec![Vec::new(); ids.len()];
    for id in model.root().map(|r| r.children()).into_iter().flatten() {
        let k = crate::agreement::structure_of(model.symbol(&model.nodes[id as usize]), &ids);
        if let Some(list) = nodes.get_mut(k as usize) {
            list.push(id);
        }
    }
    let parts = estimate
        .structures
        .iter()
        .zip(nodes)
        .filter_map(|(s, nodes)| {
            let (&node, more) = nodes.split_first()?;
            let mut attributes = BTreeMap::from([
                ("label".to_string(), Attribute::Text(s.label.name().into())),
                ("role".to_string(), Attribute::Text(s.role.name().into())),
                (
                    "height_m".to_string(),
                    Attribute::Number(s.height * metres_per_unit),
                ),
                (
                    "wall_thickness_m".to_string(),
                    Attribute::Number(s.wall_thickness * metres_per_unit),
                ),
                (
                    "facades".to_string(),
                    Attribute::Number(s.facades.len() as f64),
                ),
            ]);
            if let Some(roof) = s.roof {
                attributes.insert("roof".into(), Attribute::Text(roof.name().into()));
            }
            if let Some(c) = s.crenellated {
                attributes.insert("crenellated".into(), Attribute::Flag(c));
            }
            for (key, p) in &s.provenance {
                attributes.insert(format!("provenance.{key}"), Attribute::Text(source(p)));
            }
            Some(Part {
                node,
                more_nodes: more.to_vec(),
                name: s.id.clone(),
                kind: s.role.name().into(),
                attributes,
            })
        })
        .collect();
    let name = site
        .and_then(|s| s.name.clone())
        .unwrap_or_else(|| estimate.plan.image.clone());
    Heritage {
        name,
        parts,
        frame: Frame {
            metres_per_unit,
            placement,
        },
        attributes: BTreeMap::from([
            (
                "plan".to_string(),
                Attribute::Text(estimate.plan.image.clone()),
            ),
            (
                "units".to_string(),
                Attribute::Text(scale.units.symbol().into()),
            ),
            (
                "generator".to_string(),
                Attribute::Text(concat!("castellan ", env!("CARGO_PKG_VERSION")).into()),
            ),
        ]),
    }
}

/// A parameter's source in words: `image: step`, with the fit error and the structure it was
/// lent by when there are.
fn source(p: &Provenance) -> String {
    let mut s = format!("{}: {}", p.image, p.step);
    if let Some(e) = p.fit_error {
        s.push_str(&format!(" (error {e:.2} px)"));
    }
    if let Some(by) = &p.lent_by {
        s.push_str(&format!(" (lent by {by})"));
    }
    s
}
