//! Figures for §3.1: the façade image tinted by its pixel labels (0 background, 1 wall,
//! 2 window; §3.1.2–3.1.7): background red, wall magenta, window green, each averaged half and
//! half with the photo's own colour so the façade stays visible under the tint.

use image::{Rgb, RgbImage};

/// The image tinted by label: background red, wall magenta, window green.
pub fn label_overlay(img: &RgbImage, labels: &[u8]) -> RgbImage {
    let mut o = img.clone();
    let colours = [Rgb([255u8, 40, 40]), Rgb([255, 0, 255]), Rgb([0, 220, 0])];
    for (p, l) in o.pixels_mut().zip(labels) {
        let c = colours[usize::from(*l).min(2)];
        for k in 0..3 {
            p[k] = ((u16::from(p[k]) + u16::from(c[k])) / 2) as u8;
        }
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
