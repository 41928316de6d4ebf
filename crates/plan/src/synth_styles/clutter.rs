//! The clutter of a sheet that is never wall: letters, words, vault ribs, dashed paths,
//! dimension lines, a scale bar, a north arrow, a title, a frame, grid lines (and the
//! terrain of `terrain` and the hachured scarps of `moat`), each kind drawn with its
//! probability.

use std::f64::consts::PI;

use rand::RngExt;

use super::furnishing::furnishing;
use super::geometry::{P, Rng, add, lerp, mul, rot, sub, u, unit};
use super::layout::{Layout, Room};
use super::moat::{hachure_bands, wall_hachures};
use super::sheet::Sheet;
use super::style::{Clutter, StyleChoice};
use super::terrain::{contours, hachures};

/// Draws some of every kind of clutter, each with some probability; returns the kinds drawn.
/// Without `choice.scarps` the kinds of `moat`, and without `choice.furnishing` the fittings,
/// are left out and draw no random numbers.
pub(super) fn draw_clutter(
    sheet: &mut Sheet,
    lay: &Layout,
    rng: &mut Rng,
    choice: &StyleChoice,
) -> Vec<Clutter> {
    type Draw = fn(&mut Sheet, &Layout, &mut Rng);
    let kinds: [(Clutter, f64, Draw); 14] = [
        (Clutter::Grid, 0.15, grid),
        (Clutter::Frame, 0.5, frame),
        (Clutter::Contours, 0.25, contours),
        (Clutter::Hachures, 0.45, hachures),
        (Clutter::WallHachures, 0.45, wall_hachures),
        (Clutter::HachureBands, 0.25, hachure_bands),
        (Clutter::DashedLines, 0.4, dashed_lines),
        (Clutter::VaultRibs, 0.4, vault_ribs),
        (Clutter::DimensionLines, 0.3, dimension_lines),
        (Clutter::Letters, 0.7, letters),
        (Clutter::Words, 0.4, words),
        (Clutter::ScaleBar, 0.6, scale_bar),
        (Clutter::NorthArrow, 0.35, north_arrow),
        (Clutter::Title, 0.4, title),
    ];
    let mut drawn = Vec::new();
    let moat = [Clutter::WallHachures, Clutter::HachureBands];
    for (kind, p, f) in kinds {
        if !choice.scarps && moat.contains(&kind) {
            continue;
        }
        if rng.random_bool(p) {
            f(sheet, lay, rng);
            drawn.push(kind);
        }
    }
    if choice.furnishing && rng.random_bool(0.7) {
        furnishing(sheet, lay, rng);
        drawn.push(Clutter::Furnishing);
    }
    drawn
}

pub(super) fn size(lay: &Layout) -> P {
    (lay.main.w as f64, lay.main.h as f64)
}

pub(super) fn random_point(rng: &mut Rng, lay: &Layout) -> P {
    let (w, h) = size(lay);
    (u(rng, 0.0, w), u(rng, 0.0, h))
}

pub(super) fn random_word(rng: &mut Rng, n: usize, digits: bool) -> String {
    let pool = if digits {
        "0123456789"
    } else {
        "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
    };
    (0..n)
        .map(|_| pool.as_bytes()[rng.random_range(0..pool.len())] as char)
        .collect()
}

pub(super) fn letter_height(rng: &mut Rng, lay: &Layout) -> f64 {
    (lay.t * u(rng, 1.0, 3.0)).clamp(6.0, 60.0)
}

pub(super) fn grid(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let (w, h) = size(lay);
    let g = u(rng, 40.0, 160.0f64.max(w / 6.0));
    let v = rng.random_range(60..=200u8);
    let mut x = u(rng, 0.0, g);
    while x < w {
        sheet.line((x, 0.0), (x, h), 1.0, v);
        x += g;
    }
    let mut y = u(rng, 0.0, g);
    while y < h {
        sheet.line((0.0, y), (w, y), 1.0, v);
        y += g;
    }
}

pub(super) fn frame(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let (w, h) = size(lay);
    let m = u(rng, 3.0, w.min(h) * 0.04);
    let lw = u(rng, 1.0, 3.0);
    let rect = [(m, m), (w - m, m), (w - m, h - m), (m, h - m), (m, m)];
    sheet.polyline(&rect, lw, 0);
    if rng.random_bool(0.4) {
        let d = lw + u(rng, 2.0, 5.0);
        let inner = [(m + d, m + d), (w - m - d, m + d), (w - m - d, h - m - d)];
        sheet.polyline(
            &[inner[0], inner[1], inner[2], (m + d, h - m - d), inner[0]],
            1.0,
            0,
        );
    }
}

pub(super) fn dashed_lines(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    for _ in 0..rng.random_range(1..=4) {
        let pts: Vec<P> = (0..rng.random_range(2..=4))
            .map(|_| random_point(rng, lay))
            .collect();
        let dotted = rng.random_bool(0.4);
        let on = if dotted { 0.0 } else { u(rng, 3.0, 12.0) };
        let lw = if dotted {
            u(rng, 1.5, 3.0)
        } else {
            u(rng, 1.0, 2.0)
        };
        sheet.dashed(&pts, on, u(rng, 2.0, 8.0), lw);
    }
}

