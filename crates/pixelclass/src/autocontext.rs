//! Autocontext (Tu & Bai 2010, ilastik's "autocontext"): a second forest whose features are
//! the filter bank plus the first forest's class probability maps, smoothed at several σ and
//! averaged over each pixel's row and column. Stage 2 thus sees what stage 1 believes around
//! the pixel (a window's neighbours, the row of windows it sits in), not only the pixel.
//!
//! Stage 1's maps are over-confident on its own training pixels; with `folds > 1` the training
//! samples' context comes instead from forests trained without them (samples grouped into
//! connected clumps, i.e. the boxes they were drawn from, dealt round-robin per class).

use crate::features::Features;
use crate::filters;
use crate::forest::{Forest, ForestParams, Probabilities};

/// Autocontext settings (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct AutoContext {
    /// σ (pixels of the working image) at which every stage-1 class map is smoothed; each σ
    /// gives one feature per class.
    pub sigmas: Vec<f32>,
    /// Also each class map's mean over the pixel's row and over its column (façades align
    /// their windows in rows and columns).
    pub row_column: bool,
    /// Out-of-fold stage-1 maps for the training samples: 0 or 1 use the full stage-1 forest's
    /// (in-sample) maps; k > 1 trains k forests, each without one fold of sample clumps.
    pub folds: usize,
    /// Trees of each fold forest (0: as many as the stage-1 forest).
    pub fold_trees: usize,
    /// Return the mean of the two stages' maps instead of stage 2's alone.
    pub average: bool,
}

/// The default, measured on the façade sets (docs/pixelclass.md): row and column means only,
/// in-sample context, output the mean of the two stages' maps.
impl Default for AutoContext {
    fn default() -> Self {
        AutoContext {
            sigmas: Vec::new(),
            row_column: true,
            folds: 0,
            fold_trees: 0,
            average: true,
        }
    }
}

impl AutoContext {
    /// ilastik-like context: the maps smoothed at σ = 1, 2, 4, 8, 16 plus the row and column
    /// means, stage 2's map alone.
    pub fn smoothed() -> AutoContext {
        AutoContext {
            sigmas: vec![1.0, 2.0, 4.0, 8.0, 16.0],
            average: false,
            ..AutoContext::default()
        }
    }
}

impl AutoContext {
    /// Context planes per class.
    pub fn per_class(&self) -> usize {
        self.sigmas.len() + if self.row_column { 2 } else { 0 }
    }
}

/// The context planes of `p` (class-major: per class, the σ then the row and column means)
/// with their names.
pub fn context(p: &Probabilities, ac: &AutoContext) -> (Vec<Vec<f32>>, Vec<String>) {
    let (w, h) = (p.width, p.height);
    let mut planes = Vec::with_capacity(p.classes * ac.per_class());
    let mut names = Vec::with_capacity(planes.capacity());
    for c in 0..p.classes {
        let m = p.class_map(c);
        for &s in &ac.sigmas {
            planes.push(filters::smooth(&m, w, h, s));
            names.push(format!("p{c} σ{s}"));
        }
        if ac.row_column {
            let rows: Vec<f32> = m
                .chunks(w)
                .map(|r| r.iter().sum::<f32>() / w as f32)
                .collect();
            let mut cols = vec![0f32; w];
            for r in m.chunks(w) {
                cols.iter_mut().zip(r).for_each(|(a, v)| *a += v);
            }
            cols.iter_mut().for_each(|a| *a /= h as f32);
            planes.push(filters::plane(w, h, |_, y| rows[y]));
            names.push(format!("p{c} row"));
            planes.push(filters::plane(w, h, |x, _| cols[x]));
            names.push(format!("p{c} column"));
        }
    }
    (planes, names)
}

