//! A check of the network's blobs, learned from synthetic sheets too (issue 23, session 39):
//! each blob's size, shape, confidence, the drawing's tone and edges inside it and round it
//! (`gothic::verify::Planes`, as the estimator's check reads them),
//! and how many blobs of its size stand in its row or column (openings repeat); a forest
//! trained on the blobs of synthetic sheets the network did not train on, labelled by their
//! sheets' exact elements.

use facade::gothic::verify::Planes;
use image::GrayImage;
use pixelclass::forest::{Forest, ForestParams};
use raster::components::{Connectivity, components_where};

/// Features of a blob.
pub const DIM: usize = 16;

/// A blob of P(opening) > t: its box [x0, y0, x1, y1), pixel count, mean and largest P.
#[derive(Debug, Clone, Copy)]
pub struct Blob {
    pub bbox: [f64; 4],
    pub area: usize,
    pub mean_p: f32,
    pub max_p: f32,
}

/// The 4-connected blobs of `p > t` of at least 30 pixels and 5 × 7 px.
pub fn blobs(p: &[f32], w: usize, h: usize, t: f32) -> Vec<Blob> {
    let c = components_where(w, h, Connectivity::Four, |i| p[i] > t);
    let mut sum = vec![0f32; c.sizes.len()];
    let mut max = vec![0f32; c.sizes.len()];
    for (i, &l) in c.labels.iter().enumerate() {
        sum[l as usize] += p[i];
        max[l as usize] = max[l as usize].max(p[i]);
    }
    (1..c.sizes.len())
        .filter(|&l| {
            let b = c.bbox[l];
            c.sizes[l] >= 30 && b[2] - b[0] >= 4 && b[3] - b[1] >= 6
        })
        .map(|l| {
            let b = c.bbox[l].map(f64::from);
            Blob {
                bbox: [b[0], b[1], b[2] + 1.0, b[3] + 1.0],
                area: c.sizes[l],
                mean_p: sum[l] / c.sizes[l] as f32,
                max_p: max[l],
            }
        })
        .collect()
}

/// The features of every blob of one drawing (`grey`, its P(opening) map `p`).
pub fn features(grey: &GrayImage, p: &[f32], blobs: &[Blob]) -> Vec<[f32; DIM]> {
    let (w, h) = (grey.width() as usize, grey.height() as usize);
    let planes = Planes::of_grey(grey.clone());
    let mean_p = |b: [f64; 4]| {
        let clip = |v: f64, hi: usize| (v.max(0.0) as usize).min(hi);
        let (x0, y0, x1, y1) = (clip(b[0], w), clip(b[1], h), clip(b[2], w), clip(b[3], h));
        let n = ((x1 - x0) * (y1 - y0)).max(1) as f64;
        let s: f64 = (y0..y1)
            .flat_map(|y| (x0..x1).map(move |x| y * w + x))
            .map(|i| f64::from(p[i]))
            .sum();
        (s / n, n)
    };
    let (iw, ih) = (w as f64, h as f64);
    blobs
        .iter()
        .map(|bl| {
            let b = bl.bbox;
            let (bw, bh) = (b[2] - b[0], b[3] - b[1]);
            let (mx, my) = (0.25 * bw + 3.0, 0.25 * bh + 3.0);
            let outer_box = [b[0] - mx, b[1] - my, b[2] + mx, b[3] + my];
            // `Planes::stats` order: mean, deviation, edge share, dark share.
            let (inside, ring) = planes.inside_and_ring(b);
            let ((p_in, n_in), (p_out, n_out)) = (mean_p(b), mean_p(outer_box));
            let p_ring = if n_out > n_in {
                (p_out * n_out - p_in * n_in) / (n_out - n_in)
            } else {
                p_out
            };
            let (cx, cy) = (0.5 * (b[0] + b[2]), 0.5 * (b[1] + b[3]));
            let repeats = blobs
                .iter()
                .filter(|o| !std::ptr::eq(*o, bl))
                .filter(|o| {
                    let (ow, oh) = (o.bbox[2] - o.bbox[0], o.bbox[3] - o.bbox[1]);
                    let (ox, oy) = (0.5 * (o.bbox[0] + o.bbox[2]), 0.5 * (o.bbox[1] + o.bbox[3]));
                    let alike = (ow - bw).abs() <= 0.25 * bw && (oh - bh).abs() <= 0.25 * bh;
                    alike && ((oy - cy).abs() <= 0.3 * bh || (ox - cx).abs() <= 0.3 * bw)
                })
                .count();
            [
                bw / iw,
                bh / ih,
                bh / bw.max(1.0),
                bl.area as f64 / (bw * bh).max(1.0),
                f64::from(bl.mean_p),
                f64::from(bl.max_p),
                p_ring,
                inside[0],
                inside[1],
                inside[3],
                inside[2],
                ring[0],
                ring[3],
                ring[2],
                repeats as f64,
                cy / ih,
            ]
            .map(|v| v as f32)
        })
        .collect()
}

/// A forest on labelled blob features (`labels`: 1 = a true element).
pub fn train(rows: &[[f32; DIM]], labels: &[usize], seed: u64) -> Forest {
    let x: Vec<f32> = rows.iter().flatten().copied().collect();
    let p = ForestParams {
        trees: 64,
        max_depth: 10,
        min_leaf: 3,
        seed,
        ..ForestParams::default()
    };
    Forest::train(&x, DIM, labels, 2, &p).expect("both kinds of blob occur")
}
