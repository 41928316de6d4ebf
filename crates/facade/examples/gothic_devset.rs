//! The real development set of the Gothic estimator (issue 23): `facade::gothic::estimate`, as
//! `castellan gothic IMAGE` runs it with its default flags, on every image annotated in
//! `data/gothic_devset/annotations.json`, scored against the hand-drawn boxes.
//!
//! ```text
//! cargo run --release -p facade --example gothic_devset [-- --hatching] [--no-verify] [--without-issue-23] [--only SUBSTRING] [--dump DIR]
//! ```
//!
//! `--dump DIR` writes each estimate as GOTHIC.json (`DIR/NAME.json`) to look at.
//! `--no-verify` leaves out the learned check of issue 23 (`facade::gothic::verify`), whose
//! shipped forest was trained on these very images: with it the figures here are in-sample,
//! and `--example gothic_verifier` gives them held out.
//!
//! The images are not in the repository: they are read from
//! `../shared/data/castle_drawings_pd/` (relative to the workspace root). Prints a markdown
//! table: per image, then engravings, photos and all together, the recall and precision at box
//! IoU ≥ 0.5 (greedy one-to-one matching; difficult ground truth is neither missed nor makes a
//! match a false positive) and the nesting accuracy (matched ground-truth elements that have a
//! parent whose predicted element's parent is the parent's match).
//!
//! The metric functions are shared with `tests/gothic_devset.rs` (which includes this file).

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::Deserialize;

/// IoU threshold of a match.
pub const IOU_MIN: f64 = 0.5;

/// What an annotated image is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ImageKind {
    /// An engraving or a drawing.
    Elevation,
    Photo,
}

impl ImageKind {
    pub fn name(self) -> &'static str {
        match self {
            ImageKind::Elevation => "elevation",
            ImageKind::Photo => "photo",
        }
    }
}

/// The head of an annotated element.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum HeadKind {
    Pointed,
    Round,
    Segmental,
    Rectangular,
    Other,
}

/// An opening (window, door, arcade) or an arch that encloses other elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Role {
    Opening,
    Enclosing,
}

/// `data/gothic_devset/annotations.json`: one entry per image.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Annotated {
    /// Relative to `castle_drawings_pd/`.
    pub file: String,
    pub kind: ImageKind,
    /// The castle and the view, from the drawings' manifest.
    pub castle: String,
    pub view: Option<String>,
    pub width: u32,
    pub height: u32,
    pub book: String,
    pub author: String,
    pub source: String,
    pub elements: Vec<GtElement>,
}

/// One annotated element: its box in image pixels, its head shape and role, the index of the
/// enclosing element (in the same image's list) that contains it.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GtElement {
    #[serde(rename = "box")]
    pub bbox: [f64; 4],
    pub kind: HeadKind,
    pub role: Role,
    pub parent: Option<usize>,
    #[serde(default)]
    pub difficult: bool,
}

/// The workspace root (two levels above this crate).
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The annotation file.
pub fn annotations_path() -> PathBuf {
    workspace_root().join("data/gothic_devset/annotations.json")
}

/// Where the images are: `../shared/data/castle_drawings_pd` beside the workspace.
pub fn images_root() -> PathBuf {
    workspace_root().join("../shared/data/castle_drawings_pd")
}

pub fn read_annotations(path: &Path) -> Result<Vec<Annotated>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// Intersection over union of two boxes [x0, y0, x1, y1].
pub fn iou(a: [f64; 4], b: [f64; 4]) -> f64 {
    let w = (a[2].min(b[2]) - a[0].max(b[0])).max(0.0);
    let h = (a[3].min(b[3]) - a[1].max(b[1])).max(0.0);
    let inter = w * h;
    let area = |r: [f64; 4]| (r[2] - r[0]).max(0.0) * (r[3] - r[1]).max(0.0);
    let union = area(a) + area(b) - inter;
    if union <= 0.0 { 0.0 } else { inter / union }
}

/// One-to-one matching: `gt_of_pred[p]` is the ground-truth index matched to prediction `p`.
/// Greedy by decreasing IoU (≥ [`IOU_MIN`]), first among the ground truth that is not
/// difficult, then the predictions left over against the difficult ground truth (so a
/// difficult box never takes a prediction from a box that counts).
pub fn match_greedy(gt: &[([f64; 4], bool)], pred: &[[f64; 4]]) -> Vec<Option<usize>> {
    let mut gt_of_pred = vec![None; pred.len()];
    let mut gt_taken = vec![false; gt.len()];
    for difficult_pass in [false, true] {
        let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
        for (g, (gb, difficult)) in gt.iter().enumerate() {
            if *difficult != difficult_pass {
                continue;
            }
            for (p, pb) in pred.iter().enumerate() {
                let v = iou(*gb, *pb);
                if v >= IOU_MIN {
                    pairs.push((v, g, p));
                }
            }
        }
        // Ties broken by index, so the result does not depend on the sort's stability.
        pairs.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        for (_, g, p) in pairs {
            if !gt_taken[g] && gt_of_pred[p].is_none() {
                gt_taken[g] = true;
                gt_of_pred[p] = Some(g);
            }
        }
    }
    gt_of_pred
}

