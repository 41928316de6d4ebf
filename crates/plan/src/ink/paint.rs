//! Wall masks painted by hand on real plans (issue 26), kept as recipes rather than images:
//! a recipe says which ink regions are walls, which polygons are wall (outlined, hatched or
//! washed walls whose paper between the lines is wall too), which thick polylines are walls,
//! and which polygons are not wall or are left out of training and scoring. Rendering a recipe
//! over its drawing gives the mask; the recipes ship in `crates/plan/data/wall_masks.json`.

use image::{GrayImage, Luma};
use raster::components::{Connectivity, components_where};
use serde::Deserialize;

/// Mask value of a wall pixel.
pub const WALL: u8 = 255;
/// Mask value of a pixel that is not wall.
pub const NOT_WALL: u8 = 0;
/// Mask value of a pixel left out of training and scoring (ambiguous).
pub const IGNORE: u8 = 128;
/// Mask value of a pixel that is not wall and that training samples as a pool of its own:
/// the paper between the strokes of a synthetic hachured scarp (`train_ink --scarp-paper`),
/// which the open paper of a sheet hardly samples. Scored as not wall.
pub const HARD_NOT_WALL: u8 = 64;

/// A polygon in the drawing's pixels, `[x, y]` vertices (closed implicitly).
pub type Polygon = Vec<[f64; 2]>;

/// A wall drawn as a polyline of the given width (pixels), closed or open.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Stroke {
    pub points: Vec<[f64; 2]>,
    pub width: f64,
    #[serde(default)]
    pub closed: bool,
}

/// One drawing's painted walls. Applied in field order: `keep`, `ink`, `fill`, `walls` add
/// wall; `erase` removes it; `ignore` marks pixels to leave out.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Recipe {
    /// The drawing, relative to the public-domain set's folder.
    pub file: String,
    /// The book it comes from (the unit of leave-one-source-out measurement).
    pub book: String,
    /// Ink is darker than this grey level; `None`: Otsu's level ([`crate::binarize::threshold_level`]).
    #[serde(default)]
    pub threshold: Option<u8>,
    /// Points on ink: the 8-connected ink regions through them are wall.
    #[serde(default)]
    pub keep: Vec<[u32; 2]>,
    /// Polygons whose ink pixels are wall.
    #[serde(default)]
    pub ink: Vec<Polygon>,
    /// Polygons whose every pixel is wall.
    #[serde(default)]
    pub fill: Vec<Polygon>,
    /// Walls drawn as thick polylines.
    #[serde(default)]
    pub walls: Vec<Stroke>,
    /// Polygons with no wall.
    #[serde(default)]
    pub erase: Vec<Polygon>,
    /// Polygons left out of training and scoring.
    #[serde(default)]
    pub ignore: Vec<Polygon>,
    #[serde(default)]
    pub note: Option<String>,
}

/// The painted set: every recipe.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PaintedSet {
    pub description: String,
    pub masks: Vec<Recipe>,
}

impl PaintedSet {
    pub fn from_json(text: &str) -> Result<PaintedSet, serde_json::Error> {
        serde_json::from_str(text)
    }
}

/// Why a recipe cannot be rendered over its drawing.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PaintError {
    #[error("keep point {index} ({x}, {y}) is outside the {width} x {height} drawing")]
    KeepOutside {
        index: usize,
        x: u32,
        y: u32,
        width: u32,
        height: u32,
    },
    #[error("keep point {index} ({x}, {y}) is on paper, not ink (grey {grey})")]
    KeepOnPaper {
        index: usize,
        x: u32,
        y: u32,
        grey: u8,
    },
    #[error("wall stroke {index} has width {width}: it must be in (0, 200]")]
    BadWidth { index: usize, width: f64 },
}

