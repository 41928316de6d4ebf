//! Masonry of §4.2: pixels of the estimated elements are removed, the rest is cut into
//! watershed basins of the colour gradient, and adjacent basins of similar colour are merged;
//! the merged regions fall in two colour classes, stones and mortar (MASONRY.png: 0 not wall,
//! 1 mortar, 2 stone). Each stone is kept with its outline box for extrusion.

use image::RgbImage;
use imageproc::filter::gaussian_blur_f32;
use imageproc::gradients::sobel_gradients;
use raster::components::{Connectivity, components_where};
use serde::{Deserialize, Serialize};

use super::model::GothicEstimate;
use super::watershed::{flood, regional_minima};

/// Thresholds of the masonry step (none are given in §4.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MasonryParams {
    /// Gaussian σ (px) before the gradient: mortar joints become ridges or valleys whose
    /// centre line has a near-zero gradient and so becomes a basin of its own.
    pub sigma: f32,
    /// Largest RGB distance between the mean colours of two adjacent regions that merge.
    pub merge_distance: f64,
    /// Smallest stone area (px); smaller stone-coloured regions stay in the label image only.
    pub min_stone_area: usize,
    /// Pixels around every element also removed, so frames do not become stones.
    pub element_margin: f64,
    /// Most stones reported (the largest first).
    pub max_stones: usize,
}

impl Default for MasonryParams {
    fn default() -> Self {
        MasonryParams {
            sigma: 1.0,
            merge_distance: 28.0,
            min_stone_area: 20,
            element_margin: 2.0,
            max_stones: 20_000,
        }
    }
}

/// One stone: a connected region of the stone class.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stone {
    pub id: usize,
    /// [x_min, y_min, x_max, y_max] in pixels, inclusive.
    pub bbox: [u32; 4],
    pub area: usize,
    /// Mean RGB colour.
    pub colour: [f64; 3],
}

/// The masonry segmentation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Masonry {
    pub width: u32,
    pub height: u32,
    /// Row-major, 0 not wall (elements), 1 mortar, 2 stone.
    #[serde(skip)]
    pub labels: Vec<u8>,
    pub stones: Vec<Stone>,
    /// Mean colours of the two classes (mortar, stone); equal when the wall is uniform.
    pub class_colours: [[f64; 3]; 2],
}

/// Pixels that belong to the wall (not inside any element grown by `margin`).
pub fn wall_mask(est: &GothicEstimate, width: u32, height: u32, margin: f64) -> Vec<bool> {
    let mut wall = vec![true; (width * height) as usize];
    for e in &est.elements {
        let t = e.theta().grown(margin);
        let [x0, y0, x1, y1] = t.bbox();
        let clamp = |v: f64, hi: u32| (v.max(0.0) as u32).min(hi.saturating_sub(1));
        for y in clamp(y0.floor(), height)..=clamp(y1.ceil(), height) {
            for x in clamp(x0.floor(), width)..=clamp(x1.ceil(), width) {
                if t.contains(x as f64, y as f64) {
                    wall[(y * width + x) as usize] = false;
                }
            }
        }
    }
    wall
}

/// Segments the wall around the estimated elements into stones and mortar.
pub fn segment(img: &RgbImage, est: &GothicEstimate, params: &MasonryParams) -> Masonry {
    let (w, h) = img.dimensions();
    let (wu, hu) = (w as usize, h as usize);
    let mask = wall_mask(est, w, h, params.element_margin);
    let gray = image::imageops::grayscale(img);
    let smooth = if params.sigma > 0.0 {
        gaussian_blur_f32(&gray, params.sigma)
    } else {
        gray
    };
    let grad = sobel_gradients(&smooth);
    let levels = quantise(grad.as_raw());
    // Departure from plain flooding: a joint-edge pixel reached by a stone and a mortar basin
    // at once joins the one whose marker colour is nearest (plain flooding takes the first
    // and shifts stone outlines by a pixel).
    let (mut basins, n) = regional_minima(&levels, wu, hu, &mask);
    let marker_colour = marker_means(img, &basins, n as usize);
    flood(&levels, wu, hu, &mask, &mut basins, |i, l| {
        let p = img.as_raw();
        let c = [p[3 * i] as f64, p[3 * i + 1] as f64, p[3 * i + 2] as f64];
        dist(c, marker_colour[l as usize])
    });
    let regions = merge_by_colour(img, &basins, n as usize, params.merge_distance);
    classify(img, &basins, &regions, &mask, params)
}

fn marker_means(img: &RgbImage, markers: &[u32], n: usize) -> Vec<[f64; 3]> {
    let (mut sum, mut area) = (vec![[0.0; 3]; n + 1], vec![0usize; n + 1]);
    for (p, &l) in img.pixels().zip(markers) {
        for k in 0..3 {
            sum[l as usize][k] += p[k] as f64;
        }
        area[l as usize] += 1;
    }
    sum.iter().zip(&area).map(|(s, &a)| mean(s, a)).collect()
}