/// Counts of one image (or a sum of images).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Score {
    /// Ground truth that counts (not difficult).
    pub gt: usize,
    /// Predictions, all of them.
    pub pred: usize,
    /// Predictions matched to a difficult box (neither true nor false positives).
    pub pred_on_difficult: usize,
    /// Matched ground truth that counts (= true positives).
    pub matched: usize,
    /// Matched ground truth (not difficult) with a parent in the annotation.
    pub nested: usize,
    /// Of those, the ones whose prediction's parent is the match of their parent.
    pub nested_right: usize,
    /// Ground truth that counts and that no prediction overlaps at all: missed by the
    /// candidates, not by the matching's IoU.
    pub untouched: usize,
}

impl Score {
    pub fn add(&mut self, o: &Score) {
        self.gt += o.gt;
        self.pred += o.pred;
        self.pred_on_difficult += o.pred_on_difficult;
        self.matched += o.matched;
        self.nested += o.nested;
        self.nested_right += o.nested_right;
        self.untouched += o.untouched;
    }
    pub fn recall(&self) -> Option<f64> {
        (self.gt > 0).then(|| self.matched as f64 / self.gt as f64)
    }
    pub fn precision(&self) -> Option<f64> {
        let counted = self.pred - self.pred_on_difficult;
        (counted > 0).then(|| self.matched as f64 / counted as f64)
    }
    pub fn nesting(&self) -> Option<f64> {
        (self.nested > 0).then(|| self.nested_right as f64 / self.nested as f64)
    }
}

/// A predicted element as the metrics see it: its box and the index (in the same list) of its
/// parent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Predicted {
    pub bbox: [f64; 4],
    pub parent: Option<usize>,
}

/// Scores one image: matching, recall/precision counts and nesting.
pub fn score(gt: &[GtElement], pred: &[Predicted]) -> Score {
    let gt_boxes: Vec<([f64; 4], bool)> = gt.iter().map(|e| (e.bbox, e.difficult)).collect();
    let pred_boxes: Vec<[f64; 4]> = pred.iter().map(|p| p.bbox).collect();
    let gt_of_pred = match_greedy(&gt_boxes, &pred_boxes);
    let mut pred_of_gt = vec![None; gt.len()];
    for (p, g) in gt_of_pred.iter().enumerate() {
        if let Some(g) = g {
            pred_of_gt[*g] = Some(p);
        }
    }
    let mut s = Score {
        gt: gt.iter().filter(|e| !e.difficult).count(),
        pred: pred.len(),
        untouched: gt
            .iter()
            .filter(|e| !e.difficult && pred_boxes.iter().all(|&p| iou(e.bbox, p) == 0.0))
            .count(),
        ..Score::default()
    };
    for g in gt_of_pred.iter().flatten() {
        if gt[*g].difficult {
            s.pred_on_difficult += 1;
        } else {
            s.matched += 1;
        }
    }
    for (g, e) in gt.iter().enumerate() {
        let (Some(p), Some(parent), false) = (pred_of_gt[g], e.parent, e.difficult) else {
            continue;
        };
        s.nested += 1;
        // Right when the parent was found and the prediction's parent is that match.
        if pred_of_gt[parent].is_some() && pred[p].parent == pred_of_gt[parent] {
            s.nested_right += 1;
        }
    }
    s
}

/// The estimate's elements as [`Predicted`] (parents are element ids; ids are mapped to
/// indices).
pub fn predicted(est: &facade::gothic::GothicEstimate) -> Vec<Predicted> {
    let index_of = |id: usize| est.elements.iter().position(|e| e.id == id);
    est.elements
        .iter()
        .map(|e| Predicted {
            bbox: e.theta().bbox(),
            parent: e.parent.and_then(index_of),
        })
        .collect()
}

fn pct(v: Option<f64>) -> String {
    v.map_or("–".to_string(), |v| format!("{:.1} %", 100.0 * v))
}

fn row(name: &str, kind: &str, s: &Score, secs: f64) -> String {
    format!(
        "| {name} | {kind} | {} | {} | {} | {} ({}/{}) | {} ({}/{}) | {} ({}/{}) | {secs:.2} |",
        s.gt,
        s.pred,
        s.pred_on_difficult,
        pct(s.recall()),
        s.matched,
        s.gt,
        pct(s.precision()),
        s.matched,
        s.pred - s.pred_on_difficult,
        pct(s.nesting()),
        s.nested_right,
        s.nested,
    )
}

