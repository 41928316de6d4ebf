//! The user's strokes (issue 26, ilastik's workflow): "wall" and "not wall" painted on a few
//! pixels of one drawing refine the model for that drawing. A forest is trained on the
//! drawing's own features plus the shipped model's wall map (as context), from the stroked
//! pixels and, as pseudo-labels, pixels the model is sure of away from the strokes; so a
//! correction spreads to everything on the sheet that looks like what was stroked, and the
//! rest keeps the model's answer. With the wall-ink network (`--ink network`) the network's
//! map is the context and the fallback, and the forest's filter bank gives the features.

use pixelclass::{Forest, ForestParams};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::model::{WallInk, smoothed_context, wall_class, with_context, working_size};
use super::net::WallNet;
use super::paint::near_segment;

/// At most this many strokes and points per stroke (a request is bounded).
pub const MAX_STROKES: usize = 500;
pub const MAX_POINTS: usize = 2000;

/// A stroke painted on the drawing: a polyline (drawing pixels) of the given radius, wall or
/// not wall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InkStroke {
    pub wall: bool,
    pub radius: f64,
    pub points: Vec<[f64; 2]>,
}

/// Why strokes cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StrokeError {
    #[error("{0} ink strokes: at most {MAX_STROKES}")]
    TooMany(usize),
    #[error("ink stroke {index}: {why}")]
    Bad { index: usize, why: String },
}

/// Checks strokes against a `w` × `h` drawing.
pub fn check(strokes: &[InkStroke], w: u32, h: u32) -> Result<(), StrokeError> {
    if strokes.len() > MAX_STROKES {
        return Err(StrokeError::TooMany(strokes.len()));
    }
    for (index, s) in strokes.iter().enumerate() {
        let bad = |why: String| Err(StrokeError::Bad { index, why });
        if !(s.radius >= 0.5 && s.radius <= 100.0) {
            return bad(format!("radius {} must be in [0.5, 100]", s.radius));
        }
        if s.points.is_empty() || s.points.len() > MAX_POINTS {
            return bad(format!("{} points: 1 to {MAX_POINTS}", s.points.len()));
        }
        let inside = |p: &[f64; 2]| {
            p[0].is_finite()
                && p[1].is_finite()
                && p[0] >= 0.0
                && p[1] >= 0.0
                && p[0] < f64::from(w)
                && p[1] < f64::from(h)
        };
        if let Some(p) = s.points.iter().find(|p| !inside(p)) {
            return bad(format!(
                "point ({}, {}) is outside the {w} x {h} drawing",
                p[0], p[1]
            ));
        }
    }
    Ok(())
}

/// The working pixels (row-major in a `ws` × `hs` grid over a `w` × `h` drawing) each stroke
/// covers, with its label (1 wall, 0 not).
fn stroked(strokes: &[InkStroke], w: u32, h: u32, ws: u32, hs: u32) -> Vec<(usize, usize)> {
    let (kx, ky) = (f64::from(ws) / f64::from(w), f64::from(hs) / f64::from(h));
    let mut out = Vec::new();
    for s in strokes {
        let r = (s.radius * kx).max(0.5);
        let pts: Vec<[f64; 2]> = s.points.iter().map(|p| [p[0] * kx, p[1] * ky]).collect();
        let segs: Vec<([f64; 2], [f64; 2])> = if pts.len() == 1 {
            vec![(pts[0], pts[0])]
        } else {
            pts.windows(2).map(|p| (p[0], p[1])).collect()
        };
        for (a, b) in segs {
            near_segment(a, b, r, (ws, hs), 0.5, |x, y| {
                out.push(((y * ws + x) as usize, usize::from(s.wall)));
            });
        }
    }
    out.sort_unstable();
    out.dedup_by_key(|p| p.0);
    out
}

