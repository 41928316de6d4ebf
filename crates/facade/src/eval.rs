//! Accuracy against ground-truth label images (0 background, 1 wall, 2 window) and a simulated
//! user who draws small training boxes inside ground-truth regions (issue 4's evaluation).

use std::collections::BTreeMap;

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::classify::{Class, Training};
use crate::error::{FacadeError, Result};
use crate::search::Integral;

/// Ground-truth value of pixels left out of every measure (void / unknown).
pub const IGNORE: u8 = 255;

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
        let full = (side * side) as f64;
        let mut cands: Vec<(f64, f64)> = Vec::new();
        for _ in 0..5000 {
            if cands.len() >= 300 {
                break;
            }
            let (x, y) = (
                rng.random_range(0..=w - side),
                rng.random_range(0..=h - side),
            );
            if integral.sum(x, y, x + side, y + side) == full {
                cands.push((x as f64, y as f64));
            }
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
            classes.insert(class.name().to_string(), boxes);
        }
    }
    Ok(Training { classes })
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
        assert!(!t.classes.contains_key("background"));
        for b in &t.classes["window"] {
            assert!(b[0] >= 10.0 && b[2] <= 20.0);
        }
        assert_eq!(t.classes["wall"].len(), 3);
    }
}
