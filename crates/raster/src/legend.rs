//! An overlay's key drawn into the picture (issue 22: a person shown an overlay must be able to
//! read its colours without the documentation): a small box of swatches and names in the
//! corner of the picture that covers the least of what matters, on a pale ground that lets the
//! picture show through faintly. Not the dissertation's; its figures carry their keys in the
//! captions.

use image::{Rgb, RgbImage};

use crate::text;

/// How a key shows a colour: as the overlay draws it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Swatch {
    /// A filled square: a region tinted in this colour.
    Fill([u8; 3]),
    /// A short line: segments or contours drawn in this colour.
    Line([u8; 3]),
    /// A hollow square: a frame or circle drawn round something.
    Ring([u8; 3]),
}

/// One line of a key.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Entry {
    pub swatch: Swatch,
    pub text: String,
}

impl Entry {
    pub fn new(swatch: Swatch, text: impl Into<String>) -> Entry {
        Entry {
            swatch,
            text: text.into(),
        }
    }
}

/// Where a key was drawn: its box [x0, y0, x1, y1) in the picture.
pub type Placed = [u32; 4];

/// The font pixel for a picture: 1 under 500 px on the shorter side, 2 under 1500, else 3,
/// so that the key reads at the size the picture is looked at.
pub fn font_pixel(width: u32, height: u32) -> u32 {
    match width.min(height) {
        0..500 => 1,
        500..1500 => 2,
        _ => 3,
    }
}

/// Draws the key of `entries` into `img`, in whichever corner has the fewest pixels for which
/// `busy(x, y)` holds (ties: bottom-right, top-right, bottom-left, top-left, where drawings
/// keep their margins). Returns where it was drawn; `None`, drawing nothing, when the picture
/// is too small to hold it beside a quarter of free picture, or `entries` is empty.
pub fn draw(
    img: &mut RgbImage,
    entries: &[Entry],
    busy: &dyn Fn(u32, u32) -> bool,
) -> Option<Placed> {
    if entries.is_empty() {
        return None;
    }
    let px = font_pixel(img.width(), img.height());
    let row = (text::HEIGHT + 2) * px;
    let swatch = text::HEIGHT * px;
    let pad = 2 * px;
    let widest = entries
        .iter()
        .map(|e| text::width(&e.text, px))
        .max()
        .unwrap_or(0);
    let w = pad + swatch + 2 * px + widest + pad;
    let h = pad + row * entries.len() as u32 - 2 * px + pad;
    // The key may cover at most half of either side: otherwise the picture is the key.
    if 2 * w > img.width() || 2 * h > img.height() {
        return None;
    }
    let (right, bottom) = (img.width() - w, img.height() - h);
    let corners = [(right, bottom), (right, 0), (0, bottom), (0, 0)];
    let cost = |(x0, y0): (u32, u32)| {
        let mut n = 0usize;
        for y in (y0..y0 + h).step_by(2) {
            for x in (x0..x0 + w).step_by(2) {
                n += usize::from(busy(x, y));
            }
        }
        n
    };
    let (x0, y0) = corners
        .into_iter()
        .enumerate()
        .min_by_key(|&(k, c)| (cost(c), k))
        .map(|(_, c)| c)
        .expect("four corners");
    // A pale ground, 85 % white, and a dark frame.
    for y in y0..y0 + h {
        for x in x0..x0 + w {
            let p = img.get_pixel_mut(x, y);
            *p = Rgb(p
                .0
                .map(|v| (0.15 * f64::from(v) + 0.85 * 255.0).round() as u8));
        }
    }
    let frame = Rgb([60, 60, 60]);
    for x in x0..x0 + w {
        img.put_pixel(x, y0, frame);
        img.put_pixel(x, y0 + h - 1, frame);
    }
    for y in y0..y0 + h {
        img.put_pixel(x0, y, frame);
        img.put_pixel(x0 + w - 1, y, frame);
    }
    for (i, e) in entries.iter().enumerate() {
        let (sx, sy) = (x0 + pad, y0 + pad + i as u32 * row);
        draw_swatch(img, e.swatch, sx, sy, swatch, px);
        text::text(
            img,
            (sx + swatch + 2 * px) as i32,
            sy as i32,
            &e.text,
            px,
            [20, 20, 20],
        );
    }
    Some([x0, y0, x0 + w, y0 + h])
}

