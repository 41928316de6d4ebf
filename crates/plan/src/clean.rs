//! Plan cleaning (§5.1.1: the user erases legends and text and mends broken walls before the
//! plan is parsed): the drawing's binary image (§5.1.2's threshold) with the user's brush strokes
//! painted over it, in order; the strokes are checked against limits first, so painting is
//! bounded. The strokes are plan_cleaning.json's, which `castellan serve` keeps and replays.

use image::{GrayImage, Luma};
use serde::{Deserialize, Serialize};

/// Largest brush radius, in plan pixels.
pub const MAX_RADIUS: f64 = 200.0;
/// Most points over all strokes of one save.
pub const MAX_POINTS: usize = 200_000;
/// Painting visits each segment's bounding box; their total area may be at most this many
/// times the image's, so no list of strokes (a request to `castellan serve`) paints for ever.
const MAX_WORK_FACTOR: u64 = 200;

/// One brush stroke in plan pixels: `ink` paints wall (black), otherwise paper (white).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stroke {
    pub ink: bool,
    pub radius: f64,
    pub points: Vec<[f64; 2]>,
}

/// plan_cleaning.json.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Cleaning {
    /// The uploaded drawing, kept as it was.
    pub original: String,
    pub strokes: Vec<Stroke>,
}

/// The body of `PUT /api/plan/cleaning`: every stroke, replacing the saved ones.
#[derive(Debug, Deserialize)]
pub struct Strokes {
    pub strokes: Vec<Stroke>,
}

/// The drawing as the parser first sees it (§5.1.2: grey → binary by the automatic threshold),
/// drawn black on white like the drawing itself, so the parser reads a cleaned copy the same way.
pub fn binary_drawing(grey: &GrayImage) -> GrayImage {
    let level = crate::binarize::threshold_level(grey);
    GrayImage::from_fn(grey.width(), grey.height(), |x, y| {
        Luma([if grey.get_pixel(x, y)[0] < level {
            0
        } else {
            255
        }])
    })
}

/// Checks the strokes against the limits and the image; the message names the stroke at fault.
pub fn check(strokes: &[Stroke], width: u32, height: u32) -> Result<(), String> {
    let points: usize = strokes.iter().map(|s| s.points.len()).sum();
    if points > MAX_POINTS {
        return Err(format!(
            "{points} stroke points, more than the limit of {MAX_POINTS}"
        ));
    }
    let mut work = 0u64;
    for (i, s) in strokes.iter().enumerate() {
        if !(s.radius.is_finite() && s.radius > 0.0 && s.radius <= MAX_RADIUS) {
            return Err(format!(
                "stroke {i}: radius {} is not in (0, {MAX_RADIUS}] pixels",
                s.radius
            ));
        }
        if s.points.is_empty() || s.points.iter().flatten().any(|c| !c.is_finite()) {
            return Err(format!("stroke {i}: needs one or more finite points"));
        }
        for seg in segments(s) {
            work += bounding_box(seg, s.radius, width, height)
                .map(|[x0, y0, x1, y1]| u64::from(x1 - x0) * u64::from(y1 - y0))
                .unwrap_or(0);
        }
    }
    let limit = MAX_WORK_FACTOR * u64::from(width) * u64::from(height);
    if work > limit {
        return Err(format!(
            "the strokes cover {work} pixels in total, more than {MAX_WORK_FACTOR} times the drawing"
        ));
    }
    Ok(())
}

/// A stroke's segments; a single point is a segment of length zero (a dot).
fn segments(s: &Stroke) -> impl Iterator<Item = [[f64; 2]; 2]> + '_ {
    let first = (s.points.len() == 1).then(|| [s.points[0], s.points[0]]);
    first
        .into_iter()
        .chain(s.points.windows(2).map(|w| [w[0], w[1]]))
}

/// The pixels a segment's brush can touch, clipped to the image: `[x0, y0, x1, y1)`.
fn bounding_box(seg: [[f64; 2]; 2], r: f64, w: u32, h: u32) -> Option<[u32; 4]> {
    let clip = |v: f64, hi: u32| v.clamp(0.0, f64::from(hi)) as u32;
    let [[ax, ay], [bx, by]] = seg;
    let b = [
        clip(ax.min(bx) - r, w),
        clip(ay.min(by) - r, h),
        clip((ax.max(bx) + r).ceil() + 1.0, w),
        clip((ay.max(by) + r).ceil() + 1.0, h),
    ];
    (b[0] < b[2] && b[1] < b[3]).then_some(b)
}

