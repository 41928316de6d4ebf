//! Synthetic castle plan drawings in randomised draughting styles, with exact wall truth, for
//! training and measuring the learned wall-ink classifier (issue 26).
//!
//! Each seed gives a random castle (an irregular curtain with round and square towers, inner
//! buildings and partitions, sometimes an inner ward or a keep, door gaps), its walls drawn in
//! one or two of the [`WallStyle`]s, over clutter that is never wall (letters, words, vault
//! ribs, hachures, contours, dashed paths, dimension lines, a scale bar, a north arrow, a title,
//! a frame, grid lines), then degraded (paper tone and texture, grey ink, stains, blur,
//! 16-level quantisation, a JPEG round trip). The truth mask is the whole wall area, including
//! the paper between the outlines or hatch lines of a wall; degradations never move geometry.
//! Seeded: same seed, same drawing.

use std::f64::consts::PI;
use std::io::Cursor;

use image::codecs::jpeg::JpegEncoder;
use image::{GrayImage, Luma};
use imageproc::distance_transform::Norm;
use imageproc::morphology::erode;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

type P = (f64, f64);
type Rng = ChaCha8Rng;

/// A drawing, its wall truth (255 = wall, 0 = not) and what was drawn.
pub struct StyledPlan {
    pub image: GrayImage,
    pub walls: GrayImage,
    pub style: Style,
}

/// How walls are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WallStyle {
    /// Filled black.
    Solid,
    /// Two thin lines with paper between.
    Outlined,
    /// Outline with diagonal parallel lines inside.
    Hatched,
    /// Outline with two crossing sets of parallel lines inside.
    CrossHatched,
    /// Filled mid-grey, with or without a dark outline.
    GreyWash,
}

pub const WALL_STYLES: [WallStyle; 5] = [
    WallStyle::Solid,
    WallStyle::Outlined,
    WallStyle::Hatched,
    WallStyle::CrossHatched,
    WallStyle::GreyWash,
];

/// Kinds of non-wall clutter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clutter {
    Letters,
    Words,
    VaultRibs,
    Hachures,
    Contours,
    DashedLines,
    DimensionLines,
    ScaleBar,
    NorthArrow,
    Title,
    Frame,
    Grid,
}

/// What was drawn.
#[derive(Clone, Debug)]
pub struct Style {
    /// The style of the curtain, towers, keep and inner ward.
    pub walls: WallStyle,
    /// The style of the inner buildings and partitions when it differs.
    pub second: Option<WallStyle>,
    /// Curtain wall thickness in pixels.
    pub thickness: f64,
    pub clutter: Vec<Clutter>,
    /// Whether degradations were applied.
    pub degraded: bool,
}

/// Forced choices for [`generate_with`]; `None` lets the seed choose.
#[derive(Clone, Debug, Default)]
pub struct StyleChoice {
    pub walls: Option<WallStyle>,
    pub thickness: Option<f64>,
    /// Skip the degradations (a clean drawing: paper 255, ink 0).
    pub clean: bool,
}

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

    let clutter = draw_clutter(&mut sheet, &lay, &mut rng);
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

/// Uniform in [a, b), or a when the range is empty.
fn u(rng: &mut Rng, a: f64, b: f64) -> f64 {
    if b > a { rng.random_range(a..b) } else { a }
}

fn add(a: P, b: P) -> P {
    (a.0 + b.0, a.1 + b.1)
}
fn sub(a: P, b: P) -> P {
    (a.0 - b.0, a.1 - b.1)
}
fn mul(a: P, k: f64) -> P {
    (a.0 * k, a.1 * k)
}
fn lerp(a: P, b: P, s: f64) -> P {
    add(a, mul(sub(b, a), s))
}
fn unit(a: P) -> P {
    let n = a.0.hypot(a.1).max(1e-9);
    (a.0 / n, a.1 / n)
}
fn rot(a: P, ang: f64) -> P {
    let (s, c) = ang.sin_cos();
    (a.0 * c - a.1 * s, a.0 * s + a.1 * c)
}

fn seg_dist(p: P, a: P, b: P) -> f64 {
    let (d, q) = (sub(b, a), sub(p, a));
    let l2 = (d.0 * d.0 + d.1 * d.1).max(1e-12);
    let s = ((q.0 * d.0 + q.1 * d.1) / l2).clamp(0.0, 1.0);
    (q.0 - s * d.0).hypot(q.1 - s * d.1)
}

