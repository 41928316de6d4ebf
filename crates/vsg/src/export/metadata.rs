//! glTF structural metadata (issue 24): the semantic tree of §7.1.3 as property tables that
//! Cesium and other 3D Tiles viewers show on click. `EXT_structural_metadata` holds a schema
//! with two classes and one property table each:
//! - `part`, one row per part of the building ([`Heritage`]'s parts: the castle's structures):
//!   its name, kind, volume (m³), mass (kg), drawn terminals, and every attribute the caller gives
//!   (label, role, height, the provenance of each parameter, …);
//! - `element`, one row per part and symbol (`tower2` × `tower2.roof`): part, symbol, class
//!   ([`Class`]), volume, mass, terminals.
//!
//! `EXT_mesh_features` ties each drawn primitive to its rows by two vertex attributes,
//! `_FEATURE_ID_0` (the part row) and `_FEATURE_ID_1` (the element row), constant over the
//! primitive; a mesh is therefore shared only between terminals of one element. Terminals
//! outside every part get no feature IDs. The node tree and its `extras` stay as they are.

use std::collections::{BTreeMap, BTreeSet, HashMap};

use serde_json::{Value, json};

use super::semantics::{Attribute, Class, Heritage, Part, Totals, class_of, part_totals};
use crate::tree::{Model, NodeId};

/// The two feature IDs of a drawn terminal: its part's row and its element's row.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) struct FeatureIds {
    pub part: u32,
    pub element: u32,
}

struct ElementRow {
    part: usize,
    symbol: u32,
    class: Class,
    totals: Totals,
}

/// The property tables being gathered while the terminals are written.
pub(super) struct Features {
    parts: Vec<Part>,
    part_of: Vec<Option<usize>>,
    part_totals: Vec<Totals>,
    cubic_metres_per_unit: f64,
    elements: Vec<ElementRow>,
    element_of: HashMap<(usize, u32), u32>,
}

/// One column of a property table.
enum Column {
    Float(Vec<f64>),
    Count(Vec<u32>),
    Text(Vec<String>),
    Flag(Vec<bool>),
}

impl Features {
    pub fn new(model: &Model, heritage: &Heritage) -> Features {
        let parts = heritage.parts_or_default(model);
        let part_of = Heritage::part_of(model, &parts);
        let part_totals = part_totals(model, &parts, &part_of);
        Features {
            parts,
            part_of,
            part_totals,
            cubic_metres_per_unit: heritage.frame.metres_per_unit.powi(3),
            elements: Vec::new(),
            element_of: HashMap::new(),
        }
    }

    /// Whether any drawn terminal lies in a part (a property table has at least one row).
    pub fn has_rows(&self) -> bool {
        !self.parts.is_empty() && !self.elements.is_empty()
    }

    /// The feature IDs of drawn terminal `id` whose solid has `volume` (model units³), counted
    /// into its element's row; `None` outside every part.
    pub fn of(&mut self, model: &Model, id: NodeId, volume: f64) -> Option<FeatureIds> {
        let node = &model.nodes[id as usize];
        let part = (*self.part_of.get(id as usize)?)?;
        let next = self.elements.len() as u32;
        let element = *self.element_of.entry((part, node.symbol)).or_insert(next);
        if element == next {
            self.elements.push(ElementRow {
                part,
                symbol: node.symbol,
                class: class_of(model.symbol(node), node.state),
                totals: Totals::default(),
            });
        }
        let t = &mut self.elements[element as usize].totals;
        t.volume += volume;
        t.mass += model.appearance(node).density.unwrap_or(0.0) * volume;
        t.terminals += 1;
        Some(FeatureIds {
            part: part as u32,
            element,
        })
    }

