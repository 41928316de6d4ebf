//! `STATS.json` of `castellan vsg run` (ARCHITECTURE.md contract): terminal counts by kind and
//! symbol, exact (analytic) volumes of the terminal primitives, and the triangle count.

use std::collections::{BTreeMap, HashMap};

use serde::Serialize;

use crate::shape::Tessellation;
use crate::tree::{Model, NodeState, Solid};

#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Volumes {
    /// Every terminal, void ones included: a split conserves it.
    pub total: f64,
    pub by_symbol: BTreeMap<String, f64>,
}

/// Masses (kg) of the terminals whose appearance gives a density (kg/m³), void ones included.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Masses {
    pub total: f64,
    pub by_symbol: BTreeMap<String, f64>,
}

#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Stats {
    pub terminals: usize,
    pub visible_terminals: usize,
    pub void_terminals: usize,
    pub nonterminals: usize,
    /// Terminals per symbol.
    pub by_symbol: BTreeMap<String, usize>,
    pub volume: Volumes,
    /// Volume of the visible terminals alone.
    pub visible_volume: f64,
    /// Triangles of the visible terminals' meshes at the given tessellation.
    pub triangles: usize,
    /// Present when some terminal's appearance gives a density.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass: Option<Masses>,
}

impl Stats {
    pub fn of(model: &Model, tessellation: &Tessellation) -> Stats {
        let mut s = Stats::default();
        let mut triangles_of: HashMap<(crate::shape::ShapeType, Vec<u64>), usize> = HashMap::new();
        for (i, n) in model.nodes.iter().enumerate() {
            match n.state {
                NodeState::NonTerminal => {
                    s.nonterminals += 1;
                    continue;
                }
                NodeState::Terminal => s.visible_terminals += 1,
                NodeState::VoidTerminal => s.void_terminals += 1,
            }
            s.terminals += 1;
            let symbol = model.symbol(n);
            *s.by_symbol.entry(symbol.to_string()).or_default() += 1;
            let Some(solid) = model.solid(i as u32) else {
                continue;
            };
            let v = solid.volume();
            s.volume.total += v;
            *s.volume.by_symbol.entry(symbol.to_string()).or_default() += v;
            if let Some(density) = model.appearance(n).density {
                let m = s.mass.get_or_insert_with(Masses::default);
                m.total += v * density;
                *m.by_symbol.entry(symbol.to_string()).or_default() += v * density;
            }
            if n.state == NodeState::Terminal {
                s.visible_volume += v;
                s.triangles += match solid {
                    Solid::Primitive(shape) => {
                        let key = (
                            shape.kind,
                            shape.params().iter().map(|p| p.to_bits()).collect(),
                        );
                        *triangles_of
                            .entry(key)
                            .or_insert_with(|| shape.mesh(tessellation).triangles.len())
                    }
                    Solid::Unique(_, u) => u.mesh.triangles.len(),
                };
            }
        }
        s
    }
}
