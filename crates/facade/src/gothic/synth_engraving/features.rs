//! The groups of openings a wall is given: rows of windows, machicolation-like arcades,
//! lancets under an enclosing arch, relieving arches over small windows, loops, small square
//! lights, single large windows (doors, gates and dormers are in `doors`). Each proposal is a
//! random size and position within its context; the placer decides whether it fits.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

use super::basics::{Head, Rng, chance, int, pick, uniform};
use super::openings::{Ctx, Inside, Opening, dressed, ring, shape, spread, within};
use super::style::{Fill, Style, random_fill};
use crate::gothic::element::Theta;

/// A row of 1 to `most` windows of width in `widths`.
pub(super) fn row(
    rng: &mut Rng,
    style: &Style,
    ctx: &Ctx,
    widths: (f64, f64),
    most: usize,
) -> Option<Vec<Opening>> {
    let head = style.head(rng);
    let wmax = (ctx.w() * 0.45).min(widths.1);
    if wmax < widths.0 {
        return None;
    }
    let w = uniform(rng, widths.0, wmax);
    let total = w * if head == Head::Rectangular {
        uniform(rng, 1.0, 2.2)
    } else {
        uniform(rng, 1.3, 2.6)
    };
    let ring = ring(rng, head, w, 0.6 * style.voussoirs);
    let gap = (w * uniform(rng, 0.3, 2.5)).max(2.0 * ring + 4.0);
    let fit = ((ctx.w() + gap) / (w + gap)).floor() as usize;
    if fit == 0 {
        return None;
    }
    let n = int(rng, 1, fit.min(most));
    let y0 = uniform(rng, ctx.top + total + ring, ctx.ground - 8.0);
    let fill = if chance(rng, 0.08) {
        Fill::Open
    } else {
        style.dark_fill(rng)
    };
    let t = shape(rng, head, 0.0, y0, w, total)?;
    let proto = dressed(rng, style, t, head, fill);
    Some(
        spread(rng, ctx, n, w, gap)
            .into_iter()
            .map(|x0| Opening {
                theta: Theta { x0, ..proto.theta },
                ring,
                ..proto
            })
            .collect(),
    )
}

/// 3–12 small arches on narrow piers, high on the wall under the parapet.
pub(super) fn arcade(rng: &mut Rng, style: &Style, ctx: &Ctx) -> Option<Vec<Opening>> {
    let head = [Head::Round, Head::Pointed, Head::Segmental]
        [pick(rng, &[style.heads[1], style.heads[0], 0.3])];
    let w = uniform(rng, 8.0, 30.0);
    let gap = uniform(rng, 2.0, 8.0);
    let fit = (((ctx.w() + gap) / (w + gap)).floor() as usize).min(12);
    if fit < 3 {
        return None;
    }
    let n = int(rng, 3.max(fit * 2 / 3), fit);
    let total = w * uniform(rng, 1.3, 2.4);
    let ring = if chance(rng, style.voussoirs) {
        uniform(rng, 2.0, (0.25 * w).max(2.5))
    } else {
        0.0
    };
    let y0 = ctx.top + uniform(rng, 2.0, 14.0) + total + ring;
    let fill = style.dark_fill(rng);
    let t = shape(rng, head, 0.0, y0, w, total)?;
    let proto = dressed(rng, style, t, head, fill);
    let xs = spread(rng, ctx, n, w, gap);
    Some(
        xs.into_iter()
            .map(|x0| Opening {
                theta: Theta { x0, ..proto.theta },
                ring,
                lintel: 0.0,
                sill: 0.0,
                ..proto
            })
            .collect(),
    )
}

