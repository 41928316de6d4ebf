//! Issue 23, departure from §4.2: a learned check of the estimate's elements on drawings and
//! photos. §4.2 keeps an element when its contour lies on edges (mean distance and support);
//! on an engraving every shift of a contour along the ruled coursing lines passes that test, so
//! on the real development set 6.5 % of the elements were openings (docs/gothic.md). No single
//! measure of the fit separates right from wrong elements there, but together with what the
//! image holds inside and around an element's box (its tone, darkness and edge density
//! against a ring around it) and its place in the estimate (group, parent, children, how many
//! other elements overlap it) a small random forest does.
//!
//! The forest ([`Verifier`]) is trained on the elements the estimator returns on the annotated
//! public-domain images of `data/gothic_devset` (an element is right when its box meets an
//! annotated one at IoU ≥ 0.5), by `cargo run --release -p facade --example gothic_devset --
//! --train-verifier`, and ships in `crates/facade/models/gothic_verifier.bin`. Pure: the image
//! and the estimate in, scores or the kept estimate out.

use image::{GrayImage, RgbImage};
use pixelclass::{Forest, ForestParams};
use serde::{Deserialize, Serialize};

use super::element::ArchKind;
use super::model::{Element, GothicEstimate, Group};

/// Version of the model file; a file of another version is refused.
pub const FORMAT: u32 = 1;

/// The verifier shipped with castellan.
pub const SHIPPED: &[u8] = include_bytes!("../../models/gothic_verifier.bin");

/// The score below which an element is dropped by default (the forest's probability that the
/// element is an opening, classes balanced; chosen on the held-out runs in docs/gothic.md).
pub const DEFAULT_THRESHOLD: f32 = 0.25;

/// Features per element ([`features`]).
pub const DIM: usize = 27;

/// A gradient magnitude (central differences, 0–255 grey) above this is an edge pixel.
const EDGE: f32 = 40.0;
/// A grey level (0–1) below this is dark (shadow, dense hatching, ink).
const DARK: f64 = 0.4;

/// A trained element verifier.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Verifier {
    pub format: u32,
    /// Two classes: 0 wrong, 1 an element of the drawing.
    pub forest: Forest,
    /// How it was trained (seed, images, counts).
    pub provenance: String,
}

/// Why a verifier file cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VerifierError {
    #[error("Gothic verifier: {0}")]
    Decode(String),
    #[error("Gothic verifier has format {found}, this program reads format {FORMAT}")]
    Format { found: u32 },
    #[error("Gothic verifier: {0}")]
    Invalid(String),
}

impl Verifier {
    /// Trains on rows of [`DIM`] features with labels (`true`: right).
    pub fn train(
        rows: &[[f32; DIM]],
        right: &[bool],
        seed: u64,
        provenance: String,
    ) -> Result<Verifier, VerifierError> {
        let x: Vec<f32> = rows.iter().flatten().copied().collect();
        let labels: Vec<usize> = right.iter().map(|&r| usize::from(r)).collect();
        let params = ForestParams {
            trees: 64,
            max_depth: 6,
            min_leaf: 2,
            seed,
            ..ForestParams::default()
        };
        let forest = Forest::train(&x, DIM, &labels, 2, &params)
            .map_err(|e| VerifierError::Invalid(e.to_string()))?;
        Ok(Verifier {
            format: FORMAT,
            forest,
            provenance,
        })
    }

    pub fn to_bytes(&self) -> Vec<u8> {
        postcard::to_allocvec(self).expect("a verifier always serialises")
    }

    /// Reads and checks a verifier (format, the forest's structure and width).
    pub fn from_bytes(bytes: &[u8]) -> Result<Verifier, VerifierError> {
        let v: Verifier =
            postcard::from_bytes(bytes).map_err(|e| VerifierError::Decode(e.to_string()))?;
        if v.format != FORMAT {
            return Err(VerifierError::Format { found: v.format });
        }
        v.forest
            .validate()
            .map_err(|e| VerifierError::Invalid(e.to_string()))?;
        if v.forest.dim != DIM || v.forest.classes != 2 {
            return Err(VerifierError::Invalid(format!(
                "the forest reads {} features of {} classes, expected {DIM} of 2",
                v.forest.dim, v.forest.classes
            )));
        }
        Ok(v)
    }

