//! Figures: the corner overlay (each corner and its two asymptote directions, §2.1.3) and the
//! plot of figure 2.4 (repeatability per image pair and detections per image, §2.2), drawn
//! with imageproc lines and `raster::text`'s 3 × 5 pixel font, so no font file is needed.

use image::{Rgb, RgbImage};
use imageproc::drawing::{draw_filled_rect_mut, draw_hollow_circle_mut, draw_line_segment_mut};
use imageproc::rect::Rect;

use crate::{Corner, Gray};
use raster::legend::{Entry, Swatch};
use raster::text::text;

/// Distinct colours for plot series, IPFIT first (red, as in figure 2.4).
pub const PALETTE: [[u8; 3]; 8] = [
    [220, 30, 30],
    [30, 90, 220],
    [20, 160, 60],
    [230, 150, 0],
    [140, 60, 200],
    [0, 170, 190],
    [120, 120, 120],
    [200, 80, 160],
];

/// The image, dimmed to grey, with each corner as a red circle and its two asymptote
/// directions as yellow and cyan arms of `arm` pixels from the corner, with its key. `scale` resizes the output (e.g.
/// 0.5 for documentation figures); positions are scaled with it.
pub fn overlay(img: &Gray, corners: &[Corner], arm: f64, scale: f64) -> RgbImage {
    let scale = if scale > 0.0 && scale.is_finite() {
        scale
    } else {
        1.0
    };
    let w = ((img.width as f64 * scale).round() as u32).max(1);
    let h = ((img.height as f64 * scale).round() as u32).max(1);
    let mut out = RgbImage::new(w, h);
    if img.width > 0 && img.height > 0 {
        for (x, y, p) in out.enumerate_pixels_mut() {
            let sx = ((x as f64 + 0.5) / scale) as usize;
            let sy = ((y as f64 + 0.5) / scale) as usize;
            let v = img.at(sx.min(img.width - 1), sy.min(img.height - 1));
            let g = (60.0 + 0.6 * v.clamp(0.0, 255.0)) as u8;
            *p = Rgb([g, g, g]);
        }
    }
    let colours = [Rgb([255, 230, 0]), Rgb([0, 230, 255])];
    for c in corners {
        let (cx, cy) = ((c.x * scale) as f32, (c.y * scale) as f32);
        for (v, col) in c.directions.iter().zip(colours) {
            // Directions point from the corner along its edges: draw the two arms.
            let (dx, dy) = ((v[0] * arm * scale) as f32, (v[1] * arm * scale) as f32);
            draw_line_segment_mut(&mut out, (cx, cy), (cx + dx, cy + dy), col);
        }
        let r = (3.0 * scale.max(0.5)).round() as i32;
        draw_hollow_circle_mut(
            &mut out,
            (cx.round() as i32, cy.round() as i32),
            r,
            Rgb([255, 40, 40]),
        );
    }
    // Issue 22: the overlay carries its key.
    let key = [
        Entry::new(Swatch::Ring([255, 40, 40]), "corner"),
        Entry::new(Swatch::Line([255, 230, 0]), "first asymptote"),
        Entry::new(Swatch::Line([0, 230, 255]), "second asymptote"),
    ];
    raster::legend::draw(&mut out, &key, &|_, _| false);
    out
}

/// One curve pair of the plot: repeatability for images 2..=n against image 1, and the number
/// of detections in images 1..=n.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub name: String,
    pub color: [u8; 3],
    pub repeatability: Vec<f64>,
    pub detections: Vec<f64>,
}

fn nice_max(v: f64) -> f64 {
    if !(v > 0.0) {
        return 1.0;
    }
    let p = 10f64.powf(v.log10().floor());
    for m in [1.0, 2.0, 2.5, 5.0, 10.0] {
        if m * p >= v {
            return m * p;
        }
    }
    10.0 * p
}

fn fmt_tick(v: f64) -> String {
    if v.fract().abs() < 1e-9 {
        format!("{}", v as i64)
    } else {
        format!("{v:.1}")
    }
}

