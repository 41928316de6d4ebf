//! Windows found as repeats of one the user drew (issue 21; not in the dissertation, whose user
//! draws boxes inside each class). A training box that covers a whole window is a template:
//! its normalised cross-correlation (NCC) with the image proposes the other windows, kept by
//! an acceptance threshold and non-maximum suppression, and their centres clustered into grid
//! columns and rows. Pure: image and boxes in, boxes out.
//!
//! The NCC is computed directly on a copy of the image shrunk so that the template's longer
//! side is about [`RepeatParams::coarse_side`] pixels, with summed-area tables for each
//! window's mean and variance, then refined at full resolution around each coarse peak: on a
//! 1-Mpx façade with a 60 × 90-px window this is a few million multiply-adds instead of the
//! ~5·10⁹ of a full-resolution correlation (imageproc's `match_template` is such a direct
//! correlation).

use image::RgbImage;
use rayon::prelude::*;

use crate::classify::{Class, LogLikelihoods};
use crate::grow::GrowParams;

/// Settings of [`find_repeats`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RepeatParams {
    /// Proposals whose NCC (mean over R, G, B) is below this are dropped.
    pub threshold: f64,
    /// The template's longer side after shrinking, pixels (the coarse search's resolution).
    pub coarse_side: usize,
    /// Two proposals whose boxes overlap by more than this intersection-over-union are one
    /// (the weaker is suppressed).
    pub max_overlap: f64,
    /// Most proposals per template.
    pub max_proposals: usize,
    /// The template is the box grown by this fraction of its size on every side (a window's
    /// frame and the wall around it carry most of its pattern; a uniform pane alone matches
    /// nothing); proposals are shrunk back to the box's size.
    pub context: f64,
    /// [`evidence`]'s weight in [`crate::parse_photo`]: nats added to the window class's
    /// ln p inside every proposal before the search. 0: the repeat step is skipped.
    pub evidence: f64,
    /// When the user drew no whole window: grow the small window boxes into whole windows on
    /// a first map ([`crate::grow`]), classify again with them as whole windows and take them
    /// as the templates. `None`: small boxes stay as drawn (the text's user).
    pub grow: Option<GrowParams>,
}

impl Default for RepeatParams {
    fn default() -> Self {
        RepeatParams {
            threshold: 0.7,
            coarse_side: 16,
            max_overlap: 0.2,
            max_proposals: 200,
            context: 0.15,
            evidence: REPEAT_EVIDENCE,
            grow: Some(GrowParams::default()),
        }
    }
}

/// Default of [`RepeatParams::evidence`] (measured in docs/facade.md).
pub const REPEAT_EVIDENCE: f64 = 2.0;

/// Repeats as evidence for the search (issue 21): `weight` nats added to the window class's
/// ln p at every pixel inside a proposal (the user's own boxes included), so the search's
/// window − wall ratio rises there. A class map that is missing is left alone.
pub fn evidence(ll: &mut LogLikelihoods, r: &Repeats, weight: f64) {
    let (w, h) = (ll.width, ll.height);
    let Some(win) = ll.maps[Class::Window as usize].as_mut() else {
        return;
    };
    let mut inside = vec![false; w * h];
    for b in &r.windows {
        let x0 = b[0].max(0.0).round() as usize;
        let y0 = b[1].max(0.0).round() as usize;
        let x1 = (b[2].round().max(0.0) as usize).min(w);
        let y1 = (b[3].round().max(0.0) as usize).min(h);
        for y in y0..y1.max(y0) {
            for x in x0..x1.max(x0) {
                inside[y * w + x] = true;
            }
        }
    }
    for (v, _) in win.iter_mut().zip(&inside).filter(|(_, i)| **i) {
        *v += weight as f32;
    }
}

/// What [`find_repeats`] found: window boxes [x0, y0, x1, y1] (the templates included) with
/// their NCC, and the grid their centres form.
#[derive(Debug, Clone, PartialEq)]
pub struct Repeats {
    pub windows: Vec<[f64; 4]>,
    pub scores: Vec<f64>,
    /// Column centres (x), left to right, and row centres (y), top to bottom: the clusters of
    /// the windows' centres (one cluster per run closer than half a window).
    pub columns: Vec<f64>,
    pub rows: Vec<f64>,
}

