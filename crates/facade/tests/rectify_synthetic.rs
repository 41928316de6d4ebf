//! Rectification of synthetic façades warped by known homographies: the recovered mapping
//! elevation → photo → rectified must send the façade's horizontals and verticals back to
//! horizontal and vertical lines.

mod common;

use facade::rectify::{self, ManualLines, RectifyParams, apply, rectify, rectify_with_lines};
use nalgebra::Matrix3;

/// Worst deviation (degrees) from horizontal/vertical of the façade grid lines after `g`.
fn grid_error(g: &Matrix3<f64>, rect: [u32; 4]) -> f64 {
    let [x0, y0, x1, y1] = rect.map(|v| v as f64);
    let mut worst: f64 = 0.0;
    for i in 0..=4 {
        let t = i as f64 / 4.0;
        let y = y0 + t * (y1 - y0);
        let (a, b) = (apply(g, x0, y).unwrap(), apply(g, x1, y).unwrap());
        worst = worst.max((b.1 - a.1).atan2(b.0 - a.0).to_degrees().abs());
        let x = x0 + t * (x1 - x0);
        let (a, b) = (apply(g, x, y0).unwrap(), apply(g, x, y1).unwrap());
        worst = worst.max((b.0 - a.0).atan2(b.1 - a.1).to_degrees().abs());
    }
    worst
}

fn oblique(h_true: &Matrix3<f64>) -> (common::Synth, image::RgbImage) {
    let s = common::facade(320, 240, 4, 5, 3);
    let photo = rectify::warp(&s.img, h_true, 320, 240).unwrap();
    (s, photo)
}

fn cases() -> Vec<Matrix3<f64>> {
    vec![
        // Turned to the right, looking up a little.
        Matrix3::new(0.85, 0.02, 20.0, 0.10, 0.95, 5.0, 0.0006, 0.0002, 1.0),
        // Turned to the left.
        Matrix3::new(0.9, -0.03, 30.0, -0.08, 0.9, 20.0, -0.0005, 0.0001, 1.0),
        // Mostly a keystone (camera tilted up).
        Matrix3::new(0.9, 0.0, 15.0, 0.0, 0.9, 10.0, 0.0, 0.0007, 1.0),
    ]
}

#[test]
fn automatic_rectification_recovers_synthetic_warps() {
    for (i, h_true) in cases().iter().enumerate() {
        let (s, photo) = oblique(h_true);
        let r = rectify(&photo, &RectifyParams::default()).unwrap();
        let g = r.h * h_true;
        // Shrink the façade by 5% so grid lines stay inside the photo.
        let [x0, y0, x1, y1] = s.facade;
        let err = grid_error(&g, [x0 + 8, y0 + 8, x1 - 8, y1 - 8]);
        eprintln!("case {i}: worst grid-line deviation {err:.3}°");
        assert!(err < 0.3, "case {i}: {err}°");
        // Sensible size: within a factor 2 of the input in each direction.
        assert!(r.width > 160 && r.width < 640 && r.height > 120 && r.height < 480);
    }
}

#[test]
fn manual_lines_give_the_exact_rectification() {
    let h_true = cases()[0];
    let hi = h_true.try_inverse().unwrap();
    let _ = hi;
    let p = |x: f64, y: f64| {
        let (u, v) = apply(&h_true, x, y).unwrap();
        [u, v]
    };
    let seg = |a: [f64; 2], b: [f64; 2]| [a[0], a[1], b[0], b[1]];
    let lines = ManualLines {
        horizontal: vec![
            seg(p(40.0, 60.0), p(280.0, 60.0)),
            seg(p(40.0, 200.0), p(280.0, 200.0)),
        ],
        vertical: vec![
            seg(p(40.0, 60.0), p(40.0, 200.0)),
            seg(p(280.0, 60.0), p(280.0, 200.0)),
        ],
    };
    let r = rectify_with_lines(320, 240, &lines, &RectifyParams::default()).unwrap();
    let err = grid_error(&(r.h * h_true), [40, 60, 280, 200]);
    assert!(err < 1e-6, "{err}");
}

#[test]
fn too_few_manual_lines_is_an_error() {
    let lines = ManualLines {
        horizontal: vec![[0.0, 0.0, 10.0, 0.0]],
        vertical: vec![[0.0, 0.0, 0.0, 10.0], [5.0, 0.0, 5.0, 10.0]],
    };
    let e = rectify_with_lines(100, 100, &lines, &RectifyParams::default()).unwrap_err();
    assert!(e.to_string().contains("two horizontal"), "{e}");
}

#[test]
fn single_colour_image_is_a_clear_error() {
    let img = image::RgbImage::from_pixel(120, 90, image::Rgb([200, 10, 10]));
    let e = rectify(&img, &RectifyParams::default()).unwrap_err();
    assert!(e.to_string().contains("no two that converge"), "{e}");
}

#[test]
fn odd_images_give_results_or_errors_never_panics() {
    use rand::{RngExt, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
    for (w, h) in [(1u32, 1u32), (16, 16), (400, 17), (17, 300), (120, 90)] {
        let img = image::RgbImage::from_fn(w, h, |_, _| {
            image::Rgb([rng.random(), rng.random(), rng.random()])
        });
        if let Ok(r) = rectify(&img, &RectifyParams::default()) {
            let out = r.warp(&img).unwrap();
            assert!(out.width() > 0 && out.height() > 0);
        }
    }
}

#[test]
fn image_with_one_line_family_is_a_clear_error() {
    // Horizontal courses only: no vertical family to find a second vanishing point from.
    let img = image::RgbImage::from_fn(200, 150, |_, y| {
        if (y / 10) % 2 == 0 {
            image::Rgb([200, 190, 170])
        } else {
            image::Rgb([60, 50, 40])
        }
    });
    let e = rectify(&img, &RectifyParams::default()).unwrap_err();
    let text = e.to_string();
    assert!(text.contains("vertical"), "{text}");
}