/// Renders `recipe` over `grey`: [`WALL`], [`NOT_WALL`] or [`IGNORE`] per pixel.
pub fn render(grey: &GrayImage, recipe: &Recipe) -> Result<GrayImage, PaintError> {
    let (w, h) = grey.dimensions();
    let level = recipe
        .threshold
        .unwrap_or_else(|| crate::binarize::threshold_level(grey));
    let raw = grey.as_raw();
    let is_ink = |i: usize| raw[i] < level;
    let mut mask = GrayImage::new(w, h);
    if !recipe.keep.is_empty() {
        let regions = components_where(w as usize, h as usize, Connectivity::Eight, is_ink);
        let mut wanted = vec![false; regions.sizes.len()];
        for (index, &[x, y]) in recipe.keep.iter().enumerate() {
            if x >= w || y >= h {
                return Err(PaintError::KeepOutside {
                    index,
                    x,
                    y,
                    width: w,
                    height: h,
                });
            }
            let i = (y * w + x) as usize;
            if !is_ink(i) {
                return Err(PaintError::KeepOnPaper {
                    index,
                    x,
                    y,
                    grey: raw[i],
                });
            }
            wanted[regions.labels[i] as usize] = true;
        }
        for (p, &l) in mask.pixels_mut().zip(&regions.labels) {
            if wanted[l as usize] {
                p[0] = WALL;
            }
        }
    }
    for poly in &recipe.ink {
        paint_polygon(&mut mask, poly, |x, y| is_ink((y * w + x) as usize), WALL);
    }
    for poly in &recipe.fill {
        paint_polygon(&mut mask, poly, |_, _| true, WALL);
    }
    for (index, s) in recipe.walls.iter().enumerate() {
        if !(s.width > 0.0 && s.width <= 200.0) {
            return Err(PaintError::BadWidth {
                index,
                width: s.width,
            });
        }
        paint_stroke(&mut mask, s);
    }
    for poly in &recipe.erase {
        paint_polygon(&mut mask, poly, |_, _| true, NOT_WALL);
    }
    for poly in &recipe.ignore {
        paint_polygon(&mut mask, poly, |_, _| true, IGNORE);
    }
    Ok(mask)
}