/// A single-channel image plane.
struct Plane {
    w: usize,
    h: usize,
    v: Vec<f32>,
}

impl Plane {
    fn channel(img: &RgbImage, c: usize) -> Plane {
        Plane {
            w: img.width() as usize,
            h: img.height() as usize,
            v: img.pixels().map(|p| p.0[c] as f32).collect(),
        }
    }

    /// Mean over s × s blocks (the last partial block dropped).
    fn shrink(&self, s: usize) -> Plane {
        if s <= 1 {
            return Plane {
                w: self.w,
                h: self.h,
                v: self.v.clone(),
            };
        }
        let (w, h) = (self.w / s, self.h / s);
        let mut v = vec![0f32; w * h];
        for y in 0..h * s {
            for x in 0..w * s {
                v[(y / s) * w + x / s] += self.v[y * self.w + x];
            }
        }
        let k = 1.0 / (s * s) as f32;
        v.iter_mut().for_each(|p| *p *= k);
        Plane { w, h, v }
    }

    fn crop(&self, x0: usize, y0: usize, tw: usize, th: usize) -> Vec<f32> {
        (y0..y0 + th)
            .flat_map(|y| {
                self.v[y * self.w + x0..y * self.w + x0 + tw]
                    .iter()
                    .copied()
            })
            .collect()
    }
}

/// Summed-area tables of values and squares (f64: sums of ~10⁶ squared bytes).
struct Sat {
    w: usize,
    s1: Vec<f64>,
    s2: Vec<f64>,
}

impl Sat {
    fn new(p: &Plane) -> Sat {
        let w = p.w + 1;
        let mut s1 = vec![0f64; w * (p.h + 1)];
        let mut s2 = s1.clone();
        for y in 0..p.h {
            let (mut r1, mut r2) = (0f64, 0f64);
            for x in 0..p.w {
                let v = p.v[y * p.w + x] as f64;
                r1 += v;
                r2 += v * v;
                s1[(y + 1) * w + x + 1] = s1[y * w + x + 1] + r1;
                s2[(y + 1) * w + x + 1] = s2[y * w + x + 1] + r2;
            }
        }
        Sat { w, s1, s2 }
    }

    fn sums(&self, x: usize, y: usize, tw: usize, th: usize) -> (f64, f64) {
        let at = |s: &[f64], x: usize, y: usize| s[y * self.w + x];
        let f =
            |s: &[f64]| at(s, x + tw, y + th) - at(s, x, y + th) - at(s, x + tw, y) + at(s, x, y);
        (f(&self.s1), f(&self.s2))
    }
}

/// The zero-mean template and its norm; `None` for a constant template.
fn centred(t: &[f32]) -> Option<(Vec<f32>, f64)> {
    let mean = t.iter().map(|&v| v as f64).sum::<f64>() / t.len().max(1) as f64;
    let c: Vec<f32> = t.iter().map(|&v| (v as f64 - mean) as f32).collect();
    let norm = c.iter().map(|&v| (v as f64).powi(2)).sum::<f64>().sqrt();
    (norm > 1e-9).then_some((c, norm))
}

/// NCC of the template at one position: Σ I·T′ / (‖T′‖ · sqrt(Σ I² − (Σ I)²/n)), T′ the
/// zero-mean template; 0 where the image window is constant.
fn ncc_at(
    p: &Plane,
    sat: &Sat,
    t: &(Vec<f32>, f64),
    tw: usize,
    th: usize,
    x: usize,
    y: usize,
) -> f64 {
    let (s1, s2) = sat.sums(x, y, tw, th);
    let n = (tw * th) as f64;
    let var = s2 - s1 * s1 / n;
    if var <= 1e-9 * n {
        return 0.0;
    }
    let mut dot = 0f64;
    for ty in 0..th {
        let row = &p.v[(y + ty) * p.w + x..(y + ty) * p.w + x + tw];
        let trow = &t.0[ty * tw..(ty + 1) * tw];
        dot += row.iter().zip(trow).map(|(a, b)| a * b).sum::<f32>() as f64;
    }
    (dot / (t.1 * var.sqrt())).clamp(-1.0, 1.0)
}

