//! Gates and doors wider than the walls are thick, closed where they open an enclosure
//! (addition to §5.1.2; §5.2 item 4 names open enclosures as a cause of failure and §5.1.1
//! leaves closing them to the user). [`crate::binarize::close_gaps`] bridges gaps up to two
//! thirds of a wall: a gate passage drawn as a full break in the curtain (Saint-Médard-en-Jalle,
//! Bell's Syrian forts) is wider, the courtyard leaks through it into the surroundings and
//! chapter 5 reads the ward as outside (courtyard → surroundings is the most frequent error on
//! the plans by other hands).
//!
//! A wider closing would bridge the gate but also fill every notch between a tower and the
//! curtain and every room narrower than the gap. So the wider closing is only a probe: of what
//! it adds, a piece is kept when it stands between the surroundings (as the closing sees them)
//! and open paper that the closing cuts off from them — the plug of a gate — and nothing else.

use image::GrayImage;
use raster::components::{Connectivity, components, components_where};

use crate::pixels::close;

/// The widest probe: gates up to 121 pixels (a drawing's walls thicker than 60 pixels are
/// rare, and the closing's cost grows with the radius).
pub const MAX_RADIUS: u8 = 60;

/// Bridges the gaps up to about 2 × `radius` + 1 pixels wide whose closing encloses at least
/// `min_enclosed` pixels of paper that were open to the sheet's border. Returns the pixels
/// added.
pub fn close_gates(img: &mut GrayImage, radius: u8, min_enclosed: usize) -> usize {
    if radius == 0 {
        return 0;
    }
    let (w, h) = (img.width() as usize, img.height() as usize);
    let closed = close(img, radius);
    let before = outside(img);
    let after = outside(&closed);
    let raw = img.as_raw();
    let shut = closed.as_raw();
    // Paper the closing cuts off from the border, in regions.
    let enclosed = components_where(w, h, Connectivity::Four, |i| {
        before[i] && shut[i] == 0 && !after[i]
    });
    let large: Vec<bool> = enclosed
        .sizes
        .iter()
        .enumerate()
        .map(|(l, &s)| l > 0 && s >= min_enclosed)
        .collect();
    if !large.iter().any(|&l| l) {
        return 0;
    }
    // What the closing adds, in pieces; a piece that touches both sides is a gate's plug.
    let added = components_where(w, h, Connectivity::Eight, |i| shut[i] == 255 && raw[i] == 0);
    let mut touches = vec![[false; 2]; added.sizes.len()];
    for (i, &l) in added.labels.iter().enumerate() {
        if l == 0 {
            continue;
        }
        let (x, y) = (i % w, i / w);
        for (dx, dy) in [(-1i64, 0i64), (1, 0), (0, -1), (0, 1)] {
            let (nx, ny) = (x as i64 + dx, y as i64 + dy);
            if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                continue;
            }
            let j = ny as usize * w + nx as usize;
            touches[l as usize][0] |= after[j];
            touches[l as usize][1] |= large[enclosed.labels[j] as usize];
        }
    }
    let mut count = 0;
    for (p, &l) in img.pixels_mut().zip(&added.labels) {
        if l > 0 && touches[l as usize] == [true, true] {
            p[0] = 255;
            count += 1;
        }
    }
    count
}

/// The paper (0) pixels whose 4-connected region of paper touches the image's border.
fn outside(img: &GrayImage) -> Vec<bool> {
    let (w, h) = (img.width() as usize, img.height() as usize);
    let paper = components(img, 0, Connectivity::Four);
    let border: Vec<bool> = (0..paper.sizes.len())
        .map(|l| paper.touches_border(l, w, h))
        .collect();
    paper.labels.iter().map(|&l| border[l as usize]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Luma;

    /// A 140 × 140 sheet: a square curtain 8 px thick (outer edges 20 and 120) with a 14-px
    /// gate in its south side (x 60..74) and, on its north face, two stubs 8 px apart that
    /// make a notch open to the outside.
    fn ward_with_gate() -> GrayImage {
        GrayImage::from_fn(140, 140, |x, y| {
            let ring = (20..120).contains(&x)
                && (20..120).contains(&y)
                && !((28..112).contains(&x) && (28..112).contains(&y));
            let gate = (60..74).contains(&x) && (112..120).contains(&y);
            let stubs = (8..20).contains(&y) && ((40..48).contains(&x) || (56..64).contains(&x));
            Luma([if (ring && !gate) || stubs { 255 } else { 0 }])
        })
    }

    #[test]
    fn the_gate_is_plugged_and_the_notch_left() {
        let mut img = ward_with_gate();
        let added = close_gates(&mut img, 8, 100);
        assert_eq!(added, 14 * 8, "exactly the gate's plug");
        assert_eq!(img.get_pixel(66, 116)[0], 255, "the gate");
        assert_eq!(img.get_pixel(52, 14)[0], 0, "the notch between the stubs");
        assert_eq!(img.get_pixel(70, 70)[0], 0, "the ward");
        assert!(!outside(&img)[70 * 140 + 70], "the ward is enclosed");
    }

    #[test]
    fn nothing_is_added_where_nothing_would_be_enclosed() {
        let mut img = ward_with_gate();
        // Open the west side: the closing no longer encloses the ward.
        for y in 28..112 {
            for x in 20..28 {
                img.put_pixel(x, y, Luma([0]));
            }
        }
        let before = img.clone();
        assert_eq!(close_gates(&mut img, 8, 100), 0);
        assert_eq!(img, before);
    }

    #[test]
    fn a_gate_wider_than_the_probe_stays_open() {
        let mut img = ward_with_gate();
        assert_eq!(close_gates(&mut img, 6, 100), 0, "14 px > 2 × 6 + 1");
        // An enclosure smaller than asked for is not worth a plug.
        let mut img = ward_with_gate();
        assert_eq!(close_gates(&mut img, 8, 84 * 84 + 1), 0);
    }
}