    /// Each element's probability of being right, in `est.elements` order.
    pub fn scores(&self, img: &RgbImage, est: &GothicEstimate) -> Vec<f32> {
        features(img, est)
            .iter()
            .map(|row| self.forest.predict_one(row)[1])
            .collect()
    }
}

/// The verifier that ships with castellan, decoded once. Its file is compiled in and checked
/// by this module's tests, so decoding cannot fail in a built program.
pub fn shipped() -> &'static Verifier {
    static SHIPPED_VERIFIER: std::sync::OnceLock<Verifier> = std::sync::OnceLock::new();
    SHIPPED_VERIFIER.get_or_init(|| {
        Verifier::from_bytes(SHIPPED).expect("the shipped Gothic verifier decodes (tested)")
    })
}

/// The box [x0, y0, x1, y1] of an element (image pixels, y down).
fn element_box(e: &Element) -> [f64; 4] {
    [e.x0, e.y0 - e.h - e.v, e.x0 + e.w, e.y0]
}

fn iou(a: [f64; 4], b: [f64; 4]) -> f64 {
    let ix = (a[2].min(b[2]) - a[0].max(b[0])).max(0.0);
    let iy = (a[3].min(b[3]) - a[1].max(b[1])).max(0.0);
    let i = ix * iy;
    let u = (a[2] - a[0]) * (a[3] - a[1]) + (b[2] - b[0]) * (b[3] - b[1]) - i;
    if u > 0.0 { i / u } else { 0.0 }
}

/// The grey image (0–255) and its gradient magnitude: what the check's tone, darkness and edge
/// statistics of a box are read from (also by `examples/openings_net`'s check of blobs).
pub struct Planes {
    grey: GrayImage,
    gradient: Vec<f32>,
}

impl Planes {
    pub fn of(img: &RgbImage) -> Planes {
        Planes::of_grey(image::imageops::grayscale(img))
    }

    pub fn of_grey(grey: GrayImage) -> Planes {
        let (w, h) = (grey.width() as usize, grey.height() as usize);
        let g = |x: usize, y: usize| f32::from(grey.as_raw()[y * w + x]);
        let mut gradient = vec![0f32; w * h];
        for y in 1..h.saturating_sub(1) {
            for x in 1..w.saturating_sub(1) {
                let (gx, gy) = (g(x + 1, y) - g(x - 1, y), g(x, y + 1) - g(x, y - 1));
                gradient[y * w + x] = gx.hypot(gy);
            }
        }
        Planes { grey, gradient }
    }

