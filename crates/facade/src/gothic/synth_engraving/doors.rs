//! Openings at the ground line and in roofs: doors, gates (mostly seen through under a ring
//! of voussoirs, with figures in them) and dormer lights under their gables.

use std::f64::consts::FRAC_PI_2;

use super::basics::{Head, Rng, chance, pick, uniform};
use super::openings::{Ctx, Opening, dressed, ring, shape};
use super::style::{Fill, Style};

/// A door at the ground line.
pub(super) fn door(rng: &mut Rng, style: &Style, ctx: &Ctx) -> Option<Vec<Opening>> {
    let wmax = (ctx.w() * 0.6).min(50.0);
    if wmax < 14.0 {
        return None;
    }
    let head = style.head(rng);
    let w = uniform(rng, 14.0, wmax);
    let total = (w * uniform(rng, 1.5, 2.3)).min(ctx.h() * 0.7);
    let x0 = uniform(rng, ctx.x0, ctx.x1 - w);
    let fill = if chance(rng, 0.12) {
        Fill::Open
    } else if chance(rng, 0.4) {
        Fill::Hatched {
            angle: FRAC_PI_2,
            spacing: uniform(rng, 2.0, 4.0),
        }
    } else {
        style.dark_fill(rng)
    };
    let t = shape(rng, head, x0, ctx.ground, w, total)?;
    let ring = ring(rng, head, w, style.voussoirs);
    Some(vec![Opening {
        ring,
        sill: 0.0,
        ..dressed(rng, style, t, head, fill)
    }])
}

/// A gate at the ground line: mostly seen through under voussoirs, with figures in it.
pub(super) fn gate(rng: &mut Rng, style: &Style, ctx: &Ctx) -> Option<Vec<Opening>> {
    let ring = if chance(rng, 0.8) {
        uniform(rng, 6.0, 16.0)
    } else {
        0.0
    };
    let wmax = (ctx.w() - 2.0 * ring).min(150.0);
    if wmax < 50.0 {
        return None;
    }
    let head = [
        Head::Round,
        Head::Pointed,
        Head::Segmental,
        Head::Rectangular,
    ][pick(rng, &[style.heads[1], style.heads[0], 0.8, 0.2])];
    let w = uniform(rng, 50.0, wmax);
    let total = (w * uniform(rng, 1.1, 1.8)).min(ctx.h() * 0.85);
    let x0 = if chance(rng, 0.7) {
        ctx.cx() - w / 2.0
    } else {
        uniform(rng, ctx.x0 + ring, ctx.x1 - ring - w)
    };
    let open = chance(rng, 0.6);
    let fill = if open {
        Fill::Open
    } else {
        style.dark_fill(rng)
    };
    let t = shape(rng, head, x0, ctx.ground, w, total)?;
    let mut o = Opening {
        ring,
        figures: open && chance(rng, 0.6),
        ..Opening::new(t, head, fill)
    };
    if head == Head::Rectangular {
        o.lintel = uniform(rng, 6.0, 14.0);
    }
    if !open && chance(rng, style.reveal) {
        o.reveal = Some(chance(rng, 0.5));
    }
    Some(vec![o])
}

/// A dormer light low on a roof, under its little gable.
pub(super) fn dormer(rng: &mut Rng, style: &Style, ctx: &Ctx) -> Option<Vec<Opening>> {
    let head = [Head::Rectangular, Head::Pointed, Head::Round][pick(rng, &[1.5, 1.0, 1.0])];
    let w = uniform(rng, 8.0, 18.0);
    let total = w * uniform(rng, 1.2, 1.8);
    let y0 = ctx.ground - uniform(rng, 4.0, (0.3 * ctx.h()).max(5.0));
    let x0 = ctx.cx() - w / 2.0 + uniform(rng, -0.1, 0.1) * ctx.w();
    let t = shape(rng, head, x0, y0, w, total)?;
    Some(vec![Opening {
        gable: w * uniform(rng, 0.5, 0.8) + 3.0,
        ..Opening::new(t, head, style.dark_fill(rng))
    }])
}
