//! A random forest of Gini trees, written for this use: few labelled pixels (hundreds to tens
//! of thousands), tens of features, then a prediction for every pixel of the image.
//!
//! - Training bins each feature at up to 255 quantile edges of the training values, so a split
//!   search is one pass filling a (bin × class) histogram rather than a sort per node.
//! - Classes are balanced by weight: a sample of class c weighs N / (C · n_c), so a class drawn
//!   with few boxes counts as much as one drawn with many.
//! - Each tree draws its bootstrap and feature subsets from its own generator, seeded with
//!   `seed + tree index`, and trees are built independently in parallel: the forest is the same
//!   whatever the thread count.
//! - Trees are stored as one flat array of 16-byte nodes with the leaf class distributions in
//!   a second array; prediction runs rows in parallel and, within a row, tree by tree, so one
//!   tree's nodes stay in cache across the row's pixels.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::error::{PixelClassError, Result};

mod predict;

/// Forest settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForestParams {
    pub trees: usize,
    pub max_depth: usize,
    /// Fewest training samples in a leaf.
    pub min_leaf: usize,
    /// Features tried at each split; `None`: ⌈√dim⌉.
    pub features_per_split: Option<usize>,
    /// At most this many samples of each class are kept (seeded subsample).
    pub max_per_class: usize,
    pub seed: u64,
}

impl Default for ForestParams {
    fn default() -> Self {
        ForestParams {
            trees: 64,
            max_depth: 16,
            min_leaf: 1,
            features_per_split: None,
            max_per_class: 10_000,
            seed: 0,
        }
    }
}

/// A node: an inner split (`x[feature] < threshold` goes left) or, with `feature == LEAF`, a
/// leaf whose class distribution starts at `left` in the leaf array.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
struct Node {
    feature: u32,
    threshold: f32,
    left: u32,
    right: u32,
}

const LEAF: u32 = u32::MAX;

/// The trained forest. Serialisable (serde) so that a trained model can ship with a program;
/// a deserialised forest must pass [`Forest::validate`] before it predicts.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Forest {
    pub classes: usize,
    pub dim: usize,
    nodes: Vec<Node>,
    roots: Vec<u32>,
    leaves: Vec<f32>,
}

/// Per-class probabilities, pixel-major: `data[(y * width + x) * classes + c]`; each pixel's
/// values sum to 1.
#[derive(Debug, Clone, PartialEq)]
pub struct Probabilities {
    pub width: usize,
    pub height: usize,
    pub classes: usize,
    pub data: Vec<f32>,
}

impl Probabilities {
    pub fn get(&self, x: usize, y: usize) -> &[f32] {
        let i = (y * self.width + x) * self.classes;
        &self.data[i..i + self.classes]
    }

    /// One class's map, row-major.
    pub fn class_map(&self, class: usize) -> Vec<f32> {
        self.data
            .iter()
            .skip(class)
            .step_by(self.classes)
            .copied()
            .collect()
    }

    /// The most probable class per pixel (the lower index on a tie).
    pub fn argmax(&self) -> Vec<u8> {
        self.data
            .chunks(self.classes)
            .map(|p| {
                let mut best = 0;
                for (c, &v) in p.iter().enumerate() {
                    if v > p[best] {
                        best = c;
                    }
                }
                best as u8
            })
            .collect()
    }
}

/// The binned training set: feature-major bins and each feature's edges.
struct Binned {
    bins: Vec<Vec<u8>>,
    edges: Vec<Vec<f32>>,
    labels: Vec<u16>,
    weight: Vec<f32>,
}

