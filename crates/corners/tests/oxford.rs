//! Repeatability (§2.2) on real image pairs of the Oxford affine sequences, cropped so the test
//! stays quick in debug builds. Skips with a message when `../shared/data` is absent (the data
//! are for research use and are never copied into the repository).

use std::path::PathBuf;

use corners::repeat::{Homography, repeatability};
use corners::{Gray, Params, detect};

fn data_dir() -> Option<PathBuf> {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/oxford_affine");
    if d.is_dir() {
        Some(d)
    } else {
        eprintln!(
            "skipping: {} not found (Oxford affine sequences)",
            d.display()
        );
        None
    }
}

fn crop(g: &Gray, x0: usize, y0: usize, w: usize, h: usize) -> Gray {
    let mut data = Vec::with_capacity(w * h);
    for y in y0..y0 + h {
        data.extend_from_slice(&g.data[y * g.width + x0..y * g.width + x0 + w]);
    }
    Gray::new(w, h, data)
}

fn mul(a: &Homography, b: &Homography) -> Homography {
    Homography(std::array::from_fn(|i| {
        std::array::from_fn(|j| (0..3).map(|k| a.0[i][k] * b.0[k][j]).sum())
    }))
}

fn shift(dx: f64, dy: f64) -> Homography {
    Homography([[1.0, 0.0, dx], [0.0, 1.0, dy], [0.0, 0.0, 1.0]])
}

/// Repeatability of img1 → img`k` of `seq` on a `size` crop of img1 at (x0, y0) and the crop of
/// img`k` centred on the mapped centre.
fn crop_pair(
    seq: &str,
    k: usize,
    x0: usize,
    y0: usize,
    size: usize,
) -> Option<(f64, usize, usize)> {
    let dir = data_dir()?.join(seq);
    let load = |name: &str| {
        let img = image::open(dir.join(name)).expect("readable Oxford image");
        Gray::from_dynamic(&img)
    };
    let ext = if seq == "boat" { "pgm" } else { "ppm" };
    let (g1, gk) = (load(&format!("img1.{ext}")), load(&format!("img{k}.{ext}")));
    let h = Homography::parse(&std::fs::read_to_string(dir.join(format!("H1to{k}p"))).unwrap())
        .unwrap();
    let half = size as f64 / 2.0;
    let c = h.apply([x0 as f64 + half, y0 as f64 + half]).unwrap();
    let (xk, yk) = (
        (c[0] - half).round() as usize,
        (c[1] - half).round() as usize,
    );
    let (a, b) = (crop(&g1, x0, y0, size, size), crop(&gk, xk, yk, size, size));
    // Crop coordinates: H' = T(−o_k) · H · T(o_1).
    let hc = mul(
        &shift(-(xk as f64), -(yk as f64)),
        &mul(&h, &shift(x0 as f64, y0 as f64)),
    );
    let p = Params::default();
    let pts = |g: &Gray| -> Vec<[f64; 2]> {
        detect(g, &p)
            .unwrap()
            .corners
            .iter()
            .map(|c| [c.x, c.y])
            .collect()
    };
    let (pa, pb) = (pts(&a), pts(&b));
    let r = repeatability(&pa, (size, size), &pb, (size, size), &hc, 5.0);
    eprintln!(
        "{seq} 1→{k}: {} and {} corners, {} correspondences of min({}, {}): {:.3}",
        pa.len(),
        pb.len(),
        r.correspondences,
        r.n1,
        r.n2,
        r.rate
    );
    Some((r.rate, pa.len(), pb.len()))
}

#[test]
fn structured_scenes_repeat() {
    // wall (viewpoint) and bikes (blur): man-made structure, where figure 2.4 shows IPFIT
    // among the best.
    for (seq, k, x0, y0, min_rate) in [("wall", 2, 400, 260, 0.5), ("bikes", 2, 260, 260, 0.5)] {
        let Some((rate, n1, n2)) = crop_pair(seq, k, x0, y0, 200) else {
            return;
        };
        assert!(n1 >= 10 && n2 >= 10, "{seq}: too few corners ({n1}, {n2})");
        assert!(rate >= min_rate, "{seq} 1→{k}: repeatability {rate}");
    }
}
