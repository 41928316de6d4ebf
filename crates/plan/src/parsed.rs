//! What a parse gives: the plan's graph, faces, labels and walls ([`ParsedPlan`], re-exported
//! at the crate's root).

use crate::fit::Fit;
use crate::graph::Vertex;
use crate::label::Label;
use crate::measure::{PlanFace, Spur};
use crate::thin::Mask;
use crate::{binarize, bulges, scalebar};

/// A wall of the simplified graph.
#[derive(Debug, Clone)]
pub struct PlanEdge {
    pub from: usize,
    pub to: usize,
    pub label: Label,
    /// Skeleton pixels from `from` to `to`.
    pub points: Vec<(u32, u32)>,
    pub fit: Option<Fit>,
    /// Wall thickness, pixels (twice the mean distance from the skeleton to the wall's edge).
    pub thickness: f64,
}

/// The parsed drawing.
#[derive(Debug, Clone)]
pub struct ParsedPlan {
    pub width: u32,
    pub height: u32,
    pub vertices: Vec<Vertex>,
    pub edges: Vec<PlanEdge>,
    pub faces: Vec<PlanFace>,
    /// Label index of every pixel, row-major.
    pub labels: Vec<u8>,
    /// The cleaned binary drawing (1 = wall).
    pub walls: Mask,
    /// Number of towers found: groups of tower-wall edges (§5.1.6 (4)) joined at a vertex,
    /// plus the bulge towers.
    pub towers: usize,
    /// Towers found on the pixels rather than as tower-wall edges: rings round tower rooms on
    /// the curtain (`ring_towers`; centred in their room), bulges of the castle's outline
    /// ([`bulges::find`]), then compact thick ink standing out of the enceinte
    /// ([`crate::thick_towers::find`]); none inside a larger one's disc.
    pub bulge_towers: Vec<bulges::BulgeTower>,
    /// The wall chains §5.1.6 prunes ([`Spur`]).
    pub spurs: Vec<Spur>,
    pub pre: binarize::PreStats,
    /// What the pipeline could not find (partial results say so here).
    pub warnings: Vec<String>,
    /// The drawn scale bar, when one was found ([`scalebar::find`]).
    pub scale_bar: Option<scalebar::ScaleBar>,
}

impl ParsedPlan {
    /// A `width` × `height` plan of nothing: no graph, faces, walls or towers, every pixel
    /// the surroundings. The one start for plans built by hand (tests, callers' fixtures).
    pub fn empty(width: u32, height: u32) -> ParsedPlan {
        ParsedPlan {
            width,
            height,
            vertices: Vec::new(),
            edges: Vec::new(),
            faces: Vec::new(),
            labels: vec![Label::CastleSurroundings as u8; width as usize * height as usize],
            walls: Mask::new(width, height),
            towers: 0,
            bulge_towers: Vec::new(),
            spurs: Vec::new(),
            pre: binarize::PreStats::default(),
            warnings: Vec::new(),
            scale_bar: None,
        }
    }

    /// The label at pixel (x, y).
    pub fn label_at(&self, x: u32, y: u32) -> Label {
        Label::ALL[self.labels[(y * self.width + x) as usize] as usize]
    }

    /// The label of the pixel nearest the point `p` (plan pixels), `None` off the drawing.
    pub fn label_at_point(&self, p: [f64; 2]) -> Option<Label> {
        let (x, y) = (p[0].round(), p[1].round());
        (x >= 0.0 && y >= 0.0 && x < f64::from(self.width) && y < f64::from(self.height))
            .then(|| self.label_at(x as u32, y as u32))
    }

    /// The faces on each side of every edge (distinct, at most two), by edge index.
    pub fn faces_of_edges(&self) -> Vec<Vec<usize>> {
        let mut out = vec![Vec::new(); self.edges.len()];
        for (fi, f) in self.faces.iter().enumerate() {
            for &e in &f.edges {
                if let Some(o) = out.get_mut(e)
                    && !o.contains(&fi)
                {
                    o.push(fi);
                }
            }
        }
        out
    }
}