/// The parameters `castellan gothic IMAGE` uses with its default flags (`--min-radius 8`, no
/// `--training`), `--hatching` when asked; `--without-issue-23` starts from
/// [`GothicParams::without_issue_23`](facade::gothic::GothicParams::without_issue_23) (the
/// estimator before the enclosing-arch grid, repetition and slivers) for a same-run comparison.
pub fn castellan_params(
    hatching: bool,
    before_issue_23: bool,
    verify: bool,
) -> facade::gothic::GothicParams {
    let min_radius = 8.0_f64;
    let base = if before_issue_23 {
        facade::gothic::GothicParams::without_issue_23()
    } else {
        facade::gothic::GothicParams::default()
    };
    facade::gothic::GothicParams {
        min_seed_radius: min_radius as f32,
        min_width: 2.0 * min_radius,
        min_height: 3.0 * min_radius,
        hatching: hatching.then(facade::gothic::hatching_tone::HatchParams::default),
        verify: verify && !before_issue_23,
        ..base
    }
}

#[allow(dead_code)]
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let hatching = args.iter().any(|a| a == "--hatching");
    let only = args
        .iter()
        .position(|a| a == "--only")
        .and_then(|i| args.get(i + 1).cloned());
    let dump = args
        .iter()
        .position(|a| a == "--dump")
        .and_then(|i| args.get(i + 1).map(PathBuf::from));
    let ann = match read_annotations(&annotations_path()) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("gothic_devset: cannot read the annotations: {e}");
            std::process::exit(2);
        }
    };
    let root = images_root();
    if !root.is_dir() {
        eprintln!(
            "gothic_devset: the images are not here: {} is absent (the public-domain drawings \
             of ../shared/data/castle_drawings_pd beside the workspace); nothing to evaluate",
            root.display()
        );
        std::process::exit(2);
    }
    let before = args.iter().any(|a| a == "--without-issue-23");
    let verify = !args.iter().any(|a| a == "--no-verify");
    let params = castellan_params(hatching, before, verify);
    println!(
        "Gothic development set, `castellan gothic` defaults{}{}{}; IoU ≥ {IOU_MIN}\n",
        if hatching { " + --hatching" } else { "" },
        if verify && !before {
            " (the shipped verifier was trained on these images: for held-out figures run \
             --example gothic_verifier)"
        } else if !before {
            " + --no-verify"
        } else {
            ""
        },
        if before {
            ", without issue 23's departures"
        } else {
            ""
        }
    );
    println!(
        "| image | kind | GT | predicted | on difficult | recall | precision | nesting | seconds |"
    );
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    let mut totals = [Score::default(), Score::default()];
    let mut secs_tot = [0.0_f64; 2];
    let mut count = [0_usize; 2];
    let started = Instant::now();
    for a in &ann {
        if only.as_ref().is_some_and(|o| !a.file.contains(o.as_str())) {
            continue;
        }
        let path = root.join(&a.file);
        let img = match image::open(&path) {
            Ok(i) => i.to_rgb8(),
            Err(e) => {
                eprintln!("gothic_devset: {}: {e}", path.display());
                std::process::exit(2);
            }
        };
        let t = Instant::now();
        let est = match facade::gothic::estimate(&img, &params) {
            Ok(e) => e,
            Err(e) => {
                eprintln!("gothic_devset: {}: {e}", path.display());
                std::process::exit(1);
            }
        };
        let secs = t.elapsed().as_secs_f64();
        if let Some(dir) = &dump {
            let out = dir.join(format!("{}.json", a.file.trim_start_matches("elevations/")));
            let written = std::fs::create_dir_all(dir).and_then(|_| {
                std::fs::write(&out, serde_json::to_vec_pretty(&est).unwrap_or_default())
            });
            if let Err(e) = written {
                eprintln!("gothic_devset: {}: {e}", out.display());
                std::process::exit(1);
            }
        }
        let s = score(&a.elements, &predicted(&est));
        let k = usize::from(a.kind == ImageKind::Photo);
        totals[k].add(&s);
        secs_tot[k] += secs;
        count[k] += 1;
        let name = a.file.trim_start_matches("elevations/");
        println!("{}", row(name, a.kind.name(), &s, secs));
    }
    let mut all = Score::default();
    for (k, label) in ["**engravings**", "**photos**"].iter().enumerate() {
        all.add(&totals[k]);
        println!(
            "{}",
            row(
                &format!("{label} ({} images)", count[k]),
                "",
                &totals[k],
                secs_tot[k]
            )
        );
    }
    println!(
        "{}",
        row(
            &format!("**all** ({} images)", count[0] + count[1]),
            "",
            &all,
            secs_tot[0] + secs_tot[1]
        )
    );
    println!(
        "\n{} of the {} counted elements overlap no estimated element at all (the candidates \
         missed them; the rest of the unmatched overlap one below IoU {IOU_MIN}).",
        all.untouched, all.gt
    );
    println!(
        "\nGT: annotated elements that count (not difficult); recall = matched GT / GT; \
         precision = matched / (predicted − on difficult); nesting = matched GT with a parent \
         whose prediction's parent is the parent's match. Total wall time {:.1} s.",
        started.elapsed().as_secs_f64()
    );
}
