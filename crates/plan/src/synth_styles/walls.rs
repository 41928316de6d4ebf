//! The walls drawn in one of the [`WallStyle`]s: solid, outlined, hatched, cross-hatched or
//! grey-washed.

use std::f64::consts::PI;

use image::GrayImage;
use imageproc::distance_transform::Norm;
use imageproc::morphology::erode;
use rand::RngExt;

use super::geometry::{Mask, Rng, u};
use super::style::WallStyle;

/// Interior lines of a wall at angle `a` with `spacing`.
pub(super) fn hatch(x: f64, y: f64, a: f64, spacing: f64) -> bool {
    (x * a.cos() + y * a.sin()).rem_euclid(spacing) < 1.0
}

/// Draws the walls of mask `m` in `style` onto the clean image.
pub(super) fn render_walls(img: &mut GrayImage, m: &Mask, style: WallStyle, rng: &mut Rng) {
    let lw: u8 = rng.random_range(1..=2);
    let eroded = erode(&m.to_gray(), Norm::LInf, lw);
    let (a, sp) = (u(rng, 0.0, PI), u(rng, 2.0, 6.0));
    let (a2, sp2) = (a + u(rng, 0.35, 0.65) * PI, u(rng, 2.0, 6.0));
    let grey = rng.random_range(90..=180u8);
    let outline = style != WallStyle::GreyWash || rng.random_bool(0.6);
    let w = m.w;
    for (i, px) in img.as_mut().iter_mut().enumerate() {
        if !m.m[i] {
            continue;
        }
        let edge = eroded.as_raw()[i] == 0;
        let (x, y) = ((i % w) as f64, (i / w) as f64);
        let v = match style {
            WallStyle::Solid => 0,
            _ if edge && outline => 0,
            WallStyle::Outlined => 255,
            WallStyle::Hatched => (!hatch(x, y, a, sp)) as u8 * 255,
            WallStyle::CrossHatched => (!hatch(x, y, a, sp) && !hatch(x, y, a2, sp2)) as u8 * 255,
            WallStyle::GreyWash => grey,
        };
        *px = (*px).min(v);
    }
}
