//! Figures for ch. 4: the façade with the mortar of §4.2's masonry tinted (when segmented) and
//! the contour of every element Θ (eq. 4.1, §4.1) drawn by nesting depth (figure 4.4): top-level
//! elements red, nested ones blue, deeper ones green. Each picture carries its key (issue 22).

use image::{Rgb, RgbImage};
use raster::legend::{self, Entry, Swatch};

use super::GothicEstimate;
use super::masonry::Masonry;

/// The words of [`overlay`]'s key, for captions.
pub const LEGEND: &str =
    "contours red: arch, blue: nested arch, green: deeper; mortar tinted yellow-brown";

/// Contour colours by nesting depth (0, 1, 2 and deeper).
const DEPTH_COLOURS: [[u8; 3]; 3] = [[255, 30, 30], [40, 120, 255], [0, 220, 0]];
/// Mortar's tint on a mid-grey photo, for the key.
const MORTAR_KEY: [u8; 3] = [177, 150, 50];
/// MASONRY.view.png's colours: not wall (elements), mortar, stone.
const MASONRY_COLOURS: [[u8; 3]; 3] = [[40, 60, 140], [230, 200, 60], [150, 150, 150]];

/// The key of [`overlay`]: the depths drawn and the mortar when tinted.
fn key(est: &GothicEstimate, masonry: bool) -> Vec<Entry> {
    let deepest = est.elements.iter().map(|e| e.depth.min(2)).max();
    let mut key: Vec<Entry> = ["arch", "nested arch", "deeper arch"]
        .into_iter()
        .zip(DEPTH_COLOURS)
        .take(deepest.map_or(0, |d| d + 1))
        .map(|(name, c)| Entry::new(Swatch::Line(c), name))
        .collect();
    if masonry {
        key.push(Entry::new(Swatch::Fill(MORTAR_KEY), "mortar"));
    }
    key
}

/// The image with mortar tinted (when segmented) and every element's contour drawn: top-level
/// elements red, nested ones blue, deeper ones green; with its key.
pub fn overlay(img: &RgbImage, est: &GothicEstimate, masonry: Option<&Masonry>) -> RgbImage {
    let mut o = img.clone();
    if let Some(m) = masonry {
        for (p, &l) in o.pixels_mut().zip(&m.labels) {
            if l == 1 {
                *p = Rgb([(p[0] as u16 / 2 + 127) as u8, p[1] / 2 + 100, p[2] / 2]);
            }
        }
    }
    let colours = DEPTH_COLOURS.map(Rgb);
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
    legend::draw(&mut o, &key(est, masonry.is_some()), &|_, _| false);
    o
}

/// MASONRY.view.png: the masonry labels (0 not wall, 1 mortar, 2 stone) in colours a person
/// tells apart, with the key (MASONRY.png is an index image, black to the eye).
pub fn masonry_view(m: &Masonry) -> RgbImage {
    let mut o = RgbImage::from_fn(m.width, m.height, |x, y| {
        let l = m
            .labels
            .get((y * m.width + x) as usize)
            .copied()
            .unwrap_or(0);
        Rgb(MASONRY_COLOURS[usize::from(l).min(2)])
    });
    let key = ["not wall (arches, openings)", "mortar", "stone"]
        .into_iter()
        .zip(MASONRY_COLOURS)
        .map(|(name, c)| Entry::new(Swatch::Fill(c), name))
        .collect::<Vec<_>>();
    legend::draw(&mut o, &key, &|_, _| false);
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
        let words = |k: Vec<Entry>| k.into_iter().map(|e| e.text).collect::<Vec<_>>();
        assert_eq!(words(key(&est, true)), ["arch", "nested arch", "mortar"]);
        assert_eq!(words(key(&est, false)), ["arch", "nested arch"]);
        // The swatch of mortar is the tint the overlay gives a mid-grey photo.
        assert_eq!(o.get_pixel(0, 0).0, MORTAR_KEY);
    }

    #[test]
    fn the_masonry_view_colours_each_class_and_carries_its_key() {
        let (w, h) = (300u32, 200u32);
        let labels = (0..w * h).map(|i| (i % w / 100) as u8).collect();
        let m = Masonry {
            width: w,
            height: h,
            labels,
            stones: vec![],
            class_colours: [[0.0; 3]; 2],
        };
        let v = masonry_view(&m);
        assert_eq!(v.get_pixel(10, 10).0, MASONRY_COLOURS[0]);
        assert_eq!(v.get_pixel(150, 10).0, MASONRY_COLOURS[1]);
        assert_eq!(v.get_pixel(250, 10).0, MASONRY_COLOURS[2]);
        assert_eq!(v.get_pixel(w - 1, h - 1).0, [60, 60, 60]);
    }
}