/// Paints the strokes, in order, on the drawing: a pixel whose centre lies within `radius` of a
/// stroke's polyline takes its colour (what the page's canvas shows with round caps and joins).
/// Returns how many pixels changed. The strokes must have passed [`check`].
pub fn paint(img: &mut GrayImage, strokes: &[Stroke]) -> usize {
    let (w, h) = img.dimensions();
    let mut changed = 0;
    for s in strokes {
        let value = if s.ink { 0 } else { 255 };
        for seg in segments(s) {
            let Some([x0, y0, x1, y1]) = bounding_box(seg, s.radius, w, h) else {
                continue;
            };
            for y in y0..y1 {
                for x in x0..x1 {
                    let p = [f64::from(x) + 0.5, f64::from(y) + 0.5];
                    if crate::fit::segment_distance(p, seg[0], seg[1]) <= s.radius {
                        let px = img.get_pixel_mut(x, y);
                        changed += usize::from(px[0] != value);
                        px[0] = value;
                    }
                }
            }
        }
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stroke(ink: bool, radius: f64, points: &[[f64; 2]]) -> Stroke {
        Stroke {
            ink,
            radius,
            points: points.to_vec(),
        }
    }

    #[test]
    fn the_binary_drawing_is_black_ink_on_white_paper() {
        let grey = GrayImage::from_raw(4, 1, vec![10, 20, 240, 250]).unwrap();
        assert_eq!(binary_drawing(&grey).into_raw(), vec![0, 0, 255, 255]);
    }

    #[test]
    fn a_dot_paints_the_pixels_whose_centres_lie_within_the_radius() {
        let mut img = GrayImage::from_pixel(5, 5, Luma([255]));
        // Centre (2.5, 2.5), radius 1: the centre pixel and its four neighbours (distance 1).
        let changed = paint(&mut img, &[stroke(true, 1.0, &[[2.5, 2.5]])]);
        #[rustfmt::skip]
        let want = vec![
            255, 255, 255, 255, 255,
            255, 255,   0, 255, 255,
            255,   0,   0,   0, 255,
            255, 255,   0, 255, 255,
            255, 255, 255, 255, 255,
        ];
        assert_eq!(img.into_raw(), want);
        assert_eq!(changed, 5);
    }

    #[test]
    fn a_line_erases_a_band_and_later_strokes_paint_over_earlier_ones() {
        let mut img = GrayImage::from_pixel(6, 3, Luma([0]));
        let erase = stroke(false, 0.5, &[[0.5, 1.5], [5.5, 1.5]]);
        assert_eq!(paint(&mut img, std::slice::from_ref(&erase)), 6);
        #[rustfmt::skip]
        assert_eq!(img.clone().into_raw(), vec![
            0, 0, 0, 0, 0, 0,
            255, 255, 255, 255, 255, 255,
            0, 0, 0, 0, 0, 0,
        ]);
        let ink = stroke(true, 0.5, &[[2.5, 1.5]]);
        assert_eq!(paint(&mut img, &[erase, ink]), 1);
        assert_eq!(img.get_pixel(2, 1)[0], 0);
        assert_eq!(img.get_pixel(3, 1)[0], 255);
    }

    #[test]
    fn strokes_outside_the_image_change_nothing() {
        let mut img = GrayImage::from_pixel(3, 3, Luma([255]));
        let s = stroke(true, 2.0, &[[-50.0, -50.0], [-20.0, 80.0]]);
        assert!(check(std::slice::from_ref(&s), 3, 3).is_ok());
        assert_eq!(paint(&mut img, &[s]), 0);
    }

    #[test]
    fn bad_strokes_are_refused_naming_the_stroke() {
        let ok = stroke(true, 2.0, &[[1.0, 1.0]]);
        for (bad, says) in [
            (stroke(true, 0.0, &[[1.0, 1.0]]), "stroke 1: radius"),
            (
                stroke(true, MAX_RADIUS + 1.0, &[[1.0, 1.0]]),
                "stroke 1: radius",
            ),
            (stroke(false, 2.0, &[]), "stroke 1: needs"),
            (stroke(false, 2.0, &[[f64::NAN, 1.0]]), "stroke 1: needs"),
        ] {
            let e = check(&[ok.clone(), bad], 10, 10).unwrap_err();
            assert!(e.contains(says), "{e}");
        }
        let many = stroke(true, 1.0, &vec![[1.0, 1.0]; MAX_POINTS + 1]);
        assert!(check(&[many], 10, 10).unwrap_err().contains("limit"));
        // Thousands of wide zigzags over a small drawing: bounded work, refused.
        let zigzag: Vec<[f64; 2]> = (0..2000).map(|i| [(i % 2) as f64 * 100.0, 50.0]).collect();
        let e = check(&[stroke(true, 100.0, &zigzag)], 100, 100).unwrap_err();
        assert!(e.contains("times the drawing"), "{e}");
    }
}
