//! Synthetic Gothic façades with known answers (tests and benchmarks of ch. 4): bays of 2–4
//! identical round or pointed windows, each bay under an enclosing arch outlined by a dark
//! groove, on a running-bond brick wall with light mortar and seeded noise.

use image::{Rgb, RgbImage};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::element::Theta;

/// One bay: `windows` identical windows under an enclosing arch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bay {
    pub windows: usize,
    pub pointed: bool,
}

/// What to draw.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthSpec {
    pub width: u32,
    pub height: u32,
    pub bays: Vec<Bay>,
    /// Brick size (px) without mortar, and the mortar joint width.
    pub brick: (u32, u32),
    pub mortar: u32,
    /// Amplitude of the uniform pixel noise.
    pub noise: i32,
}

impl SynthSpec {
    /// 480 x 400: a bay of two round windows and a bay of three pointed ones.
    pub fn small() -> SynthSpec {
        SynthSpec {
            width: 480,
            height: 400,
            bays: vec![
                Bay {
                    windows: 2,
                    pointed: false,
                },
                Bay {
                    windows: 3,
                    pointed: true,
                },
            ],
            brick: (22, 9),
            mortar: 2,
            noise: 8,
        }
    }

    /// 1000 x 1000 (one megapixel): three bays of 2, 4 and 3 windows.
    pub fn megapixel() -> SynthSpec {
        SynthSpec {
            width: 1000,
            height: 1000,
            bays: vec![
                Bay {
                    windows: 2,
                    pointed: true,
                },
                Bay {
                    windows: 4,
                    pointed: false,
                },
                Bay {
                    windows: 3,
                    pointed: true,
                },
            ],
            brick: (30, 12),
            mortar: 3,
            noise: 8,
        }
    }
}

/// A known element: its shape, the index of its enclosing element and its bay.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrueElement {
    pub theta: Theta,
    pub parent: Option<usize>,
    /// The bay of a window (windows of one bay form one group); None for enclosing arches.
    pub group: Option<usize>,
}

/// How many of the true elements some found shape matches within `tol` px in x0, y0, width and
/// apex height: the recovery figure of the synthetic tests and the benchmark.
pub fn recovered(truth: &[TrueElement], found: &[Theta], tol: f64) -> usize {
    truth
        .iter()
        .filter(|t| {
            found.iter().any(|a| {
                let b = t.theta;
                [a.x0 - b.x0, a.y0 - b.y0, a.w - b.w, a.apex() - b.apex()]
                    .iter()
                    .all(|d| d.abs() <= tol)
            })
        })
        .count()
}

/// The picture and its answers.
#[derive(Debug, Clone)]
pub struct Synthetic {
    pub image: RgbImage,
    pub elements: Vec<TrueElement>,
    /// Row-major: true on mortar joints of the brick wall (outside every element).
    pub mortar: Vec<bool>,
    /// Row-major: true on brick wall (mortar or brick) outside every element.
    pub wall: Vec<bool>,
}

/// The element layout of a spec, enclosing arch of each bay first, then its windows.
pub fn layout(spec: &SynthSpec) -> Vec<TrueElement> {
    let (w, h) = (spec.width as f64, spec.height as f64);
    let n = spec.bays.len().max(1) as f64;
    let margin = 0.04 * w;
    let bay_w = (w - 2.0 * margin) / n;
    let mut out = Vec::new();
    for (b, bay) in spec.bays.iter().enumerate() {
        let c = bay.windows.clamp(1, 8) as f64;
        let ex0 = margin + b as f64 * bay_w + 0.08 * bay_w;
        let ew = 0.84 * bay_w;
        let ww = ew / (c + 0.35 * (c + 1.0));
        let gap = 0.35 * ww;
        let ey0 = 0.92 * h;
        let wy0 = ey0 - gap;
        let wh = 1.2 * ww;
        let wv = if bay.pointed { 0.8 * ww } else { 0.5 * ww };
        let spring = wy0 - wh - wv - gap;
        let ev = if bay.pointed { 0.6 * ew } else { 0.5 * ew };
        let parent = out.len();
        out.push(TrueElement {
            theta: Theta {
                x0: ex0,
                y0: ey0,
                h: ey0 - spring,
                w: ew,
                v: ev,
            },
            parent: None,
            group: None,
        });
        for k in 0..bay.windows.clamp(1, 8) {
            out.push(TrueElement {
                theta: Theta {
                    x0: ex0 + gap + k as f64 * (ww + gap),
                    y0: wy0,
                    h: wh,
                    w: ww,
                    v: wv,
                },
                parent: Some(parent),
                group: Some(b),
            });
        }
    }
    out
}

