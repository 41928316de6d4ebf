//! Openings placed on the masses: each feature (`features`, `doors`) proposes a group (a row,
//! an arcade, lancets under their arch, a gate), and the group is kept only where its members
//! and their dressings (voussoirs, lintel, sill, gable) lie wholly on the visible part of one
//! wall or roof and clear of every opening already placed. So openings never overlap, except
//! children inside their enclosing arch.

use super::basics::{Rect, Rng, chance, int, mass_id, opening_id, pick, roof_id, uniform};
use super::doors;
use super::features;
use super::layout::{Kind, Scene};
use super::openings::{Ctx, Opening};
use super::pen::Canvas;
use super::style::Style;
use crate::gothic::element::Theta;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Feature {
    Row,
    Arcade,
    Lancets,
    Relieving,
    Slits,
    SmallRow,
    Window,
    Door,
    Gate,
    Dormer,
}

pub(super) fn propose(rng: &mut Rng, style: &Style, ctx: &Ctx, f: Feature) -> Option<Vec<Opening>> {
    match f {
        Feature::Row => features::row(rng, style, ctx, (10.0, 50.0), 6),
        Feature::Window => features::row(rng, style, ctx, (25.0, 80.0), 1),
        Feature::Arcade => features::arcade(rng, style, ctx),
        Feature::Lancets => features::lancets(rng, style, ctx),
        Feature::Relieving => features::relieving(rng, style, ctx),
        Feature::Slits => features::slits(rng, ctx),
        Feature::SmallRow => features::small_row(rng, ctx),
        Feature::Door => doors::door(rng, style, ctx),
        Feature::Gate => doors::gate(rng, style, ctx),
        Feature::Dormer => doors::dormer(rng, style, ctx),
    }
}

/// The openings placed so far and the boxes they keep clear.
struct Placer<'a> {
    canvas: &'a mut Canvas,
    taken: Vec<Rect>,
    out: Vec<Opening>,
    ground: f64,
    pad: f64,
}

impl Placer<'_> {
    /// Whether every pixel centre of `r` belongs to `host`, inside the sheet.
    fn on_host(&self, r: &Rect, host: u16) -> bool {
        let c = &self.canvas;
        if r.x0 < 0.0 || r.y0 < 0.0 || r.x1 > c.w as f64 || r.y1 > c.h as f64 {
            return false;
        }
        let (xa, xb) = ((r.x0 - 0.5).ceil() as usize, (r.x1 - 0.5).floor() as i64);
        let (ya, yb) = ((r.y0 - 0.5).ceil() as usize, (r.y1 - 0.5).floor() as i64);
        (ya as i64..=yb)
            .all(|y| (xa as i64..=xb).all(|x| c.owner_at(x as usize, y as usize) == host))
    }

    /// Adds a group (parents before their children, parent indices local to the group) if
    /// its top-level members fit on the host, clear of every opening and of each other.
    fn commit(&mut self, ctx: &Ctx, group: &[Opening]) -> bool {
        if group.is_empty()
            || self.out.len() + group.len() > (u16::MAX - super::basics::OPENING_BASE) as usize
        {
            return false;
        }
        let mut mine: Vec<Rect> = Vec::new();
        let mut clear: Vec<Rect> = Vec::new();
        for o in group.iter().filter(|o| o.parent.is_none()) {
            let reach = o.reach(self.pad, self.ground);
            let [x0, y0, x1, y1] = o.theta.bbox();
            let own = Rect {
                x0: x0 - 1.0,
                y0: y0 - 1.0,
                x1: x1 + 1.0,
                y1: y1 + 1.0,
            };
            if !self.on_host(&reach, ctx.host)
                || self.taken.iter().any(|t| t.overlaps(&reach))
                || mine.iter().any(|t| t.overlaps(&own))
            {
                return false;
            }
            mine.push(own);
            clear.push(reach);
        }
        let base = self.out.len();
        for o in group {
            let id = opening_id(self.out.len());
            let t = o.theta;
            self.canvas.claim(id, t.bbox(), |x, y| t.contains(x, y));
            self.canvas.set_layer(id, ctx.layer);
            self.out.push(Opening {
                host: ctx.host,
                parent: o.parent.map(|p| base + p),
                ..*o
            });
        }
        self.taken.extend(clear);
        true
    }

    /// Up to `tries` proposals of `feature`; a kept group is repeated a storey up or down
    /// with probability `stack`.
    fn attempt(
        &mut self,
        rng: &mut Rng,
        style: &Style,
        ctx: &Ctx,
        feature: Feature,
        tries: usize,
        stack: f64,
    ) {
        for _ in 0..tries {
            let Some(group) = propose(rng, style, ctx, feature) else {
                continue;
            };
            if !self.commit(ctx, &group) {
                continue;
            }
            if chance(rng, stack) {
                let [_, top, _, bottom] = group[0].reach(0.0, self.ground).arr();
                let pitch = (bottom - top) * uniform(rng, 1.3, 2.3);
                let dir = if chance(rng, 0.7) { -1.0 } else { 1.0 };
                for k in 1..=int(rng, 1, 3) {
                    let dy = dir * pitch * k as f64;
                    let copy: Vec<Opening> = group
                        .iter()
                        .map(|o| Opening {
                            theta: Theta {
                                y0: o.theta.y0 + dy,
                                ..o.theta
                            },
                            ..*o
                        })
                        .collect();
                    if !self.commit(ctx, &copy) {
                        break;
                    }
                }
            }
            return;
        }
    }
}

