//! The composition: one to three principal wall masses (a keep, a gatehouse between two
//! towers, a tower between curtains, a donjon and its wing) with low curtains running off the
//! sheet, all standing on the ground line, listed back to front; their tops (crenellations,
//! corbelled parapets, roofs) and buttresses.

use super::basics::{
    MAX_BUTTRESSES, MAX_MASSES, Rect, Rng, buttress_id, chance, int, mass_id, pick, roof_id,
    uniform,
};
use super::pen::Canvas;
use super::roofs::{Roof, RoofShape};
use super::style::{Style, Wall};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    Tower,
    Block,
    Curtain,
}

/// One wall mass.
#[derive(Debug, Clone)]
pub(super) struct Mass {
    pub kind: Kind,
    /// The wall from the top of its masonry to the ground line.
    pub body: Rect,
    pub round: bool,
    /// A corbelled parapet band above the body, wider than it.
    pub parapet: Option<Rect>,
    pub merlons: Vec<Rect>,
    pub roof: Option<Roof>,
    pub wall: Wall,
}

impl Mass {
    /// The box round the body, parapet and merlons.
    pub fn extent(&self) -> Rect {
        let mut r = self.body;
        for p in self.parapet.iter().chain(&self.merlons) {
            r = r.union(p);
        }
        r
    }
}

/// A buttress against a mass: its box and the height of its sloped cap.
#[derive(Debug, Clone, Copy)]
pub(super) struct Buttress {
    pub mass: usize,
    pub rect: Rect,
    pub cap: f64,
}

#[derive(Debug, Clone)]
pub(super) struct Scene {
    pub ground: f64,
    /// Back to front.
    pub masses: Vec<Mass>,
    pub buttresses: Vec<Buttress>,
}

/// What a mass is before its top is chosen: kind, x range and height above the ground.
struct Spec(Kind, f64, f64, f64);