fn quantise(g: &[u16]) -> Vec<u8> {
    let mut sorted = g.to_vec();
    if sorted.is_empty() {
        return Vec::new();
    }
    let k = (sorted.len() - 1) * 99 / 100;
    let top = (*sorted.select_nth_unstable(k).1).max(1) as u32;
    g.iter()
        .map(|&v| (v as u32 * 255 / top).min(255) as u8)
        .collect()
}

struct Regions {
    /// Merged region of each basin (index by basin label).
    root: Vec<usize>,
    sum: Vec<[f64; 3]>,
    area: Vec<usize>,
}

fn find(root: &mut [usize], mut i: usize) -> usize {
    while root[i] != i {
        root[i] = root[root[i]];
        i = root[i];
    }
    i
}

fn mean(sum: &[f64; 3], area: usize) -> [f64; 3] {
    let a = area.max(1) as f64;
    [sum[0] / a, sum[1] / a, sum[2] / a]
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Merges adjacent basins, most similar pairs first, while their current mean colours are
/// within `max_distance` (one pass over the adjacency list, so the work is bounded).
fn merge_by_colour(img: &RgbImage, basins: &[u32], n: usize, max_distance: f64) -> Regions {
    let width = img.width() as usize;
    let mut sum = vec![[0.0; 3]; n + 1];
    let mut area = vec![0usize; n + 1];
    for (i, p) in img.pixels().enumerate() {
        let b = basins[i] as usize;
        for k in 0..3 {
            sum[b][k] += p[k] as f64;
        }
        area[b] += 1;
    }
    let mut pairs = std::collections::HashSet::new();
    for (i, &b) in basins.iter().enumerate() {
        if b == 0 {
            continue;
        }
        for j in [i + 1, i + width] {
            if j < basins.len() && (j != i + 1 || j % width != 0) {
                let c = basins[j];
                if c != 0 && c != b {
                    pairs.insert((b.min(c) as usize, b.max(c) as usize));
                }
            }
        }
    }
    let mut edges: Vec<(f64, usize, usize)> = pairs
        .into_iter()
        .map(|(a, b)| (dist(mean(&sum[a], area[a]), mean(&sum[b], area[b])), a, b))
        .collect();
    edges.sort_by(|x, y| x.0.total_cmp(&y.0).then((x.1, x.2).cmp(&(y.1, y.2))));
    let mut root: Vec<usize> = (0..=n).collect();
    for (_, a, b) in edges {
        let (ra, rb) = (find(&mut root, a), find(&mut root, b));
        if ra == rb {
            continue;
        }
        if dist(mean(&sum[ra], area[ra]), mean(&sum[rb], area[rb])) <= max_distance {
            root[ra] = rb;
            let s = sum[ra];
            for k in 0..3 {
                sum[rb][k] += s[k];
            }
            area[rb] += area[ra];
        }
    }
    Regions { root, sum, area }
}

/// Two-means on the merged regions' luminance (area-weighted); the class whose pixels touch
/// the other class most often per pixel (thin joints) is mortar.
fn classify(
    img: &RgbImage,
    basins: &[u32],
    regions: &Regions,
    mask: &[bool],
    params: &MasonryParams,
) -> Masonry {
    let (w, h) = img.dimensions();
    let mut root = regions.root.clone();
    let n = root.len();
    let region_of: Vec<usize> = (0..n).map(|b| find(&mut root, b)).collect();
    let luma = |c: [f64; 3]| 0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2];
    let reps: Vec<usize> = (1..n)
        .filter(|&b| region_of[b] == b && regions.area[b] > 0)
        .collect();
    let lum: Vec<f64> = reps
        .iter()
        .map(|&r| luma(mean(&regions.sum[r], regions.area[r])))
        .collect();
    let (mut c0, mut c1) = lum
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &l| (a.min(l), b.max(l)));
    for _ in 0..50 {
        let (mut s, mut a) = ([0.0; 2], [0.0; 2]);
        for (k, &r) in reps.iter().enumerate() {
            let c = usize::from((lum[k] - c1).abs() < (lum[k] - c0).abs());
            s[c] += lum[k] * regions.area[r] as f64;
            a[c] += regions.area[r] as f64;
        }
        let next = [
            if a[0] > 0.0 { s[0] / a[0] } else { c0 },
            if a[1] > 0.0 { s[1] / a[1] } else { c1 },
        ];
        if next == [c0, c1] {
            break;
        }
        (c0, c1) = (next[0], next[1]);
    }
    let mut class_of = vec![0u8; n];
    for (k, &r) in reps.iter().enumerate() {
        class_of[r] = u8::from((lum[k] - c1).abs() < (lum[k] - c0).abs());
    }
    let pixel_class: Vec<Option<u8>> = basins
        .iter()
        .zip(mask)
        .map(|(&b, &m)| (m && b != 0).then(|| class_of[region_of[b as usize]]))
        .collect();
    // Boundary share per class decides which is mortar.
    let (mut touch, mut count) = ([0usize; 2], [0usize; 2]);
    let (wu, hu) = (w as usize, h as usize);
    for y in 0..hu {
        for x in 0..wu {
            let Some(c) = pixel_class[y * wu + x] else {
                continue;
            };
            count[c as usize] += 1;
            let other = [(x + 1, y), (x, y + 1)]
                .iter()
                .any(|&(a, b)| a < wu && b < hu && pixel_class[b * wu + a] == Some(1 - c));
            if other {
                touch[c as usize] += 1;
            }
        }
    }
    let share = |c: usize| touch[c] as f64 / count[c].max(1) as f64;
    // A uniform wall (one colour class) is all stone.
    let two_classes = (c1 - c0).abs() > params.merge_distance / 2.0 && count[0] > 0 && count[1] > 0;
    let mortar_class = if share(0) >= share(1) { 0u8 } else { 1 };
    let labels: Vec<u8> = pixel_class
        .iter()
        .map(|c| match c {
            None => 0,
            Some(c) if two_classes && *c == mortar_class => 1,
            Some(_) => 2,
        })
        .collect();
    let mut class_colours = [[0.0; 3]; 2];
    let mut class_area = [0usize; 2];
    for (p, &l) in img.pixels().zip(&labels) {
        if l > 0 {
            for k in 0..3 {
                class_colours[(l - 1) as usize][k] += p[k] as f64;
            }
            class_area[(l - 1) as usize] += 1;
        }
    }
    for c in 0..2 {
        class_colours[c] = mean(&class_colours[c], class_area[c]);
    }
    if class_area[0] == 0 {
        class_colours[0] = class_colours[1];
    }
    let stones = stones(img, &labels, params);
    Masonry {
        width: w,
        height: h,
        labels,
        stones,
        class_colours,
    }
}

