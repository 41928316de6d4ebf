//! GOTHIC.json: the detected elements, their self-similar groups and the estimate holding
//! both, as the pipeline returns them (ARCHITECTURE.md contract); re-exported from
//! `facade::gothic`.

use serde::{Deserialize, Serialize};

use super::element::{ArchKind, Theta};

/// One detected element (GOTHIC.json `elements[]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Element {
    pub id: usize,
    pub x0: f64,
    pub y0: f64,
    pub h: f64,
    pub w: f64,
    pub v: f64,
    /// The self-similar group it belongs to.
    pub group: Option<usize>,
    /// The smallest element containing it.
    pub parent: Option<usize>,
    pub kind: ArchKind,
    /// Number of ancestors (0: top level).
    pub depth: usize,
    /// ∮ D ds / ∮ ds (px) at the estimate.
    pub mean_distance: f64,
    /// Share of the contour within 1.5 px of an edge.
    pub support: f64,
}

impl Element {
    pub fn theta(&self) -> Theta {
        Theta {
            x0: self.x0,
            y0: self.y0,
            h: self.h,
            w: self.w,
            v: self.v,
        }
    }
}

/// A self-similar group (GOTHIC.json `groups[]`): members share (h, w, v).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Group {
    pub id: usize,
    pub members: Vec<usize>,
    pub h: f64,
    pub w: f64,
    pub v: f64,
    /// The element enclosing the whole group, when one was found.
    pub enclosing: Option<usize>,
}

/// GOTHIC.json.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GothicEstimate {
    pub width: u32,
    pub height: u32,
    pub elements: Vec<Element>,
    pub groups: Vec<Group>,
}