pub(super) fn compose(rng: &mut Rng, style: &Style, w: usize, h: usize) -> Scene {
    let (wf, hf) = (w as f64, h as f64);
    let ground = hf * uniform(rng, 0.8, 0.94);
    let sky = hf * uniform(rng, 0.02, 0.08);
    let avail = (ground - sky).max(1.0);
    let mut specs = Vec::new();
    let curtain = |rng: &mut Rng, x0: f64, x1: f64| {
        Spec(Kind::Curtain, x0, x1, avail * uniform(rng, 0.18, 0.45))
    };
    match pick(rng, &[1.0, 1.3, 1.3, 0.8]) {
        0 => {
            // A keep, maybe with corner turrets, between curtains.
            let (bw, cx) = (wf * uniform(rng, 0.35, 0.75), wf * uniform(rng, 0.35, 0.65));
            let hb = avail * uniform(rng, 0.45, 0.9);
            let (l, r) = (cx - bw / 2.0, cx + bw / 2.0);
            for (x0, x1) in [(-10.0, l + 5.0), (r - 5.0, wf + 10.0)] {
                if chance(rng, 0.6) && x1 > x0 + 20.0 {
                    specs.push(curtain(rng, x0, x1));
                }
            }
            specs.push(Spec(Kind::Block, l, r, hb));
            if chance(rng, 0.45) {
                let tw = wf * uniform(rng, 0.06, 0.12);
                let th = (hb * uniform(rng, 1.0, 1.25)).min(avail);
                specs.push(Spec(Kind::Tower, l - tw / 2.0, l + tw / 2.0, th));
                specs.push(Spec(Kind::Tower, r - tw / 2.0, r + tw / 2.0, th));
            }
        }
        1 => {
            // A gatehouse: a gate block between two towers.
            let tw = wf * uniform(rng, 0.13, 0.26);
            let gap = wf * uniform(rng, 0.12, 0.35);
            let cx = wf * uniform(rng, 0.4, 0.6);
            let th = avail * uniform(rng, 0.6, 1.0);
            let (l, r) = (cx - gap / 2.0, cx + gap / 2.0);
            if chance(rng, 0.7) {
                specs.push(curtain(rng, -10.0, l - tw + 5.0));
            }
            if chance(rng, 0.7) {
                specs.push(curtain(rng, r + tw - 5.0, wf + 10.0));
            }
            let hb = (th * uniform(rng, 0.5, 1.1)).min(avail);
            specs.push(Spec(Kind::Block, l - 4.0, r + 4.0, hb));
            for (x0, x1) in [(l - tw, l), (r, r + tw)] {
                let t = (th * uniform(rng, 0.95, 1.05)).min(avail);
                specs.push(Spec(Kind::Tower, x0, x1, t));
            }
        }
        2 => {
            // A tower between curtains, maybe a second smaller tower at one end.
            let tw = wf * uniform(rng, 0.18, 0.4);
            let cx = wf * uniform(rng, 0.3, 0.7);
            let th = avail * uniform(rng, 0.6, 1.0);
            let (l, r) = (cx - tw / 2.0, cx + tw / 2.0);
            if chance(rng, 0.75) {
                specs.push(curtain(rng, -10.0, l + 5.0));
            }
            if chance(rng, 0.75) {
                specs.push(curtain(rng, r - 5.0, wf + 10.0));
            }
            specs.push(Spec(Kind::Tower, l, r, th));
            if chance(rng, 0.35) {
                let sw = wf * uniform(rng, 0.1, 0.2);
                let x = if cx > wf / 2.0 {
                    uniform(rng, 0.0, (l - sw - 10.0).max(0.0))
                } else {
                    uniform(rng, r + 10.0, (wf - sw).max(r + 10.0))
                };
                let sh = avail * uniform(rng, 0.4, 0.8);
                specs.push(Spec(Kind::Tower, x, x + sw, sh));
            }
        }
        _ => {
            // A donjon with a lower wing.
            let bw = wf * uniform(rng, 0.3, 0.55);
            let cx = wf * uniform(rng, 0.35, 0.65);
            let (l, r) = (cx - bw / 2.0, cx + bw / 2.0);
            if chance(rng, 0.6) {
                let ww = wf * uniform(rng, 0.15, 0.35);
                let (x0, x1) = if chance(rng, 0.5) {
                    (l - ww, l + 5.0)
                } else {
                    (r - 5.0, r + ww)
                };
                specs.push(Spec(Kind::Block, x0, x1, avail * uniform(rng, 0.25, 0.5)));
            }
            specs.push(Spec(Kind::Tower, l, r, avail * uniform(rng, 0.6, 1.0)));
        }
    }
    // Curtains behind blocks behind towers.
    let rank = |k: Kind| match k {
        Kind::Curtain => 0,
        Kind::Block => 1,
        Kind::Tower => 2,
    };
    specs.sort_by_key(|s| rank(s.0));
    specs.truncate(MAX_MASSES);
    let masses: Vec<Mass> = specs
        .into_iter()
        .map(|s| build(rng, style, s, ground, sky))
        .collect();
    let mut buttresses = Vec::new();
    for (k, m) in masses.iter().enumerate() {
        if m.round || m.kind == Kind::Tower || !chance(rng, 0.3) {
            continue;
        }
        let n = int(rng, 2, 4);
        let bw = uniform(rng, 6.0, 14.0);
        let frac = uniform(rng, 0.3, 0.85);
        for i in 0..n {
            let xc = m.body.x0 + (i as f64 + 0.5) * m.body.w() / n as f64;
            let rect = Rect {
                x0: xc - bw / 2.0,
                y0: ground - frac * m.body.h(),
                x1: xc + bw / 2.0,
                y1: ground,
            };
            if buttresses.len() < MAX_BUTTRESSES {
                let cap = bw * uniform(rng, 0.6, 1.3);
                buttresses.push(Buttress { mass: k, rect, cap });
            }
        }
    }
    Scene {
        ground,
        masses,
        buttresses,
    }
}

