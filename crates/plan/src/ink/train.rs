//! Training the wall-ink model (issue 26) from drawings with exact or painted wall masks:
//! synthetic plans in randomised styles ([`crate::synth_styles`]) and the masks painted on
//! public-domain plans ([`super::paint`]). Pure: sheets in, model out; the `train_ink`
//! example reads the files and writes `models/wall_ink.bin`.

use image::GrayImage;
use pixelclass::{Features, FilterBank, Forest, ForestParams};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::model::{
    FORMAT, WallInk, Working, smoothed_context, with_context, working_features, working_size,
};
use super::paint::{HARD_NOT_WALL, IGNORE, WALL};

/// The source of a drawing for leave-one-source-out measurement: its book, the tomes of one
/// work taken together (one hand drew them all). The one home of this rule.
pub fn source_of(book: &str) -> String {
    match book.find(", tome") {
        Some(i) => book[..i].to_string(),
        None => book.to_string(),
    }
}

/// One training drawing: its grey image and its mask ([`WALL`], not wall, [`HARD_NOT_WALL`]
/// or [`IGNORE`]) of the same size.
#[derive(Clone)]
pub struct Sheet {
    pub grey: GrayImage,
    pub truth: GrayImage,
}

/// Training settings.
#[derive(Debug, Clone, PartialEq)]
pub struct TrainParams {
    pub bank: FilterBank,
    pub working: Working,
    /// [`WallInk::ink_sigmas`].
    pub ink_sigmas: Vec<f32>,
    /// Empty: one stage.
    pub context_sigmas: Vec<f32>,
    pub forest: ForestParams,
    /// Pixels sampled per class and drawing; as many again among ink that is not wall (the
    /// letters, hatching and hachures the model must learn to refuse), and as many again among
    /// the paper marked [`HARD_NOT_WALL`] where a sheet has it.
    pub per_class: usize,
}

impl Default for TrainParams {
    fn default() -> Self {
        TrainParams {
            bank: FilterBank {
                sigmas: vec![0.7, 1.6, 3.5, 7.0, 14.0],
                families: vec![
                    pixelclass::Family::Smoothing,
                    pixelclass::Family::GradientMagnitude,
                    pixelclass::Family::LaplacianOfGaussian,
                    pixelclass::Family::Hessian,
                ],
            },
            working: Working::default(),
            ink_sigmas: Vec::new(),
            context_sigmas: vec![1.0, 3.0, 8.0],
            forest: ForestParams {
                trees: 16,
                max_depth: 13,
                min_leaf: 8,
                max_per_class: 60_000,
                ..ForestParams::default()
            },
            per_class: 1500,
        }
    }
}