fn inside_poly(p: P, pts: &[P]) -> bool {
    let mut inside = false;
    for k in 0..pts.len() {
        let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < a.0 + (p.1 - a.1) / (b.1 - a.1) * (b.0 - a.0) {
            inside = !inside;
        }
    }
    inside
}

/// Calls `f` for every pixel of a `w` × `h` sheet in the box lo..hi where `pred` holds.
fn scan(w: usize, h: usize, lo: P, hi: P, pred: impl Fn(P) -> bool, mut f: impl FnMut(usize)) {
    let x0 = lo.0.floor().max(0.0) as usize;
    let y0 = lo.1.floor().max(0.0) as usize;
    let x1 = (hi.0.ceil() + 1.0).clamp(0.0, w as f64) as usize;
    let y1 = (hi.1.ceil() + 1.0).clamp(0.0, h as f64) as usize;
    for y in y0..y1 {
        for x in x0..x1 {
            if pred((x as f64, y as f64)) {
                f(y * w + x);
            }
        }
    }
}

fn bbox(pts: &[P], pad: f64) -> (P, P) {
    let lo = pts
        .iter()
        .fold((f64::MAX, f64::MAX), |m, p| (m.0.min(p.0), m.1.min(p.1)));
    let hi = pts
        .iter()
        .fold((f64::MIN, f64::MIN), |m, p| (m.0.max(p.0), m.1.max(p.1)));
    ((lo.0 - pad, lo.1 - pad), (hi.0 + pad, hi.1 + pad))
}

/// A boolean layer of a sheet.
#[derive(Clone)]
struct Mask {
    w: usize,
    h: usize,
    m: Vec<bool>,
}

impl Mask {
    fn new(w: u32, h: u32) -> Mask {
        let (w, h) = (w as usize, h as usize);
        Mask {
            w,
            h,
            m: vec![false; w * h],
        }
    }
    /// A wall of thickness `t` from a to b (set to `v`).
    fn wall(&mut self, a: P, b: P, t: f64, v: bool) {
        let (lo, hi) = bbox(&[a, b], t / 2.0 + 1.0);
        let m = &mut self.m;
        scan(
            self.w,
            self.h,
            lo,
            hi,
            |p| seg_dist(p, a, b) <= t / 2.0,
            |i| m[i] = v,
        );
    }
    fn poly(&mut self, pts: &[P], t: f64) {
        for k in 0..pts.len() {
            self.wall(pts[k], pts[(k + 1) % pts.len()], t, true);
        }
    }
    fn disc(&mut self, c: P, r: f64, v: bool) {
        let m = &mut self.m;
        let pred = |p: P| (p.0 - c.0).hypot(p.1 - c.1) <= r;
        scan(self.w, self.h, sub(c, (r, r)), add(c, (r, r)), pred, |i| {
            m[i] = v
        });
    }
    fn fill(&mut self, pts: &[P], v: bool) {
        let (lo, hi) = bbox(pts, 1.0);
        let m = &mut self.m;
        scan(
            self.w,
            self.h,
            lo,
            hi,
            |p| inside_poly(p, pts),
            |i| m[i] = v,
        );
    }
    fn minus(&self, o: &Mask) -> Mask {
        let m = self.m.iter().zip(&o.m).map(|(a, b)| *a && !*b).collect();
        Mask { m, ..*self }
    }
    fn or(&self, o: &Mask) -> Mask {
        let m = self.m.iter().zip(&o.m).map(|(a, b)| *a || *b).collect();
        Mask { m, ..*self }
    }
    #[cfg(test)]
    fn count(&self) -> usize {
        self.m.iter().filter(|v| **v).count()
    }
    fn to_gray(&self) -> GrayImage {
        let px = self.m.iter().map(|&v| if v { 255 } else { 0 }).collect();
        GrayImage::from_raw(self.w as u32, self.h as u32, px).expect("size")
    }
}

/// A room inside walls: where vault ribs (not in halls) and labels go.
enum Room {
    Round(P, f64),
    Square(P, f64, f64),
    Hall(P),
}

/// The walls of a castle: `main` (curtain, towers, keep, inner ward) and `inner` (buildings,
/// partitions), which may be drawn in a second style.
struct Layout {
    main: Mask,
    inner: Mask,
    rooms: Vec<Room>,
    curtain: Vec<P>,
    centre: P,
    radius: P,
    t: f64,
}

