//! The class-driven Gothic mode (`gothic::classes`, a departure from §4.2) on a synthetic
//! photographed-style façade: windows with white frames, glazing bars and dark noisy panes on
//! a noisy brick wall. The edges of §4.2 split every window into panes; the ch. 3 window class
//! (training boxes from the simulated user of `eval.rs`) gives the whole window back.

use facade::classify::{ClassifyParams, Method, Training};
use facade::eval::simulate_user;
use facade::gothic::classes::{ClassMapParams, estimate_with_classes};
use facade::gothic::{GothicEstimate, GothicParams, Theta, estimate};
use image::{Rgb, RgbImage};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A 400 x 300 brick façade with two rows of four 40 x 64 windows; each window has a 2-px white
/// frame, a 3-px white cross of glazing bars and four dark panes. Returns the image, the
/// ground-truth labels (1 wall, 2 window) and the window boxes as Θ (rectangles, v = 0).
fn photographed_facade(seed: u64) -> (RgbImage, Vec<u8>, Vec<Theta>) {
    let (w, h) = (400u32, 300u32);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut img = RgbImage::new(w, h);
    for y in 0..h {
        for x in 0..w {
            let course = y / 11;
            let shift = if course % 2 == 0 { 0 } else { 12 };
            let mortar = y % 11 < 2 || (x + shift) % 24 < 2;
            let base = if mortar {
                [200i32, 190, 175]
            } else {
                [165, 80, 55]
            };
            let n = rng.random_range(-18i32..=18);
            img.put_pixel(x, y, Rgb(base.map(|c| (c + n).clamp(0, 255) as u8)));
        }
    }
    let mut truth = vec![1u8; (w * h) as usize];
    let mut windows = Vec::new();
    for row in 0..2u32 {
        for col in 0..4u32 {
            let (x0, y0) = (30 + col * 95, 40 + row * 130);
            let (ww, wh) = (40u32, 64u32);
            for y in y0..y0 + wh {
                for x in x0..x0 + ww {
                    let (dx, dy) = (x - x0, y - y0);
                    let frame = dx < 2 || dy < 2 || dx >= ww - 2 || dy >= wh - 2;
                    let bar = (ww / 2 - 1..ww / 2 + 2).contains(&dx)
                        || (wh / 2 - 1..wh / 2 + 2).contains(&dy);
                    let n = rng.random_range(-12i32..=12);
                    let c = if frame || bar {
                        [235, 235, 230]
                    } else {
                        [40, 55, 75]
                    };
                    img.put_pixel(x, y, Rgb(c.map(|v| (v + n).clamp(0, 255) as u8)));
                    truth[(y * w + x) as usize] = 2;
                }
            }
            // Θ's x0, y0 are the bottom-left corner in pixel-centre coordinates of the
            // boundary between the window and the wall.
            windows.push(Theta {
                x0: x0 as f64 - 0.5,
                y0: (y0 + wh) as f64 - 0.5,
                h: wh as f64,
                w: ww as f64,
                v: 0.0,
            });
        }
    }
    (img, truth, windows)
}

/// True windows with an estimated element whose box corners are all within `tol` px.
fn found(est: &GothicEstimate, truth: &[Theta], tol: f64) -> usize {
    truth
        .iter()
        .filter(|t| {
            est.elements.iter().any(|e| {
                let (a, b) = (e.theta().bbox(), t.bbox());
                a.iter().zip(&b).all(|(p, q)| (p - q).abs() <= tol)
            })
        })
        .count()
}

fn training(truth: &[u8]) -> Training {
    simulate_user(truth, 400, 300, 3, 9, 1).unwrap()
}

#[test]
fn edges_alone_miss_the_barred_windows() {
    let (img, _, windows) = photographed_facade(3);
    let est = estimate(&img, &GothicParams::default()).unwrap();
    let hits = found(&est, &windows, 3.0);
    assert!(hits <= 2, "{hits} of 8 windows found from edges alone");
}

/// The GMM's window map, explicitly: the class map's clip, smoothing and edge band were
/// measured on GMM maps. The forest's map (the façade default) covers the windows too, 2-4 px
/// wider, and the contour fit then finds 7 of the 8 within 3 px; retuning the class map for it
/// is open work (docs/pixelclass.md).
#[test]
fn the_window_class_finds_every_window_within_three_pixels() {
    let (img, truth, windows) = photographed_facade(3);
    let est = estimate_with_classes(
        &img,
        &training(&truth),
        &GothicParams::default(),
        &ClassifyParams {
            method: Method::Gmm,
            ..Default::default()
        },
        &ClassMapParams::default(),
    )
    .unwrap();
    assert_eq!(found(&est, &windows, 3.0), 8, "{:#?}", est.elements);
    let on_windows = est
        .elements
        .iter()
        .filter(|e| {
            windows
                .iter()
                .any(|t| t.contains(e.x0 + e.w / 2.0, e.y0 - 1.0))
        })
        .count();
    assert_eq!(
        on_windows,
        est.elements.len(),
        "every element is on a window"
    );
    assert_eq!(est.elements.len(), 8);
}

#[test]
fn training_without_a_window_class_is_an_error() {
    let (img, truth, _) = photographed_facade(3);
    let mut t = training(&truth);
    t.classes.remove(&facade::classify::Class::Window);
    let e = estimate_with_classes(
        &img,
        &t,
        &GothicParams::default(),
        &ClassifyParams::default(),
        &ClassMapParams::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("no window boxes"), "{e}");
}