impl Forest {
    /// Trains on `n` samples given as rows of `dim` features (`x[i * dim..][..dim]`) with class
    /// indices `labels[i] < classes`. Every class needs at least one sample.
    pub fn train(
        x: &[f32],
        dim: usize,
        labels: &[usize],
        classes: usize,
        p: &ForestParams,
    ) -> Result<Forest> {
        if classes < 2 {
            return Err(PixelClassError::TooFewClasses { classes });
        }
        if dim == 0 || x.len() != labels.len() * dim {
            return Err(PixelClassError::BadInput {
                what: "training rows".into(),
                why: format!(
                    "{} values for {} samples of {dim} features",
                    x.len(),
                    labels.len()
                ),
            });
        }
        let mut by_class = vec![Vec::new(); classes];
        for (i, &l) in labels.iter().enumerate() {
            if l >= classes {
                return Err(PixelClassError::UnknownClass {
                    index: i,
                    class: l,
                    classes,
                });
            }
            by_class[l].push(i);
        }
        if let Some(class) = by_class.iter().position(Vec::is_empty) {
            return Err(PixelClassError::EmptyClass { class, classes });
        }
        // Cap each class (a seeded partial shuffle keeps a random subset).
        let mut rng = ChaCha8Rng::seed_from_u64(p.seed ^ 0xca9_c1a55);
        let cap = p.max_per_class.max(1);
        for v in &mut by_class {
            if v.len() > cap {
                for i in 0..cap {
                    let j = rng.random_range(i..v.len());
                    v.swap(i, j);
                }
                v.truncate(cap);
                v.sort_unstable();
            }
        }
        let kept: Vec<usize> = by_class.iter().flatten().copied().collect();
        let n = kept.len();
        let class_weight: Vec<f32> = by_class
            .iter()
            .map(|v| n as f32 / (classes as f32 * v.len() as f32))
            .collect();
        let binned = bin(x, dim, &kept, labels, &class_weight);
        let mtry = p
            .features_per_split
            .unwrap_or_else(|| (dim as f64).sqrt().ceil() as usize)
            .clamp(1, dim);
        let trees: Vec<(Vec<Node>, Vec<f32>)> = (0..p.trees.max(1))
            .into_par_iter()
            .map(|t| {
                let mut rng = ChaCha8Rng::seed_from_u64(p.seed.wrapping_add(t as u64));
                grow(&binned, classes, mtry, p, &mut rng)
            })
            .collect();
        let mut forest = Forest {
            classes,
            dim,
            nodes: Vec::new(),
            roots: Vec::new(),
            leaves: Vec::new(),
        };
        for (nodes, leaves) in trees {
            let (no, lo) = (forest.nodes.len() as u32, forest.leaves.len() as u32);
            forest.roots.push(no);
            forest.nodes.extend(nodes.into_iter().map(|mut nd| {
                if nd.feature == LEAF {
                    nd.left += lo;
                } else {
                    nd.left += no;
                    nd.right += no;
                }
                nd
            }));
            forest.leaves.extend(leaves);
        }
        Ok(forest)
    }

    pub fn trees(&self) -> usize {
        self.roots.len()
    }

    /// Checks a forest that did not come from [`Forest::train`] (a model file): every index in
    /// range, children after their parents (so every walk ends at a leaf), leaf distributions
    /// inside the leaf array. Prediction on a forest that fails this could panic or loop.
    pub fn validate(&self) -> Result<()> {
        let bad = |why: String| {
            Err(PixelClassError::BadInput {
                what: "forest".into(),
                why,
            })
        };
        if self.classes < 2 || self.dim == 0 || self.roots.is_empty() {
            return bad(format!(
                "{} classes, {} features, {} trees",
                self.classes,
                self.dim,
                self.roots.len()
            ));
        }
        let n = self.nodes.len();
        if let Some(r) = self.roots.iter().find(|&&r| r as usize >= n) {
            return bad(format!("root {r} outside {n} nodes"));
        }
        for (i, nd) in self.nodes.iter().enumerate() {
            if nd.feature == LEAF {
                if nd.left as usize + self.classes > self.leaves.len() {
                    return bad(format!("leaf node {i} points outside the leaf values"));
                }
            } else if nd.feature as usize >= self.dim
                || !nd.threshold.is_finite()
                || nd.left as usize <= i
                || nd.right as usize <= i
                || nd.left as usize >= n
                || nd.right as usize >= n
            {
                return bad(format!("node {i} is malformed"));
            }
        }
        Ok(())
    }

    pub fn nodes(&self) -> usize {
        self.nodes.len()
    }
}