/// Thin lines radiating across rooms.
pub(super) fn vault_ribs(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let lw = u(rng, 1.0, 1.8);
    for room in &lay.rooms {
        let (c, r, a0) = match room {
            Room::Round(c, r) => (*c, *r, u(rng, 0.0, PI)),
            Room::Square(c, r, a) => (*c, *r * std::f64::consts::SQRT_2, a + PI / 4.0),
            Room::Hall(_) => continue,
        };
        let n = rng.random_range(2..=4);
        for k in 0..n {
            let d = rot((r, 0.0), a0 + PI * k as f64 / n as f64);
            sheet.line(sub(c, d), add(c, d), lw, 0);
        }
    }
}

pub(super) fn dimension_lines(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    for _ in 0..rng.random_range(1..=3) {
        let (a, b) = (random_point(rng, lay), random_point(rng, lay));
        let d = sub(b, a);
        let al = (lay.t * 1.5).clamp(5.0, 20.0);
        sheet.line(a, b, 1.0, 0);
        sheet.arrow_head(a, mul(d, -1.0), al);
        sheet.arrow_head(b, d, al);
        let n = mul(unit(rot(d, PI / 2.0)), al);
        sheet.line(sub(a, n), add(a, n), 1.0, 0);
        sheet.line(sub(b, n), add(b, n), 1.0, 0);
        let h = letter_height(rng, lay);
        let digits = rng.random_range(1..=3);
        sheet.text(
            &random_word(rng, digits, true),
            add(lerp(a, b, 0.5), (2.0, 2.0)),
            h,
        );
    }
}

pub(super) fn letters(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let rooms = lay.rooms.iter().map(|r| match r {
        Room::Round(c, _) | Room::Square(c, _, _) | Room::Hall(c) => *c,
    });
    let spots: Vec<P> = rooms
        .collect::<Vec<P>>()
        .into_iter()
        .chain((0..rng.random_range(3..12)).map(|_| random_point(rng, lay)))
        .collect();
    for p in spots {
        let n = rng.random_range(1..=2);
        let digits = rng.random_bool(0.3);
        let w = random_word(rng, n, digits);
        sheet.text(&w, p, letter_height(rng, lay));
    }
}

pub(super) fn words(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    for _ in 0..rng.random_range(1..=5) {
        let n = rng.random_range(4..=9);
        let w = random_word(rng, n, false);
        let p = random_point(rng, lay);
        sheet.text(&w, p, letter_height(rng, lay) * 0.7);
    }
}

pub(super) fn scale_bar(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let (w, h) = size(lay);
    let at = (w * u(rng, 0.05, 0.5), h * u(rng, 0.85, 0.93));
    let (n, step) = (rng.random_range(3..=6), w * u(rng, 0.03, 0.07));
    let tick = (lay.t * 1.2).clamp(4.0, 14.0);
    sheet.line(at, add(at, (n as f64 * step, 0.0)), 1.0, 0);
    let filled = rng.random_bool(0.5);
    let th = (letter_height(rng, lay) * 0.7).min(step * 0.3).max(5.0);
    for k in 0..=n {
        let x = add(at, (k as f64 * step, 0.0));
        sheet.line(x, add(x, (0.0, -tick)), 1.0, 0);
        if filled && k < n && k % 2 == 0 {
            for dy in 0..(tick * 0.5) as usize {
                let y = dy as f64 + 1.0;
                sheet.line(sub(x, (0.0, y)), sub(x, (-step, y)), 1.0, 0);
            }
        }
        sheet.text(&(k * 10).to_string(), add(x, (-th * 0.3, 3.0)), th);
    }
}

pub(super) fn north_arrow(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let (w, h) = size(lay);
    let p = (w * u(rng, 0.82, 0.93), h * u(rng, 0.12, 0.3));
    let len = w.min(h) * u(rng, 0.06, 0.12);
    let dir = rot((0.0, -1.0), u(rng, -0.5, 0.5));
    let tip = add(p, mul(dir, len));
    sheet.line(p, tip, u(rng, 1.0, 2.5), 0);
    sheet.arrow_head(tip, dir, len * 0.3);
    let th = letter_height(rng, lay);
    sheet.text("N", add(tip, (-th / 4.0, -th * 1.3)), th);
}

pub(super) fn title(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let (w, h) = size(lay);
    let th = (h * u(rng, 0.02, 0.04)).max(7.0);
    let n = rng.random_range(2..=4);
    let text: Vec<String> = (0..n)
        .map(|_| {
            let len = rng.random_range(3..=8);
            random_word(rng, len, false)
        })
        .collect();
    let text = text.join(" ");
    let width = text.len() as f64 * th * 0.75;
    let y = if rng.random_bool(0.5) {
        h * 0.03
    } else {
        h * 0.95 - th
    };
    sheet.text(&text, ((w - width).max(0.0) / 2.0, y), th);
}
