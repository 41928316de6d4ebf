//! Synthetic corners at known sub-pixel positions and angles, drawn with anti-aliasing, blurred
//! and noisy (seeded): the detector's position error, recall and precision have bounds.

use corners::edge::{gaussian_kernel, smooth};
use corners::{Gray, Params, detect};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A convex polygon's vertices (counter-clockwise or clockwise, consistently).
type Poly = Vec<[f64; 2]>;

fn inside(poly: &Poly, x: f64, y: f64) -> bool {
    let n = poly.len();
    let mut sign = 0.0;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let cr = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
        if sign == 0.0 {
            sign = cr.signum();
        } else if cr * sign < 0.0 {
            return false;
        }
    }
    true
}

struct Scene {
    img: Gray,
    truth: Vec<[f64; 2]>,
}

/// `cells` × `cells` cells of `cell` px, one quadrilateral in each: a rotated rectangle or a
/// parallelogram with corner angles from 55° to 125°, at a random sub-pixel offset.
fn scene(seed: u64, cells: usize, cell: usize, blur: f64, noise: f64) -> Scene {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let size = cells * cell;
    let mut polys: Vec<(Poly, f32)> = Vec::new();
    for cy in 0..cells {
        for cx in 0..cells {
            let c = [
                (cx * cell) as f64 + cell as f64 / 2.0 + rng.random_range(-3.0..3.0),
                (cy * cell) as f64 + cell as f64 / 2.0 + rng.random_range(-3.0..3.0),
            ];
            let rot: f64 = rng.random_range(0.0..std::f64::consts::PI);
            let angle: f64 = if rng.random::<bool>() {
                std::f64::consts::FRAC_PI_2
            } else {
                rng.random_range(55f64..125.0).to_radians()
            };
            let (a, b) = (
                rng.random_range(0.42..0.55) * cell as f64,
                rng.random_range(0.42..0.55) * cell as f64,
            );
            // Parallelogram with sides a (along u) and b (along v), centred on c.
            let u = [rot.cos(), rot.sin()];
            let v = [(rot + angle).cos(), (rot + angle).sin()];
            let p = |s: f64, t: f64| {
                [
                    c[0] + (s - 0.5) * a * u[0] + (t - 0.5) * b * v[0],
                    c[1] + (s - 0.5) * a * u[1] + (t - 0.5) * b * v[1],
                ]
            };
            let poly = vec![p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)];
            let level = rng.random_range(150.0f32..220.0);
            polys.push((poly, level));
        }
    }
    // 4 × 4 supersampling; pixel (x, y) covers [x − ½, x + ½]².
    let bg = 50.0f32;
    let mut data = vec![bg; size * size];
    for (poly, level) in &polys {
        let xs = poly.iter().map(|p| p[0]);
        let ys = poly.iter().map(|p| p[1]);
        let x0 = xs.clone().fold(f64::MAX, f64::min).floor().max(0.0) as usize;
        let x1 = (xs.fold(f64::MIN, f64::max).ceil() as usize + 1).min(size);
        let y0 = ys.clone().fold(f64::MAX, f64::min).floor().max(0.0) as usize;
        let y1 = (ys.fold(f64::MIN, f64::max).ceil() as usize + 1).min(size);
        for y in y0..y1 {
            for x in x0..x1 {
                let mut cov = 0;
                for sy in 0..4 {
                    for sx in 0..4 {
                        let px = x as f64 - 0.375 + sx as f64 * 0.25;
                        let py = y as f64 - 0.375 + sy as f64 * 0.25;
                        cov += inside(poly, px, py) as u32;
                    }
                }
                let f = cov as f32 / 16.0;
                data[y * size + x] = bg * (1.0 - f) + level * f;
            }
        }
    }
    let mut img = Gray::new(size, size, data);
    if blur > 0.0 {
        img = smooth(
            &img,
            &gaussian_kernel(2 * (3.0 * blur).ceil() as usize + 1, blur),
        );
    }
    for v in img.data.iter_mut() {
        // Box–Muller.
        let (u1, u2): (f64, f64) = (rng.random_range(1e-12..1.0), rng.random());
        let n = (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos();
        *v += (noise * n) as f32;
    }
    Scene {
        img,
        truth: polys.into_iter().flat_map(|(p, _)| p).collect(),
    }
}

struct Score {
    recall: f64,
    precision: f64,
    mean_error: f64,
    max_error: f64,
}

fn score(found: &[[f64; 2]], truth: &[[f64; 2]], radius: f64) -> Score {
    let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    let mut errors = Vec::new();
    for t in truth {
        let best = found.iter().map(|f| dist(*f, *t)).fold(f64::MAX, f64::min);
        if best <= radius {
            errors.push(best);
        }
    }
    let true_pos = found
        .iter()
        .filter(|f| truth.iter().any(|t| dist(**f, *t) <= radius))
        .count();
    Score {
        recall: errors.len() as f64 / truth.len() as f64,
        precision: if found.is_empty() {
            0.0
        } else {
            true_pos as f64 / found.len() as f64
        },
        mean_error: errors.iter().sum::<f64>() / errors.len().max(1) as f64,
        max_error: errors.iter().copied().fold(0.0, f64::max),
    }
}

fn run(seed: u64, blur: f64, noise: f64) -> Score {
    let s = scene(seed, 4, 64, blur, noise);
    let found = detect(&s.img, &Params::default()).unwrap();
    let pts: Vec<[f64; 2]> = found.corners.iter().map(|c| [c.x, c.y]).collect();
    let sc = score(&pts, &s.truth, 3.0);
    eprintln!(
        "seed {seed} blur {blur} noise {noise}: {} found, {} true; recall {:.3} precision {:.3} \
         mean error {:.3} px, max {:.3} px",
        pts.len(),
        s.truth.len(),
        sc.recall,
        sc.precision,
        sc.mean_error,
        sc.max_error
    );
    sc
}