fn layout(rng: &mut Rng, w: u32, h: u32, t: f64) -> Layout {
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

fn edges(pts: &[P], t: f64) -> Vec<(P, P, f64)> {
    (0..pts.len())
        .map(|k| (pts[k], pts[(k + 1) % pts.len()], t))
        .collect()
}

/// The unit normal of a→b pointing towards `c`.
fn inward(a: P, b: P, c: P) -> P {
    let n = unit(rot(sub(b, a), PI / 2.0));
    let m = sub(c, lerp(a, b, 0.5));
    if n.0 * m.0 + n.1 * m.1 >= 0.0 {
        n
    } else {
        mul(n, -1.0)
    }
}

/// Ranges of rooms against the curtain, with cross walls.
fn add_buildings(rng: &mut Rng, lay: &mut Layout, segs: &mut Vec<(P, P, f64)>) {
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
fn add_ward(rng: &mut Rng, lay: &mut Layout, segs: &mut Vec<(P, P, f64)>) {
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
fn add_doors(rng: &mut Rng, lay: &mut Layout, segs: &[(P, P, f64)]) {
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
fn add_towers(rng: &mut Rng, lay: &mut Layout) {
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

fn tower(rng: &mut Rng, lay: &mut Layout, at: P, dir: P, s: f64) {
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

fn square(c: P, h: f64, ang: f64) -> [P; 4] {
    [(-h, -h), (h, -h), (h, h), (-h, h)].map(|p| add(c, rot(p, ang)))
}

/// A square keep near the centre, with a cross wall and sometimes corner turrets.
fn add_keep(rng: &mut Rng, lay: &mut Layout) {
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

/// The clean drawing: paper 255, ink 0, the truth and where clutter was drawn.
struct Sheet {
    img: GrayImage,
    truth: Mask,
    clutter: Mask,
}

impl Sheet {
    fn new(w: u32, h: u32, lay: &Layout) -> Sheet {
        Sheet {
            img: GrayImage::from_pixel(w, h, Luma([255])),
            truth: lay.main.or(&lay.inner),
            clutter: Mask::new(w, h),
        }
    }
    /// Clutter ink of value `v` at pixel i, never on a wall.
    fn ink(&mut self, i: usize, v: u8) {
        if !self.truth.m[i] {
            self.clutter.m[i] = true;
            let px = &mut self.img.as_mut()[i];
            *px = (*px).min(v);
        }
    }
    fn line(&mut self, a: P, b: P, lw: f64, v: u8) {
        let (w, h) = (self.truth.w, self.truth.h);
        let r = (lw / 2.0).max(0.55);
        let mut hits = Vec::new();
        let (lo, hi) = bbox(&[a, b], r + 1.0);
        scan(w, h, lo, hi, |p| seg_dist(p, a, b) <= r, |i| hits.push(i));
        hits.into_iter().for_each(|i| self.ink(i, v));
    }
    fn polyline(&mut self, pts: &[P], lw: f64, v: u8) {
        pts.windows(2).for_each(|s| self.line(s[0], s[1], lw, v));
    }
    /// A dashed (or, with `on` ≈ 0, dotted) polyline.
    fn dashed(&mut self, pts: &[P], on: f64, off: f64, lw: f64) {
        let mut phase = 0.0;
        for s in pts.windows(2) {
            let len = sub(s[1], s[0]).0.hypot(sub(s[1], s[0]).1);
            while phase < len {
                let e = (phase + on).min(len);
                self.line(
                    lerp(s[0], s[1], phase / len),
                    lerp(s[0], s[1], e / len),
                    lw,
                    0,
                );
                phase += on + off;
            }
            phase -= len;
        }
    }
    fn arrow_head(&mut self, tip: P, dir: P, len: f64) {
        let d = unit(dir);
        for a in [PI * 0.85, -PI * 0.85] {
            self.line(tip, add(tip, mul(rot(d, a), len)), 1.0, 0);
        }
    }
    /// Text in the stroke font, `h` pixels high, its top-left corner at `at`.
    fn text(&mut self, s: &str, at: P, h: f64) {
        let cell = h / 4.0;
        let lw = (h / 9.0).max(1.0);
        for (k, ch) in s.chars().enumerate() {
            let origin = add(at, (k as f64 * cell * 3.0, 0.0));
            for stroke in glyph(ch).split('|') {
                let pts: Vec<P> = stroke
                    .as_bytes()
                    .chunks(2)
                    .map(|c| {
                        add(
                            origin,
                            mul(((c[0] - b'0') as f64, (c[1] - b'0') as f64), cell),
                        )
                    })
                    .collect();
                self.polyline(&pts, lw, 0);
            }
        }
    }
}

/// Strokes of a character on a 3 × 5 grid ("xy" pairs; strokes split by '|').
fn glyph(c: char) -> &'static str {
    const LETTERS: [&str; 26] = [
        "0401102124|0222",
        "000414231202|12211000",
        "211001031423",
        "00041423211000",
        "20000424|0212",
        "200004|0212",
        "2110010314242212",
        "0004|2024|0222",
        "0020|1014|0424",
        "20231403",
        "0004|2002|1124",
        "000424",
        "0400122024",
        "04002420",
        "10010314232110",
        "040010211202",
        "10010314232110|1324",
        "040010211202|1224",
        "21100112231403",
        "0020|1014",
        "0003142320",
        "001420",
        "0004122420",
        "0024|2004",
        "0012|2012|1214",
        "00200424",
    ];
    const DIGITS: [&str; 10] = [
        "10010314232110|2103",
        "011014|0424",
        "011021220424",
        "00102112|12231404",
        "14100323",
        "20000212231404",
        "2010010314231203",
        "002004",
        "1001122110|1203142312",
        "2112011021231404",
    ];
    match c {
        'A'..='Z' => LETTERS[c as usize - 'A' as usize],
        '0'..='9' => DIGITS[c as usize - '0' as usize],
        _ => "",
    }
}

/// Interior lines of a wall at angle `a` with `spacing`.
fn hatch(x: f64, y: f64, a: f64, spacing: f64) -> bool {
    (x * a.cos() + y * a.sin()).rem_euclid(spacing) < 1.0
}

/// Draws the walls of mask `m` in `style` onto the clean image.
fn render_walls(img: &mut GrayImage, m: &Mask, style: WallStyle, rng: &mut Rng) {
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

/// Draws some of every kind of clutter, each with some probability; returns the kinds drawn.
fn draw_clutter(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) -> Vec<Clutter> {
    type Draw = fn(&mut Sheet, &Layout, &mut Rng);
    let kinds: [(Clutter, f64, Draw); 12] = [
        (Clutter::Grid, 0.15, grid),
        (Clutter::Frame, 0.5, frame),
        (Clutter::Contours, 0.25, contours),
        (Clutter::Hachures, 0.45, hachures),
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
    for (kind, p, f) in kinds {
        if rng.random_bool(p) {
            f(sheet, lay, rng);
            drawn.push(kind);
        }
    }
    drawn
}

fn size(lay: &Layout) -> P {
    (lay.main.w as f64, lay.main.h as f64)
}

fn random_point(rng: &mut Rng, lay: &Layout) -> P {
    let (w, h) = size(lay);
    (u(rng, 0.0, w), u(rng, 0.0, h))
}

fn random_word(rng: &mut Rng, n: usize, digits: bool) -> String {
    let pool = if digits {
        "0123456789"
    } else {
        "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
    };
    (0..n)
        .map(|_| pool.as_bytes()[rng.random_range(0..pool.len())] as char)
        .collect()
}

fn letter_height(rng: &mut Rng, lay: &Layout) -> f64 {
    (lay.t * u(rng, 1.0, 3.0)).clamp(6.0, 60.0)
}

fn grid(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
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

fn frame(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
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

/// A closed wobbly curve around the castle at `f` times its radius.
fn ring(lay: &Layout, f: f64, wobble: &[(f64, f64)]) -> Vec<P> {
    (0..=120)
        .map(|k| {
            let a = 2.0 * PI * k as f64 / 120.0;
            let r = f + wobble
                .iter()
                .map(|(m, ph)| 0.04 * (m * a + ph).sin())
                .sum::<f64>();
            add(
                lay.centre,
                (lay.radius.0 * r * a.cos(), lay.radius.1 * r * a.sin()),
            )
        })
        .collect()
}

fn wobble(rng: &mut Rng) -> Vec<(f64, f64)> {
    (0..3)
        .map(|_| (rng.random_range(2..6) as f64, u(rng, 0.0, 2.0 * PI)))
        .collect()
}

fn contours(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let wob = wobble(rng);
    let mut f = u(rng, 1.3, 1.4);
    for _ in 0..rng.random_range(2..=5) {
        sheet.polyline(&ring(lay, f, &wob), 1.0, 0);
        f += u(rng, 0.08, 0.2);
    }
}

/// A band of short strokes perpendicular to a curve around the castle (a moat or slope).
fn hachures(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    let wob = wobble(rng);
    let curve = ring(lay, u(rng, 1.3, 1.45), &wob);
    let band = lay.radius.0.min(lay.radius.1) * u(rng, 0.08, 0.2);
    let (sp, lw) = (u(rng, 2.5, 6.0), u(rng, 1.0, 1.6));
    let mut k = 0;
    for s in curve.windows(2) {
        let d = sub(s[1], s[0]);
        let len = d.0.hypot(d.1);
        let out = mul(inward(s[0], s[1], lay.centre), -1.0);
        let mut t = 0.0;
        while t < len {
            let p = lerp(s[0], s[1], t / len);
            let l = band * if k % 2 == 0 { 1.0 } else { u(rng, 0.4, 0.7) };
            sheet.line(p, add(p, mul(out, l)), lw, 0);
            t += sp;
            k += 1;
        }
    }
}

fn dashed_lines(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
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
fn vault_ribs(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
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

fn dimension_lines(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
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

fn letters(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
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

fn words(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
    for _ in 0..rng.random_range(1..=5) {
        let n = rng.random_range(4..=9);
        let w = random_word(rng, n, false);
        let p = random_point(rng, lay);
        sheet.text(&w, p, letter_height(rng, lay) * 0.7);
    }
}

fn scale_bar(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
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

fn north_arrow(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
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

fn title(sheet: &mut Sheet, lay: &Layout, rng: &mut Rng) {
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

/// Paper tone and texture, grey ink, stains, blur, quantisation and a JPEG round trip.
fn degrade(img: &mut GrayImage, rng: &mut Rng) {
    let (paper, ink) = (u(rng, 195.0, 250.0), u(rng, 0.0, 90.0));
    let tone = paper_tone(rng, img.width() as usize, img.height() as usize);
    let (noise, key) = (u(rng, 0.0, 12.0), rng.random::<u64>());
    for (i, px) in img.as_mut().iter_mut().enumerate() {
        let h = splitmix(key ^ i as u64);
        let sum: u64 = (0..3).map(|k| (h >> (k * 21)) & 0x1f_ffff).sum();
        let n = (sum as f64 / 0x1f_ffff as f64 - 1.5) * 2.0 * noise;
        let v = ink + (paper + tone[i] as f64 - ink) * *px as f64 / 255.0 + n;
        *px = v.clamp(0.0, 255.0) as u8;
    }
    let sigma = u(rng, 0.0, 1.5) as f32;
    if sigma > 0.3 {
        *img = imageproc::filter::gaussian_blur_f32(img, sigma);
    }
    if rng.random_bool(0.25) {
        img.as_mut()
            .iter_mut()
            .for_each(|p| *p = (*p & 0xf0) | (*p >> 4));
    }
    if rng.random_bool(0.5) {
        jpeg(img, rng.random_range(30..=90));
    }
}

/// Low-frequency brightness variation (three plane waves) less a few soft stains.
fn paper_tone(rng: &mut Rng, w: usize, h: usize) -> Vec<f32> {
    let mut tone = vec![0f32; w * h];
    for _ in 0..3 {
        let (fx, fy) = (u(rng, 0.5, 3.0) * 2.0 * PI, u(rng, 0.5, 3.0) * 2.0 * PI);
        let (ph, a) = (u(rng, 0.0, 2.0 * PI), u(rng, 0.0, 8.0) as f32);
        let xs: Vec<(f32, f32)> = (0..w).map(|x| sc(fx * x as f64 / w as f64)).collect();
        for y in 0..h {
            let (sy, cy) = sc(fy * y as f64 / h as f64 + ph);
            for (t, (sx, cx)) in tone[y * w..(y + 1) * w].iter_mut().zip(&xs) {
                *t += a * (sx * cy + cx * sy);
            }
        }
    }
    for _ in 0..rng.random_range(0..4) {
        let c = (u(rng, 0.0, w as f64), u(rng, 0.0, h as f64));
        let (r, d) = (u(rng, 5.0, w.min(h) as f64 * 0.1), u(rng, 10.0, 40.0));
        let stain = |p: P| (-((p.0 - c.0).powi(2) + (p.1 - c.1).powi(2)) / (r * r)).exp();
        let (lo, hi) = (sub(c, (3.0 * r, 3.0 * r)), add(c, (3.0 * r, 3.0 * r)));
        scan(
            w,
            h,
            lo,
            hi,
            |_| true,
            |i| {
                let p = ((i % w) as f64, (i / w) as f64);
                tone[i] -= (d * stain(p)) as f32;
            },
        );
    }
    tone
}

fn sc(a: f64) -> (f32, f32) {
    (a.sin() as f32, a.cos() as f32)
}

fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

fn jpeg(img: &mut GrayImage, quality: u8) {
    let mut buf = Vec::new();
    let enc = JpegEncoder::new_with_quality(Cursor::new(&mut buf), quality);
    if img.write_with_encoder(enc).is_ok()
        && let Ok(d) = image::load_from_memory(&buf)
    {
        *img = d.to_luma8();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn synth_styles_same_seed_same_drawing() {
        let (a, b) = (generate(7, 300, 200), generate(7, 300, 200));
        assert_eq!(a.image, b.image);
        assert_eq!(a.walls, b.walls);
        let c = generate(8, 300, 200);
        assert!(a.image != c.image && a.walls != c.walls);
    }

    #[test]
    fn synth_styles_wall_share_in_range() {
        for seed in 0..50 {
            let p = generate_with(
                seed,
                400,
                300,
                &StyleChoice {
                    clean: true,
                    ..Default::default()
                },
            );
            let share = p.walls.pixels().filter(|v| v.0[0] == 255).count() as f64 / (400.0 * 300.0);
            assert!(
                (0.01..0.4).contains(&share),
                "seed {seed}: wall share {share}"
            );
        }
    }

    #[test]
    fn synth_styles_solid_walls_dark_and_clutter_outside() {
        let choice = StyleChoice {
            walls: Some(WallStyle::Solid),
            clean: true,
            ..Default::default()
        };
        for seed in 0..10 {
            let (sheet, style) = draw(seed, 500, 400, &choice);
            assert!(style.second.is_none());
            let walls = sheet.truth.count();
            let dark = (0..sheet.truth.m.len())
                .filter(|&i| sheet.truth.m[i] && sheet.img.as_raw()[i] < 60)
                .count();
            assert!(
                dark as f64 >= 0.99 * walls as f64,
                "seed {seed}: {dark} of {walls}"
            );
            assert!(sheet.clutter.count() > 0, "seed {seed}: no clutter");
            assert!(
                !sheet
                    .truth
                    .m
                    .iter()
                    .zip(&sheet.clutter.m)
                    .any(|(a, b)| *a && *b)
            );
        }
    }

    #[test]
    fn synth_styles_outlined_truth_covers_paper() {
        let choice = StyleChoice {
            walls: Some(WallStyle::Outlined),
            thickness: Some(10.0),
            clean: true,
        };
        for seed in 0..5 {
            let p = generate_with(seed, 500, 400, &choice);
            let truth: Vec<u8> = p
                .walls
                .as_raw()
                .iter()
                .zip(p.image.as_raw())
                .filter(|(t, _)| **t == 255)
                .map(|(_, v)| *v)
                .collect();
            let light = truth.iter().filter(|v| **v > 200).count() as f64 / truth.len() as f64;
            assert!(light > 0.3, "seed {seed}: light share {light}");
            assert!(light < 0.9, "seed {seed}: light share {light}");
        }
    }

    #[test]
    fn synth_styles_degraded_solid_walls_stay_darker_than_paper() {
        let choice = StyleChoice {
            walls: Some(WallStyle::Solid),
            ..Default::default()
        };
        for seed in 0..10 {
            let p = generate_with(seed, 400, 300, &choice);
            let (mut sum, mut n) = ([0f64; 2], [0f64; 2]);
            for (t, v) in p.walls.as_raw().iter().zip(p.image.as_raw()) {
                let k = (*t == 255) as usize;
                sum[k] += *v as f64;
                n[k] += 1.0;
            }
            let (paper, wall) = (sum[0] / n[0], sum[1] / n[1]);
            assert!(
                wall + 60.0 < paper,
                "seed {seed}: walls {wall:.0}, rest {paper:.0}"
            );
        }
    }

    #[test]
    fn synth_styles_every_style_occurs() {
        let seen: Vec<WallStyle> = (0..40).map(|s| generate(s, 200, 150).style.walls).collect();
        for style in WALL_STYLES {
            assert!(seen.contains(&style), "{style:?} never drawn");
        }
    }

    #[test]
    fn synth_styles_sizes() {
        for (w, h) in [(300, 200), (2000, 1500)] {
            let p = generate(3, w, h);
            assert_eq!(p.image.dimensions(), (w, h));
            assert_eq!(p.walls.dimensions(), (w, h));
        }
    }
}
