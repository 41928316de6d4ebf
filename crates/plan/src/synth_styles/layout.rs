//! A random castle: an irregular curtain with round and square towers, ranges of rooms,
//! sometimes an inner ward or a keep, door gaps; its walls as masks and its rooms.

use std::f64::consts::PI;

use rand::RngExt;

use super::geometry::{Mask, P, Rng, add, lerp, mul, rot, sub, u, unit};

/// A room inside walls: where vault ribs (not in halls) and labels go.
pub(super) enum Room {
    Round(P, f64),
    Square(P, f64, f64),
    Hall(P),
}

/// The walls of a castle: `main` (curtain, towers, keep, inner ward) and `inner` (buildings,
/// partitions), which may be drawn in a second style.
pub(super) struct Layout {
    pub(super) main: Mask,
    pub(super) inner: Mask,
    pub(super) rooms: Vec<Room>,
    pub(super) curtain: Vec<P>,
    pub(super) centre: P,
    pub(super) radius: P,
    pub(super) t: f64,
}

pub(super) fn layout(rng: &mut Rng, w: u32, h: u32, t: f64) -> Layout {
    let (wf, hf) = (w as f64, h as f64);
    let centre = (wf * u(rng, 0.45, 0.55), hf * u(rng, 0.45, 0.55));
    let radius = (wf * u(rng, 0.24, 0.32), hf * u(rng, 0.24, 0.32));
    let n = rng.random_range(4..=8);
    let phase = u(rng, 0.0, 2.0 * PI);
    let curtain: Vec<P> = (0..n)
        .map(|k| {
            let a = phase + 2.0 * PI * (k as f64 + u(rng, -0.3, 0.3)) / n as f64;
            let r = u(rng, 0.72, 1.0);
            (
                centre.0 + radius.0 * r * a.cos(),
                centre.1 + radius.1 * r * a.sin(),
            )
        })
        .collect();
    let mut lay = Layout {
        main: Mask::new(w, h),
        inner: Mask::new(w, h),
        rooms: Vec::new(),
        curtain,
        centre,
        radius,
        t,
    };
    let mut segs = Vec::new();
    lay.main.poly(&lay.curtain, t);
    segs.extend(edges(&lay.curtain, t));
    add_buildings(rng, &mut lay, &mut segs);
    if rng.random_bool(0.3) {
        add_ward(rng, &mut lay, &mut segs);
    }
    add_doors(rng, &mut lay, &segs);
    add_towers(rng, &mut lay);
    if rng.random_bool(0.4) {
        add_keep(rng, &mut lay);
    }
    lay
}

pub(super) fn edges(pts: &[P], t: f64) -> Vec<(P, P, f64)> {
    (0..pts.len())
        .map(|k| (pts[k], pts[(k + 1) % pts.len()], t))
        .collect()
}

/// The unit normal of a→b pointing towards `c`.
pub(super) fn inward(a: P, b: P, c: P) -> P {
    let n = unit(rot(sub(b, a), PI / 2.0));
    let m = sub(c, lerp(a, b, 0.5));
    if n.0 * m.0 + n.1 * m.1 >= 0.0 {
        n
    } else {
        mul(n, -1.0)
    }
}

/// Ranges of rooms against the curtain, with cross walls.
pub(super) fn add_buildings(rng: &mut Rng, lay: &mut Layout, segs: &mut Vec<(P, P, f64)>) {
    let n = lay.curtain.len();
    let depth = lay.radius.0.min(lay.radius.1);
    let first = rng.random_range(0..n);
    for j in 0..rng.random_range(1..=4.min(n)) {
        let k = (first + j * 2) % n;
        let (a, b) = (lay.curtain[k], lay.curtain[(k + 1) % n]);
        let nrm = inward(a, b, lay.centre);
        let s0 = u(rng, 0.15, 0.45);
        let s1 = (s0 + u(rng, 0.2, 0.45)).min(0.88);
        let d = depth * u(rng, 0.12, 0.3);
        let (p0, p1) = (lerp(a, b, s0), lerp(a, b, s1));
        let rect = [p0, p1, add(p1, mul(nrm, d)), add(p0, mul(nrm, d))];
        let tb = (lay.t * u(rng, 0.5, 1.0)).max(2.0);
        lay.inner.poly(&rect, tb);
        segs.extend(edges(&rect, tb).into_iter().skip(1));
        let parts = rng.random_range(0..=3);
        for j in 0..parts {
            let q = lerp(p0, p1, (j as f64 + u(rng, 0.6, 1.4)) / (parts as f64 + 1.0));
            lay.inner.wall(q, add(q, mul(nrm, d)), tb * 0.8, true);
        }
        let mid = add(lerp(p0, p1, 0.5), mul(nrm, d / 2.0));
        lay.rooms.push(Room::Hall(mid));
    }
}