/// Draws the façade of `spec` with noise from `seed`.
pub fn synthetic_facade(spec: &SynthSpec, seed: u64) -> Synthetic {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (w, h) = (spec.width, spec.height);
    let elements = layout(spec);
    let (bw, bh, m) = (spec.brick.0.max(2), spec.brick.1.max(2), spec.mortar);
    let (cw, ch) = (bw + m, bh + m);
    // Brick colours per course and brick, drawn up front so the noise stream is fixed.
    let courses = h / ch + 2;
    let per_course = w / cw + 3;
    let tints: Vec<[i32; 3]> = (0..courses * per_course)
        .map(|_| {
            let r = rng.random_range(125..165);
            [
                r,
                r / 2 + rng.random_range(0..15),
                r / 3 + rng.random_range(0..10),
            ]
        })
        .collect();
    let noise = |base: [i32; 3], rng: &mut ChaCha8Rng| {
        let a = spec.noise.max(0);
        let d = if a > 0 { rng.random_range(-a..=a) } else { 0 };
        Rgb(base.map(|c| (c + d).clamp(0, 255) as u8))
    };
    let mut image = RgbImage::new(w, h);
    let mut mortar = vec![false; (w * h) as usize];
    let mut wall = vec![true; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            let course = y / ch;
            let shift = if course % 2 == 1 { cw / 2 } else { 0 };
            let xs = x + shift;
            let joint = y % ch >= bh || xs % cw >= bw;
            let i = (y * w + x) as usize;
            mortar[i] = joint;
            let tint = tints[(course * per_course + xs / cw) as usize % tints.len()];
            let base = if joint { [205, 200, 188] } else { tint };
            image.put_pixel(x, y, noise(base, &mut rng));
        }
    }
    let inside = |t: &Theta, x: u32, y: u32| t.contains(x as f64, y as f64);
    for e in elements.iter().filter(|e| e.parent.is_none()) {
        let grown = e.theta.grown(2.0);
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) as usize;
                if inside(&grown, x, y) {
                    wall[i] = false;
                    mortar[i] = false;
                }
                if inside(&e.theta, x, y) {
                    image.put_pixel(x, y, noise([172, 163, 148], &mut rng));
                }
            }
        }
        // The groove: a dark band 3 px wide centred on the contour.
        for s in e.theta.contour_at(0.5) {
            for dy in -2i32..=2 {
                for dx in -2i32..=2 {
                    let (px, py) = (s.x + dx as f64, s.y + dy as f64);
                    let (xi, yi) = (px.round(), py.round());
                    if xi < 0.0 || yi < 0.0 || xi >= w as f64 || yi >= h as f64 {
                        continue;
                    }
                    if (xi - s.x).hypot(yi - s.y) <= 1.5 {
                        image.put_pixel(xi as u32, yi as u32, Rgb([70, 60, 55]));
                    }
                }
            }
        }
    }
    for e in elements.iter().filter(|e| e.parent.is_some()) {
        for y in 0..h {
            for x in 0..w {
                if inside(&e.theta, x, y) {
                    image.put_pixel(x, y, noise([38, 46, 62], &mut rng));
                }
            }
        }
    }
    Synthetic {
        image,
        elements,
        mortar,
        wall,
    }
}

/// The layout of `spec` drawn as an engraving (the hatching test of the Viollet-le-Duc
/// elevations): white paper, the wall ruled with coursing lines every `course` px, the
/// tympana hatched diagonally, the window openings hatched vertically every 3 px, and each
/// element outlined in ink. Only `elements` is filled in the answer (no masonry truth).
pub fn engraving(spec: &SynthSpec, course: u32, seed: u64) -> Synthetic {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (w, h) = (spec.width, spec.height);
    let elements = layout(spec);
    let course = course.max(2);
    let ink = 35;
    let mut image = RgbImage::new(w, h);
    for y in 0..h {
        for x in 0..w {
            let (xf, yf) = (x as f64, y as f64);
            let window = elements
                .iter()
                .any(|e| e.parent.is_some() && e.theta.contains(xf, yf));
            let arch = elements
                .iter()
                .any(|e| e.parent.is_none() && e.theta.contains(xf, yf));
            let stroke = if window {
                x % 3 == 0
            } else if arch {
                (x + y) % 5 == 0
            } else {
                y % course == 0
            };
            let tone = if stroke { ink } else { 235 };
            let a = spec.noise.max(0);
            let d = if a > 0 { rng.random_range(-a..=a) } else { 0 };
            image.put_pixel(x, y, Rgb([(tone + d).clamp(0, 255) as u8; 3]));
        }
    }
    for e in &elements {
        for s in e.theta.contour_at(0.5) {
            let (xi, yi) = (s.x.round(), s.y.round());
            if xi >= 0.0 && yi >= 0.0 && xi < w as f64 && yi < h as f64 {
                image.put_pixel(xi as u32, yi as u32, Rgb([ink as u8; 3]));
            }
        }
    }
    Synthetic {
        image,
        elements,
        mortar: vec![false; (w * h) as usize],
        wall: vec![false; (w * h) as usize],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gothic::hierarchy::contains;

    #[test]
    fn windows_sit_inside_their_enclosing_arch_and_the_image() {
        for spec in [SynthSpec::small(), SynthSpec::megapixel()] {
            let els = layout(&spec);
            for e in &els {
                let [x0, y0, x1, y1] = e.theta.bbox();
                assert!(x0 > 0.0 && y0 > 0.0 && x1 < spec.width as f64 && y1 < spec.height as f64);
                if let Some(p) = e.parent {
                    assert!(contains(&els[p].theta, &e.theta, 0.0));
                }
            }
        }
    }

    #[test]
    fn drawing_is_deterministic_and_windows_are_dark() {
        let spec = SynthSpec {
            width: 200,
            height: 160,
            ..SynthSpec::small()
        };
        let (a, b) = (synthetic_facade(&spec, 3), synthetic_facade(&spec, 3));
        assert_eq!(a.image, b.image);
        let win = a.elements[1].theta;
        let c = a
            .image
            .get_pixel((win.x0 + win.w / 2.0) as u32, (win.y0 - 2.0) as u32);
        assert!(c[0] < 60, "{c:?}");
        assert!(a.mortar.iter().any(|&m| m) && a.wall.iter().any(|&w| !w));
    }
}