/// Quantile edges per feature (at most 255, so bins fit a byte) and the samples' bins.
fn bin(x: &[f32], dim: usize, kept: &[usize], labels: &[usize], class_weight: &[f32]) -> Binned {
    let (edges, bins): (Vec<Vec<f32>>, Vec<Vec<u8>>) = (0..dim)
        .into_par_iter()
        .map(|f| {
            let vals: Vec<f32> = kept.iter().map(|&i| x[i * dim + f]).collect();
            let mut sorted = vals.clone();
            sorted.sort_unstable_by(f32::total_cmp);
            sorted.dedup();
            // Edges halfway between consecutive distinct values; with more than 256 distinct
            // values, at evenly spaced ranks.
            let gaps = sorted.len().saturating_sub(1);
            let mut e: Vec<f32> = if gaps <= 255 {
                (0..gaps)
                    .map(|k| 0.5 * (sorted[k] + sorted[k + 1]))
                    .collect()
            } else {
                (1..=255)
                    .map(|k| {
                        let j = k * gaps / 256;
                        0.5 * (sorted[j] + sorted[j + 1])
                    })
                    .collect()
            };
            e.dedup();
            // bin(v) = edges ≤ v, so "bin ≤ b" is "v < edges[b]".
            let b = vals
                .iter()
                .map(|v| e.partition_point(|edge| edge <= v) as u8)
                .collect();
            (e, b)
        })
        .unzip();
    Binned {
        bins,
        edges,
        labels: kept.iter().map(|&i| labels[i] as u16).collect(),
        weight: kept.iter().map(|&i| class_weight[labels[i]]).collect(),
    }
}

/// One tree on a bootstrap sample: depth-first, nodes in a local array (children and leaf
/// offsets local to the tree).
fn grow(
    d: &Binned,
    classes: usize,
    mtry: usize,
    p: &ForestParams,
    rng: &mut ChaCha8Rng,
) -> (Vec<Node>, Vec<f32>) {
    let n = d.labels.len();
    let mut idx: Vec<u32> = (0..n).map(|_| rng.random_range(0..n) as u32).collect();
    let dim = d.bins.len();
    let mut order: Vec<usize> = (0..dim).collect();
    let mut nodes: Vec<Node> = Vec::new();
    let mut leaves: Vec<f32> = Vec::new();
    let mut hist = vec![0f32; 256 * classes];
    let mut count = vec![0u32; 256];
    // (node slot, sample range, depth)
    nodes.push(Node {
        feature: LEAF,
        threshold: 0.0,
        left: 0,
        right: 0,
    });
    let mut stack = vec![(0usize, 0usize, n, 0usize)];
    let mut totals = vec![0f32; classes];
    while let Some((slot, lo, hi, depth)) = stack.pop() {
        let s = &idx[lo..hi];
        totals.fill(0.0);
        for &i in s {
            totals[d.labels[i as usize] as usize] += d.weight[i as usize];
        }
        let pure = totals.iter().filter(|&&t| t > 0.0).count() <= 1;
        let split = if pure || depth >= p.max_depth || s.len() < 2 * p.min_leaf.max(1) {
            None
        } else {
            best_split(
                d,
                s,
                &totals,
                mtry,
                p.min_leaf.max(1),
                &mut order,
                &mut hist,
                &mut count,
                rng,
            )
        };
        let Some((f, b)) = split else {
            let sum: f32 = totals.iter().sum();
            nodes[slot] = Node {
                feature: LEAF,
                threshold: 0.0,
                left: leaves.len() as u32,
                right: 0,
            };
            leaves.extend(totals.iter().map(|t| t / sum));
            continue;
        };
        // Partition the range: bins ≤ b first.
        let col = &d.bins[f];
        let range = &mut idx[lo..hi];
        let mut k = 0;
        for j in 0..range.len() {
            if col[range[j] as usize] <= b {
                range.swap(j, k);
                k += 1;
            }
        }
        let (l, r) = (nodes.len(), nodes.len() + 1);
        for _ in 0..2 {
            nodes.push(Node {
                feature: LEAF,
                threshold: 0.0,
                left: 0,
                right: 0,
            });
        }
        nodes[slot] = Node {
            feature: f as u32,
            threshold: d.edges[f][b as usize],
            left: l as u32,
            right: r as u32,
        };
        stack.push((r, lo + k, hi, depth + 1));
        stack.push((l, lo, lo + k, depth + 1));
    }
    (nodes, leaves)
}

