//! Synthetic castle plan drawings in randomised draughting styles, with exact wall truth, for
//! training and measuring the learned wall-ink classifier (issue 26).
//!
//! Each seed gives a random castle (an irregular curtain with round and square towers, inner
//! buildings and partitions, sometimes an inner ward or a keep, door gaps), its walls drawn in
//! one or two of the [`WallStyle`]s, over clutter that is never wall (letters, words, vault
//! ribs, hachures on a ring, contours, dashed paths, dimension lines, a scale bar, a north
//! arrow, a title, a frame, grid lines; when asked, hachured scarps and moats against the
//! walls and contour-like hachure bands), then degraded (paper tone and texture, grey ink, stains, blur,
//! 16-level quantisation, a JPEG round trip). The truth mask is the whole wall area, including
//! the paper between the outlines or hatch lines of a wall; degradations never move geometry.
//! Seeded: same seed, same drawing.
//!
//! Files: `style` (what a drawing holds and the choices a caller forces), `geometry` (points,
//! the random source, pixel masks), `layout` (the castle), `sheet` (the clean drawing and its
//! pens), `walls` (the wall styles), `clutter`, `terrain`, `moat` and `furnishing` (what is never wall),
//! `degrade`.

mod clutter;
mod degrade;
mod furnishing;
mod geometry;
mod layout;
mod moat;
mod sheet;
mod style;
mod terrain;
#[cfg(test)]
mod tests;
mod walls;

use rand::{RngExt, SeedableRng};

use clutter::draw_clutter;
use degrade::degrade;
use geometry::{Rng, u};
use layout::layout;
use sheet::Sheet;
pub use style::{Clutter, Style, StyleChoice, StyledPlan, WALL_STYLES, WallStyle};
use walls::render_walls;

/// A random drawing of `width` × `height` pixels.
pub fn generate(seed: u64, width: u32, height: u32) -> StyledPlan {
    generate_with(seed, width, height, &StyleChoice::default())
}

/// A random drawing with some choices forced.
pub fn generate_with(seed: u64, width: u32, height: u32, choice: &StyleChoice) -> StyledPlan {
    let (sheet, style) = draw(seed, width, height, choice);
    StyledPlan {
        image: sheet.img,
        walls: sheet.truth.to_gray(),
        scarps: sheet.scarps.to_gray(),
        style,
    }
}

/// The drawing before it becomes a [`StyledPlan`], with the clutter mask (for tests).
fn draw(seed: u64, width: u32, height: u32, choice: &StyleChoice) -> (Sheet, Style) {
    let mut rng = Rng::seed_from_u64(seed);
    let s = width.min(height) as f64;
    let (lo, hi) = (2f64.max(s * 0.005), 25f64.min(s * 0.04).max(2.5));
    let t = choice
        .thickness
        .unwrap_or_else(|| (u(&mut rng, lo.ln(), hi.ln())).exp());
    let walls = choice.walls.unwrap_or_else(|| pick_style(&mut rng));
    let second = rng
        .random_bool(0.25)
        .then(|| pick_style(&mut rng))
        .filter(|&w| w != walls && choice.walls.is_none());
    let lay = layout(&mut rng, width, height, t);
    let mut sheet = Sheet::new(width, height, &lay);
    match second {
        None => render_walls(&mut sheet.img, &sheet.truth, walls, &mut rng),
        Some(other) => {
            render_walls(&mut sheet.img, &lay.main, walls, &mut rng);
            render_walls(&mut sheet.img, &lay.inner.minus(&lay.main), other, &mut rng);
        }
    }

    let clutter = draw_clutter(&mut sheet, &lay, &mut rng, choice);
    if !choice.clean {
        degrade(&mut sheet.img, &mut rng);
    }
    let style = Style {
        walls,
        second,
        thickness: t,
        clutter,
        degraded: !choice.clean,
    };
    (sheet, style)
}

fn pick_style(rng: &mut Rng) -> WallStyle {
    WALL_STYLES[rng.random_range(0..WALL_STYLES.len())]
}
