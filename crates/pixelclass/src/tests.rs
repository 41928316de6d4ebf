//! The pipeline end to end: known answers, errors, determinism across thread counts.

use super::*;
use image::{Rgb, RgbImage};

/// A wall with a grid of dark windows and a light sky band; samples from three windows, three
/// wall spots and the sky.
fn scene() -> (RgbImage, Vec<Sample>) {
    let (w, h) = (160u32, 120u32);
    let mut img = RgbImage::from_fn(w, h, |x, y| {
        if y < 20 {
            Rgb([150, 190, 230])
        } else {
            // Brick-ish texture: rows of slightly different reds.
            let v = if (y / 3 + x / 7) % 2 == 0 { 8 } else { 0 };
            Rgb([180 + v, 100 + v, 80])
        }
    });
    for gy in 0..3 {
        for gx in 0..5 {
            for y in 0..14 {
                for x in 0..10 {
                    img.put_pixel(10 + gx * 30 + x, 30 + gy * 30 + y, Rgb([40, 50, 70]));
                }
            }
        }
    }
    let mut s = Vec::new();
    let mut add = |x0: usize, y0: usize, c: usize| {
        for y in y0..y0 + 3 {
            for x in x0..x0 + 3 {
                s.push(Sample { x, y, class: c });
            }
        }
    };
    add(5, 5, 0);
    add(100, 8, 0);
    add(14, 35, 2);
    add(74, 65, 2);
    add(134, 95, 2);
    add(25, 50, 1);
    add(85, 110, 1);
    add(145, 25, 1);
    (img, s)
}

fn window_truth(x: usize, y: usize) -> usize {
    if y < 20 {
        return 0;
    }
    let inside = |v: usize, start: usize, len: usize| v >= start && (v - start) % 30 < len;
    if (10..160).contains(&x)
        && inside(x, 10, 10)
        && (30..120).contains(&y)
        && inside(y, 30, 14)
        && x < 10 + 4 * 30 + 10
        && y < 30 + 2 * 30 + 14
    {
        2
    } else {
        1
    }
}

#[test]
fn a_synthetic_facade_is_classified() {
    let (img, s) = scene();
    let p = classify(&Channels::from_rgb(&img), &s, 3, &Params::default()).unwrap();
    let labels = p.argmax();
    let right = (0..160 * 120)
        .filter(|&i| labels[i] as usize == window_truth(i % 160, i / 160))
        .count();
    assert!(right as f64 > 0.97 * 160.0 * 120.0, "{right}");
    for px in p.data.chunks(3) {
        assert!((px.iter().sum::<f32>() - 1.0).abs() < 1e-5);
    }
}

#[test]
fn the_working_resolution_changes_little_on_large_shapes() {
    let (img, s) = scene();
    let ch = Channels::from_rgb(&img);
    let p = Params {
        max_pixels: 160 * 120 / 4,
        ..Default::default()
    };
    assert_eq!(working_size(160, 120, p.max_pixels), (80, 60));
    let small = classify(&ch, &s, 3, &p).unwrap();
    assert_eq!((small.width, small.height), (160, 120));
    let labels = small.argmax();
    let right = (0..160 * 120)
        .filter(|&i| labels[i] as usize == window_truth(i % 160, i / 160))
        .count();
    assert!(right as f64 > 0.93 * 160.0 * 120.0, "{right}");
}

#[test]
fn same_seed_gives_bit_identical_maps_whatever_the_thread_count() {
    let (img, s) = scene();
    let ch = Channels::from_rgb(&img);
    let p = Params::default();
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| classify(&ch, &s, 3, &p).unwrap())
    };
    let one = run(1);
    assert_eq!(one, run(3));
    assert_eq!(one, run(1));
    let mut other = p.clone();
    other.forest.seed = 1;
    assert_ne!(one, classify(&ch, &s, 3, &other).unwrap());
}

#[test]
fn a_gray_drawing_separates_ink_from_paper() {
    let img = image::GrayImage::from_fn(50, 40, |x, y| {
        image::Luma([if x % 10 == 0 || y == 20 { 20 } else { 235 }])
    });
    let s = [
        Sample {
            x: 10,
            y: 5,
            class: 1,
        },
        Sample {
            x: 30,
            y: 20,
            class: 1,
        },
        Sample {
            x: 5,
            y: 5,
            class: 0,
        },
        Sample {
            x: 25,
            y: 33,
            class: 0,
        },
    ];
    let p = classify(&Channels::from_gray(&img), &s, 2, &Params::default()).unwrap();
    let l = p.argmax();
    assert_eq!(l[30 * 50 + 40], 1);
    assert_eq!(l[30 * 50 + 45], 0);
}

#[test]
fn errors_name_the_sample_or_class() {
    let (img, mut s) = scene();
    let ch = Channels::from_rgb(&img);
    let p = Params::default();
    s.push(Sample {
        x: 160,
        y: 3,
        class: 1,
    });
    let e = classify(&ch, &s, 3, &p).unwrap_err();
    assert!(
        e.to_string().contains("sample 72 at (160, 3)") && e.to_string().contains("160x120"),
        "{e}"
    );
    s.pop();
    let e = classify(&ch, &s, 4, &p).unwrap_err();
    assert!(
        e.to_string().contains("class 3 has no training samples"),
        "{e}"
    );
    let e = classify(&ch, &s, 1, &p).unwrap_err();
    assert!(e.to_string().contains("at least two"), "{e}");
    let tiny = Channels::new(1, 5, vec![vec![0.0; 5]]).unwrap();
    let e = classify(&tiny, &[], 2, &p).unwrap_err();
    assert!(e.to_string().contains("1x5 is too small"), "{e}");
}
