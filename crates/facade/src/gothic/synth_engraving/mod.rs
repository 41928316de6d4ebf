//! Synthetic architectural engravings in randomised styles, with the exact truth of their
//! openings (issue 23).
//!
//! Why: the learned candidate stage of the Gothic pipeline (ch. 4, issue 23) needs far more
//! annotated openings than the 27 images of the development set hold. This module draws
//! elevation plates in the vocabulary of the 19th-century line engravings the stage is meant
//! for (Viollet-le-Duc's *Dictionnaire*, the plates of Loftie's *Tower of London*): white
//! paper; towers, curtains and gate blocks ruled with ashlar coursing and shaded with dense
//! hatching; crenellations, corbelled parapets, buttresses, string courses, conical, pyramidal
//! and hipped roofs with slate hatching, domes; openings whose inside is black, hatched,
//! cross-hatched or barred, or white and seen through under a ring of voussoirs; heads round,
//! pointed, segmental or flat; arcades, rows, stacked storeys, lancets under wall-coloured
//! enclosing arches, doors and gates at the ground line; figures, lettering, a scale bar.
//! The styles are imitated from those public-domain plates; nothing is copied from them.
//!
//! Every sheet comes from one seed (ChaCha8: the same seed gives the same bytes), in stages
//! of one file each (`basics` holds what they share):
//! - `style`: the sheet's pen, wall textures, opening fills and degradation, drawn at random;
//! - `layout`: the wall masses (which stand in front of which) and their tops and roofs;
//! - `openings`, `features`, `doors`, `place`: openings as Θ of §4.1, groups of them proposed
//!   (rows, arcades, lancets under their arch, doors, gates, dormers) and placed on the masses
//!   without overlapping;
//! - `pen`: the ink layer, its owner map and anti-aliased strokes clipped to owners;
//! - `ashlar`, `walls`, `roofs`: coursing and shading; outlines, parapets, buttresses; roofs;
//! - `fills`: the inside of every opening, its outline, voussoirs, lintel and sill;
//! - `clutter`: ground line, figures, lettering, scale bar, trees, frame, ruled sky;
//! - `degrade`: paper tone and mottling, blur, noise, 16-level quantisation, JPEG.
//!
//! Truth: pixel (x, y) covers [x, x + 1) × [y, y + 1) and belongs to an opening when its centre
//! (x + 0.5, y + 0.5) is inside the opening's Θ ([`Theta::contains`]). The fills are drawn
//! through the same owner map, so the mask, the boxes ([`Theta::bbox`]) and the ink all come
//! from one geometry.
//!
//! ```
//! use facade::gothic::synth_engraving::generate;
//!
//! let sheet = generate(7, 320, 320);
//! assert_eq!(sheet.image.dimensions(), (320, 320));
//! assert_eq!(sheet.openings.dimensions(), (320, 320));
//! ```

mod ashlar;
mod basics;
mod clutter;
mod degrade;
mod doors;
mod features;
mod fills;
mod layout;
mod openings;
mod pen;
mod place;
mod roofs;
mod style;
mod walls;

#[cfg(test)]
mod tests;

use image::{GrayImage, Luma};
use rand::SeedableRng;

use super::element::Theta;
use basics::Rng;

pub use basics::Head;

/// One synthetic plate and its answers.
#[derive(Debug, Clone)]
pub struct EngravingSheet {
    /// The drawing.
    pub image: GrayImage,
    /// 255 inside every opening (the dark or seen-through void up to its intrados, jambs and
    /// sill), 0 elsewhere; enclosing arches are not marked (their inside is wall).
    pub openings: GrayImage,
    pub elements: Vec<SheetElement>,
}

/// One opening or enclosing arch of a sheet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SheetElement {
    /// x0, y0, x1, y1 in pixels, tight round the opening (intrados, jambs, sill or ground).
    pub bbox: [f64; 4],
    pub head: Head,
    /// An arch enclosing a group of openings; its inside is wall, not opening.
    pub enclosing: bool,
    /// Index of the enclosing element, if any.
    pub parent: Option<usize>,
}

/// Draws the sheet of `seed` at `width` × `height` pixels.
pub fn generate(seed: u64, width: u32, height: u32) -> EngravingSheet {
    let (w, h) = (width.max(1), height.max(1));
    let mut rng = Rng::seed_from_u64(seed);
    let style = style::Style::random(&mut rng);
    let scene = layout::compose(&mut rng, &style, w as usize, h as usize);
    let mut canvas = pen::Canvas::new(w as usize, h as usize);
    layout::paint(&scene, &mut canvas);
    let placed = place::place(&mut rng, &style, &scene, &mut canvas);
    walls::draw(&mut rng, &style, &scene, &placed, &mut canvas);
    fills::draw(&mut rng, &style, &placed, &mut canvas);
    clutter::draw(&mut rng, &style, &scene, &placed, &mut canvas);
    let image = degrade::finish(&mut rng, &style, &canvas);

    let mut mask = GrayImage::new(w, h);
    for o in placed.iter().filter(|o| !o.enclosing) {
        for (x, y) in pixels_of(&o.theta, w, h) {
            mask.put_pixel(x, y, Luma([255]));
        }
    }
    let elements = placed
        .iter()
        .map(|o| SheetElement {
            bbox: o.theta.bbox(),
            head: o.head,
            enclosing: o.enclosing,
            parent: o.parent,
        })
        .collect();
    EngravingSheet {
        image,
        openings: mask,
        elements,
    }
}

/// The pixels of a `w` × `h` image whose centres lie inside `t` (the truth of one opening).
fn pixels_of(t: &Theta, w: u32, h: u32) -> impl Iterator<Item = (u32, u32)> + '_ {
    let [x0, y0, x1, y1] = t.bbox();
    let lo = |a: f64| (a - 0.5).floor().max(0.0) as i64;
    let hi = |b: f64, n: u32| ((b - 0.5).ceil() as i64).min(n as i64 - 1);
    let (xa, xb, ya, yb) = (lo(x0), hi(x1, w), lo(y0), hi(y1, h));
    (ya..=yb)
        .flat_map(move |y| (xa..=xb).map(move |x| (x, y)))
        .filter(move |&(x, y)| t.contains(x as f64 + 0.5, y as f64 + 0.5))
        .map(|(x, y)| (x as u32, y as u32))
}