fn draw_swatch(img: &mut RgbImage, swatch: Swatch, x0: u32, y0: u32, side: u32, px: u32) {
    for y in y0..y0 + side {
        for x in x0..x0 + side {
            let (dx, dy) = (x - x0, y - y0);
            let on = match swatch {
                Swatch::Fill(_) => true,
                // A line across the middle, `px` thick.
                Swatch::Line(_) => dy >= (side - px) / 2 && dy < (side - px) / 2 + px,
                Swatch::Ring(_) => dx < px || dy < px || dx >= side - px || dy >= side - px,
            };
            // A filled swatch has a grey rim, so that white (an unknown wall) shows on the
            // pale ground.
            let rim = matches!(swatch, Swatch::Fill(_))
                && (dx == 0 || dy == 0 || dx == side - 1 || dy == side - 1);
            if rim {
                img.put_pixel(x, y, Rgb([110, 110, 110]));
            } else if on {
                let (Swatch::Fill(c) | Swatch::Line(c) | Swatch::Ring(c)) = swatch;
                img.put_pixel(x, y, Rgb(c));
            }
        }
    }
}

/// The words of a key as one line, for captions and `--help`: "red: wall, grey: drawing".
pub fn caption(entries: &[Entry]) -> String {
    entries
        .iter()
        .map(|e| e.text.clone())
        .collect::<Vec<_>>()
        .join("; ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key() -> Vec<Entry> {
        vec![
            Entry::new(Swatch::Fill([200, 0, 0]), "wall"),
            Entry::new(Swatch::Line([0, 0, 200]), "line"),
        ]
    }

    #[test]
    fn the_key_goes_in_the_emptiest_corner_with_its_swatches() {
        let mut img = RgbImage::from_pixel(200, 100, Rgb([0, 0, 0]));
        // Everything busy but the top-left quarter.
        let placed = draw(&mut img, &key(), &|x, y| x >= 100 || y >= 50).unwrap();
        let [x0, y0, x1, y1] = placed;
        assert_eq!((x0, y0), (0, 0));
        // 2 + 5 + 2 + "wall" (15) + 2 wide, two rows of 7 less 2, padded.
        assert_eq!((x1, y1), (26, 16));
        // The first swatch is filled in its colour inside a grey rim, on the pale ground.
        assert_eq!(img.get_pixel(4, 4), &Rgb([200, 0, 0]));
        assert_eq!(img.get_pixel(2, 4), &Rgb([110, 110, 110]));
        assert_eq!(img.get_pixel(1, 1), &Rgb([217, 217, 217]));
        // The second swatch is a line through its middle, not a square.
        assert_eq!(img.get_pixel(4, 11), &Rgb([0, 0, 200]));
        assert_ne!(img.get_pixel(4, 9), &Rgb([0, 0, 200]));
        // Outside the box nothing changed.
        assert_eq!(img.get_pixel(30, 30), &Rgb([0, 0, 0]));
    }

    #[test]
    fn with_nothing_busy_the_key_goes_bottom_right() {
        let mut img = RgbImage::new(200, 100);
        assert_eq!(
            draw(&mut img, &key(), &|_, _| false),
            Some([174, 84, 200, 100])
        );
    }

    #[test]
    fn a_picture_too_small_for_its_key_is_left_as_it_is() {
        let mut img = RgbImage::new(40, 20);
        assert_eq!(draw(&mut img, &key(), &|_, _| false), None);
        assert!(img.pixels().all(|p| p.0 == [0, 0, 0]));
        assert_eq!(draw(&mut RgbImage::new(400, 400), &[], &|_, _| false), None);
    }

    #[test]
    fn large_pictures_get_a_larger_font() {
        assert_eq!(font_pixel(400, 300), 1);
        assert_eq!(font_pixel(1000, 800), 2);
        assert_eq!(font_pixel(3000, 2000), 3);
        assert_eq!(caption(&key()), "wall; line");
    }
}