/// Normalised cross-correlation of a `tw` × `th` template (row-major) with a `w` × `h` image
/// plane, at every position where the template fits: ((w − tw + 1) × (h − th + 1) values,
/// row-major), in [−1, 1]; 0 where the template or the image window is constant.
pub fn ncc(image: &[f32], w: usize, h: usize, template: &[f32], tw: usize, th: usize) -> Vec<f64> {
    if tw == 0 || th == 0 || tw > w || th > h || template.len() != tw * th || image.len() != w * h {
        return Vec::new();
    }
    let p = Plane {
        w,
        h,
        v: image.to_vec(),
    };
    let (ow, oh) = (w - tw + 1, h - th + 1);
    let Some(t) = centred(template) else {
        return vec![0.0; ow * oh];
    };
    let sat = Sat::new(&p);
    (0..ow * oh)
        .map(|i| ncc_at(&p, &sat, &t, tw, th, i % ow, i / ow))
        .collect()
}

/// The other windows like the template boxes `templates` ([x0, y0, x1, y1], each covering one
/// whole window) in `img`, with the templates themselves: every template's NCC (mean over the
/// three colour channels) at a coarse scale, peaks above `p.threshold` refined at full
/// resolution, and non-maximum suppression over all templates' proposals.
pub fn find_repeats(img: &RgbImage, templates: &[[f64; 4]], p: &RepeatParams) -> Repeats {
    let (w, h) = (img.width() as usize, img.height() as usize);
    let planes: Vec<Plane> = (0..3).map(|c| Plane::channel(img, c)).collect();
    let mut found: Vec<([f64; 4], f64)> = Vec::new();
    for t in templates {
        if !(t[2] - t[0] >= 2.0 && t[3] - t[1] >= 2.0) {
            continue;
        }
        found.push((*t, 1.0));
        let (gx, gy) = (p.context * (t[2] - t[0]), p.context * (t[3] - t[1]));
        let x0 = (t[0] - gx).max(0.0).round() as usize;
        let y0 = (t[1] - gy).max(0.0).round() as usize;
        let x1 = ((t[2] + gx).round().max(0.0) as usize).min(w);
        let y1 = ((t[3] + gy).round().max(0.0) as usize).min(h);
        if x1 < x0 + 2 || y1 < y0 + 2 {
            continue;
        }
        // The box inside the grown template.
        let inner = [
            t[0] - x0 as f64,
            t[1] - y0 as f64,
            t[2] - x0 as f64,
            t[3] - y0 as f64,
        ];
        let (tw, th) = (x1 - x0, y1 - y0);
        let s = (tw.max(th) / p.coarse_side.max(1)).max(1);
        let (ctw, cth) = (tw / s, th / s);
        let (cw, ch) = (w / s, h / s);
        if ctw < 2 || cth < 2 || ctw > cw || cth > ch {
            continue;
        }
        // Coarse: mean NCC over the channels at every shrunk position.
        let small: Vec<Plane> = planes.iter().map(|q| q.shrink(s)).collect();
        let (ow, oh) = (cw - ctw + 1, ch - cth + 1);
        let mut score = vec![0f64; ow * oh];
        let mut used = 0;
        for q in &small {
            let Some(tc) = centred(&q.crop(x0 / s, y0 / s, ctw, cth)) else {
                continue;
            };
            used += 1;
            let sat = Sat::new(q);
            score.par_iter_mut().enumerate().for_each(|(i, sc)| {
                *sc += ncc_at(q, &sat, &tc, ctw, cth, i % ow, i / ow);
            });
        }
        if used == 0 {
            continue;
        }
        score.iter_mut().for_each(|v| *v /= used as f64);
        // Coarse peaks: 3 × 3 local maxima above a slightly lower threshold (the shrunk
        // image blurs the match), strongest first.
        let mut peaks: Vec<(usize, f64)> = (0..ow * oh)
            .filter(|&i| {
                let (x, y) = (i % ow, i / ow);
                score[i] >= p.threshold - 0.1
                    && (y.saturating_sub(1)..(y + 2).min(oh)).all(|yy| {
                        (x.saturating_sub(1)..(x + 2).min(ow))
                            .all(|xx| score[yy * ow + xx] <= score[i])
                    })
            })
            .map(|i| (i, score[i]))
            .collect();
        peaks.sort_by(|a, b| b.1.total_cmp(&a.1));
        peaks.truncate(p.max_proposals * 4);
        // Full resolution around each coarse peak.
        let full: Vec<(Sat, (Vec<f32>, f64))> = planes
            .iter()
            .filter_map(|q| Some((Sat::new(q), centred(&q.crop(x0, y0, tw, th))?)))
            .collect();
        if full.is_empty() {
            continue;
        }
        let fine = |x: usize, y: usize| -> f64 {
            planes
                .iter()
                .zip(&full)
                .map(|(q, (sat, t))| ncc_at(q, sat, t, tw, th, x, y))
                .sum::<f64>()
                / full.len() as f64
        };
        // The peaks refined in parallel, kept in their order: the same result on any number
        // of threads.
        let refined: Vec<(f64, usize, usize)> = peaks
            .par_iter()
            .map(|&(i, _)| {
                let (cx, cy) = ((i % ow) * s, (i / ow) * s);
                // Every other position within the coarse pixel's reach, then every position
                // next to the best of them: a quarter of the correlations of a full scan.
                let look = |xs: std::ops::RangeInclusive<usize>,
                            ys: std::ops::RangeInclusive<usize>,
                            step: usize,
                            mut best: (f64, usize, usize)| {
                    for y in ys.step_by(step) {
                        for x in xs.clone().step_by(step) {
                            let v = fine(x, y);
                            if v > best.0 {
                                best = (v, x, y);
                            }
                        }
                    }
                    best
                };
                let coarse = look(
                    cx.saturating_sub(s)..=(cx + s).min(w - tw),
                    cy.saturating_sub(s)..=(cy + s).min(h - th),
                    2,
                    (f64::NEG_INFINITY, 0, 0),
                );
                let (bx, by) = (coarse.1, coarse.2);
                look(
                    bx.saturating_sub(1)..=(bx + 1).min(w - tw),
                    by.saturating_sub(1)..=(by + 1).min(h - th),
                    1,
                    coarse,
                )
            })
            .collect();
        for (score, x, y) in refined {
            if score >= p.threshold {
                let (x, y) = (x as f64, y as f64);
                found.push((
                    [x + inner[0], y + inner[1], x + inner[2], y + inner[3]],
                    score,
                ));
            }
        }
    }
    // Non-maximum suppression: the templates (score 1) first, then by score.
    found.sort_by(|a, b| b.1.total_cmp(&a.1));
    let mut kept: Vec<([f64; 4], f64)> = Vec::new();
    for (b, sc) in found {
        if kept.len() >= p.max_proposals.max(templates.len()) {
            break;
        }
        if kept.iter().all(|(k, _)| iou(k, &b) <= p.max_overlap) {
            kept.push((b, sc));
        }
    }
    kept.sort_by(|a, b| (a.0[1], a.0[0]).partial_cmp(&(b.0[1], b.0[0])).unwrap());
    let mean = |f: &dyn Fn(&[f64; 4]) -> f64| {
        kept.iter().map(|(b, _)| f(b)).sum::<f64>() / kept.len().max(1) as f64
    };
    let (mw, mh) = (mean(&|b| b[2] - b[0]), mean(&|b| b[3] - b[1]));
    let columns = clusters(
        kept.iter().map(|(b, _)| (b[0] + b[2]) / 2.0).collect(),
        mw / 2.0,
    );
    let rows = clusters(
        kept.iter().map(|(b, _)| (b[1] + b[3]) / 2.0).collect(),
        mh / 2.0,
    );
    Repeats {
        windows: kept.iter().map(|k| k.0).collect(),
        scores: kept.iter().map(|k| k.1).collect(),
        columns,
        rows,
    }
}

