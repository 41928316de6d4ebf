//! An opening as the sheet draws it (Θ, head, fill, dressings), where one may go, and the
//! shapes the features build openings from.

use super::basics::{Head, Rect, Rng, chance, uniform};
use super::style::{Fill, Style};
use crate::gothic::element::Theta;

/// What fills an enclosing arch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Inside {
    /// The wall's coursing and shading run on inside it.
    Wall,
    /// A hatched tympanum.
    Tympanum { angle: f64, spacing: f64 },
    /// Bare paper.
    Plain,
}

/// An opening (or an enclosing arch) and how it is drawn.
#[derive(Debug, Clone, Copy)]
pub(super) struct Opening {
    pub theta: Theta,
    pub head: Head,
    pub enclosing: bool,
    /// Index of the enclosing arch (within its group while proposed, then in the sheet).
    pub parent: Option<usize>,
    pub fill: Fill,
    pub inside: Inside,
    /// Owner id of the wall or roof it is cut in.
    pub host: u16,
    /// Depth of the ring of voussoirs round an arched head (0: none).
    pub ring: f64,
    /// Height of a lintel over a flat head, depth of a sill ledge, height of a dormer's
    /// gable (0: none).
    pub lintel: f64,
    pub sill: f64,
    pub gable: f64,
    /// Offset of a frame (a chamfer or hood mould) drawn round the jambs and head (0: none).
    pub frame: f64,
    /// No outline: the void is bounded by its fill alone.
    pub bare: bool,
    /// A lighter reveal along the left (true) or right jamb.
    pub reveal: Option<bool>,
    /// Figures stand in it (an open gate).
    pub figures: bool,
}

impl Opening {
    pub fn new(theta: Theta, head: Head, fill: Fill) -> Opening {
        Opening {
            theta,
            head,
            enclosing: false,
            parent: None,
            fill,
            inside: Inside::Wall,
            host: 0,
            ring: 0.0,
            lintel: 0.0,
            sill: 0.0,
            gable: 0.0,
            frame: 0.0,
            bare: false,
            reveal: None,
            figures: false,
        }
    }

    /// The box of the opening and its dressings, grown by `pad` (not below a sill on the
    /// ground line).
    pub fn reach(&self, pad: f64, ground: f64) -> Rect {
        let [x0, y0, x1, y1] = self.theta.bbox();
        let side = self
            .ring
            .max(self.frame)
            .max(if self.sill > 0.0 { 3.0 } else { 0.0 })
            + pad;
        let up = self.ring.max(self.lintel).max(self.frame) + self.gable + pad;
        let at_ground = (y1 - ground).abs() < 0.5;
        Rect {
            x0: x0 - side,
            y0: y0 - up,
            x1: x1 + side,
            y1: if at_ground { y1 } else { y1 + self.sill + pad },
        }
    }
}

/// Where a feature may go: the visible stretch of one wall (or roof) between its margins.
#[derive(Debug, Clone, Copy)]
pub(super) struct Ctx {
    pub host: u16,
    pub layer: usize,
    pub x0: f64,
    pub x1: f64,
    pub top: f64,
    pub ground: f64,
}

impl Ctx {
    pub fn w(&self) -> f64 {
        self.x1 - self.x0
    }
    pub fn h(&self) -> f64 {
        self.ground - self.top
    }
    pub fn cx(&self) -> f64 {
        0.5 * (self.x0 + self.x1)
    }
}

/// Θ of an opening with the given head, width and total height (jambs + rise).
pub(super) fn shape(
    rng: &mut Rng,
    head: Head,
    x0: f64,
    y0: f64,
    w: f64,
    total: f64,
) -> Option<Theta> {
    let v = match head {
        Head::Rectangular => 0.0,
        Head::Segmental => w * uniform(rng, 0.12, 0.35),
        Head::Round => w / 2.0,
        Head::Pointed => w * uniform(rng, 0.58, 0.95),
    };
    let h = total - v;
    (w >= 4.0 && h >= 2.0 && x0.is_finite() && y0.is_finite()).then_some(Theta { x0, y0, h, w, v })
}

/// Whether `inner`, widened by `gap` at the sides and head (not below its sill), lies inside
/// `outer`.
pub(super) fn within(outer: &Theta, inner: &Theta, gap: f64) -> bool {
    let g = Theta {
        x0: inner.x0 - gap,
        w: inner.w + 2.0 * gap,
        v: inner.v + gap,
        ..*inner
    };
    g.contour_at(1.0).iter().all(|s| outer.contains(s.x, s.y))
}

pub(super) fn ring(rng: &mut Rng, head: Head, w: f64, p: f64) -> f64 {
    if head != Head::Rectangular && chance(rng, p) {
        uniform(rng, 3.0, (0.3 * w).clamp(3.5, 16.0))
    } else {
        0.0
    }
}

/// A dark opening with the sheet's dressings: lintel over a flat head, sill, reveal.
pub(super) fn dressed(rng: &mut Rng, style: &Style, t: Theta, head: Head, fill: Fill) -> Opening {
    let mut o = Opening::new(t, head, fill);
    if head == Head::Rectangular && chance(rng, 0.5) {
        o.lintel = uniform(rng, 3.0, (0.3 * t.w).clamp(3.5, 10.0));
    }
    if chance(rng, 0.4) {
        o.sill = uniform(rng, 2.0, 4.0);
    }
    if fill != Fill::Open && t.w >= 14.0 && chance(rng, style.reveal) {
        o.reveal = Some(chance(rng, 0.5));
    }
    if chance(rng, style.frames) {
        o.frame = uniform(rng, 2.0, 4.5);
    }
    o.bare = fill != Fill::Open && chance(rng, style.bare);
    o
}

/// `n` equal openings `gap` apart, centred on the context or anywhere in it.
pub(super) fn spread(rng: &mut Rng, ctx: &Ctx, n: usize, w: f64, gap: f64) -> Vec<f64> {
    let span = n as f64 * w + (n as f64 - 1.0) * gap;
    let x = if chance(rng, 0.6) {
        ctx.cx() - span / 2.0
    } else {
        uniform(rng, ctx.x0, ctx.x1 - span)
    };
    (0..n).map(|i| x + i as f64 * (w + gap)).collect()
}