/// Connected components (4-neighbour) of the stone label, the largest `max_stones` kept.
fn stones(img: &RgbImage, labels: &[u8], params: &MasonryParams) -> Vec<Stone> {
    let (w, h) = (img.width() as usize, img.height() as usize);
    let c = components_where(w, h, Connectivity::Four, |i| labels[i] == 2);
    // Colour sums per stone: sums of whole numbers, exact in any order.
    let mut sums = vec![[0.0; 3]; c.sizes.len()];
    for (&l, p) in c.labels.iter().zip(img.pixels()) {
        if l > 0 {
            for k in 0..3 {
                sums[l as usize][k] += p[k] as f64;
            }
        }
    }
    let mut out: Vec<Stone> = (1..c.sizes.len())
        .filter(|&l| c.sizes[l] >= params.min_stone_area)
        .map(|l| Stone {
            id: 0,
            bbox: c.bbox[l],
            area: c.sizes[l],
            colour: mean(&sums[l], c.sizes[l]),
        })
        .collect();
    out.sort_by(|a, b| b.area.cmp(&a.area).then(a.bbox.cmp(&b.bbox)));
    out.truncate(params.max_stones);
    out.sort_by(|a, b| (a.bbox[1], a.bbox[0]).cmp(&(b.bbox[1], b.bbox[0])));
    for (i, s) in out.iter_mut().enumerate() {
        s.id = i;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Rgb;

    /// Four 6x4 stones in a 1-px light mortar cross.
    fn wall() -> RgbImage {
        RgbImage::from_fn(13, 9, |x, y| {
            if x % 7 == 6 || y % 5 == 4 {
                Rgb([220, 220, 210])
            } else {
                Rgb([120, 60, 40])
            }
        })
    }

    fn empty(w: u32, h: u32) -> GothicEstimate {
        GothicEstimate {
            width: w,
            height: h,
            elements: vec![],
            groups: vec![],
        }
    }

    #[test]
    fn a_grid_wall_gives_four_stones_in_mortar() {
        let params = MasonryParams {
            sigma: 0.0,
            min_stone_area: 4,
            ..Default::default()
        };
        let m = segment(&wall(), &empty(13, 9), &params);
        assert_eq!(m.stones.len(), 4, "{:?}", m.stones);
        assert_eq!(m.stones[0].bbox, [0, 0, 5, 3]);
        assert_eq!(m.stones[3].bbox, [7, 5, 12, 8]);
        assert!(m.stones.iter().all(|s| s.area == 24));
        assert_eq!(m.labels[6], 1);
        assert_eq!(m.labels[4 * 13 + 2], 1);
        assert_eq!(m.labels[0], 2);
        assert!(m.class_colours[0][0] > 200.0 && m.class_colours[1][0] < 130.0);
    }

    #[test]
    fn a_uniform_wall_is_one_stone_and_element_pixels_are_zero() {
        let img = RgbImage::from_pixel(30, 30, Rgb([150, 150, 150]));
        let mut est = empty(30, 30);
        est.elements.push(crate::gothic::model::Element {
            id: 0,
            x0: 10.0,
            y0: 25.0,
            h: 10.0,
            w: 10.0,
            v: 5.0,
            group: None,
            parent: None,
            kind: crate::gothic::element::ArchKind::Round,
            depth: 0,
            mean_distance: 0.0,
            support: 1.0,
        });
        let m = segment(&img, &est, &MasonryParams::default());
        assert_eq!(m.stones.len(), 1);
        assert_eq!(m.labels[20 * 30 + 15], 0);
        assert_eq!(m.labels[0], 2);
    }
}