/// The runs of pixels of `host` along row y at least `min` px long, as [x0, x1).
fn runs(canvas: &Canvas, host: u16, y: f64, min: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    if y < 0.0 || y >= canvas.h as f64 {
        return out;
    }
    let yi = y as usize;
    let mut start = None;
    for x in 0..=canvas.w {
        let on = x < canvas.w && canvas.owner_at(x, yi) == host;
        match (on, start) {
            (true, None) => start = Some(x),
            (false, Some(s)) => {
                if (x - s) as f64 >= min {
                    out.push((s as f64, x as f64));
                }
                start = None;
            }
            _ => {}
        }
    }
    out
}

/// Places the openings of every mass and roof, claiming their pixels in the owner map.
pub(super) fn place(
    rng: &mut Rng,
    style: &Style,
    scene: &Scene,
    canvas: &mut Canvas,
) -> Vec<Opening> {
    let pad = style.pen.outline + uniform(rng, 2.0, 6.0);
    let mut placer = Placer {
        canvas,
        taken: Vec::new(),
        out: Vec::new(),
        ground: scene.ground,
        pad,
    };
    for (k, m) in scene.masses.iter().enumerate() {
        let host = mass_id(k);
        let mid = 0.5 * (m.body.y0 + scene.ground);
        for (a, b) in runs(placer.canvas, host, mid, 30.0) {
            let margin = uniform(rng, 4.0, 12.0);
            let ctx = Ctx {
                host,
                layer: k,
                x0: a + margin,
                x1: b - margin,
                top: m.body.y0 + margin,
                ground: scene.ground,
            };
            if ctx.h() < 25.0 || ctx.w() < 12.0 {
                continue;
            }
            let gate = match m.kind {
                Kind::Block => 0.6,
                Kind::Tower => 0.3,
                Kind::Curtain => 0.1,
            };
            if ctx.w() >= 70.0 && chance(rng, gate) {
                placer.attempt(rng, style, &ctx, Feature::Gate, 12, 0.0);
            } else if chance(rng, if m.kind == Kind::Curtain { 0.25 } else { 0.45 }) {
                placer.attempt(rng, style, &ctx, Feature::Door, 12, 0.0);
            }
            if ctx.w() >= 50.0 && chance(rng, 0.35) {
                placer.attempt(rng, style, &ctx, Feature::Arcade, 6, 0.0);
            }
            let n = int(rng, 2, (3 + (ctx.h() / 90.0) as usize).min(8));
            for _ in 0..n {
                let big = if ctx.w() >= 70.0 { 1.0 } else { 0.0 };
                let (f, stack) = match pick(rng, &[3.0, 2.5, big, 1.0, 1.5, 1.0]) {
                    0 => (Feature::Row, 0.45),
                    1 => (Feature::Lancets, 0.3),
                    2 => (Feature::Relieving, 0.0),
                    3 => (Feature::Slits, 0.5),
                    4 => (Feature::SmallRow, 0.4),
                    _ => (Feature::Window, 0.4),
                };
                placer.attempt(rng, style, &ctx, f, 15, stack);
            }
        }
        let roof = m
            .roof
            .filter(|r| r.x1 - r.x0 >= 50.0 && r.base - r.apex >= 40.0);
        if let Some(roof) = roof
            && chance(rng, 0.4)
        {
            let ctx = Ctx {
                host: roof_id(k),
                layer: k,
                x0: roof.x0,
                x1: roof.x1,
                top: roof.apex,
                ground: roof.base,
            };
            placer.attempt(rng, style, &ctx, Feature::Dormer, 8, 0.0);
        }
    }
    placer.out
}