/// 1–3 enclosing arches, each over 2–4 lancets.
pub(super) fn lancets(rng: &mut Rng, style: &Style, ctx: &Ctx) -> Option<Vec<Opening>> {
    let wmax = ctx.w().min(150.0);
    if wmax < 36.0 {
        return None;
    }
    let big = uniform(rng, 36.0, wmax);
    let k = if big > 90.0 && chance(rng, 0.15) {
        4
    } else if chance(rng, 0.3) {
        3
    } else {
        2
    };
    let gap = uniform(rng, 3.0, 9.0);
    let lw = (big - (k as f64 + 1.0) * gap) / k as f64;
    if lw < 6.0 {
        return None;
    }
    let head = style.arched(rng);
    let total = big * uniform(rng, 1.2, 2.3);
    let ring = ring(rng, head, big, style.voussoirs);
    let y0 = uniform(rng, ctx.top + total + ring, ctx.ground - 8.0);
    let enc = shape(rng, head, 0.0, y0, big, total)?;
    let lhead = if head == Head::Pointed && chance(rng, 0.8) {
        Head::Pointed
    } else {
        style.arched(rng)
    };
    let lift = uniform(rng, 0.0, 6.0);
    let mut lt = total * uniform(rng, 0.6, 0.85);
    let lancet = loop {
        let t = shape(rng, lhead, enc.x0 + gap, y0 - lift, lw, lt)?;
        // Every lancet of the row fits when the outermost ones do (the arch is symmetric).
        if within(&enc, &t, gap * 0.7) {
            break t;
        }
        lt *= 0.94;
        if lt < lw {
            return None;
        }
    };
    let inside = match pick(rng, &[0.6, 0.3, 0.1]) {
        0 => Inside::Wall,
        1 => Inside::Tympanum {
            angle: if chance(rng, 0.5) { FRAC_PI_4 } else { 0.0 },
            spacing: uniform(rng, 2.5, 5.0),
        },
        _ => Inside::Plain,
    };
    let groups = if big * 2.0 + 2.0 * ring + 12.0 < ctx.w() && chance(rng, 0.4) {
        int(rng, 2, 3)
    } else {
        1
    };
    let between = (2.0 * ring + uniform(rng, 8.0, 40.0)).max(10.0);
    let fill = style.dark_fill(rng);
    let mut out = Vec::new();
    let fit = (((ctx.w() + between) / (big + between)).floor() as usize).max(1);
    for x in spread(rng, ctx, groups.min(fit), big, between) {
        let parent = out.len();
        out.push(Opening {
            enclosing: true,
            inside,
            ring,
            sill: if chance(rng, 0.5) {
                uniform(rng, 2.0, 4.0)
            } else {
                0.0
            },
            ..Opening::new(Theta { x0: x, ..enc }, head, Fill::Solid)
        });
        let proto = dressed(rng, style, lancet, lhead, fill);
        for i in 0..k {
            let x0 = x + gap + i as f64 * (lw + gap);
            out.push(Opening {
                theta: Theta { x0, ..lancet },
                parent: Some(parent),
                lintel: 0.0,
                sill: 0.0,
                ..proto
            });
        }
    }
    Some(out)
}

