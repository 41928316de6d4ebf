//! What every stage shares: the random stream and its helpers, the owner ids of the pen's
//! owner map, boxes, and the heads of openings.

use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// The random stream every stage draws from.
pub(super) type Rng = ChaCha8Rng;

/// The head of an opening (§4.1's families of Θ).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Head {
    Pointed,
    Round,
    Segmental,
    Rectangular,
}

/// An axis-aligned box in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Rect {
    pub x0: f64,
    pub y0: f64,
    pub x1: f64,
    pub y1: f64,
}

impl Rect {
    pub fn w(&self) -> f64 {
        self.x1 - self.x0
    }
    pub fn h(&self) -> f64 {
        self.y1 - self.y0
    }
    pub fn arr(&self) -> [f64; 4] {
        [self.x0, self.y0, self.x1, self.y1]
    }
    pub fn overlaps(&self, o: &Rect) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }
    pub fn union(&self, o: &Rect) -> Rect {
        Rect {
            x0: self.x0.min(o.x0),
            y0: self.y0.min(o.y0),
            x1: self.x1.max(o.x1),
            y1: self.y1.max(o.y1),
        }
    }
}

// Owner ids of the pen's owner map: 0 is paper.
pub(super) const MASS_BASE: u16 = 1;
pub(super) const ROOF_BASE: u16 = 64;
pub(super) const BUTTRESS_BASE: u16 = 128;
pub(super) const OPENING_BASE: u16 = 1024;
/// Most masses, roofs and buttresses a sheet may have (their id ranges).
pub(super) const MAX_MASSES: usize = 60;
pub(super) const MAX_BUTTRESSES: usize = 800;

pub(super) fn mass_id(k: usize) -> u16 {
    MASS_BASE + k as u16
}
pub(super) fn roof_id(k: usize) -> u16 {
    ROOF_BASE + k as u16
}
pub(super) fn buttress_id(b: usize) -> u16 {
    BUTTRESS_BASE + b as u16
}
pub(super) fn opening_id(j: usize) -> u16 {
    OPENING_BASE + j as u16
}

/// Uniform in [lo, hi), or `lo` when the range is empty.
pub(super) fn uniform(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
    if hi > lo {
        rng.random_range(lo..hi)
    } else {
        lo
    }
}

/// Uniform integer in [lo, hi], or `lo` when the range is empty.
pub(super) fn int(rng: &mut Rng, lo: usize, hi: usize) -> usize {
    if hi > lo {
        rng.random_range(lo..=hi)
    } else {
        lo
    }
}

/// True with probability `p` (clamped to [0, 1]).
pub(super) fn chance(rng: &mut Rng, p: f64) -> bool {
    rng.random_bool(p.clamp(0.0, 1.0))
}

/// Index drawn with the given weights (the first when they are all zero).
pub(super) fn pick(rng: &mut Rng, weights: &[f64]) -> usize {
    let total: f64 = weights.iter().sum();
    let mut r = uniform(rng, 0.0, total);
    for (i, w) in weights.iter().enumerate() {
        if r < *w {
            return i;
        }
        r -= w;
    }
    0
}
