//! The sheet's style, drawn once per seed: the pen, the heads and fills the openings favour,
//! the wall textures the masses draw from, and the degradation of the print.

use super::basics::{Head, Rng, chance, int, pick, uniform};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// The engraver's pen.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pen {
    /// Grey level of full ink (0–90).
    pub ink: f32,
    /// Width of outlines (px, 1–3).
    pub outline: f64,
    /// Width of coursing and hatching lines (px).
    pub fine: f64,
    /// Amplitude of the hand's tremor along long lines (px).
    pub wobble: f64,
    /// Exponent on ink coverage (< 1 darkens the anti-aliased edges: a crisper, heavier line).
    pub gamma: f32,
}

/// How the paper and the print are degraded.
#[derive(Debug, Clone, Copy)]
pub(super) struct Degrade {
    /// Paper tone (215–255).
    pub paper: f32,
    /// Amplitude of the paper's slow mottling (grey levels) and its cell size (px).
    pub mottle: f32,
    pub mottle_cell: f64,
    /// Gaussian blur σ (px; 0 for none).
    pub blur: f64,
    /// Gaussian noise σ (grey levels).
    pub noise: f32,
    /// Quantise to 16 grey levels (the 4-bit palettes of the scanned plates).
    pub quantise: bool,
    /// JPEG round trip at this quality.
    pub jpeg: Option<u8>,
}

/// Hatched shading of a wall mass.
#[derive(Debug, Clone, Copy)]
pub(super) enum Shade {
    None,
    /// A band on one side, densest at the edge.
    Side {
        right: bool,
        frac: f64,
        angle: f64,
        spacing: f64,
    },
    /// The whole mass in shadow.
    Whole {
        angle: f64,
        spacing: f64,
    },
    /// A round tower: vertical lines crowding towards both edges, most on the shadow side.
    Cylinder {
        right: bool,
        dense: f64,
    },
}

/// The ashlar texture of one wall mass.
#[derive(Debug, Clone, Copy)]
pub(super) struct Wall {
    /// Course height (px, 4–12) and its relative jitter.
    pub course: f64,
    pub jitter: f64,
    /// Mean stone length (px) and the chance a joint is drawn.
    pub stone: f64,
    pub joints: f64,
    /// Chance a stretch of coursing line is drawn (light walls leave many out).
    pub lines: f64,
    /// Line width factor of the coursing.
    pub weight: f64,
    /// Chance a stone carries a few tooling marks.
    pub stipple: f64,
    pub shade: Shade,
}

/// The inside of an opening.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Fill {
    Solid,
    Hatched {
        angle: f64,
        spacing: f64,
    },
    Cross {
        angle: f64,
        spacing: f64,
    },
    /// Black behind a grille of light bars.
    Barred {
        bars: (usize, usize),
    },
    /// White: seen through (a gate passage), with the soffit and a reveal hatched.
    Open,
}

impl Fill {
    /// Name of the fill's family (tests).
    #[cfg(test)]
    pub fn family(&self) -> &'static str {
        match self {
            Fill::Solid => "solid",
            Fill::Hatched { .. } => "hatched",
            Fill::Cross { .. } => "cross",
            Fill::Barred { .. } => "barred",
            Fill::Open => "open",
        }
    }
}

/// Everything about a sheet that is not its layout.
#[derive(Debug, Clone)]
pub(super) struct Style {
    pub pen: Pen,
    pub degrade: Degrade,
    /// Weights of Pointed, Round, Segmental, Rectangular heads (a Gothic or a Romanesque sheet).
    pub heads: [f64; 4],
    /// The sheet's usual window fill and how often it is used.
    pub fill: Fill,
    pub fill_usual: f64,
    /// Chance an arched opening gets a ring of voussoirs.
    pub voussoirs: f64,
    /// Chance a dark opening shows a lighter reveal on one side.
    pub reveal: f64,
    /// Chance a window has a frame round it, and that a dark one has no outline.
    pub frames: f64,
    pub bare: f64,
    /// A wall style the masses vary about.
    pub wall: Wall,
}