/// A large wall-coloured arch over one to three small windows or a door.
pub(super) fn relieving(rng: &mut Rng, style: &Style, ctx: &Ctx) -> Option<Vec<Opening>> {
    let wmax = ctx.w().min(170.0);
    if wmax < 50.0 {
        return None;
    }
    let big = uniform(rng, 50.0, wmax);
    let head = if chance(rng, style.heads[1] / (style.heads[0] + style.heads[1])) {
        Head::Round
    } else {
        Head::Pointed
    };
    let total = (big * uniform(rng, 1.3, 2.6)).min(ctx.h() - 6.0);
    let ring = if chance(rng, 0.8) {
        uniform(rng, 4.0, 12.0)
    } else {
        0.0
    };
    let y0 = if chance(rng, 0.4) {
        ctx.ground
    } else {
        uniform(rng, ctx.top + total + ring, ctx.ground - 8.0)
    };
    let x0 = uniform(rng, ctx.x0, ctx.x1 - big);
    let enc = shape(rng, head, x0, y0, big, total)?;
    let inside = if chance(rng, 0.9) {
        Inside::Wall
    } else {
        Inside::Tympanum {
            angle: FRAC_PI_2,
            spacing: uniform(rng, 2.5, 4.5),
        }
    };
    let mut out = vec![Opening {
        enclosing: true,
        inside,
        ring,
        ..Opening::new(enc, head, Fill::Solid)
    }];
    let fill = style.dark_fill(rng);
    for _ in 0..int(rng, 1, 3) {
        for _ in 0..20 {
            let chead =
                [Head::Rectangular, Head::Round, Head::Segmental][pick(rng, &[2.0, 1.0, 0.5])];
            let w = uniform(rng, 8.0, (0.4 * big).max(9.0));
            let door = (y0 - ctx.ground).abs() < 0.5 && out.len() == 1 && chance(rng, 0.4);
            let cx = uniform(rng, x0 + 4.0, x0 + big - w - 4.0);
            let t = if door {
                let h = w * uniform(rng, 1.6, 2.2);
                shape(rng, chead, cx, y0, w, h)
            } else {
                let h = w * uniform(rng, 1.0, 2.0);
                let cy = uniform(rng, y0 - total + h, y0 - 4.0);
                shape(rng, chead, cx, cy, w, h)
            };
            let Some(t) = t else { continue };
            let clear = out[1..].iter().all(|o| {
                let (a, b) = (o.theta.bbox(), t.bbox());
                a[0] - 6.0 > b[2] || b[0] - 6.0 > a[2] || a[1] - 6.0 > b[3] || b[1] - 6.0 > a[3]
            });
            if clear && within(&enc, &t, 4.0) {
                out.push(Opening {
                    parent: Some(0),
                    sill: 0.0,
                    ..dressed(rng, style, t, chead, fill)
                });
                break;
            }
        }
    }
    (out.len() > 1).then_some(out)
}

/// One to three narrow loops side by side.
pub(super) fn slits(rng: &mut Rng, ctx: &Ctx) -> Option<Vec<Opening>> {
    let head = [Head::Rectangular, Head::Round, Head::Pointed][pick(rng, &[2.0, 1.2, 0.8])];
    let w = uniform(rng, 5.0, 10.0);
    let total = (w * uniform(rng, 4.0, 10.0)).min(ctx.h() - 10.0);
    let gap = w * uniform(rng, 3.0, 12.0);
    let fit = ((ctx.w() + gap) / (w + gap)).floor() as usize;
    if fit == 0 {
        return None;
    }
    let n = int(rng, 1, fit.min(3));
    let y0 = uniform(rng, ctx.top + total, ctx.ground - 10.0);
    let fill = if chance(rng, 0.6) {
        Fill::Solid
    } else {
        Fill::Hatched {
            angle: FRAC_PI_2,
            spacing: 2.0,
        }
    };
    let t = shape(rng, head, 0.0, y0, w, total)?;
    Some(
        spread(rng, ctx, n, w, gap)
            .into_iter()
            .map(|x0| Opening::new(Theta { x0, ..t }, head, fill))
            .collect(),
    )
}

/// Two to eight small square lights in a row.
pub(super) fn small_row(rng: &mut Rng, ctx: &Ctx) -> Option<Vec<Opening>> {
    let w = uniform(rng, 7.0, 18.0);
    let total = w * uniform(rng, 0.7, 1.6);
    let gap = w * uniform(rng, 1.0, 4.0);
    let fit = ((ctx.w() + gap) / (w + gap)).floor() as usize;
    if fit < 2 {
        return None;
    }
    let n = int(rng, 2, fit.min(8));
    let y0 = uniform(rng, ctx.top + total, ctx.ground - 8.0);
    let fill = match pick(rng, &[2.0, 1.0, 1.0]) {
        0 => Fill::Solid,
        1 => Fill::Barred {
            bars: (int(rng, 1, 2), int(rng, 0, 2)),
        },
        _ => random_fill(rng),
    };
    let fill = if fill == Fill::Open {
        Fill::Solid
    } else {
        fill
    };
    let t = shape(rng, Head::Rectangular, 0.0, y0, w, total)?;
    Some(
        spread(rng, ctx, n, w, gap)
            .into_iter()
            .map(|x0| Opening::new(Theta { x0, ..t }, Head::Rectangular, fill))
            .collect(),
    )
}