/// A mass and its top: crenellations, a corbelled parapet, a roof, or a plain coping.
fn build(rng: &mut Rng, style: &Style, s: Spec, ground: f64, sky: f64) -> Mass {
    let Spec(kind, x0, x1, height) = s;
    let round = kind == Kind::Tower && chance(rng, 0.45);
    let wall = style.mass_wall(rng, round);
    let width = x1 - x0;
    let top = match kind {
        Kind::Curtain => pick(rng, &[0.8, 0.0, 0.2]),
        Kind::Tower => pick(rng, &[0.4, 0.45, 0.15]),
        Kind::Block => pick(rng, &[0.45, 0.35, 0.2]),
    };
    let mut body = Rect {
        x0,
        y0: ground - height,
        x1,
        y1: ground,
    };
    let parapet = (chance(rng, if top == 1 { 0.3 } else { 0.45 })).then(|| {
        let o = uniform(rng, 2.0, 6.0);
        let ph = uniform(rng, 8.0, 18.0);
        body.y0 += ph;
        Rect {
            x0: x0 - o,
            y0: body.y0 - ph,
            x1: x1 + o,
            y1: body.y0,
        }
    });
    let crown = parapet.unwrap_or(body);
    let mut merlons = Vec::new();
    let mut roof = None;
    if top == 1 {
        let shape = match kind {
            Kind::Block => [RoofShape::Hip, RoofShape::Pyramid][pick(rng, &[2.0, 1.0])],
            _ => {
                [RoofShape::Cone, RoofShape::Pyramid, RoofShape::Dome][pick(rng, &[2.0, 1.5, 0.6])]
            }
        };
        let overhang = uniform(rng, 0.0, 6.0);
        let want = match shape {
            RoofShape::Dome => width * uniform(rng, 0.4, 0.75),
            RoofShape::Hip => width * uniform(rng, 0.25, 0.5),
            _ => width * uniform(rng, 0.6, 1.5),
        };
        let rh = want.min(crown.y0 - 0.5 * sky);
        if rh >= 10.0 {
            let half = width / 2.0 + overhang;
            let ridge = if shape == RoofShape::Hip {
                (half - rh * uniform(rng, 0.8, 1.3)).max(0.0)
            } else {
                0.0
            };
            roof = Some(Roof {
                x0: x0 - overhang,
                x1: x1 + overhang,
                base: crown.y0,
                apex: crown.y0 - rh,
                ridge,
                shape,
                finial: shape != RoofShape::Hip && chance(rng, 0.6),
            });
        }
    }
    if top == 0 || (top == 1 && roof.is_none()) {
        let m = uniform(rng, 7.0, 18.0);
        let c = m * uniform(rng, 0.5, 1.0);
        let hm = (m * uniform(rng, 0.6, 1.1))
            .min(crown.y0 - 0.3 * sky)
            .max(0.0);
        let span = crown.w();
        let n = (((span + c) / (m + c)).floor() as usize).max(1);
        let m = if n > 1 {
            (span - (n - 1) as f64 * c) / n as f64
        } else {
            span
        };
        if hm >= 3.0 {
            merlons = (0..n)
                .map(|i| {
                    let a = crown.x0 + i as f64 * (m + c);
                    Rect {
                        x0: a,
                        y0: crown.y0 - hm,
                        x1: a + m,
                        y1: crown.y0,
                    }
                })
                .collect();
        }
    }
    Mass {
        kind,
        body,
        round,
        parapet,
        merlons,
        roof,
        wall,
    }
}

/// Gives every pixel to the mass, roof or buttress in front at it, and sets their layers.
pub(super) fn paint(scene: &Scene, canvas: &mut Canvas) {
    for (k, m) in scene.masses.iter().enumerate() {
        let id = mass_id(k);
        canvas.set_layer(id, k);
        for r in std::iter::once(&m.body).chain(&m.parapet).chain(&m.merlons) {
            canvas.claim(id, r.arr(), |_, _| true);
        }
        for (b, t) in scene
            .buttresses
            .iter()
            .enumerate()
            .filter(|(_, t)| t.mass == k)
        {
            let id = buttress_id(b);
            canvas.set_layer(id, k);
            let r = t.rect;
            let cap = t.cap;
            // The cap slopes down to the front: the box less the triangle above the slope.
            canvas.claim(id, r.arr(), |x, y| {
                y >= r.y0 + cap * (x - r.x0) / r.w().max(1e-9)
            });
        }
        if let Some(roof) = &m.roof {
            let id = roof_id(k);
            canvas.set_layer(id, k);
            canvas.claim(id, roof.rect().arr(), |x, y| roof.contains(x, y));
        }
    }
}
