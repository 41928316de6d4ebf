//! The print: ink laid on toned paper with a slow mottling, a slight Gaussian blur, Gaussian
//! noise, optionally the 16 grey levels of the scanned plates' 4-bit palettes, optionally a
//! JPEG round trip (the `image` crate's in-memory encoder and decoder).

use image::codecs::jpeg::JpegEncoder;
use image::{GrayImage, ImageFormat};

use super::basics::{Rng, uniform};
use super::pen::Canvas;
use super::style::Style;

pub(super) fn finish(rng: &mut Rng, style: &Style, canvas: &Canvas) -> GrayImage {
    let d = style.degrade;
    let (w, h) = (canvas.w, canvas.h);
    let ink = style.pen.ink;
    // The 4-bit scans have clean white paper: no tone, no mottling to band into levels.
    let (paper, amp) = if d.quantise {
        (d.paper.max(240.0), 0.0)
    } else {
        (d.paper, d.mottle)
    };
    let mottle = mottling(rng, w, h, d.mottle_cell, amp);
    let mut lum: Vec<f32> = canvas
        .ink
        .iter()
        .zip(&mottle)
        .map(|(&a, &m)| {
            let paper = (paper + m).clamp(0.0, 255.0);
            paper - a.powf(style.pen.gamma) * (paper - ink)
        })
        .collect();
    if d.blur > 0.05 {
        lum = blur(&lum, w, h, d.blur);
    }
    if d.noise > 0.0 {
        for v in &mut lum {
            *v += d.noise * gaussian(rng);
        }
    }
    let mut img = GrayImage::new(w as u32, h as u32);
    for (p, &v) in img.iter_mut().zip(&lum) {
        let v = v.clamp(0.0, 255.0);
        *p = if d.quantise {
            ((v / 17.0).round() * 17.0) as u8
        } else {
            v.round() as u8
        };
    }
    if let Some(q) = d.jpeg {
        img = jpeg_round_trip(&img, q).unwrap_or(img);
    }
    img
}

/// Paper tone variation: random values on a coarse grid, bilinearly interpolated.
fn mottling(rng: &mut Rng, w: usize, h: usize, cell: f64, amp: f32) -> Vec<f32> {
    if amp <= 0.0 {
        return vec![0.0; w * h];
    }
    let cell = cell.max(4.0);
    let (gw, gh) = (
        (w as f64 / cell).ceil() as usize + 2,
        (h as f64 / cell).ceil() as usize + 2,
    );
    let grid: Vec<f32> = (0..gw * gh)
        .map(|_| amp * uniform(rng, -1.0, 1.0) as f32)
        .collect();
    let mut out = vec![0.0; w * h];
    // Smoothstep weights: no creases along the grid.
    let smooth = |t: f64| (t * t * (3.0 - 2.0 * t)) as f32;
    for y in 0..h {
        let fy = y as f64 / cell;
        let (gy, ty) = (fy.floor() as usize, smooth(fy - fy.floor()));
        for x in 0..w {
            let fx = x as f64 / cell;
            let (gx, tx) = (fx.floor() as usize, smooth(fx - fx.floor()));
            let at = |i: usize, j: usize| grid[(gy + j) * gw + gx + i];
            let top = at(0, 0) * (1.0 - tx) + at(1, 0) * tx;
            let bot = at(0, 1) * (1.0 - tx) + at(1, 1) * tx;
            out[y * w + x] = top * (1.0 - ty) + bot * ty;
        }
    }
    out
}

/// Separable Gaussian blur with clamped edges.
fn blur(src: &[f32], w: usize, h: usize, sigma: f64) -> Vec<f32> {
    let r = (3.0 * sigma).ceil() as i64;
    let mut k: Vec<f32> = (-r..=r)
        .map(|i| (-(i * i) as f64 / (2.0 * sigma * sigma)).exp() as f32)
        .collect();
    let s: f32 = k.iter().sum();
    k.iter_mut().for_each(|v| *v /= s);
    let pass = |src: &[f32], horizontal: bool| {
        let mut out = vec![0.0; w * h];
        for y in 0..h {
            for x in 0..w {
                let mut acc = 0.0;
                for (ki, kv) in k.iter().enumerate() {
                    let o = ki as i64 - r;
                    let (xx, yy) = if horizontal {
                        ((x as i64 + o).clamp(0, w as i64 - 1) as usize, y)
                    } else {
                        (x, (y as i64 + o).clamp(0, h as i64 - 1) as usize)
                    };
                    acc += kv * src[yy * w + xx];
                }
                out[y * w + x] = acc;
            }
        }
        out
    };
    pass(&pass(src, true), false)
}

/// A standard normal deviate (Box–Muller).
fn gaussian(rng: &mut Rng) -> f32 {
    let u1 = uniform(rng, 1e-12, 1.0);
    let u2 = uniform(rng, 0.0, 1.0);
    ((-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()) as f32
}

fn jpeg_round_trip(img: &GrayImage, quality: u8) -> Option<GrayImage> {
    let mut bytes = Vec::new();
    JpegEncoder::new_with_quality(&mut bytes, quality.clamp(1, 100))
        .encode_image(img)
        .ok()?;
    let back = image::load_from_memory_with_format(&bytes, ImageFormat::Jpeg).ok()?;
    Some(back.to_luma8())
}
