//! Accuracy against ground-truth label images (0 background, 1 wall, 2 window) and simulated
//! users: one who draws small training boxes inside ground-truth regions (issue 4's
//! evaluation), one who marks whole windows (issue 21).

use std::collections::BTreeMap;

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::classify::{Class, Training};
use crate::error::{FacadeError, Result};
use crate::search::Integral;

/// Ground-truth value of pixels left out of every measure (void / unknown).
pub const IGNORE: u8 = 255;

/// CMP label colours → 0 background, 1 wall, 2 window (the masks are palette PNGs the image
/// crate expands to RGB; every class but background and window counts as wall).
pub const CMP_PALETTE: [([u8; 3], u8); 12] = [
    ([0, 0, 170], 0),
    ([0, 0, 255], 1),
    ([0, 85, 255], 2),
    ([0, 170, 255], 1),
    ([0, 255, 255], 1),
    ([85, 255, 170], 1),
    ([170, 255, 85], 1),
    ([255, 255, 0], 1),
    ([255, 170, 0], 1),
    ([255, 85, 0], 1),
    ([255, 0, 0], 1),
    ([170, 0, 0], 1),
];

/// A CMP label image as ground-truth classes; colours outside [`CMP_PALETTE`] are [`IGNORE`].
pub fn cmp_classes(img: &image::RgbImage) -> Vec<u8> {
    img.pixels()
        .map(|p| {
            CMP_PALETTE
                .iter()
                .find(|(c, _)| *c == p.0)
                .map_or(IGNORE, |(_, l)| *l)
        })
        .collect()
}

/// Fraction of (non-ignored) pixels whose labels agree.
pub fn pixel_accuracy(pred: &[u8], truth: &[u8]) -> f64 {
    let (mut same, mut n) = (0usize, 0usize);
    for (a, b) in pred.iter().zip(truth) {
        if *b != IGNORE {
            n += 1;
            same += (a == b) as usize;
        }
    }
    same as f64 / n.max(1) as f64
}

/// Intersection over union of one class; `None` when neither labelling has it.
pub fn class_iou(pred: &[u8], truth: &[u8], class: Class) -> Option<f64> {
    let c = class as u8;
    let (mut inter, mut union) = (0usize, 0usize);
    for (a, b) in pred.iter().zip(truth).filter(|(_, b)| **b != IGNORE) {
        let (p, t) = (*a == c, *b == c);
        inter += (p && t) as usize;
        union += (p || t) as usize;
    }
    (union > 0).then(|| inter as f64 / union as f64)
}

/// Up to `per_class` boxes of side `side` per class, each entirely inside pixels of that class in
/// `truth` (w × h). Like a user picking representative regions, the boxes are spread out: from up
/// to 300 seeded random valid positions (at most 5000 tries), the first is taken, then each next
/// one is the candidate farthest from those already chosen. Classes with no room are left out.
pub fn simulate_user(
    truth: &[u8],
    w: usize,
    h: usize,
    per_class: usize,
    side: usize,
    seed: u64,
) -> Result<Training> {
    simulate_user_inside(truth, w, h, per_class, side, 0, seed)
}

