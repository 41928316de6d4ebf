//! Degradations that never move geometry: paper tone and texture, grey ink, stains, blur,
//! 16-level quantisation and a JPEG round trip.

use std::f64::consts::PI;
use std::io::Cursor;

use image::GrayImage;
use image::codecs::jpeg::JpegEncoder;
use rand::RngExt;

use super::geometry::{P, Rng, add, scan, sub, u};

/// Paper tone and texture, grey ink, stains, blur, quantisation and a JPEG round trip.
pub(super) fn degrade(img: &mut GrayImage, rng: &mut Rng) {
    let (paper, ink) = (u(rng, 195.0, 250.0), u(rng, 0.0, 90.0));
    let tone = paper_tone(rng, img.width() as usize, img.height() as usize);
    let (noise, key) = (u(rng, 0.0, 12.0), rng.random::<u64>());
    for (i, px) in img.as_mut().iter_mut().enumerate() {
        let h = splitmix(key ^ i as u64);
        let sum: u64 = (0..3).map(|k| (h >> (k * 21)) & 0x1f_ffff).sum();
        let n = (sum as f64 / 0x1f_ffff as f64 - 1.5) * 2.0 * noise;
        let v = ink + (paper + tone[i] as f64 - ink) * *px as f64 / 255.0 + n;
        *px = v.clamp(0.0, 255.0) as u8;
    }
    let sigma = u(rng, 0.0, 1.5) as f32;
    if sigma > 0.3 {
        *img = imageproc::filter::gaussian_blur_f32(img, sigma);
    }
    if rng.random_bool(0.25) {
        img.as_mut()
            .iter_mut()
            .for_each(|p| *p = (*p & 0xf0) | (*p >> 4));
    }
    if rng.random_bool(0.5) {
        jpeg(img, rng.random_range(30..=90));
    }
}

/// Low-frequency brightness variation (three plane waves) less a few soft stains.
pub(super) fn paper_tone(rng: &mut Rng, w: usize, h: usize) -> Vec<f32> {
    let mut tone = vec![0f32; w * h];
    for _ in 0..3 {
        let (fx, fy) = (u(rng, 0.5, 3.0) * 2.0 * PI, u(rng, 0.5, 3.0) * 2.0 * PI);
        let (ph, a) = (u(rng, 0.0, 2.0 * PI), u(rng, 0.0, 8.0) as f32);
        let xs: Vec<(f32, f32)> = (0..w).map(|x| sc(fx * x as f64 / w as f64)).collect();
        for y in 0..h {
            let (sy, cy) = sc(fy * y as f64 / h as f64 + ph);
            for (t, (sx, cx)) in tone[y * w..(y + 1) * w].iter_mut().zip(&xs) {
                *t += a * (sx * cy + cx * sy);
            }
        }
    }
    for _ in 0..rng.random_range(0..4) {
        let c = (u(rng, 0.0, w as f64), u(rng, 0.0, h as f64));
        let (r, d) = (u(rng, 5.0, w.min(h) as f64 * 0.1), u(rng, 10.0, 40.0));
        let stain = |p: P| (-((p.0 - c.0).powi(2) + (p.1 - c.1).powi(2)) / (r * r)).exp();
        let (lo, hi) = (sub(c, (3.0 * r, 3.0 * r)), add(c, (3.0 * r, 3.0 * r)));
        scan(
            w,
            h,
            lo,
            hi,
            |_| true,
            |i| {
                let p = ((i % w) as f64, (i / w) as f64);
                tone[i] -= (d * stain(p)) as f32;
            },
        );
    }
    tone
}

pub(super) fn sc(a: f64) -> (f32, f32) {
    (a.sin() as f32, a.cos() as f32)
}

pub(super) fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

pub(super) fn jpeg(img: &mut GrayImage, quality: u8) {
    let mut buf = Vec::new();
    let enc = JpegEncoder::new_with_quality(Cursor::new(&mut buf), quality);
    if img.write_with_encoder(enc).is_ok()
        && let Ok(d) = image::load_from_memory(&buf)
    {
        *img = d.to_luma8();
    }
}