/// Why training failed.
#[derive(Debug, thiserror::Error)]
pub enum TrainError {
    #[error("sheet {index}: mask {mw}x{mh} for a {w}x{h} drawing")]
    SizeMismatch {
        index: usize,
        w: u32,
        h: u32,
        mw: u32,
        mh: u32,
    },
    #[error("no sheets to train on")]
    Empty,
    #[error(transparent)]
    Forest(#[from] pixelclass::PixelClassError),
}

/// The sampled pixels of one sheet: working-resolution indices and labels.
struct Picks {
    idx: Vec<usize>,
    labels: Vec<usize>,
}

/// Trains a model on `sheets`; `provenance` is recorded in it.
pub fn train(sheets: &[Sheet], p: &TrainParams, provenance: &str) -> Result<WallInk, TrainError> {
    if sheets.is_empty() {
        return Err(TrainError::Empty);
    }
    for (index, s) in sheets.iter().enumerate() {
        let ((w, h), (mw, mh)) = (s.grey.dimensions(), s.truth.dimensions());
        if (w, h) != (mw, mh) {
            return Err(TrainError::SizeMismatch {
                index,
                w,
                h,
                mw,
                mh,
            });
        }
    }
    let picks: Vec<Picks> = sheets
        .iter()
        .enumerate()
        .map(|(i, s)| pick(s, p, p.forest.seed.wrapping_add(i as u64)))
        .collect();
    // Stage-1 rows, one block per sheet.
    let blocks: Vec<(Vec<f32>, Vec<usize>)> = sheets
        .iter()
        .zip(&picks)
        .map(|(s, pk)| {
            let f = working_features(&s.grey, &p.working, &p.bank, &p.ink_sigmas);
            let mut rows = (Vec::new(), Vec::new());
            push_rows(&f, pk, &mut rows.0, &mut rows.1);
            rows
        })
        .collect();
    let dim = p.bank.dim(1) + p.ink_sigmas.len();
    let joined = |which: &mut dyn Iterator<Item = usize>| {
        let (mut x, mut l) = (Vec::new(), Vec::new());
        for i in which {
            x.extend_from_slice(&blocks[i].0);
            l.extend_from_slice(&blocks[i].1);
        }
        (x, l)
    };
    let (x, labels) = joined(&mut (0..sheets.len()));
    let mut stages = vec![Forest::train(&x, dim, &labels, 2, &p.forest)?];
    if !p.context_sigmas.is_empty() {
        // Stage 2 must learn from the maps stage 1 gives on drawings it did not see: two
        // forests, each trained on half the sheets, give the other half's context.
        let mut other = Vec::new();
        for parity in [1, 0] {
            let (x, l) = joined(&mut (0..sheets.len()).filter(|i| i % 2 == parity));
            other.push(if l.contains(&0) && l.contains(&1) {
                Forest::train(&x, dim, &l, 2, &p.forest)?
            } else {
                stages[0].clone() // one sheet, or a half without a class: in-sample context
            });
        }
        let (mut x, mut l) = (Vec::new(), Vec::new());
        let ac = smoothed_context(&p.context_sigmas);
        for (i, (s, pk)) in sheets.iter().zip(&picks).enumerate() {
            let f = working_features(&s.grey, &p.working, &p.bank, &p.ink_sigmas);
            let map = other[i % 2].predict(&f)?;
            push_rows(&with_context(f, &map, &ac), pk, &mut x, &mut l);
        }
        let mut fp = p.forest;
        fp.seed = fp.seed.wrapping_add(0x5eed);
        stages.push(Forest::train(&x, dim + p.context_sigmas.len(), &l, 2, &fp)?);
    }
    Ok(WallInk {
        format: FORMAT,
        bank: p.bank.clone(),
        working: p.working,
        ink_sigmas: p.ink_sigmas.clone(),
        context_sigmas: p.context_sigmas.clone(),
        stages,
        provenance: provenance.to_string(),
    })
}

fn push_rows(f: &Features, picks: &Picks, x: &mut Vec<f32>, labels: &mut Vec<usize>) {
    for (&i, &l) in picks.idx.iter().zip(&picks.labels) {
        x.extend(f.planes.iter().map(|pl| pl[i]));
        labels.push(l);
    }
}

/// Samples a sheet's working pixels: up to `per_class` walls, as many non-walls, and as many
/// dark non-wall pixels (clutter ink); ignored pixels never.
fn pick(s: &Sheet, p: &TrainParams, seed: u64) -> Picks {
    let (w, h) = s.grey.dimensions();
    let (ws, hs) = working_size(w, h, &p.working);
    let norm = super::model::normalise(&s.grey);
    let (mut wall, mut open, mut clutter, mut hard) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for y in 0..hs {
        for x in 0..ws {
            // The source pixel under the working pixel's centre.
            let sx = ((f64::from(x) + 0.5) * f64::from(w) / f64::from(ws)) as u32;
            let sy = ((f64::from(y) + 0.5) * f64::from(h) / f64::from(hs)) as u32;
            let i = (y * ws + x) as usize;
            let ink = norm.get_pixel(sx.min(w - 1), sy.min(h - 1))[0] < 128;
            match s.truth.get_pixel(sx.min(w - 1), sy.min(h - 1))[0] {
                IGNORE => {}
                WALL => wall.push(i),
                _ if ink => clutter.push(i),
                HARD_NOT_WALL => hard.push(i),
                _ => open.push(i),
            }
        }
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut idx = Vec::new();
    let mut labels = Vec::new();
    // An empty pool draws no random numbers: sheets without hard paper sample as before.
    for (pool, label) in [(wall, 1), (open, 0), (clutter, 0), (hard, 0)] {
        for i in choose(pool, p.per_class, &mut rng) {
            idx.push(i);
            labels.push(label);
        }
    }
    Picks { idx, labels }
}

/// Up to `n` of `pool`, chosen without replacement.
fn choose(mut pool: Vec<usize>, n: usize, rng: &mut ChaCha8Rng) -> Vec<usize> {
    let k = n.min(pool.len());
    for i in 0..k {
        let j = rng.random_range(i..pool.len());
        pool.swap(i, j);
    }
    pool.truncate(k);
    pool
}

/// The model's wall mask (P(wall) > 0.5) against a truth mask: (true positives, false
/// positives, false negatives), ignored pixels left out.
pub fn confusion(prob: &[f32], truth: &GrayImage) -> (usize, usize, usize) {
    let (mut tp, mut fp, mut fn_) = (0, 0, 0);
    for (&q, t) in prob.iter().zip(truth.pixels()) {
        match (q > 0.5, t[0]) {
            (_, IGNORE) => {}
            (true, WALL) => tp += 1,
            (true, _) => fp += 1,
            (false, WALL) => fn_ += 1,
            _ => {}
        }
    }
    (tp, fp, fn_)
}

/// Toy sheets and small settings, for the tests of training and refinement.
#[cfg(test)]
pub(crate) mod fixtures {
    use super::*;
    use image::Luma;

    /// A sheet with a thick wall frame (6 px), thin letter strokes (1 px) inside and out.
    pub fn sheet(seed: u64) -> Sheet {
        let (w, h) = (90, 70);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut grey = GrayImage::from_pixel(w, h, Luma([235]));
        let mut truth = GrayImage::new(w, h);
        for y in 0..h {
            for x in 0..w {
                let frame = (10..80).contains(&x) && (10..60).contains(&y);
                let inner = (16..74).contains(&x) && (16..54).contains(&y);
                if frame && !inner {
                    grey.put_pixel(x, y, Luma([20]));
                    truth.put_pixel(x, y, Luma([WALL]));
                }
            }
        }
        for _ in 0..12 {
            let (x, y) = (rng.random_range(20..70), rng.random_range(20..50));
            for k in 0..5 {
                grey.put_pixel(x, y + k, Luma([20]));
            }
        }
        Sheet { grey, truth }
    }

    pub fn small() -> TrainParams {
        TrainParams {
            bank: FilterBank {
                sigmas: vec![1.0, 3.0],
                families: vec![pixelclass::Family::Smoothing, pixelclass::Family::Hessian],
            },
            forest: ForestParams {
                trees: 8,
                ..TrainParams::default().forest
            },
            per_class: 300,
            ..TrainParams::default()
        }
    }

    /// A model trained on four toy sheets.
    pub fn toy_model() -> WallInk {
        let sheets: Vec<Sheet> = (0..4).map(sheet).collect();
        train(&sheets, &small(), "toy").unwrap()
    }
}

#[cfg(test)]
mod tests {
    use super::fixtures::{sheet, small};
    use super::*;

    #[test]
    fn learns_thick_walls_from_thin_strokes_and_the_model_round_trips() {
        let sheets: Vec<Sheet> = (0..4).map(sheet).collect();
        let m = train(&sheets, &small(), "test").unwrap();
        assert_eq!(m.stages.len(), 2);
        assert_eq!(WallInk::from_bytes(&m.to_bytes()).unwrap(), m);
        let test = sheet(9);
        let prob = m.wall_probability(&test.grey, 90, 70);
        let (tp, fp, fn_) = confusion(&prob, &test.truth);
        let iou = tp as f64 / (tp + fp + fn_) as f64;
        assert!(iou > 0.9, "IoU {iou}: {tp} {fp} {fn_}");
        // The letter strokes are ink, and not wall.
        let strokes = test
            .grey
            .pixels()
            .zip(test.truth.pixels())
            .zip(&prob)
            .filter(|((g, t), _)| g[0] < 128 && t[0] != WALL);
        let (n, wrong) = strokes.fold((0, 0), |(n, k), (_, &q)| (n + 1, k + usize::from(q > 0.5)));
        assert!(
            n > 20 && wrong * 5 < n,
            "{wrong} of {n} stroke pixels taken for wall"
        );
    }

    #[test]
    fn tomes_of_one_work_are_one_source() {
        assert_eq!(
            source_of("Dictionnaire raisonné, tome 3"),
            "Dictionnaire raisonné"
        );
        assert_eq!(source_of("Annals of a Fortress"), "Annals of a Fortress");
    }

    #[test]
    fn bad_training_input_is_refused() {
        assert!(matches!(train(&[], &small(), ""), Err(TrainError::Empty)));
        let mut s = sheet(1);
        s.truth = GrayImage::new(3, 3);
        assert!(matches!(
            train(&[s], &small(), ""),
            Err(TrainError::SizeMismatch { index: 0, .. })
        ));
    }
}