/// Fold of every sample: samples within 2 px of each other (Chebyshev) form a clump, and each
/// class's clumps, in order of their first sample, are dealt to folds 0, 1, …, k−1, 0, ….
pub fn folds(pos: &[(usize, usize)], labels: &[usize], classes: usize, k: usize) -> Vec<usize> {
    let n = pos.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    let mut at: std::collections::HashMap<(usize, usize), usize> =
        std::collections::HashMap::with_capacity(n);
    for (i, &q) in pos.iter().enumerate() {
        at.entry(q).or_insert(i);
    }
    for (i, &(x, y)) in pos.iter().enumerate() {
        for dy in 0..=4 {
            for dx in 0..=4 {
                let (Some(xx), Some(yy)) = ((x + dx).checked_sub(2), (y + dy).checked_sub(2))
                else {
                    continue;
                };
                if let Some(&j) = at.get(&(xx, yy))
                    && labels[j] == labels[i]
                {
                    let (a, b) = (find(&mut parent, i), find(&mut parent, j));
                    parent[a.max(b)] = a.min(b);
                }
            }
        }
    }
    let mut next = vec![0usize; classes];
    let mut fold_of_root = std::collections::HashMap::new();
    (0..n)
        .map(|i| {
            let r = find(&mut parent, i);
            *fold_of_root.entry(r).or_insert_with(|| {
                let f = next[labels[i]] % k;
                next[labels[i]] += 1;
                f
            })
        })
        .collect()
}

/// Stage 2: trains on the bank features plus the context of stage 1 (`p1`, from the forest
/// trained on all samples) and predicts every pixel. `idx` are the samples' pixel indices in
/// `f`, `pos` their positions.
#[allow(clippy::too_many_arguments)]
pub fn stage_two(
    f: Features,
    p1: &Probabilities,
    idx: &[usize],
    pos: &[(usize, usize)],
    labels: &[usize],
    classes: usize,
    forest: &ForestParams,
    ac: &AutoContext,
) -> crate::Result<Probabilities> {
    let (ctx, names) = context(p1, ac);
    let dim1 = f.dim();
    let mut rows: Vec<Vec<f32>> = idx
        .iter()
        .map(|&i| ctx.iter().map(|pl| pl[i]).collect())
        .collect();
    if ac.folds > 1 {
        let fold = folds(pos, labels, classes, ac.folds);
        let x1: Vec<f32> = idx
            .iter()
            .flat_map(|&i| f.planes.iter().map(move |pl| pl[i]))
            .collect();
        for k in 0..ac.folds {
            let train: Vec<usize> = (0..idx.len()).filter(|&i| fold[i] != k).collect();
            if train.len() == idx.len() {
                continue;
            }
            let mut seen = vec![false; classes];
            train.iter().for_each(|&i| seen[labels[i]] = true);
            if seen.contains(&false) {
                continue; // a class lies wholly in this fold: keep in-sample context
            }
            let x: Vec<f32> = train
                .iter()
                .flat_map(|&i| x1[i * dim1..(i + 1) * dim1].iter().copied())
                .collect();
            let l: Vec<usize> = train.iter().map(|&i| labels[i]).collect();
            let mut fp = *forest;
            fp.seed = forest.seed.wrapping_add(0x5eed_0000 * (k as u64 + 1));
            if ac.fold_trees > 0 {
                fp.trees = ac.fold_trees;
            }
            let pk = Forest::train(&x, dim1, &l, classes, &fp)?.predict(&f)?;
            let (ck, _) = context(&pk, ac);
            for i in (0..idx.len()).filter(|&i| fold[i] == k) {
                rows[i] = ck.iter().map(|pl| pl[idx[i]]).collect();
            }
        }
    }
    let mut f2 = f;
    f2.planes.extend(ctx);
    f2.names.extend(names);
    let dim = f2.dim();
    let mut x = Vec::with_capacity(idx.len() * dim);
    for (&i, r) in idx.iter().zip(&rows) {
        x.extend(f2.planes[..dim1].iter().map(|pl| pl[i]));
        x.extend_from_slice(r);
    }
    let mut fp = *forest;
    fp.seed = forest.seed.wrapping_add(0xac_0000_0000);
    let mut p2 = Forest::train(&x, dim, labels, classes, &fp)?.predict(&f2)?;
    if ac.average {
        p2.data
            .iter_mut()
            .zip(&p1.data)
            .for_each(|(a, b)| *a = 0.5 * (*a + b));
    }
    Ok(p2)
}