impl Style {
    pub fn random(rng: &mut Rng) -> Style {
        let pen = Pen {
            ink: uniform(rng, 0.0, 90.0) as f32,
            outline: uniform(rng, 1.0, 3.0),
            fine: uniform(rng, 0.7, 1.5),
            wobble: uniform(rng, 0.0, 0.6),
            gamma: uniform(rng, 0.45, 1.0) as f32,
        };
        let degrade = Degrade {
            paper: uniform(rng, 215.0, 255.0) as f32,
            mottle: if chance(rng, 0.5) {
                uniform(rng, 0.0, 6.0) as f32
            } else {
                0.0
            },
            mottle_cell: uniform(rng, 24.0, 120.0),
            blur: if chance(rng, 0.7) {
                uniform(rng, 0.2, 0.9)
            } else {
                0.0
            },
            noise: if chance(rng, 0.6) {
                uniform(rng, 0.0, 7.0) as f32
            } else {
                0.0
            },
            quantise: chance(rng, 0.4),
            jpeg: chance(rng, 0.35).then(|| uniform(rng, 35.0, 92.0) as u8),
        };
        let heads = match pick(rng, &[0.45, 0.35, 0.2]) {
            0 => [6.0, 2.0, 1.0, 1.5],
            1 => [1.5, 6.0, 1.0, 1.5],
            _ => [2.0, 2.0, 2.0, 2.0],
        };
        let fill = random_fill(rng);
        let wall = Wall::random(rng);
        Style {
            pen,
            degrade,
            heads,
            fill,
            fill_usual: uniform(rng, 0.4, 0.9),
            voussoirs: uniform(rng, 0.2, 0.8),
            reveal: uniform(rng, 0.0, 0.5),
            frames: uniform(rng, 0.0, 0.5),
            bare: uniform(rng, 0.0, 0.3),
            wall,
        }
    }

    /// A head drawn with the sheet's weights.
    pub fn head(&self, rng: &mut Rng) -> Head {
        [
            Head::Pointed,
            Head::Round,
            Head::Segmental,
            Head::Rectangular,
        ][pick(rng, &self.heads)]
    }

    /// An arched head (no rectangles) with the sheet's weights.
    pub fn arched(&self, rng: &mut Rng) -> Head {
        let [p, r, s, _] = self.heads;
        [Head::Pointed, Head::Round, Head::Segmental][pick(rng, &[p, r, s])]
    }

    /// A dark fill for a window: the sheet's usual one, or another.
    pub fn dark_fill(&self, rng: &mut Rng) -> Fill {
        if chance(rng, self.fill_usual) && self.fill != Fill::Open {
            return self.fill;
        }
        loop {
            let f = random_fill(rng);
            if f != Fill::Open {
                return f;
            }
        }
    }

    /// The wall of one mass: the sheet's wall, varied.
    pub fn mass_wall(&self, rng: &mut Rng, round: bool) -> Wall {
        let mut w = if chance(rng, 0.6) {
            self.wall
        } else {
            Wall::random(rng)
        };
        if round && chance(rng, 0.75) {
            w.shade = Shade::Cylinder {
                right: chance(rng, 0.7),
                dense: uniform(rng, 1.8, 3.0),
            };
        } else if !round && matches!(w.shade, Shade::Cylinder { .. }) {
            w.shade = Shade::None;
        }
        w
    }
}

impl Wall {
    fn random(rng: &mut Rng) -> Wall {
        let shade = match pick(rng, &[1.0, 2.0, 0.6]) {
            0 => Shade::None,
            1 => Shade::Side {
                right: chance(rng, 0.65),
                frac: uniform(rng, 0.1, 0.45),
                angle: hatch_angle(rng, 0.6),
                spacing: uniform(rng, 1.8, 3.5),
            },
            _ => Shade::Whole {
                angle: hatch_angle(rng, 0.3),
                spacing: uniform(rng, 2.2, 4.5),
            },
        };
        Wall {
            course: uniform(rng, 4.0, 12.0),
            jitter: uniform(rng, 0.0, 0.2),
            stone: uniform(rng, 10.0, 40.0),
            joints: uniform(rng, 0.4, 0.95),
            lines: uniform(rng, 0.55, 1.0),
            weight: uniform(rng, 0.8, 1.4),
            stipple: if chance(rng, 0.4) {
                uniform(rng, 0.1, 0.5)
            } else {
                0.0
            },
            shade,
        }
    }
}

/// Vertical with probability `vertical`, else a diagonal of either hand.
fn hatch_angle(rng: &mut Rng, vertical: f64) -> f64 {
    if chance(rng, vertical) {
        FRAC_PI_2
    } else if chance(rng, 0.5) {
        FRAC_PI_4 + uniform(rng, -0.25, 0.25)
    } else {
        PI - FRAC_PI_4 + uniform(rng, -0.25, 0.25)
    }
}

/// Any fill: horizontal hatching most often, as in the Dictionnaire's window voids.
pub(super) fn random_fill(rng: &mut Rng) -> Fill {
    match pick(rng, &[1.5, 3.0, 1.2, 0.7, 0.4]) {
        0 => Fill::Solid,
        1 => {
            let angle = match pick(rng, &[3.0, 2.0, 1.5]) {
                0 => 0.0,
                1 => FRAC_PI_2,
                _ => uniform(rng, 0.2, PI - 0.2),
            };
            Fill::Hatched {
                angle,
                spacing: uniform(rng, 2.0, 5.0),
            }
        }
        2 => Fill::Cross {
            angle: if chance(rng, 0.5) {
                0.0
            } else {
                uniform(rng, 0.0, PI)
            },
            spacing: uniform(rng, 2.5, 5.0),
        },
        3 => Fill::Barred {
            bars: (int(rng, 1, 3), int(rng, 0, 3)),
        },
        _ => Fill::Open,
    }
}
