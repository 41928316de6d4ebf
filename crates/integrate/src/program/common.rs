//! What the program's writers share: the generation settings and how numbers, lists and
//! storeys are written (§7.2.2).

use crate::estimate::Structure;

/// Generation settings.
#[derive(Debug, Clone)]
pub struct Options {
    /// Storey height for structures without a façade, metres.
    pub storey_metres: f64,
    /// Texture files from which walls without a photo pick one per shape (figure 7.6); empty
    /// for plain colours.
    pub wall_textures: Vec<String>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            storey_metres: 4.0,
            wall_textures: Vec::new(),
        }
    }
}

/// `{"a.png", "b.png"}`.
pub(super) fn string_list(v: &[String]) -> String {
    let quoted: Vec<String> = v.iter().map(|t| format!("{t:?}")).collect();
    format!("{{{}}}", quoted.join(", "))
}

/// A number as the program writes it.
pub(super) fn n(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

pub(super) fn list(v: &[f64]) -> String {
    v.iter().map(|x| n(*x)).collect::<Vec<_>>().join(", ")
}

/// Storeys of a structure: its first rectangular façade's floor count, else height / storey
/// height.
pub(super) fn storeys(s: &Structure, o: &Options, u: f64) -> u32 {
    s.facades
        .iter()
        .find(|f| !f.floors.is_empty())
        .map(|f| f.floors.len() as u32)
        .unwrap_or_else(|| (s.height / (o.storey_metres * u)).round() as u32)
        .clamp(1, 30)
}

/// What a structure written inline (not imported from the library) adds to the program: its
/// parameters, its mass models in the axiom (instantiation, successor), and its rules — or
/// what a kind of them shares once.
#[derive(Default)]
pub(super) struct Part {
    pub params: String,
    pub axiom: Vec<(String, String)>,
    pub rules: String,
}
