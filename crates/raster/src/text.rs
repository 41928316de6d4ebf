//! A 3 × 5 pixel font, so figures and overlay keys need no font file: digits, capitals and the
//! punctuation captions use. One home for the corner plots (ch. 2) and every overlay's key
//! ([`crate::legend`], issue 22).

use image::{Rgb, RgbImage};
use imageproc::drawing::draw_filled_rect_mut;
use imageproc::rect::Rect;

/// Advance of one character, in font pixels (3 of glyph, 1 of space).
pub const ADVANCE: u32 = 4;
/// Height of a glyph, in font pixels.
pub const HEIGHT: u32 = 5;

/// Each glyph's five rows of three pixels (`#` ink).
const GLYPHS: &[(char, [&str; 5])] = &[
    ('0', ["###", "#.#", "#.#", "#.#", "###"]),
    ('1', [".#.", "##.", ".#.", ".#.", "###"]),
    ('2', ["###", "..#", "###", "#..", "###"]),
    ('3', ["###", "..#", ".##", "..#", "###"]),
    ('4', ["#.#", "#.#", "###", "..#", "..#"]),
    ('5', ["###", "#..", "###", "..#", "###"]),
    ('6', ["###", "#..", "###", "#.#", "###"]),
    ('7', ["###", "..#", ".#.", ".#.", ".#."]),
    ('8', ["###", "#.#", "###", "#.#", "###"]),
    ('9', ["###", "#.#", "###", "..#", "###"]),
    ('.', ["...", "...", "...", "...", ".#."]),
    ('-', ["...", "...", "###", "...", "..."]),
    ('/', ["..#", "..#", ".#.", "#..", "#.."]),
    ('(', [".#.", "#..", "#..", "#..", ".#."]),
    (')', [".#.", "..#", "..#", "..#", ".#."]),
    (':', ["...", ".#.", "...", ".#.", "..."]),
    (',', ["...", "...", "...", ".#.", "#.."]),
    ('=', ["...", "###", "...", "###", "..."]),
    ('+', ["...", ".#.", "###", ".#.", "..."]),
    ('%', ["#.#", "..#", ".#.", "#..", "#.#"]),
    ('>', ["#..", ".#.", "..#", ".#.", "#.."]),
    ('<', ["..#", ".#.", "#..", ".#.", "..#"]),
    ('\'', [".#.", ".#.", "...", "...", "..."]),
    ('×', ["...", "#.#", ".#.", "#.#", "..."]),
    ('§', [".##", "##.", "#.#", ".##", "##."]),
    ('?', ["##.", "..#", ".#.", "...", ".#."]),
    ('A', [".#.", "#.#", "###", "#.#", "#.#"]),
    ('B', ["##.", "#.#", "##.", "#.#", "##."]),
    ('C', [".##", "#..", "#..", "#..", ".##"]),
    ('D', ["##.", "#.#", "#.#", "#.#", "##."]),
    ('E', ["###", "#..", "##.", "#..", "###"]),
    ('F', ["###", "#..", "##.", "#..", "#.."]),
    ('G', [".##", "#..", "#.#", "#.#", ".##"]),
    ('H', ["#.#", "#.#", "###", "#.#", "#.#"]),
    ('I', ["###", ".#.", ".#.", ".#.", "###"]),
    ('J', ["..#", "..#", "..#", "#.#", ".#."]),
    ('K', ["#.#", "#.#", "##.", "#.#", "#.#"]),
    ('L', ["#..", "#..", "#..", "#..", "###"]),
    ('M', ["#.#", "###", "###", "#.#", "#.#"]),
    ('N', ["##.", "#.#", "#.#", "#.#", "#.#"]),
    ('O', [".#.", "#.#", "#.#", "#.#", ".#."]),
    ('P', ["##.", "#.#", "##.", "#..", "#.."]),
    ('Q', [".#.", "#.#", "#.#", "##.", ".##"]),
    ('R', ["##.", "#.#", "##.", "#.#", "#.#"]),
    ('S', [".##", "#..", ".#.", "..#", "##."]),
    ('T', ["###", ".#.", ".#.", ".#.", ".#."]),
    ('U', ["#.#", "#.#", "#.#", "#.#", "###"]),
    ('V', ["#.#", "#.#", "#.#", "#.#", ".#."]),
    ('W', ["#.#", "#.#", "###", "###", "#.#"]),
    ('X', ["#.#", "#.#", ".#.", "#.#", "#.#"]),
    ('Y', ["#.#", "#.#", ".#.", ".#.", ".#."]),
    ('Z', ["###", "..#", ".#.", "#..", "###"]),
];

/// Writes `text` (upper-cased, accents dropped; unknown characters become blanks) with its
/// top-left corner at (x, y), each font pixel `px` × `px`; pixels off the image are clipped.
/// Returns the x after the text.
pub fn text(img: &mut RgbImage, x: i32, y: i32, text: &str, px: u32, color: [u8; 3]) -> i32 {
    let mut cx = x;
    for ch in text.chars().flat_map(char::to_uppercase).map(unaccented) {
        if let Some((_, rows)) = GLYPHS.iter().find(|(c, _)| *c == ch) {
            for (r, row) in rows.iter().enumerate() {
                for (k, b) in row.bytes().enumerate() {
                    if b == b'#' {
                        let rect =
                            Rect::at(cx + (k as u32 * px) as i32, y + (r as u32 * px) as i32)
                                .of_size(px, px);
                        draw_filled_rect_mut(img, rect, Rgb(color));
                    }
                }
            }
        }
        cx += (4 * px) as i32;
    }
    cx
}

/// The base letter of the accented capitals French names use (É, È, Ê, À, Ç, …).
fn unaccented(c: char) -> char {
    match c {
        'À' | 'Â' | 'Ä' => 'A',
        'É' | 'È' | 'Ê' | 'Ë' => 'E',
        'Î' | 'Ï' => 'I',
        'Ô' | 'Ö' => 'O',
        'Ù' | 'Û' | 'Ü' => 'U',
        'Ç' => 'C',
        _ => c,
    }
}

/// The width in image pixels of `text` at font pixel `px` (no trailing space).
pub fn width(text: &str, px: u32) -> u32 {
    let n = text.chars().count() as u32;
    (n * ADVANCE).saturating_sub(1) * px
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_glyph_is_drawn_at_its_place_and_accents_are_dropped() {
        let mut img = RgbImage::new(12, 6);
        let end = text(&mut img, 0, 0, "é1", 1, [255, 0, 0]);
        assert_eq!(end, 8);
        let ink = |x, y| img.get_pixel(x, y)[0] == 255;
        // E: full top row, left column; 1: the stem in the middle column.
        assert!(ink(0, 0) && ink(1, 0) && ink(2, 0) && ink(0, 2) && !ink(2, 1));
        assert!(ink(5, 0) && ink(5, 4) && !ink(4, 0));
        assert_eq!(width("é1", 1), 7);
        assert_eq!(width("", 2), 0);
    }

    #[test]
    fn text_off_the_image_is_clipped() {
        let mut img = RgbImage::new(4, 4);
        text(&mut img, -2, -2, "88", 2, [9, 9, 9]);
        assert!(img.pixels().any(|p| p[0] == 9));
    }
}