    /// Over the pixels of box `b` (clipped): mean grey (0–1), its deviation, the share of edge
    /// pixels, the share of dark pixels, and the box's pixel count.
    pub fn stats(&self, b: [f64; 4]) -> [f64; 5] {
        let (w, h) = (self.grey.width() as usize, self.grey.height() as usize);
        let clip = |v: f64, hi: usize| (v.max(0.0) as usize).min(hi);
        let (x0, y0, x1, y1) = (clip(b[0], w), clip(b[1], h), clip(b[2], w), clip(b[3], h));
        let (mut s, mut s2, mut edges, mut dark, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for y in y0..y1 {
            for x in x0..x1 {
                let v = f64::from(self.grey.as_raw()[y * w + x]) / 255.0;
                s += v;
                s2 += v * v;
                n += 1.0;
                edges += f64::from(u8::from(self.gradient[y * w + x] > EDGE));
                dark += f64::from(u8::from(v < DARK));
            }
        }
        if n == 0.0 {
            return [0.0; 5];
        }
        let m = s / n;
        [m, (s2 / n - m * m).max(0.0).sqrt(), edges / n, dark / n, n]
    }

    /// [`Planes::stats`] of box `b`, and the mean of each of its first four statistics over a
    /// ring round it a quarter of its size (+ 3 px) wide: the outer box's total less the box's.
    pub fn inside_and_ring(&self, b: [f64; 4]) -> ([f64; 5], [f64; 4]) {
        let (bw, bh) = (b[2] - b[0], b[3] - b[1]);
        let inside = self.stats(b);
        let (mx, my) = (0.25 * bw + 3.0, 0.25 * bh + 3.0);
        let outer = self.stats([b[0] - mx, b[1] - my, b[2] + mx, b[3] + my]);
        let extra = outer[4] - inside[4];
        let ring = std::array::from_fn(|i| {
            if extra > 0.0 {
                (outer[i] * outer[4] - inside[i] * inside[4]) / extra
            } else {
                outer[i]
            }
        });
        (inside, ring)
    }
}

/// The features of every element, in `est.elements` order: its size against the image,
/// shape, head, depth, fit (mean distance, support), group size, parent and children, height
/// in the image; the tone, its deviation, edge and dark shares inside its box and in a ring a
/// quarter of its size (+ 3 px) around it, and their differences; the number of other
/// elements whose box meets its box at IoU > 0.3.
pub fn features(img: &RgbImage, est: &GothicEstimate) -> Vec<[f32; DIM]> {
    let planes = Planes::of(img);
    let (iw, ih) = (f64::from(img.width()), f64::from(img.height()));
    let boxes: Vec<[f64; 4]> = est.elements.iter().map(element_box).collect();
    let group_size = |g: Option<usize>| -> usize {
        g.and_then(|g| est.groups.iter().find(|x: &&Group| x.id == g))
            .map_or(1, |x| x.members.len())
    };
    est.elements
        .iter()
        .enumerate()
        .map(|(k, e)| {
            let b = boxes[k];
            let (bw, bh) = (b[2] - b[0], b[3] - b[1]);
            let (inside, ring) = planes.inside_and_ring(b);
            let children = est
                .elements
                .iter()
                .filter(|o| o.parent == Some(e.id))
                .count();
            let overlaps = boxes
                .iter()
                .enumerate()
                .filter(|&(q, o)| q != k && iou(b, *o) > 0.3)
                .count();
            let row = [
                bw / iw,
                bh / ih,
                bh / bw.max(1.0),
                e.v / e.w.max(1.0),
                f64::from(u8::from(e.kind == ArchKind::Rectangle)),
                f64::from(u8::from(e.kind == ArchKind::Round)),
                f64::from(u8::from(e.kind == ArchKind::Pointed)),
                f64::from(u8::from(e.kind == ArchKind::Segmental)),
                e.depth as f64,
                e.mean_distance,
                e.support,
                f64::from(u8::from(e.group.is_some())),
                group_size(e.group) as f64,
                f64::from(u8::from(e.parent.is_some())),
                children as f64,
                0.5 * (b[1] + b[3]) / ih,
                inside[0],
                inside[1],
                inside[2],
                inside[3],
                ring[0],
                ring[1],
                ring[2],
                ring[3],
                inside[0] - ring[0],
                inside[2] - ring[2],
                overlaps as f64,
            ];
            row.map(|v| v as f32)
        })
        .collect()
}

/// The estimate with only the elements `keep` marks: ids renumbered in order, a dropped
/// parent replaced by its nearest kept ancestor, depths recounted, groups reduced to their
/// kept members (a group left with fewer than two is dissolved, an enclosing arch dropped is
/// forgotten).
pub fn retain(est: &GothicEstimate, keep: &[bool]) -> GothicEstimate {
    retain_mapped(est, keep).0
}

/// [`retain`], with the new index of each element (`None`: dropped).
pub fn retain_mapped(est: &GothicEstimate, keep: &[bool]) -> (GothicEstimate, Vec<Option<usize>>) {
    let by_id = |id: usize| est.elements.iter().position(|e| e.id == id);
    let mut new_id = vec![None; est.elements.len()];
    let mut n = 0;
    for (i, &k) in keep.iter().enumerate() {
        if k {
            new_id[i] = Some(n);
            n += 1;
        }
    }
    let id_of = |old: usize| by_id(old).and_then(|i| new_id[i]);
    let mut groups = Vec::new();
    let mut group_of = std::collections::HashMap::new();
    for g in &est.groups {
        let members: Vec<usize> = g.members.iter().filter_map(|&m| id_of(m)).collect();
        if members.len() < 2 {
            continue;
        }
        group_of.insert(g.id, groups.len());
        groups.push(Group {
            id: groups.len(),
            members,
            enclosing: g.enclosing.and_then(id_of),
            ..g.clone()
        });
    }
    let mut elements: Vec<Element> = Vec::with_capacity(n);
    for (i, e) in est.elements.iter().enumerate() {
        let Some(id) = new_id[i] else { continue };
        // The nearest kept ancestor (parents form a forest: the walk ends).
        let mut parent = e.parent;
        let mut steps = 0;
        while let Some(p) = parent {
            if id_of(p).is_some() || steps > est.elements.len() {
                break;
            }
            parent = by_id(p).and_then(|j| est.elements[j].parent);
            steps += 1;
        }
        elements.push(Element {
            id,
            group: e.group.and_then(|g| group_of.get(&g).copied()),
            parent: parent.and_then(id_of),
            ..e.clone()
        });
    }
    for i in 0..elements.len() {
        let mut depth = 0;
        let mut at = elements[i].parent;
        while let Some(p) = at {
            depth += 1;
            at = elements[p].parent;
            if depth > elements.len() {
                break;
            }
        }
        elements[i].depth = depth;
    }
    (
        GothicEstimate {
            width: est.width,
            height: est.height,
            elements,
            groups,
        },
        new_id,
    )
}

/// The pipeline's check (`GothicParams::verify`): the elements the shipped verifier scores
/// below [`DEFAULT_THRESHOLD`] taken out when `enabled`, except those with ids in `kept_ids`
/// (the user's); with each old id's new id (ids are indices).
pub(crate) fn checked(
    img: &RgbImage,
    est: GothicEstimate,
    kept_ids: &[usize],
    enabled: bool,
) -> (GothicEstimate, Vec<Option<usize>>) {
    if !enabled || est.elements.is_empty() {
        let ids = (0..est.elements.len()).map(Some).collect();
        return (est, ids);
    }
    let keep: Vec<bool> = passing(shipped(), img, &est, DEFAULT_THRESHOLD)
        .into_iter()
        .zip(&est.elements)
        .map(|(pass, e)| pass || kept_ids.contains(&e.id))
        .collect();
    retain_mapped(&est, &keep)
}

/// Whether each element scores at least `threshold`.
fn passing(verifier: &Verifier, img: &RgbImage, est: &GothicEstimate, threshold: f32) -> Vec<bool> {
    verifier
        .scores(img, est)
        .iter()
        .map(|&s| s >= threshold)
        .collect()
}

/// The estimate without the elements `verifier` scores below `threshold`. An enclosing arch
/// is judged like any element: keeping the parents of kept elements as well was measured
/// (docs/gothic.md) and gained one nested element for many wrong arches.
pub fn verified(
    img: &RgbImage,
    est: &GothicEstimate,
    verifier: &Verifier,
    threshold: f32,
) -> GothicEstimate {
    retain(est, &passing(verifier, img, est, threshold))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn element(id: usize, b: [f64; 4], parent: Option<usize>, group: Option<usize>) -> Element {
        Element {
            id,
            x0: b[0],
            y0: b[3],
            h: b[3] - b[1],
            w: b[2] - b[0],
            v: 0.0,
            group,
            parent,
            kind: ArchKind::Rectangle,
            depth: usize::from(parent.is_some()),
            mean_distance: 0.5,
            support: 1.0,
        }
    }

    /// An enclosing box (0) over a group of two windows (1, 2) and a lone window (3).
    fn estimate() -> GothicEstimate {
        GothicEstimate {
            width: 100,
            height: 80,
            elements: vec![
                element(0, [10.0, 10.0, 60.0, 70.0], None, None),
                element(1, [15.0, 30.0, 30.0, 70.0], Some(0), Some(0)),
                element(2, [40.0, 30.0, 55.0, 70.0], Some(0), Some(0)),
                element(3, [70.0, 30.0, 85.0, 70.0], None, None),
            ],
            groups: vec![Group {
                id: 0,
                members: vec![1, 2],
                h: 40.0,
                w: 15.0,
                v: 0.0,
                enclosing: Some(0),
            }],
        }
    }

    #[test]
    fn dropping_the_enclosing_arch_lifts_its_children_and_forgets_it() {
        let (kept, index) = retain_mapped(&estimate(), &[false, true, true, true]);
        assert_eq!(index, vec![None, Some(0), Some(1), Some(2)]);
        let ids: Vec<usize> = kept.elements.iter().map(|e| e.id).collect();
        assert_eq!(ids, vec![0, 1, 2]);
        assert!(
            kept.elements
                .iter()
                .all(|e| e.parent.is_none() && e.depth == 0)
        );
        assert_eq!(kept.groups.len(), 1);
        assert_eq!(kept.groups[0].members, vec![0, 1]);
        assert_eq!(kept.groups[0].enclosing, None);
        assert_eq!(kept.elements[0].group, Some(0));
    }

    #[test]
    fn a_group_left_with_one_member_is_dissolved() {
        let kept = retain(&estimate(), &[true, false, true, false]);
        assert_eq!(kept.elements.len(), 2);
        assert!(kept.groups.is_empty());
        assert_eq!(kept.elements[1].group, None);
        // The window keeps its enclosing box as parent, renumbered.
        assert_eq!(kept.elements[1].parent, Some(0));
        assert_eq!(kept.elements[1].depth, 1);
        assert_eq!(kept.elements[1].x0, 40.0);
    }

    #[test]
    fn features_read_the_box_and_the_ring_around_it() {
        // White paper with one black 20 × 40 opening at (40, 20).
        let mut img = RgbImage::from_pixel(100, 80, image::Rgb([255, 255, 255]));
        for y in 20..60 {
            for x in 40..60 {
                img.put_pixel(x, y, image::Rgb([0, 0, 0]));
            }
        }
        let est = GothicEstimate {
            width: 100,
            height: 80,
            elements: vec![element(0, [40.0, 20.0, 60.0, 60.0], None, None)],
            groups: vec![],
        };
        let f = features(&img, &est)[0];
        assert_eq!(f.len(), DIM);
        assert_eq!((f[0], f[1], f[2]), (0.2, 0.5, 2.0));
        assert_eq!(f[4], 1.0, "a rectangle");
        // Inside: black, no deviation, dark everywhere; the edges only on its border rows.
        assert_eq!((f[16], f[17], f[19]), (0.0, 0.0, 1.0));
        assert!(f[18] > 0.0 && f[18] < 0.2, "{}", f[18]);
        // The ring is white but for the edge pixels just outside the box.
        assert_eq!((f[20], f[23]), (1.0, 0.0));
        assert_eq!(f[24], -1.0, "inside darker than around by the whole range");
        assert_eq!(f[26], 0.0, "nothing overlaps it");
    }

    #[test]
    fn the_shipped_verifier_decodes_and_bad_files_are_refused() {
        let v = shipped();
        assert_eq!((v.forest.dim, v.forest.classes), (DIM, 2));
        assert!(
            v.provenance.contains("data/gothic_devset"),
            "{}",
            v.provenance
        );
        let cut = &SHIPPED[..SHIPPED.len() / 2];
        assert!(matches!(
            Verifier::from_bytes(cut),
            Err(VerifierError::Decode(_))
        ));
        let mut other = v.clone();
        other.format = FORMAT + 1;
        assert_eq!(
            Verifier::from_bytes(&other.to_bytes()),
            Err(VerifierError::Format { found: FORMAT + 1 })
        );
    }

    #[test]
    fn training_is_reproducible_and_learns_a_separable_rule() {
        // Right elements are dark inside (feature 16 low), wrong ones are not.
        let rows: Vec<[f32; DIM]> = (0..40)
            .map(|i| {
                let mut r = [0.5; DIM];
                r[16] = if i % 2 == 0 { 0.1 } else { 0.9 };
                r[0] = (i as f32) / 40.0;
                r
            })
            .collect();
        let right: Vec<bool> = (0..40).map(|i| i % 2 == 0).collect();
        let a = Verifier::train(&rows, &right, 7, "t".into()).unwrap();
        let b = Verifier::train(&rows, &right, 7, "t".into()).unwrap();
        assert_eq!(a.to_bytes(), b.to_bytes());
        let mut dark = [0.5; DIM];
        dark[16] = 0.1;
        let mut pale = [0.5; DIM];
        pale[16] = 0.9;
        // Trees that do not draw feature 16 split on feature 0 only, so not every tree is sure.
        let (d, p) = (
            a.forest.predict_one(&dark)[1],
            a.forest.predict_one(&pale)[1],
        );
        assert!(d > 0.6 && p < 0.4, "{d} {p}");
    }
}