    /// Writes both property tables through `push` (which stores bytes in an 8-byte aligned
    /// buffer view and returns its index) and returns the root's `EXT_structural_metadata`.
    pub fn extension(&self, model: &Model, push: &mut dyn FnMut(&[u8]) -> u32) -> Value {
        let m3 = self.cubic_metres_per_unit;
        let mut part_columns: Vec<(String, &str, Column)> = vec![
            (
                "name".into(),
                "The part's name",
                Column::Text(self.parts.iter().map(|p| p.name.clone()).collect()),
            ),
            (
                "kind".into(),
                "What the part is",
                Column::Text(self.parts.iter().map(|p| p.kind.clone()).collect()),
            ),
            (
                "volume_m3".into(),
                "Volume of its drawn solids, m³",
                Column::Float(self.part_totals.iter().map(|t| t.volume * m3).collect()),
            ),
            (
                "mass_kg".into(),
                "Mass of its drawn solids from their densities, kg",
                Column::Float(self.part_totals.iter().map(|t| t.mass * m3).collect()),
            ),
            (
                "terminals".into(),
                "Drawn terminal solids",
                Column::Count(
                    self.part_totals
                        .iter()
                        .map(|t| t.terminals as u32)
                        .collect(),
                ),
            ),
        ];
        let taken: BTreeSet<String> = part_columns.iter().map(|c| c.0.clone()).collect();
        for (key, column) in attribute_columns(&self.parts) {
            let mut id = property_id(&key);
            while taken.contains(&id) || part_columns.iter().any(|c| c.0 == id) {
                id.push('_');
            }
            part_columns.push((id, "", column));
        }
        let element_columns: Vec<(String, &str, Column)> = vec![
            (
                "part".into(),
                "The part it belongs to",
                Column::Text(
                    self.elements
                        .iter()
                        .map(|e| self.parts[e.part].name.clone())
                        .collect(),
                ),
            ),
            (
                "symbol".into(),
                "The VSG symbol of its terminals",
                Column::Text(
                    self.elements
                        .iter()
                        .map(|e| model.symbols[e.symbol as usize].clone())
                        .collect(),
                ),
            ),
            (
                "class".into(),
                "wall, roof, floor, window or door",
                Column::Text(
                    self.elements
                        .iter()
                        .map(|e| e.class.name().to_string())
                        .collect(),
                ),
            ),
            (
                "volume_m3".into(),
                "Volume of its solids, m³",
                Column::Float(self.elements.iter().map(|e| e.totals.volume * m3).collect()),
            ),
            (
                "mass_kg".into(),
                "Mass of its solids from their densities, kg",
                Column::Float(self.elements.iter().map(|e| e.totals.mass * m3).collect()),
            ),
            (
                "terminals".into(),
                "Terminal solids",
                Column::Count(
                    self.elements
                        .iter()
                        .map(|e| e.totals.terminals as u32)
                        .collect(),
                ),
            ),
        ];
        let (part_class, part_table) = table("part", self.parts.len(), part_columns, &mut *push);
        let (element_class, element_table) =
            table("element", self.elements.len(), element_columns, push);
        json!({
            "schema": {
                "id": "castellan",
                "name": "castellan semantic model",
                "classes": { "part": part_class, "element": element_class },
            },
            "propertyTables": [part_table, element_table],
        })
    }

    /// The primitive's `EXT_mesh_features`, its attributes being `_FEATURE_ID_0` and `_1`.
    pub fn mesh_features() -> Value {
        json!({
            "featureIds": [
                { "featureCount": 1, "attribute": 0, "propertyTable": 0, "label": "part" },
                { "featureCount": 1, "attribute": 1, "propertyTable": 1, "label": "element" },
            ]
        })
    }
}

