//! Figures for §3.1: the façade image tinted by its pixel labels (0 background, 1 wall,
//! 2 window; §3.1.2–3.1.7) or by the classifier's class probabilities (§3.1.4): background red,
//! wall magenta, window green, each averaged half and half with the photo's own colour so the
//! façade stays visible under the tint. Each picture carries its key (issue 22).

use image::RgbImage;
use raster::legend::{self, Entry, Swatch};

use crate::classify::{Class, LogLikelihoods};

/// Tint colours by class (the discriminant indexes it).
const COLOURS: [[u8; 3]; 3] = [[255, 40, 40], [255, 0, 255], [0, 220, 0]];

/// The words a caption uses for the tints.
pub const LEGEND: &str = "green window, magenta wall, red background";

/// The key of the classes `present` (indexed as [`Class::ALL`]), window first as in
/// [`LEGEND`].
pub fn key(present: [bool; 3]) -> Vec<Entry> {
    [(2, "window"), (1, "wall"), (0, "background")]
        .into_iter()
        .filter(|&(c, _)| present[c])
        .map(|(c, name)| Entry::new(Swatch::Fill(COLOURS[c]), name))
        .collect()
}

fn present(labels: &[u8]) -> [bool; 3] {
    let mut seen = [false; 3];
    for &l in labels {
        seen[usize::from(l).min(2)] = true;
    }
    seen
}

/// The image tinted by label: background red, wall magenta, window green; with its key.
pub fn label_overlay(img: &RgbImage, labels: &[u8]) -> RgbImage {
    let mut o = img.clone();
    for (p, l) in o.pixels_mut().zip(labels) {
        let c = COLOURS[usize::from(*l).min(2)];
        for k in 0..3 {
            p[k] = ((u16::from(p[k]) + u16::from(c[k])) / 2) as u8;
        }
    }
    legend::draw(&mut o, &key(present(labels)), &|_, _| false);
    o
}

/// LABELS.view.png: a label image (0 background, 1 wall, 2 window) in the class colours with
/// its key, as a person views it (LABELS.png itself is an index image, black to the eye).
pub fn labels_view(width: u32, height: u32, labels: &[u8]) -> RgbImage {
    let mut o = RgbImage::from_fn(width, height, |x, y| {
        let l = labels.get((y * width + x) as usize).copied().unwrap_or(0);
        image::Rgb(COLOURS[usize::from(l).min(2)])
    });
    legend::draw(&mut o, &key(present(labels)), &|_, _| false);
    o
}

/// The image tinted by the per-pixel class probabilities (the softmax of the log-likelihoods
/// over the trained classes): each pixel's tint is the probability-weighted mix of the class
/// colours, so a sure pixel shows its class's colour and a doubtful one a blend, as in
/// ilastik's live view. `img` and `ll` must have the same size (pixels past `ll` are left).
pub fn probability_overlay(img: &RgbImage, ll: &LogLikelihoods) -> RgbImage {
    let mut o = img.clone();
    let maps: Vec<(usize, &[f32])> = Class::ALL
        .iter()
        .filter_map(|&c| ll.get(c).map(|m| (c as usize, m)))
        .collect();
    for (i, p) in o.pixels_mut().enumerate().take(ll.width * ll.height) {
        let top = maps
            .iter()
            .map(|(_, m)| m[i])
            .fold(f32::NEG_INFINITY, f32::max);
        let weights: Vec<f32> = maps.iter().map(|(_, m)| (m[i] - top).exp()).collect();
        let total: f32 = weights.iter().sum();
        for k in 0..3 {
            let tint: f32 = maps
                .iter()
                .zip(&weights)
                .map(|((c, _), w)| w * f32::from(COLOURS[*c][k]))
                .sum::<f32>()
                / total;
            p[k] = ((f32::from(p[k]) + tint) / 2.0).round() as u8;
        }
    }
    let trained = [0, 1, 2].map(|c| maps.iter().any(|(m, _)| *m == c));
    legend::draw(&mut o, &key(trained), &|_, _| false);
    o
}