/// The (feature, bin) of the largest Gini decrease among `mtry` random features, leaving at
/// least `min_leaf` samples on each side; `None` when no tried feature separates the samples.
#[allow(clippy::too_many_arguments)]
fn best_split(
    d: &Binned,
    s: &[u32],
    totals: &[f32],
    mtry: usize,
    min_leaf: usize,
    order: &mut [usize],
    hist: &mut [f32],
    count: &mut [u32],
    rng: &mut ChaCha8Rng,
) -> Option<(usize, u8)> {
    let classes = totals.len();
    let dim = order.len();
    let total: f32 = totals.iter().sum();
    // Σ_c w_c² / W of the parent; a split scores Σ over its sides, higher is purer.
    let parent: f32 = totals.iter().map(|t| t * t).sum::<f32>() / total;
    let mut best: Option<(f32, usize, u8)> = None;
    let mut left = vec![0f32; classes];
    for k in 0..mtry {
        let j = rng.random_range(k..dim);
        order.swap(k, j);
        let f = order[k];
        let nb = d.edges[f].len() + 1;
        if nb < 2 {
            continue;
        }
        let col = &d.bins[f];
        hist[..nb * classes].fill(0.0);
        count[..nb].fill(0);
        for &i in s {
            let b = col[i as usize] as usize;
            hist[b * classes + d.labels[i as usize] as usize] += d.weight[i as usize];
            count[b] += 1;
        }
        left.fill(0.0);
        let mut nl = 0usize;
        for b in 0..nb - 1 {
            nl += count[b] as usize;
            for c in 0..classes {
                left[c] += hist[b * classes + c];
            }
            if count[b] == 0 || nl < min_leaf {
                continue;
            }
            if s.len() - nl < min_leaf {
                break;
            }
            let wl: f32 = left.iter().sum();
            let wr = total - wl;
            if wl <= 0.0 || wr <= 0.0 {
                continue;
            }
            let sl: f32 = left.iter().map(|v| v * v).sum::<f32>() / wl;
            let sr: f32 = left
                .iter()
                .zip(totals)
                .map(|(l, t)| (t - l) * (t - l))
                .sum::<f32>()
                / wr;
            let score = sl + sr;
            if score > parent + 1e-7 * total && best.is_none_or(|(bs, _, _)| score > bs) {
                best = Some((score, f, b as u8));
            }
        }
    }
    best.map(|(_, f, b)| (f, b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::features::Features;

    fn xor(n: usize) -> (Vec<f32>, Vec<usize>) {
        let mut x = Vec::new();
        let mut y = Vec::new();
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for _ in 0..n {
            let (a, b): (f32, f32) = (rng.random(), rng.random());
            x.extend([a, b, rng.random()]); // the third feature is noise
            y.push(((a > 0.5) ^ (b > 0.5)) as usize);
        }
        (x, y)
    }

    #[test]
    fn learns_xor() {
        let (x, y) = xor(2000);
        let f = Forest::train(&x, 3, &y, 2, &ForestParams::default()).unwrap();
        let (tx, ty) = {
            let mut rng = ChaCha8Rng::seed_from_u64(99);
            let pts: Vec<[f32; 3]> = (0..500)
                .map(|_| [rng.random(), rng.random(), rng.random()])
                .collect();
            let labels: Vec<usize> = pts
                .iter()
                .map(|p| ((p[0] > 0.5) ^ (p[1] > 0.5)) as usize)
                .collect();
            (pts, labels)
        };
        let right = tx
            .iter()
            .zip(&ty)
            .filter(|(p, l)| {
                let pr = f.predict_one(&p[..]);
                (pr[1] > pr[0]) as usize == **l
            })
            .count();
        assert!(right >= 480, "{right} / 500");
    }

    #[test]
    fn a_forest_survives_serialisation_and_a_damaged_one_is_refused() {
        let (x, y) = xor(500);
        let f = Forest::train(&x, 3, &y, 2, &ForestParams::default()).unwrap();
        let bytes = postcard::to_allocvec(&f).unwrap();
        let back: Forest = postcard::from_bytes(&bytes).unwrap();
        assert_eq!(back, f);
        assert!(back.validate().is_ok());
        // A child pointing back at its parent would loop; an index past the end would panic.
        let i = f.nodes.iter().position(|n| n.feature != LEAF).unwrap();
        let mut looped = f.clone();
        looped.nodes[i + 1..]
            .iter_mut()
            .find(|n| n.feature != LEAF)
            .unwrap()
            .left = i as u32;
        assert!(looped.validate().is_err());
        let mut outside = f.clone();
        outside.nodes[i].feature = 3;
        assert!(outside.validate().is_err());
        let mut leafless = f.clone();
        leafless.leaves.truncate(1);
        assert!(leafless.validate().is_err());
    }

    #[test]
    fn probabilities_sum_to_one_and_pure_training_gives_certainty() {
        let x = vec![0.0, 0.1, 0.2, 1.0, 1.1, 1.2];
        let y = vec![0, 0, 0, 1, 1, 1];
        let f = Forest::train(&x, 1, &y, 2, &ForestParams::default()).unwrap();
        assert_eq!(f.predict_one(&[-5.0]), vec![1.0, 0.0]);
        assert_eq!(f.predict_one(&[7.0]), vec![0.0, 1.0]);
        let (x, y) = xor(300);
        let f = Forest::train(
            &x,
            3,
            &y,
            2,
            &ForestParams {
                max_depth: 2,
                ..Default::default()
            },
        )
        .unwrap();
        for k in 0..50 {
            let s: f32 = f.predict_one(&[k as f32 / 50.0, 0.3, 0.9]).iter().sum();
            assert!((s - 1.0).abs() < 1e-5, "{s}");
        }
    }

    #[test]
    fn the_batched_walk_gives_each_pixel_its_own_path_bit_for_bit() {
        // Trees of uneven depth (leaves from depth 1 to 12), three classes, a NaN feature
        // (goes right, as in `predict_one`), and a width that is no multiple of the batch.
        let (x, y) = xor(600);
        let y: Vec<usize> = y
            .iter()
            .enumerate()
            .map(|(i, &c)| c + (i % 7 == 0) as usize)
            .collect();
        let params = ForestParams {
            trees: 9,
            max_depth: 12,
            ..Default::default()
        };
        let forest = Forest::train(&x, 3, &y, 3, &params).unwrap();
        let (w, h) = (13, 5);
        let planes: Vec<Vec<f32>> = (0..3)
            .map(|d| {
                (0..w * h)
                    .map(|i| match (d, i) {
                        (1, 17) => f32::NAN,
                        _ => ((i * 37 + d * 11) % 101) as f32 / 100.0,
                    })
                    .collect()
            })
            .collect();
        let f = Features {
            width: w,
            height: h,
            names: vec![String::new(); 3],
            planes,
        };
        let p = forest.predict(&f).unwrap();
        for i in 0..w * h {
            let one = forest.predict_one(&f.pixel(i));
            let got = &p.data[i * 3..i * 3 + 3];
            assert!(
                one.iter().zip(got).all(|(a, b)| a.to_bits() == b.to_bits()),
                "pixel {i}: {one:?} vs {got:?}"
            );
        }
    }

    #[test]
    fn classes_are_balanced_by_weight() {
        // 1000 samples of class 0 and 10 of class 1 on one overlapping feature: at the
        // shared value the balanced forest must not simply vote for the majority.
        let mut x = vec![0.5f32; 1000];
        let mut y = vec![0usize; 1000];
        x.extend([0.5f32; 10]);
        y.extend([1usize; 10]);
        let f = Forest::train(&x, 1, &y, 2, &ForestParams::default()).unwrap();
        let p = f.predict_one(&[0.5]);
        assert!((p[0] - 0.5).abs() < 0.15, "{p:?}");
    }

    #[test]
    fn training_errors_name_the_class() {
        let x = vec![0.0, 1.0];
        let e = Forest::train(&x, 1, &[0, 0], 3, &ForestParams::default()).unwrap_err();
        assert_eq!(
            e,
            PixelClassError::EmptyClass {
                class: 1,
                classes: 3
            }
        );
        assert!(e.to_string().contains("class 1"), "{e}");
        let e = Forest::train(&x, 1, &[0, 0], 1, &ForestParams::default()).unwrap_err();
        assert!(e.to_string().contains("at least two"), "{e}");
        let e = Forest::train(&x, 1, &[0, 5], 2, &ForestParams::default()).unwrap_err();
        assert!(e.to_string().contains("sample 1 has class 5"), "{e}");
    }

    #[test]
    fn same_seed_same_forest_other_seed_other_forest() {
        let (x, y) = xor(500);
        let p = ForestParams::default();
        let a = Forest::train(&x, 3, &y, 2, &p).unwrap();
        let b = Forest::train(&x, 3, &y, 2, &p).unwrap();
        assert_eq!(a, b);
        let c = Forest::train(&x, 3, &y, 2, &ForestParams { seed: 1, ..p }).unwrap();
        assert_ne!(a, c);
    }
}
