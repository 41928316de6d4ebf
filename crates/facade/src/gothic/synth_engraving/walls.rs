//! The masses drawn back to front: ashlar coursing (ruled courses with staggered joints,
//! crowding to the limbs of a round tower), hatched shading, buttresses, string courses,
//! parapets on corbels, merlons, outlines, and roofs with slate hatching and finials.

use std::f64::consts::FRAC_PI_2;

use super::ashlar::{coursing, shade};
use super::basics::{Rng, buttress_id, chance, int, mass_id, opening_id, roof_id, uniform};
use super::layout::{Mass, Scene};
use super::openings::{Inside, Opening};
use super::pen::{Canvas, Clip, P};
use super::roofs;
use super::style::{Pen, Style, Wall};

pub(super) fn draw(
    rng: &mut Rng,
    style: &Style,
    scene: &Scene,
    openings: &[Opening],
    canvas: &mut Canvas,
) {
    let pen = style.pen;
    let layers: Vec<i16> = (0..=opening_id(openings.len()) as usize)
        .map(|o| canvas.layer(o as u16))
        .collect();
    for (k, m) in scene.masses.iter().enumerate() {
        let host = mass_id(k);
        // Wall-coloured enclosing arches carry the wall's texture on.
        let walled: Vec<u16> = (0..openings.len())
            .filter(|&j| {
                openings[j].host == host
                    && openings[j].enclosing
                    && openings[j].inside == Inside::Wall
            })
            .map(opening_id)
            .collect();
        let on_wall = |_: usize, _: usize, o: u16| o == host || walled.contains(&o);
        let ext = m.extent();
        coursing(rng, canvas, ext, &m.wall, pen, m.round, &on_wall);
        shade(rng, canvas, ext, &m.wall, pen, &on_wall);
        // Outlines stop at the masses in front.
        let behind =
            |_: usize, _: usize, o: u16| layers.get(o as usize).copied().unwrap_or(-1) <= k as i16;
        for (b, t) in scene
            .buttresses
            .iter()
            .enumerate()
            .filter(|(_, t)| t.mass == k)
        {
            let id = buttress_id(b);
            let own = move |_: usize, _: usize, o: u16| o == id;
            let r = t.rect;
            let wall = Wall {
                lines: m.wall.lines * 0.8,
                ..m.wall
            };
            coursing(rng, canvas, r, &wall, pen, false, &own);
            let band = [r.x0 + uniform(rng, 0.35, 0.65) * r.w(), r.y0, r.x1, r.y1];
            let s = uniform(rng, 1.5, 2.5);
            canvas.hatch(rng, band, FRAC_PI_2, s, pen.fine, 1.0, 0.2, &own);
            let (a, c) = ([r.x0, r.y0], [r.x1, r.y0 + t.cap]);
            canvas.polyline(
                &[[r.x0, r.y1], a, c, [r.x1, r.y1]],
                false,
                pen.outline,
                1.0,
                &behind,
            );
        }
        strings(rng, canvas, m, scene.ground, openings, host, pen, &on_wall);
        dressing(rng, canvas, m, pen, &on_wall, &behind);
        if let Some(roof) = &m.roof {
            roofs::draw(rng, canvas, roof, roof_id(k), pen, &behind);
            // The eaves' shadow on the wall below.
            if chance(rng, 0.6) {
                let band = [
                    m.body.x0,
                    roof.base,
                    m.body.x1,
                    roof.base + uniform(rng, 3.0, 9.0),
                ];
                canvas.hatch(rng, band, 0.0, 1.6, pen.fine, 1.0, 0.1, &on_wall);
            }
        }
    }
}

/// One or two string courses (double lines) at heights no opening of the mass reaches.
#[allow(clippy::too_many_arguments)]
fn strings(
    rng: &mut Rng,
    canvas: &mut Canvas,
    m: &Mass,
    ground: f64,
    openings: &[Opening],
    host: u16,
    pen: Pen,
    clip: Clip,
) {
    if m.body.h() < 80.0 || !chance(rng, 0.45) {
        return;
    }
    let gap = uniform(rng, 2.0, 4.0);
    for _ in 0..int(rng, 1, 2) {
        for _ in 0..10 {
            let y = uniform(rng, m.body.y0 + 15.0, ground - 15.0);
            let hit = openings
                .iter()
                .filter(|o| o.host == host && o.parent.is_none())
                .any(|o| {
                    let r = o.reach(3.0, ground);
                    y + gap >= r.y0 && y <= r.y1
                });
            if !hit {
                for yy in [y, y + gap] {
                    canvas.hand(
                        rng,
                        [m.body.x0, yy],
                        [m.body.x1, yy],
                        pen.outline * 0.8,
                        1.0,
                        pen.wobble,
                        clip,
                    );
                }
                break;
            }
        }
    }
}

/// Outline of the body, the corbelled parapet and its corbels, the merlons.
fn dressing(rng: &mut Rng, canvas: &mut Canvas, m: &Mass, pen: Pen, on_wall: Clip, behind: Clip) {
    let b = m.body;
    let w = pen.outline;
    for x in [b.x0, b.x1] {
        canvas.hand(rng, [x, b.y0], [x, b.y1], w, 1.0, pen.wobble, behind);
    }
    let crown = match m.parapet {
        Some(p) => {
            canvas.polyline(
                &[[p.x0, p.y1], [p.x0, p.y0], [p.x1, p.y0], [p.x1, p.y1]],
                true,
                w,
                1.0,
                behind,
            );
            // Corbels under the parapet, their shadow between them.
            let (cw, pitch) = (uniform(rng, 3.0, 6.0), uniform(rng, 9.0, 18.0));
            let depth = uniform(rng, 4.0, 8.0);
            let mut x = b.x0 + uniform(rng, 2.0, pitch);
            while x + cw < b.x1 {
                let pts = [
                    [x, b.y0],
                    [x, b.y0 + depth * 0.6],
                    [x + cw * 0.5, b.y0 + depth],
                    [x + cw, b.y0 + depth * 0.6],
                    [x + cw, b.y0],
                ];
                canvas.polyline(&pts, false, pen.fine, 1.0, on_wall);
                x += pitch;
            }
            p
        }
        None => b,
    };
    if m.merlons.is_empty() {
        canvas.segment([crown.x0, crown.y0], [crown.x1, crown.y0], w, 1.0, behind);
        return;
    }
    // The crenellated skyline: up each merlon, across, down into the crenel.
    let mut pts: Vec<P> = vec![[crown.x0, crown.y0]];
    for r in &m.merlons {
        pts.extend([
            [r.x0, crown.y0],
            [r.x0, r.y0],
            [r.x1, r.y0],
            [r.x1, crown.y0],
        ]);
    }
    pts.push([crown.x1, crown.y0]);
    canvas.polyline(&pts, false, w, 1.0, behind);
    // Arrow loops in some merlons, drawn as single strokes (too thin to be openings).
    if chance(rng, 0.4) {
        for r in &m.merlons {
            let cx = 0.5 * (r.x0 + r.x1);
            canvas.segment(
                [cx, r.y0 + 0.3 * r.h()],
                [cx, r.y1 - 0.15 * r.h()],
                pen.fine,
                1.0,
                on_wall,
            );
        }
    }
}
