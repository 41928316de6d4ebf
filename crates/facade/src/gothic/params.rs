//! The settings of the Gothic pipeline (§4.2 fixes none of its thresholds) and the progress
//! it reports; re-exported from `facade::gothic`.

use serde::{Deserialize, Serialize};

use super::hatching_tone;
use super::optimise::ShapeBounds;

/// Every threshold of the Gothic pipeline. The dissertation fixes none of them (§4.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct GothicParams {
    /// Prewitt magnitude threshold, as a share of the 99th-percentile magnitude.
    pub edge_threshold: f64,
    /// Contour sample step (px); sub-pixel as §4.2 asks.
    pub step: f64,
    /// Smallest distance-transform peak (px) that seeds an element.
    pub min_seed_radius: f32,
    /// Most seeds per image (bounds the work on busy images).
    pub max_seeds: usize,
    /// Most conjugate-gradient iterations per maximisation.
    pub max_iters: u64,
    /// Smallest element width (px).
    pub min_width: f64,
    /// Smallest element height h + v (px).
    pub min_height: f64,
    /// Significance: largest mean distance ∮D ds / ∮ds (px) of a kept element.
    pub max_mean_distance: f64,
    /// Significance: smallest share of the contour within 1.5 px of an edge.
    pub min_support: f64,
    /// Bounding-box IoU at which two detections are the same element.
    pub duplicate_iou: f64,
    /// Shape similarity for grouping: relative tolerance on h, w, v ...
    pub group_relative: f64,
    /// ... plus this many pixels.
    pub group_absolute: f64,
    /// Most rounds of grouping and enclosing-arch search (levels of figure 4.4).
    pub max_levels: usize,
    /// Slack (px) when testing whether one element contains another.
    pub nesting_tolerance: f64,
    /// Hatching suppression before the edges (engravings; [`hatching_tone`]), off for
    /// photographs.
    pub hatching: Option<hatching_tone::HatchParams>,
    /// Issue 23, departure from §4.2: enclosing arches are also searched over a grid of
    /// shapes centred on their group ([`enclose`](super::enclose)), for arches whose inside
    /// is the wall. `false`: §4.2's proposals and CG only.
    pub enclosing_grid: bool,
    /// Issue 23, departure from §4.2: rectangles and seed-disc-wide boxes among the first
    /// shapes ([`detect::starts_with`](super::detect::starts_with)). `false`: the round- and
    /// pointed-headed walked boxes only.
    pub more_starts: bool,
    /// Issue 23, departure from §4.2: rows of identical elements split where the spacing
    /// jumps, and members proposed where it repeats ([`repeat`](super::repeat)). `false`:
    /// groups by (h, w, v) and sill line only.
    pub repetition: bool,
    /// Issue 23, departure from §4.2: a group's joint re-estimation also starts from its
    /// best-fitting member's shape and sill line, and keeps the start that fits the members
    /// better (`joint_fit` in the module). `false`: from the mean shape only.
    pub joint_from_best: bool,
    /// Issue 23, departure from §4.2 (with `repetition`): elements with the same head on one
    /// apex line, or the same width on one sill line, are tried as a group
    /// ([`group::Likeness::Loose`](super::group::Likeness)); refused, its twins by box are
    /// tried. `false`: by box and sill line only.
    pub group_by_heads: bool,
    /// Relative tolerance on the spacing: a spacing more than (1 + this) × its neighbour's is
    /// a jump; a gap within this share of k spacings holds k − 1 missing members.
    pub spacing_tolerance: f64,
    /// Issue 23, departure from §4.2 ([`sliver`](super::sliver)): an ungrouped element
    /// narrower than this share of the widest group in the same parent is dropped, ...
    pub sliver_of_group: f64,
    /// ... and one narrower than this share of its parent's width. 0 and 0: every significant
    /// element is kept, as §4.2 does.
    pub sliver_of_parent: f64,
    /// Issue 23, departure from §4.2 ([`verify`](super::verify)): the finished estimate's
    /// elements are scored by the shipped verifier, a forest learned from the annotated
    /// public-domain drawings and generated façades, and those below
    /// [`verify::DEFAULT_THRESHOLD`](super::verify::DEFAULT_THRESHOLD) are dropped (never an
    /// element the user corrected). `false`: every significant element is kept, as §4.2 does.
    pub verify: bool,
}

impl Default for GothicParams {
    fn default() -> Self {
        GothicParams {
            edge_threshold: 0.2,
            step: 0.5,
            min_seed_radius: 8.0,
            max_seeds: 400,
            max_iters: 60,
            min_width: 16.0,
            min_height: 24.0,
            max_mean_distance: 0.8,
            min_support: 0.9,
            duplicate_iou: 0.6,
            group_relative: 0.06,
            group_absolute: 2.0,
            max_levels: 3,
            nesting_tolerance: 3.0,
            hatching: None,
            enclosing_grid: true,
            more_starts: true,
            repetition: true,
            joint_from_best: true,
            group_by_heads: true,
            spacing_tolerance: 0.25,
            sliver_of_group: 0.5,
            sliver_of_parent: 0.15,
            verify: true,
        }
    }
}

impl GothicParams {
    /// The defaults without issue 23's departures (the enclosing-arch grid, the rectangle and
    /// disc starts, repetition, the joint fit from the best member, groups by head, slivers,
    /// the learned check):
    /// §4.2's grouping and enclosing proposals as they were
    /// before, for comparison.
    pub fn without_issue_23() -> GothicParams {
        GothicParams {
            enclosing_grid: false,
            more_starts: false,
            repetition: false,
            joint_from_best: false,
            group_by_heads: false,
            sliver_of_group: 0.0,
            sliver_of_parent: 0.0,
            verify: false,
            ..GothicParams::default()
        }
    }

    pub fn bounds(&self) -> ShapeBounds {
        ShapeBounds {
            min_width: self.min_width,
            min_height: self.min_height,
        }
    }
}

/// How far the element pipeline has got, for a progress bar (a long photo can take minutes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    /// Edges and their distance transform.
    Edges,
    /// `done` of `total` starting shapes maximised.
    Detecting { done: usize, total: usize },
    /// Grouping round `level` (from 1) of at most `of`: `done` of `total` clusters of similar
    /// elements re-estimated jointly, with their enclosing arches.
    Organising {
        level: usize,
        of: usize,
        done: usize,
        total: usize,
    },
}
