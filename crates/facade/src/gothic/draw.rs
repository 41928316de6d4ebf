//! Figures for ch. 4: the façade with the mortar of §4.2's masonry tinted (when segmented) and
//! the contour of every element Θ (eq. 4.1, §4.1) drawn by nesting depth (figure 4.4): top-level
//! elements red, nested ones blue, deeper ones green.

use image::{Rgb, RgbImage};

use super::GothicEstimate;
use super::masonry::Masonry;

/// The image with mortar tinted (when segmented) and every element's contour drawn: top-level
/// elements red, nested ones blue, deeper ones green.
pub fn overlay(img: &RgbImage, est: &GothicEstimate, masonry: Option<&Masonry>) -> RgbImage {
    let mut o = img.clone();
    if let Some(m) = masonry {
        for (p, &l) in o.pixels_mut().zip(&m.labels) {
            if l == 1 {
                *p = Rgb([(p[0] as u16 / 2 + 127) as u8, p[1] / 2 + 100, p[2] / 2]);
            }
        }
    }
    let colours = [Rgb([255u8, 30, 30]), Rgb([40, 120, 255]), Rgb([0, 220, 0])];
    let (w, h) = (o.width() as i64, o.height() as i64);
    for e in &est.elements {
        let c = colours[e.depth.min(2)];
        for s in e.theta().contour_at(0.5) {
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let (x, y) = (s.x.round() as i64 + dx, s.y.round() as i64 + dy);
                if x >= 0 && y >= 0 && x < w && y < h {
                    o.put_pixel(x as u32, y as u32, c);
                }
            }
        }
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gothic::{ArchKind, Element};

    #[test]
    fn mortar_tinted_and_contours_coloured_by_depth() {
        let img = RgbImage::from_pixel(40, 40, Rgb([100, 100, 100]));
        let element = |id, x0, y0, depth| Element {
            id,
            x0,
            y0,
            h: 10.0,
            w: 10.0,
            v: 0.0,
            group: None,
            parent: None,
            kind: ArchKind::Rectangle,
            depth,
            mean_distance: 0.0,
            support: 1.0,
        };
        let est = GothicEstimate {
            width: 40,
            height: 40,
            elements: vec![element(0, 2.0, 15.0, 0), element(1, 22.0, 35.0, 1)],
            groups: vec![],
        };
        let mut labels = vec![2u8; 40 * 40];
        labels[0] = 1;
        let masonry = Masonry {
            width: 40,
            height: 40,
            labels,
            stones: vec![],
            class_colours: [[0.0; 3]; 2],
        };
        let o = overlay(&img, &est, Some(&masonry));
        assert_eq!(o.get_pixel(0, 0), &Rgb([177, 150, 50]));
        assert_eq!(o.get_pixel(39, 0), &Rgb([100, 100, 100]));
        let count = |c: Rgb<u8>| o.pixels().filter(|p| **p == c).count();
        assert!(count(Rgb([255, 30, 30])) > 20);
        assert!(count(Rgb([40, 120, 255])) > 20);
        assert_eq!(
            overlay(&img, &est, None).get_pixel(0, 0),
            img.get_pixel(0, 0)
        );
    }
}