/// A smaller polygon inside the curtain.
pub(super) fn add_ward(rng: &mut Rng, lay: &mut Layout, segs: &mut Vec<(P, P, f64)>) {
    let n = rng.random_range(4..=6);
    let c = add(lay.centre, mul(lay.radius, u(rng, -0.15, 0.15)));
    let f = u(rng, 0.3, 0.5);
    let pts: Vec<P> = (0..n)
        .map(|k| {
            let a = 2.0 * PI * (k as f64 + u(rng, -0.25, 0.25)) / n as f64;
            (
                c.0 + lay.radius.0 * f * a.cos(),
                c.1 + lay.radius.1 * f * a.sin(),
            )
        })
        .collect();
    let tw = (lay.t * u(rng, 0.6, 1.0)).max(2.0);
    lay.main.poly(&pts, tw);
    segs.extend(edges(&pts, tw));
}

/// Gaps through some walls.
pub(super) fn add_doors(rng: &mut Rng, lay: &mut Layout, segs: &[(P, P, f64)]) {
    for _ in 0..rng.random_range(1..=6) {
        let (a, b, t) = segs[rng.random_range(0..segs.len())];
        let len = sub(b, a).0.hypot(sub(b, a).1);
        let g = (t * u(rng, 1.2, 3.0)).max(5.0) / len.max(1.0);
        let s = u(rng, 0.2, 0.8 - g);
        let (p, q) = (lerp(a, b, s), lerp(a, b, s + g));
        let n = mul(unit(rot(sub(q, p), PI / 2.0)), t / 2.0 + 2.0);
        let gap = [add(p, n), add(q, n), sub(q, n), sub(p, n)];
        lay.main.fill(&gap, false);
        lay.inner.fill(&gap, false);
    }
}

/// Round and square towers at the curtain's corners and some mid-walls.
pub(super) fn add_towers(rng: &mut Rng, lay: &mut Layout) {
    let n = lay.curtain.len();
    let s = lay.radius.0.min(lay.radius.1);
    for k in 0..n {
        let (a, b) = (lay.curtain[k], lay.curtain[(k + 1) % n]);
        if rng.random_bool(0.8) {
            tower(rng, lay, a, sub(b, a), s);
        }
        if rng.random_bool(0.3) {
            let at = lerp(a, b, u(rng, 0.35, 0.65));
            tower(rng, lay, at, sub(b, a), s);
        }
    }
}

pub(super) fn tower(rng: &mut Rng, lay: &mut Layout, at: P, dir: P, s: f64) {
    let tt = lay.t * u(rng, 1.0, 1.5);
    let r = (lay.t * u(rng, 1.8, 3.5)).max(s * u(rng, 0.06, 0.14));
    let out = unit(sub(at, lay.centre));
    let c = add(at, mul(out, r * u(rng, 0.0, 0.7)));
    let room = r > 2.2 * tt && rng.random_bool(0.75);
    if rng.random_bool(0.55) {
        lay.main.disc(c, r, true);
        if room {
            lay.main.disc(c, r - tt, false);
            lay.inner.disc(c, r - tt, false);
            lay.rooms.push(Room::Round(c, r - tt));
        }
    } else {
        let ang = dir.1.atan2(dir.0);
        let sq = |h: f64| square(c, h, ang);
        lay.main.fill(&sq(r * 0.9), true);
        if room {
            lay.main.fill(&sq(r * 0.9 - tt), false);
            lay.inner.fill(&sq(r * 0.9 - tt), false);
            lay.rooms.push(Room::Square(c, r * 0.9 - tt, ang));
        }
    }
}

pub(super) fn square(c: P, h: f64, ang: f64) -> [P; 4] {
    [(-h, -h), (h, -h), (h, h), (-h, h)].map(|p| add(c, rot(p, ang)))
}

/// A square keep near the centre, with a cross wall and sometimes corner turrets.
pub(super) fn add_keep(rng: &mut Rng, lay: &mut Layout) {
    let c = add(lay.centre, mul(lay.radius, u(rng, -0.1, 0.1)));
    let h = lay.radius.0.min(lay.radius.1) * u(rng, 0.12, 0.22);
    let tk = (lay.t * u(rng, 1.2, 2.2)).min(h * 0.4);
    let ang = u(rng, -0.3, 0.3);
    let outer = square(c, h, ang);
    lay.inner.fill(&outer, false);
    lay.main.fill(&outer, true);
    lay.main.fill(&square(c, h - tk, ang), false);
    lay.main.wall(
        lerp(outer[0], outer[1], 0.5),
        lerp(outer[3], outer[2], 0.5),
        tk * 0.7,
        true,
    );
    lay.rooms.push(Room::Square(c, h - tk, ang));
    if rng.random_bool(0.5) {
        for p in outer {
            lay.main.disc(p, tk * 1.2, true);
        }
    }
}