/// Intersection over union of two boxes.
fn iou(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    let iw = (a[2].min(b[2]) - a[0].max(b[0])).max(0.0);
    let ih = (a[3].min(b[3]) - a[1].max(b[1])).max(0.0);
    let inter = iw * ih;
    let area = |r: &[f64; 4]| (r[2] - r[0]) * (r[3] - r[1]);
    inter / (area(a) + area(b) - inter).max(1e-12)
}

/// 1-D clusters: sorted values split where consecutive ones are more than `tol` apart; the
/// mean of each.
fn clusters(mut v: Vec<f64>, tol: f64) -> Vec<f64> {
    v.sort_by(|a, b| a.total_cmp(b));
    let mut out: Vec<Vec<f64>> = Vec::new();
    for x in v {
        match out.last_mut() {
            Some(c) if x - c[c.len() - 1] <= tol => c.push(x),
            _ => out.push(vec![x]),
        }
    }
    out.iter()
        .map(|c| c.iter().sum::<f64>() / c.len() as f64)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ncc_literal_cases() {
        // A 4 × 3 image; the template is its 2 × 2 top-left patch.
        let img = [1.0, 2.0, 0.0, 5.0, 3.0, 4.0, 1.0, 0.0, 0.0, 0.0, 9.0, 9.0];
        let t = [1.0, 2.0, 3.0, 4.0];
        let r = ncc(&img, 4, 3, &t, 2, 2);
        assert_eq!(r.len(), 3 * 2);
        assert!((r[0] - 1.0).abs() < 1e-9, "{r:?}");
        // Position (1, 0): window [2, 0; 4, 1], centred [0.25, -1.75; 2.25, -0.75] against
        // [-1.5, -0.5; 0.5, 1.5]: dot = -0.375 + 0.875 + 1.125 - 1.125 = 0.5,
        // norms sqrt(5) and sqrt(0.0625 + 3.0625 + 5.0625 + 0.5625) = sqrt(8.75).
        assert!((r[1] - 0.5 / (5f64 * 8.75).sqrt()).abs() < 1e-6, "{}", r[1]);
        // The negated template correlates −1 at the same place; a constant one 0 everywhere.
        let neg = ncc(&img, 4, 3, &[-1.0, -2.0, -3.0, -4.0], 2, 2);
        assert!((neg[0] + 1.0).abs() < 1e-9);
        assert!(ncc(&img, 4, 3, &[7.0; 4], 2, 2).iter().all(|&v| v == 0.0));
        // A constant image: 0 everywhere.
        let flat = ncc(&[5.0; 9], 3, 3, &t, 2, 2);
        assert!(flat.iter().all(|&v| v == 0.0));
        assert!(ncc(&img, 4, 3, &t, 5, 2).is_empty());
    }

    #[test]
    fn clusters_split_at_gaps() {
        assert_eq!(
            clusters(vec![10.0, 52.0, 11.0, 50.0, 90.0], 5.0),
            vec![10.5, 51.0, 90.0]
        );
    }
}

#[cfg(test)]
mod evidence_tests {
    use super::*;

    #[test]
    fn evidence_raises_window_inside_proposals_only() {
        let mut ll = LogLikelihoods {
            width: 10,
            height: 6,
            maps: [None, Some(vec![-1.0; 60]), Some(vec![-2.0; 60])],
        };
        let r = Repeats {
            windows: vec![[1.0, 1.0, 3.0, 4.0], [8.0, 4.0, 12.0, 9.0]],
            scores: vec![1.0, 0.8],
            columns: vec![2.0, 10.0],
            rows: vec![2.5, 6.5],
        };
        evidence(&mut ll, &r, 2.0);
        let win = ll.get(Class::Window).unwrap();
        let raised: usize = win.iter().filter(|v| **v == 0.0).count();
        assert_eq!(raised, 2 * 3 + 2 * 2);
        assert_eq!(win[10 + 1], 0.0);
        assert_eq!(win[0], -2.0);
        assert_eq!(ll.get(Class::Wall).unwrap(), &[-1.0; 60][..]);
    }
}