/// Sets `value` at the pixels whose centres lie inside `poly` (even–odd rule) and pass `when`.
fn paint_polygon(
    mask: &mut GrayImage,
    poly: &[[f64; 2]],
    when: impl Fn(u32, u32) -> bool,
    value: u8,
) {
    if poly.len() < 3 {
        return;
    }
    let (w, h) = mask.dimensions();
    let y0 = poly
        .iter()
        .map(|p| p[1])
        .fold(f64::INFINITY, f64::min)
        .floor()
        .max(0.0) as u32;
    let y1 = poly
        .iter()
        .map(|p| p[1])
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil()
        .min(f64::from(h) - 1.0);
    if y1 < 0.0 {
        return;
    }
    for y in y0..=y1 as u32 {
        let yc = f64::from(y);
        let mut xs: Vec<f64> = Vec::new();
        for k in 0..poly.len() {
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            if (a[1] <= yc) != (b[1] <= yc) {
                xs.push(a[0] + (yc - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
            }
        }
        xs.sort_by(f64::total_cmp);
        for pair in xs.chunks_exact(2) {
            let from = pair[0].ceil().max(0.0);
            let to = pair[1].floor().min(f64::from(w) - 1.0);
            if to < from {
                continue;
            }
            for x in from as u32..=to as u32 {
                if when(x, y) {
                    mask.put_pixel(x, y, Luma([value]));
                }
            }
        }
    }
}

/// Sets [`WALL`] within half the stroke's width of its polyline.
fn paint_stroke(mask: &mut GrayImage, s: &Stroke) {
    let n = s.points.len();
    let segments = if s.closed && n > 2 {
        n
    } else {
        n.saturating_sub(1)
    };
    let (w, h) = mask.dimensions();
    for k in 0..segments.max(usize::from(n == 1)) {
        let (a, b) = (s.points[k], s.points[(k + 1) % n]);
        near_segment(a, b, s.width / 2.0, (w, h), 0.0, |x, y| {
            mask.put_pixel(x, y, Luma([WALL]))
        });
    }
}

/// Calls `visit` for every pixel of a `size` grid whose position (x + `offset`, y + `offset`)
/// lies within `r` of the segment from `a` to `b` (a point when they coincide). The one
/// brush rule of the painted masks and the user's strokes.
pub(crate) fn near_segment(
    a: [f64; 2],
    b: [f64; 2],
    r: f64,
    size: (u32, u32),
    offset: f64,
    mut visit: impl FnMut(u32, u32),
) {
    let (w, h) = size;
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let x0 = (a[0].min(b[0]) - r - offset).floor().max(0.0) as u32;
    let y0 = (a[1].min(b[1]) - r - offset).floor().max(0.0) as u32;
    let x1 = (a[0].max(b[0]) + r).ceil().min(f64::from(w) - 1.0);
    let y1 = (a[1].max(b[1]) + r).ceil().min(f64::from(h) - 1.0);
    if x1 < 0.0 || y1 < 0.0 {
        return;
    }
    for y in y0..=y1 as u32 {
        for x in x0..=x1 as u32 {
            let (px, py) = (f64::from(x) + offset - a[0], f64::from(y) + offset - a[1]);
            let t = if len2 > 0.0 {
                ((px * dx + py * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            if (px - t * dx).hypot(py - t * dy) <= r {
                visit(x, y);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn recipe(json: &str) -> Recipe {
        serde_json::from_str(json).unwrap()
    }

    /// A 20 × 10 sheet with two ink blocks: x 2..5 and x 12..15, rows 2..8.
    fn sheet() -> GrayImage {
        GrayImage::from_fn(20, 10, |x, y| {
            let ink = (2..8).contains(&y) && ((2..5).contains(&x) || (12..15).contains(&x));
            Luma([if ink { 10 } else { 240 }])
        })
    }

    fn count(m: &GrayImage, v: u8) -> usize {
        m.pixels().filter(|p| p[0] == v).count()
    }

    #[test]
    fn keep_takes_the_whole_ink_region_through_the_point_only() {
        let m = render(
            &sheet(),
            &recipe(r#"{"file":"f","book":"b","keep":[[3,4]]}"#),
        )
        .unwrap();
        assert_eq!(count(&m, WALL), 18);
        assert_eq!(m.get_pixel(13, 4)[0], NOT_WALL);
    }

    #[test]
    fn fill_covers_paper_erase_and_ignore_come_last() {
        let r = recipe(
            r#"{"file":"f","book":"b","fill":[[[0,0],[9.5,0],[9.5,9.5],[0,9.5]]],
                "erase":[[[0,0],[1.5,0],[1.5,9.5],[0,9.5]]],
                "ignore":[[[8,0],[9.5,0],[9.5,9.5],[8,9.5]]]}"#,
        );
        let m = render(&sheet(), &r).unwrap();
        // Columns 0..=9 filled, 0..=1 erased, 8..=9 ignored: 6 wall columns of 10 rows.
        assert_eq!(count(&m, WALL), 60);
        assert_eq!(count(&m, IGNORE), 20);
        assert_eq!(m.get_pixel(0, 5)[0], NOT_WALL);
    }

    #[test]
    fn ink_polygon_takes_only_its_ink_and_strokes_have_their_width() {
        let r = recipe(
            r#"{"file":"f","book":"b","ink":[[[10,0],[19.5,0],[19.5,9.5],[10,9.5]]],
                "walls":[{"points":[[0,0],[0,9]],"width":2}]}"#,
        );
        let m = render(&sheet(), &r).unwrap();
        // The right block (18 px) and column 0 and 1 (within 1 px of x = 0): 20 px.
        assert_eq!(count(&m, WALL), 18 + 20);
    }

    #[test]
    fn bad_recipes_name_the_entry() {
        let e = render(
            &sheet(),
            &recipe(r#"{"file":"f","book":"b","keep":[[8,4]]}"#),
        );
        assert_eq!(
            e.unwrap_err(),
            PaintError::KeepOnPaper {
                index: 0,
                x: 8,
                y: 4,
                grey: 240
            }
        );
        let e = render(
            &sheet(),
            &recipe(r#"{"file":"f","book":"b","keep":[[3,4],[30,4]]}"#),
        );
        assert!(matches!(e, Err(PaintError::KeepOutside { index: 1, .. })));
        let bad = r#"{"file":"f","book":"b","walls":[{"points":[[0,0]],"width":0}]}"#;
        assert!(matches!(
            render(&sheet(), &recipe(bad)),
            Err(PaintError::BadWidth { .. })
        ));
        assert!(serde_json::from_str::<Recipe>(r#"{"file":"f","book":"b","kep":[]}"#).is_err());
    }
}
