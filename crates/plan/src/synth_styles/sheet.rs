//! The clean drawing (paper 255, ink 0) with its wall truth and the mask of clutter drawn,
//! and the clutter pens: lines, dashes, arrow heads and a stroke font. Clutter never inks a
//! wall pixel.

use std::f64::consts::PI;

use image::{GrayImage, Luma};

use super::geometry::{Mask, P, add, bbox, lerp, mul, rot, scan, seg_dist, sub, unit};
use super::layout::Layout;

/// The clean drawing: paper 255, ink 0, the truth, where clutter was drawn and the zones of
/// the hachured scarps (their strokes and the paper between them).
pub(super) struct Sheet {
    pub(super) img: GrayImage,
    pub(super) truth: Mask,
    pub(super) clutter: Mask,
    pub(super) scarps: Mask,
}

impl Sheet {
    pub(super) fn new(w: u32, h: u32, lay: &Layout) -> Sheet {
        Sheet {
            img: GrayImage::from_pixel(w, h, Luma([255])),
            truth: lay.main.or(&lay.inner),
            clutter: Mask::new(w, h),
            scarps: Mask::new(w, h),
        }
    }
    /// Marks pixel i, off the walls, as inside a hachured scarp.
    pub(super) fn scarp(&mut self, i: usize) {
        if !self.truth.m[i] {
            self.scarps.m[i] = true;
        }
    }
    /// Marks the pixels within `r` of the segment a–b, off the walls, as inside a scarp.
    pub(super) fn scarp_band(&mut self, a: P, b: P, r: f64) {
        self.near_segment(a, b, r)
            .into_iter()
            .for_each(|i| self.scarp(i));
    }
    /// The pixels whose centres lie within `r` of the segment a–b.
    fn near_segment(&self, a: P, b: P, r: f64) -> Vec<usize> {
        let mut hits = Vec::new();
        let (lo, hi) = bbox(&[a, b], r + 1.0);
        scan(
            self.truth.w,
            self.truth.h,
            lo,
            hi,
            |p| seg_dist(p, a, b) <= r,
            |i| hits.push(i),
        );
        hits
    }
    /// Clutter ink of value `v` at pixel i, never on a wall.
    pub(super) fn ink(&mut self, i: usize, v: u8) {
        if !self.truth.m[i] {
            self.clutter.m[i] = true;
            let px = &mut self.img.as_mut()[i];
            *px = (*px).min(v);
        }
    }
    pub(super) fn line(&mut self, a: P, b: P, lw: f64, v: u8) {
        let r = (lw / 2.0).max(0.55);
        self.near_segment(a, b, r)
            .into_iter()
            .for_each(|i| self.ink(i, v));
    }
    pub(super) fn polyline(&mut self, pts: &[P], lw: f64, v: u8) {
        pts.windows(2).for_each(|s| self.line(s[0], s[1], lw, v));
    }
    /// A dashed (or, with `on` ≈ 0, dotted) polyline.
    pub(super) fn dashed(&mut self, pts: &[P], on: f64, off: f64, lw: f64) {
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
    pub(super) fn arrow_head(&mut self, tip: P, dir: P, len: f64) {
        let d = unit(dir);
        for a in [PI * 0.85, -PI * 0.85] {
            self.line(tip, add(tip, mul(rot(d, a), len)), 1.0, 0);
        }
    }
    /// Text in the stroke font, `h` pixels high, its top-left corner at `at`.
    pub(super) fn text(&mut self, s: &str, at: P, h: f64) {
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
pub(super) fn glyph(c: char) -> &'static str {
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