#[test]
fn clean_corners_are_found_precisely() {
    for seed in [1, 2] {
        let s = run(seed, 0.7, 1.0);
        assert!(s.recall >= 0.9, "recall {}", s.recall);
        assert!(s.precision >= 0.95, "precision {}", s.precision);
        assert!(s.mean_error <= 0.35, "mean error {}", s.mean_error);
    }
}

#[test]
fn blurred_noisy_corners_are_still_found() {
    for seed in [3, 4] {
        let s = run(seed, 1.5, 6.0);
        assert!(s.recall >= 0.85, "recall {}", s.recall);
        assert!(s.precision >= 0.93, "precision {}", s.precision);
        assert!(s.mean_error <= 0.6, "mean error {}", s.mean_error);
    }
}

#[test]
fn asymptotes_follow_the_sides() {
    // One parallelogram at a random angle: both asymptotes of every corner within 5° of its
    // side directions (the blur rounds the corner, which tilts the fitted asymptotes a little).
    let s = scene(9, 1, 64, 0.7, 1.0);
    let found = detect(&s.img, &Params::default()).unwrap();
    let sides: Vec<f64> = (0..4)
        .map(|i| {
            let (a, b) = (s.truth[i], s.truth[(i + 1) % 4]);
            (b[1] - a[1])
                .atan2(b[0] - a[0])
                .rem_euclid(std::f64::consts::PI)
        })
        .collect();
    assert!(!found.corners.is_empty());
    for c in &found.corners {
        for v in c.directions {
            let ang = v[1].atan2(v[0]).rem_euclid(std::f64::consts::PI);
            let err = sides
                .iter()
                .map(|s| {
                    let d = (ang - s).abs();
                    d.min(std::f64::consts::PI - d)
                })
                .fold(f64::MAX, f64::min);
            assert!(
                err < 5f64.to_radians(),
                "direction {ang} vs sides {sides:?}"
            );
        }
    }
}

#[test]
fn bad_inputs_give_empty_results() {
    let p = Params::default();
    for (w, h) in [(1, 1), (2, 5), (0, 0), (13, 13)] {
        let r = detect(&Gray::new(w, h, vec![9.0; w * h]), &p).unwrap();
        assert!(r.corners.is_empty());
    }
    // Pure noise has edges but no structure worth many corners; never a panic.
    let s = scene(5, 2, 64, 0.0, 0.0);
    let flat = Gray::new(s.img.width, s.img.height, vec![128.0; s.img.data.len()]);
    assert!(detect(&flat, &p).unwrap().corners.is_empty());
    // 16-bit and RGBA images convert to the same grey.
    let g8 = image::GrayImage::from_fn(40, 40, |x, y| {
        image::Luma([if x > 15 && y > 15 { 200 } else { 30 }])
    });
    let d8 = image::DynamicImage::ImageLuma8(g8.clone());
    let d16 = image::DynamicImage::ImageLuma16(image::ImageBuffer::from_fn(40, 40, |x, y| {
        image::Luma([g8.get_pixel(x, y)[0] as u16 * 257])
    }));
    let rgba = image::DynamicImage::ImageRgba8(d8.to_rgba8());
    let a = detect(&Gray::from_dynamic(&d8), &p).unwrap();
    assert_eq!(a.corners.len(), 1);
    for other in [d16, rgba] {
        let b = detect(&Gray::from_dynamic(&other), &p).unwrap();
        assert_eq!(b.corners.len(), 1);
        // Rounding differs in the last bits, which may move a thinned edge point.
        let (ca, cb) = (&a.corners[0], &b.corners[0]);
        assert!(
            (ca.x - cb.x).abs() < 0.3 && (ca.y - cb.y).abs() < 0.3,
            "{ca:?} vs {cb:?}"
        );
    }
}

/// A `side` × `side` square centred in a `size` image, turned by `angle`, 4 × 4 anti-aliased.
fn turned_square(size: usize, side: f64, angle: f64) -> Gray {
    let c = size as f64 / 2.0;
    let (sn, cs) = angle.sin_cos();
    let h = side / 2.0;
    let poly: Poly = [(-h, -h), (h, -h), (h, h), (-h, h)]
        .iter()
        .map(|&(x, y)| [c + cs * x - sn * y, c + sn * x + cs * y])
        .collect();
    let data = (0..size * size)
        .map(|i| {
            let (x, y) = ((i % size) as f64, (i / size) as f64);
            let mut cov = 0;
            for sy in 0..4 {
                for sx in 0..4 {
                    let (px, py) = (x - 0.375 + sx as f64 * 0.25, y - 0.375 + sy as f64 * 0.25);
                    cov += inside(&poly, px, py) as u32;
                }
            }
            40.0 + 160.0 * cov as f32 / 16.0
        })
        .collect();
    Gray::new(size, size, data)
}

#[test]
fn rectified_mode_keeps_only_axis_aligned_corners() {
    let rectified = Params {
        rectified: true,
        ..Params::default()
    };
    let straight = turned_square(80, 36.0, 3f64.to_radians());
    let turned = turned_square(80, 36.0, 30f64.to_radians());
    assert_eq!(
        detect(&straight, &Params::default()).unwrap().corners.len(),
        4
    );
    assert_eq!(
        detect(&turned, &Params::default()).unwrap().corners.len(),
        4
    );
    assert_eq!(detect(&straight, &rectified).unwrap().corners.len(), 4);
    assert_eq!(detect(&turned, &rectified).unwrap().corners.len(), 0);
}