/// Outlines boxes [x0, y0, x1, y1] (exclusive ends) two pixels thick in the window colour,
/// inside each box: the windows `repeat` proposed, over a probability or label overlay.
pub fn outline_windows(img: &mut RgbImage, boxes: &[[f64; 4]]) {
    let colour = image::Rgb(COLOURS[2]);
    for b in boxes {
        let (x0, y0) = (b[0].round() as i32, b[1].round() as i32);
        let (w, h) = ((b[2] - b[0]).round() as i32, (b[3] - b[1]).round() as i32);
        for inset in 0..2 {
            let (w, h) = (w - 2 * inset, h - 2 * inset);
            if w > 0 && h > 0 {
                let r =
                    imageproc::rect::Rect::at(x0 + inset, y0 + inset).of_size(w as u32, h as u32);
                imageproc::drawing::draw_hollow_rect_mut(img, r, colour);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Rgb;

    #[test]
    fn labels_tint_half_and_half() {
        let img = RgbImage::from_pixel(4, 1, Rgb([100, 100, 100]));
        let o = label_overlay(&img, &[0, 1, 2, 9]);
        assert_eq!(o.get_pixel(0, 0), &Rgb([177, 70, 70]));
        assert_eq!(o.get_pixel(1, 0), &Rgb([177, 50, 177]));
        assert_eq!(o.get_pixel(2, 0), &Rgb([50, 160, 50]));
        // Labels past 2 draw as windows.
        assert_eq!(o.get_pixel(3, 0), &Rgb([50, 160, 50]));
    }

    #[test]
    fn the_overlays_and_the_label_view_carry_their_key() {
        // A 200 × 100 façade: window on the left half, wall on the right, no background.
        let labels: Vec<u8> = (0..200 * 100)
            .map(|i| if i % 200 < 100 { 2 } else { 1 })
            .collect();
        let words = |k: Vec<Entry>| k.into_iter().map(|e| e.text).collect::<Vec<_>>();
        assert_eq!(words(key(present(&labels))), ["window", "wall"]);
        let img = RgbImage::from_pixel(200, 100, Rgb([100, 100, 100]));
        let o = label_overlay(&img, &labels);
        let v = labels_view(200, 100, &labels);
        for pic in [&o, &v] {
            // The key's frame at the bottom right, the picture untouched at the top left.
            assert_eq!(pic.get_pixel(199, 99), &Rgb([60, 60, 60]));
        }
        assert_eq!(o.get_pixel(0, 0), &Rgb([50, 160, 50]));
        assert_eq!(v.get_pixel(0, 0), &Rgb(COLOURS[2]));
        assert_eq!(v.get_pixel(150, 10), &Rgb(COLOURS[1]));
    }

    #[test]
    fn windows_are_outlined_two_pixels_thick_inside_their_box() {
        let mut img = RgbImage::from_pixel(8, 8, Rgb([0, 0, 0]));
        outline_windows(&mut img, &[[1.0, 1.0, 7.0, 7.0]]);
        let green = Rgb([0, 220, 0]);
        for (x, y) in [(1, 1), (6, 6), (2, 2), (5, 3), (3, 5)] {
            assert_eq!(img.get_pixel(x, y), &green, "({x}, {y})");
        }
        for (x, y) in [(0, 0), (7, 7), (3, 3), (4, 4)] {
            assert_eq!(img.get_pixel(x, y), &Rgb([0, 0, 0]), "({x}, {y})");
        }
    }

    #[test]
    fn probabilities_mix_the_class_colours() {
        let img = RgbImage::from_pixel(2, 1, Rgb([100, 100, 100]));
        let half = 0.5f32.ln();
        let ll = LogLikelihoods {
            width: 2,
            height: 1,
            // Pixel 0: sure window; pixel 1: wall or window, even odds. No background map.
            maps: [None, Some(vec![-30.0, half]), Some(vec![0.0, half])],
        };
        let o = probability_overlay(&img, &ll);
        assert_eq!(o.get_pixel(0, 0), &Rgb([50, 160, 50]));
        // Tint (127.5, 110, 127.5) averaged with the grey.
        assert_eq!(o.get_pixel(1, 0), &Rgb([114, 105, 114]));
    }
}