/// [`simulate_user`], but a user who keeps each box `margin` pixels clear of the class's
/// border, as one marks the middle of a window rather than its frame. Where no position has
/// that margin the margin is halved (down to 0), so small regions still get boxes.
pub fn simulate_user_inside(
    truth: &[u8],
    w: usize,
    h: usize,
    per_class: usize,
    side: usize,
    margin: usize,
    seed: u64,
) -> Result<Training> {
    if truth.len() != w * h || w < side || h < side || side == 0 {
        return Err(FacadeError::BadTraining(
            "ground truth too small for the boxes".into(),
        ));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut classes = BTreeMap::new();
    for class in Class::ALL {
        let mask: Vec<f64> = truth
            .iter()
            .map(|&l| (l == class as u8) as u8 as f64)
            .collect();
        let integral = Integral::new(&mask, w, h);
        let mut cands: Vec<(f64, f64)> = Vec::new();
        let mut m = margin;
        loop {
            let outer = side + 2 * m;
            if w >= outer && h >= outer {
                let full = (outer * outer) as f64;
                for _ in 0..5000 {
                    if cands.len() >= 300 {
                        break;
                    }
                    let (x, y) = (
                        rng.random_range(0..=w - outer),
                        rng.random_range(0..=h - outer),
                    );
                    if integral.sum(x, y, x + outer, y + outer) == full {
                        cands.push(((x + m) as f64, (y + m) as f64));
                    }
                }
            }
            if cands.len() >= per_class || m == 0 {
                break;
            }
            cands.clear();
            m /= 2;
        }
        let mut chosen: Vec<(f64, f64)> = Vec::new();
        while chosen.len() < per_class.min(cands.len()) {
            let next = if chosen.is_empty() {
                cands[0]
            } else {
                *cands
                    .iter()
                    .max_by(|a, b| {
                        let d = |p: &&(f64, f64)| {
                            chosen
                                .iter()
                                .map(|c| (c.0 - p.0).hypot(c.1 - p.1))
                                .fold(f64::INFINITY, f64::min)
                        };
                        d(a).total_cmp(&d(b))
                    })
                    .unwrap_or(&cands[0])
            };
            chosen.push(next);
        }
        let s = side as f64;
        let boxes: Vec<[f64; 4]> = chosen.iter().map(|&(x, y)| [x, y, x + s, y + s]).collect();
        if !boxes.is_empty() {
            classes.insert(class, boxes);
        }
    }
    Ok(Training {
        classes,
        ..Default::default()
    })
}

/// A user who marks whole windows: the bounding boxes ([x0, y0, x1, y1], exclusive ends) of up
/// to `windows` connected components (8-connected) of the window class in `truth`, spread out
/// (seeded farthest-point choice among components at least a quarter of the median
/// component's area, so that window fragments and slivers are not picked), and, for the other
/// classes, the `side` × `side` boxes of [`simulate_user`]. The windows are
/// [`Training::whole_windows`]; the user draws no other window box.
pub fn simulate_window_user(
    truth: &[u8],
    w: usize,
    h: usize,
    windows: usize,
    per_class: usize,
    side: usize,
    seed: u64,
) -> Result<Training> {
    let mut t = simulate_user(truth, w, h, per_class, side, seed)?;
    let comps =
        raster::components::components_where(w, h, raster::components::Connectivity::Eight, |i| {
            truth[i] == Class::Window as u8
        });
    let mut sizes: Vec<usize> = comps.sizes[1..].to_vec();
    sizes.sort_unstable();
    let median = sizes.get(sizes.len() / 2).copied().unwrap_or(0);
    let mut cands: Vec<[f64; 4]> = (1..comps.sizes.len())
        .filter(|&l| comps.sizes[l] * 4 >= median && comps.sizes[l] > 0)
        .map(|l| {
            let b = comps.bbox[l];
            [
                b[0] as f64,
                b[1] as f64,
                b[2] as f64 + 1.0,
                b[3] as f64 + 1.0,
            ]
        })
        .collect();
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x77);
    let centre = |b: &[f64; 4]| ((b[0] + b[2]) / 2.0, (b[1] + b[3]) / 2.0);
    let mut chosen: Vec<[f64; 4]> = Vec::new();
    if !cands.is_empty() {
        chosen.push(cands.swap_remove(rng.random_range(0..cands.len())));
    }
    while chosen.len() < windows && !cands.is_empty() {
        let far = |b: &[f64; 4]| {
            let (x, y) = centre(b);
            chosen
                .iter()
                .map(|c| {
                    let (cx, cy) = centre(c);
                    (cx - x).hypot(cy - y)
                })
                .fold(f64::INFINITY, f64::min)
        };
        let (i, _) = cands
            .iter()
            .enumerate()
            .max_by(|a, b| far(a.1).total_cmp(&far(b.1)))
            .expect("not empty");
        chosen.push(cands.swap_remove(i));
    }
    // The whole windows replace the small window boxes.
    t.classes.remove(&Class::Window);
    t.whole_windows = chosen;
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn metrics_on_a_literal_case() {
        let t = [0, 1, 2, 2];
        let p = [0, 1, 2, 1];
        assert_eq!(pixel_accuracy(&p, &t), 0.75);
        assert_eq!(class_iou(&p, &t, Class::Window), Some(0.5));
        assert_eq!(class_iou(&[0, 0], &[0, 0], Class::Window), None);
        assert_eq!(pixel_accuracy(&[2, 0], &[IGNORE, 0]), 1.0);
    }

    #[test]
    fn simulated_boxes_lie_inside_their_class() {
        let (w, h) = (20, 10);
        let truth: Vec<u8> = (0..w * h).map(|i| if i % w < 10 { 1 } else { 2 }).collect();
        let t = simulate_user(&truth, w, h, 3, 3, 1).unwrap();
        assert!(!t.classes.contains_key(&Class::Background));
        for b in &t.classes[&Class::Window] {
            assert!(b[0] >= 10.0 && b[2] <= 20.0);
        }
        assert_eq!(t.classes[&Class::Wall].len(), 3);
    }

    #[test]
    fn boxes_keep_their_margin_where_they_can() {
        // Window class: columns 10..30 of a 40 x 20 image; a 4-px box with a 5-px margin must
        // start at x in 15..=21; the wall (columns 0..10 and 30..40) is too thin for that
        // margin and gets boxes with a smaller one.
        let (w, h) = (40, 20);
        let truth: Vec<u8> = (0..w * h)
            .map(|i| if (10..30).contains(&(i % w)) { 2 } else { 1 })
            .collect();
        let t = simulate_user_inside(&truth, w, h, 3, 4, 5, 1).unwrap();
        for b in &t.classes[&Class::Window] {
            assert!(
                b[0] >= 15.0 && b[2] <= 25.0 && b[1] >= 5.0 && b[3] <= 15.0,
                "{b:?}"
            );
        }
        assert_eq!(t.classes[&Class::Wall].len(), 3);
        for b in &t.classes[&Class::Wall] {
            assert!(b[2] <= 10.0 || b[0] >= 30.0, "{b:?}");
        }
    }

    #[test]
    fn window_user_marks_whole_spread_windows() {
        // A 60 x 20 wall with windows at x 2..8, 20..26, 40..46, 52..58 (rows 5..15) and a
        // one-pixel speck at (30, 2), too small to be chosen.
        let (w, h) = (60, 20);
        let mut truth = vec![1u8; w * h];
        for x0 in [2, 20, 40, 52] {
            for y in 5..15 {
                for x in x0..x0 + 6 {
                    truth[y * w + x] = 2;
                }
            }
        }
        truth[2 * w + 30] = 2;
        let t = simulate_window_user(&truth, w, h, 2, 3, 3, 5).unwrap();
        let wins = &t.whole_windows;
        assert_eq!(wins.len(), 2);
        assert!(
            !t.classes.contains_key(&Class::Window),
            "only whole windows"
        );
        for b in wins {
            assert!([2.0, 20.0, 40.0, 52.0].contains(&b[0]), "{b:?}");
            assert_eq!((b[2] - b[0], b[1], b[3]), (6.0, 5.0, 15.0));
        }
        // Spread out: the second is the window farthest from the first.
        let d = (wins[0][0] - wins[1][0]).abs();
        assert!(d >= 32.0, "{wins:?}");
        assert_eq!(t.classes[&Class::Wall].len(), 3);
        // Asking for more windows than there are gives them all.
        let all = simulate_window_user(&truth, w, h, 9, 3, 3, 5).unwrap();
        assert_eq!(all.whole_windows.len(), 4);
    }
}