/// P(wall) of every pixel of `grey` at `out_w` × `out_h`, the model refined by `strokes`
/// (checked with [`check`]); without strokes, the model's own map.
///
/// `net`: the wall-ink network, whose map then stands for the forest's.
pub fn wall_probability(
    model: &WallInk,
    net: Option<&WallNet>,
    grey: &image::GrayImage,
    strokes: &[InkStroke],
    seed: u64,
    out_w: u32,
    out_h: u32,
) -> Vec<f32> {
    if strokes.is_empty() {
        return match net {
            Some(n) => n.wall_probability(grey, out_w, out_h),
            None => model.wall_probability(grey, out_w, out_h),
        };
    }
    let (w, h) = grey.dimensions();
    let (ws, hs) = working_size(w, h, &model.working);
    let mut f = model.features(grey);
    let map = match net {
        Some(n) => n.two_class_map(grey, &model.working),
        None => model.working_map(&mut f),
    };
    let f = with_context(f, &map, &smoothed_context(&[1.0, 3.0, 8.0]));
    let user = stroked(strokes, w, h, ws, hs);
    let mut near = vec![false; f.width * f.height];
    user.iter().for_each(|&(i, _)| near[i] = true);
    // Pseudo-labels: pixels the model is sure of, away from the strokes.
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let wall = map.class_map(1);
    let mut pseudo: Vec<(usize, usize)> = Vec::new();
    for _ in 0..20_000 {
        let i = rng.random_range(0..wall.len());
        if !near[i] && (wall[i] > 0.8 || wall[i] < 0.2) {
            pseudo.push((i, usize::from(wall[i] > 0.5)));
        }
    }
    // Each stroked pixel counts as much as ten pseudo-labels (repeated), so that a few strokes
    // outweigh the model where they disagree.
    let mut x = Vec::new();
    let mut labels = Vec::new();
    for &(i, l) in user
        .iter()
        .flat_map(|p| std::iter::repeat_n(p, 10))
        .chain(&pseudo)
    {
        x.extend(f.planes.iter().map(|pl| pl[i]));
        labels.push(l);
    }
    let params = ForestParams {
        trees: 16,
        max_depth: 14,
        min_leaf: 2,
        max_per_class: 60_000,
        seed,
        ..ForestParams::default()
    };
    let p = match Forest::train(&x, f.dim(), &labels, 2, &params) {
        Ok(forest) => forest.predict(&f).expect("its own features"),
        // Strokes and sure pixels of one class only: nothing to learn the other from.
        Err(_) => map,
    };
    pixelclass::resample::enlarge(&wall_class(&p), out_w as usize, out_h as usize).data
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ink::train::fixtures::{sheet, toy_model};

    fn stroke(wall: bool, points: Vec<[f64; 2]>) -> InkStroke {
        InkStroke {
            wall,
            radius: 1.0,
            points,
        }
    }

    #[test]
    fn strokes_are_checked_against_the_drawing() {
        assert!(check(&[stroke(true, vec![[1.0, 1.0], [9.0, 9.0]])], 10, 10).is_ok());
        let e = check(
            &[
                stroke(true, vec![[1.0, 1.0]]),
                stroke(false, vec![[10.0, 1.0]]),
            ],
            10,
            10,
        );
        assert!(matches!(e, Err(StrokeError::Bad { index: 1, .. })));
        assert!(check(&[stroke(true, vec![])], 10, 10).is_err());
        let wide = InkStroke {
            radius: 0.0,
            ..stroke(true, vec![[1.0, 1.0]])
        };
        assert!(check(&[wide], 10, 10).is_err());
        assert!(
            check(
                &vec![stroke(true, vec![[1.0, 1.0]]); MAX_STROKES + 1],
                10,
                10
            )
            .is_err()
        );
    }

    #[test]
    fn a_stroke_covers_the_pixels_within_its_radius() {
        // A horizontal stroke of radius 1 along y = 5.5 from x = 2.5 to 6.5 on a 10 x 10 grid:
        // rows 4..=6 (centres within 1 of 5.5: 4.5, 5.5, 6.5), columns 2..=6, plus the
        // round caps' centres within 1 of the ends (none beyond, at 1.5 and 7.5: distance 1).
        let px = stroked(
            &[stroke(false, vec![[2.5, 5.5], [6.5, 5.5]])],
            10,
            10,
            10,
            10,
        );
        assert!(px.iter().all(|&(_, l)| l == 0));
        let cells: Vec<(usize, usize)> = px.iter().map(|&(i, _)| (i % 10, i / 10)).collect();
        assert!(cells.contains(&(2, 4)) && cells.contains(&(6, 6)) && cells.contains(&(4, 5)));
        assert!(cells.iter().all(|&(_, y)| (4..=6).contains(&y)));
        assert_eq!(cells.iter().filter(|&&(_, y)| y == 5).count(), 7);
    }

    #[test]
    fn a_wall_stroke_on_a_letter_makes_it_wall_and_the_frame_stays() {
        letter_stroked_as_wall(None);
    }

    #[test]
    fn the_strokes_refine_the_network_too() {
        letter_stroked_as_wall(Some(&crate::ink::shipped_net()));
    }

    /// A wall stroke on a letter of the toy sheet, refining the toy forest or, given `net`,
    /// the network read through the toy forest's features.
    fn letter_stroked_as_wall(net: Option<&WallNet>) {
        let model = toy_model();
        let test = sheet(9);
        let (w, h) = test.grey.dimensions();
        // One letter stroke (5 dark pixels in a column, not on the frame).
        let (x, y) = (16..74u32)
            .flat_map(|x| (16..50u32).map(move |y| (x, y)))
            .find(|&(x, y)| (0..5).all(|k| test.grey.get_pixel(x, y + k)[0] < 128))
            .unwrap();
        let before = wall_probability(&model, net, &test.grey, &[], 1, w, h);
        let at = |p: &[f32]| p[((y + 2) * w + x) as usize];
        assert!(
            at(&before) < 0.5,
            "the model reads the letter as wall already"
        );
        let strokes = [InkStroke {
            wall: true,
            radius: 0.7,
            points: vec![
                [f64::from(x) + 0.5, f64::from(y) + 0.5],
                [f64::from(x) + 0.5, f64::from(y) + 4.5],
            ],
        }];
        check(&strokes, w, h).unwrap();
        let after = wall_probability(&model, net, &test.grey, &strokes, 1, w, h);
        assert!(at(&after) > 0.5, "P(wall) under the stroke {}", at(&after));
        let frame = (10..80)
            .filter(|&fx| after[(12 * w + fx) as usize] > 0.5)
            .count();
        assert!(
            frame >= 60,
            "{frame} of 70 frame pixels on row 12 still wall"
        );
        // Same strokes, same seed: same map.
        assert_eq!(
            after,
            wall_probability(&model, net, &test.grey, &strokes, 1, w, h)
        );
    }
}