/// One panel: x from `x0` in unit steps over `n` points, y from 0 to `ymax`.
#[allow(clippy::too_many_arguments)]
fn panel(
    img: &mut RgbImage,
    left: i32,
    top: i32,
    w: i32,
    h: i32,
    title: &str,
    x0: usize,
    ymax: f64,
    curves: &[(&[f64], [u8; 3])],
) {
    let black = Rgb([0, 0, 0]);
    let n = curves.iter().map(|c| c.0.len()).max().unwrap_or(0).max(2);
    let (x_at, y_at) = (
        |i: usize| left as f32 + i as f32 * (w as f32 / (n - 1) as f32),
        |v: f64| top as f32 + h as f32 * (1.0 - (v / ymax).clamp(0.0, 1.05) as f32),
    );
    // Grid and y ticks.
    for k in 0..=5 {
        let v = ymax * k as f64 / 5.0;
        let y = y_at(v);
        draw_line_segment_mut(
            img,
            (left as f32, y),
            ((left + w) as f32, y),
            Rgb([225, 225, 225]),
        );
        draw_line_segment_mut(img, (left as f32 - 5.0, y), (left as f32, y), black);
        let label = fmt_tick(v);
        let lw = label.len() as i32 * 8;
        text(img, left - 8 - lw, y as i32 - 5, &label, 2, [0, 0, 0]);
    }
    for i in 0..n {
        let x = x_at(i);
        draw_line_segment_mut(img, (x, (top + h) as f32), (x, (top + h + 5) as f32), black);
        text(
            img,
            x as i32 - 3,
            top + h + 9,
            &(x0 + i).to_string(),
            2,
            [0, 0, 0],
        );
    }
    draw_line_segment_mut(
        img,
        (left as f32, top as f32),
        (left as f32, (top + h) as f32),
        black,
    );
    draw_line_segment_mut(
        img,
        (left as f32, (top + h) as f32),
        ((left + w) as f32, (top + h) as f32),
        black,
    );
    text(img, left, top - 22, title, 3, [0, 0, 0]);
    for (vals, col) in curves {
        let pts: Vec<(f32, f32)> = vals
            .iter()
            .enumerate()
            .filter(|(_, v)| v.is_finite())
            .map(|(i, &v)| (x_at(i), y_at(v)))
            .collect();
        for s in pts.windows(2) {
            for o in [-0.5f32, 0.0, 0.5] {
                draw_line_segment_mut(img, (s[0].0, s[0].1 + o), (s[1].0, s[1].1 + o), Rgb(*col));
            }
        }
        for p in &pts {
            let r = Rect::at(p.0 as i32 - 3, p.1 as i32 - 3).of_size(7, 7);
            draw_filled_rect_mut(img, r, Rgb(*col));
        }
    }
}

/// The two graphs of figure 2.4 for one sequence: repeatability against image 1 for images
/// 2..=n (left, 0 to 1) and detections per image 1..=n (right), with a legend of coloured
/// swatches and names along the bottom.
pub fn plot(title: &str, series: &[Series]) -> RgbImage {
    let (w, h) = (1000u32, 480u32);
    let mut img = RgbImage::from_pixel(w, h, Rgb([255, 255, 255]));
    text(&mut img, 20, 12, title, 3, [0, 0, 0]);
    let rep: Vec<(&[f64], [u8; 3])> = series
        .iter()
        .map(|s| (s.repeatability.as_slice(), s.color))
        .collect();
    panel(&mut img, 80, 80, 380, 290, "repeatability", 2, 1.0, &rep);
    let dmax = series
        .iter()
        .flat_map(|s| s.detections.iter().copied())
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    let det: Vec<(&[f64], [u8; 3])> = series
        .iter()
        .map(|s| (s.detections.as_slice(), s.color))
        .collect();
    panel(
        &mut img,
        590,
        80,
        380,
        290,
        "detections",
        1,
        nice_max(dmax),
        &det,
    );
    let (mut x, mut y) = (20, 420);
    for s in series {
        let needed = 28 + s.name.len() as i32 * 8 + 24;
        if x + needed > w as i32 {
            x = 20;
            y += 24;
        }
        draw_filled_rect_mut(&mut img, Rect::at(x, y).of_size(20, 12), Rgb(s.color));
        x = text(&mut img, x + 28, y + 1, &s.name, 2, [0, 0, 0]) + 24;
    }
    img
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlay_marks_the_corner_and_its_arms() {
        let img = Gray::new(40, 40, vec![100.0; 1600]);
        let c = Corner {
            x: 20.0,
            y: 20.0,
            directions: [[1.0, 0.0], [0.0, 1.0]],
            epsilon: 0.1,
            lambda: 0.5,
            delta: 0.0,
            psi: 0.78,
        };
        let out = overlay(&img, &[c], 10.0, 1.0);
        assert_eq!(out.dimensions(), (40, 40));
        assert_eq!(out.get_pixel(28, 20), &Rgb([255, 230, 0]));
        assert_eq!(out.get_pixel(20, 28), &Rgb([0, 230, 255]));
        assert_eq!(out.get_pixel(35, 35), &Rgb([120, 120, 120]));
        // Arms only: nothing on the far side of the corner.
        assert_eq!(out.get_pixel(12, 20), &Rgb([120, 120, 120]));
        assert_eq!(overlay(&img, &[], 10.0, 0.5).dimensions(), (20, 20));
    }

    #[test]
    fn plot_draws_each_series_colour() {
        let s = vec![
            Series {
                name: "ipfit".into(),
                color: PALETTE[0],
                repeatability: vec![0.9, 0.8, 0.5, 0.4, 0.2],
                detections: vec![300.0, 280.0, 250.0, 200.0, 150.0, 120.0],
            },
            Series {
                name: "harris".into(),
                color: PALETTE[1],
                repeatability: vec![0.7, 0.6, f64::NAN, 0.3, 0.1],
                detections: vec![1000.0; 6],
            },
        ];
        let img = plot("graf", &s);
        for c in [PALETTE[0], PALETTE[1]] {
            assert!(img.pixels().filter(|p| p.0 == c).count() > 200, "{c:?}");
        }
        assert_eq!(nice_max(1234.0), 2000.0);
        assert_eq!(nice_max(0.0), 1.0);
    }
}