/// One column per attribute key of any part: numbers and flags typed when every part has a
/// value, otherwise text (empty where a part has none, the column's no-data value).
fn attribute_columns(parts: &[Part]) -> Vec<(String, Column)> {
    let keys: BTreeSet<&String> = parts.iter().flat_map(|p| p.attributes.keys()).collect();
    keys.into_iter()
        .map(|key| {
            let values: Vec<Option<&Attribute>> =
                parts.iter().map(|p| p.attributes.get(key)).collect();
            let column = if let Some(v) = values
                .iter()
                .map(|v| match v {
                    Some(Attribute::Number(x)) => Some(*x),
                    _ => None,
                })
                .collect::<Option<Vec<f64>>>()
            {
                Column::Float(v)
            } else if let Some(v) = values
                .iter()
                .map(|v| match v {
                    Some(Attribute::Flag(b)) => Some(*b),
                    _ => None,
                })
                .collect::<Option<Vec<bool>>>()
            {
                Column::Flag(v)
            } else {
                Column::Text(
                    values
                        .iter()
                        .map(|v| match v {
                            None => String::new(),
                            Some(Attribute::Text(s)) => s.clone(),
                            Some(Attribute::Number(x)) => format!("{x}"),
                            Some(Attribute::Flag(b)) => b.to_string(),
                        })
                        .collect(),
                )
            };
            (key.clone(), column)
        })
        .collect()
}

/// A property id as the schema allows them (`[A-Za-z_][A-Za-z0-9_]*`).
fn property_id(key: &str) -> String {
    let mut id: String = key
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if !id.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_') {
        id.insert(0, '_');
    }
    id
}

/// The class definition and the property table of `count` rows.
fn table(
    class: &str,
    count: usize,
    columns: Vec<(String, &str, Column)>,
    push: &mut dyn FnMut(&[u8]) -> u32,
) -> (Value, Value) {
    let mut properties = BTreeMap::new();
    let mut values = BTreeMap::new();
    for (id, description, column) in columns {
        let mut definition = match &column {
            Column::Float(_) => json!({ "type": "SCALAR", "componentType": "FLOAT64" }),
            Column::Count(_) => json!({ "type": "SCALAR", "componentType": "UINT32" }),
            Column::Text(_) => json!({ "type": "STRING", "noData": "" }),
            Column::Flag(_) => json!({ "type": "BOOLEAN" }),
        };
        if !description.is_empty() {
            definition["description"] = description.into();
        }
        if id == "name" {
            definition["semantic"] = "NAME".into();
            definition
                .as_object_mut()
                .expect("an object")
                .remove("noData");
            definition["required"] = true.into();
        }
        let stored = match column {
            Column::Float(v) => {
                json!({ "values": push(&bytes(v.iter().map(|x| x.to_le_bytes()))) })
            }
            Column::Count(v) => {
                json!({ "values": push(&bytes(v.iter().map(|x| x.to_le_bytes()))) })
            }
            Column::Flag(v) => {
                let mut bits = vec![0u8; v.len().div_ceil(8)];
                for (i, _) in v.iter().enumerate().filter(|(_, b)| **b) {
                    bits[i / 8] |= 1 << (i % 8);
                }
                json!({ "values": push(&bits) })
            }
            Column::Text(v) => {
                let mut offsets = Vec::with_capacity(v.len() + 1);
                let mut text = Vec::new();
                offsets.push(0u32);
                for s in &v {
                    text.extend_from_slice(s.as_bytes());
                    offsets.push(text.len() as u32);
                }
                if text.is_empty() {
                    // A buffer view has at least one byte; the offsets keep every string empty.
                    text.push(b' ');
                }
                let values = push(&text);
                let offsets = push(&bytes(offsets.iter().map(|x| x.to_le_bytes())));
                json!({ "values": values, "stringOffsets": offsets })
            }
        };
        properties.insert(id.clone(), definition);
        values.insert(id, stored);
    }
    (
        json!({ "properties": properties }),
        json!({ "name": class, "class": class, "count": count, "properties": values }),
    )
}

fn bytes<const N: usize>(words: impl Iterator<Item = [u8; N]>) -> Vec<u8> {
    words.flatten().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn property_ids_are_what_the_schema_allows() {
        assert_eq!(property_id("provenance.height"), "provenance_height");
        assert_eq!(property_id("3d"), "_3d");
        assert_eq!(property_id("höhe"), "h_he");
    }
}
