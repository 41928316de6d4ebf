//! The whole parsing pipeline on synthetic façades with known layouts.

mod common;

use facade::classify::{Class, ClassifyParams, FeatureParams, classify};
use facade::eval::{class_iou, pixel_accuracy, simulate_user};
use facade::search::{SearchParams, parse};

fn truth_labels(s: &common::Synth) -> Vec<u8> {
    let (w, h) = s.img.dimensions();
    let mut t = vec![0u8; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            let inside = |r: &[u32; 4]| x >= r[0] && x < r[2] && y >= r[1] && y < r[3];
            t[(y * w + x) as usize] = if s.windows.iter().any(inside) {
                2
            } else if inside(&s.facade) {
                1
            } else {
                0
            };
        }
    }
    t
}

fn params() -> ClassifyParams {
    ClassifyParams {
        features: FeatureParams {
            pca_samples: 200,
            ..Default::default()
        },
        ..Default::default()
    }
}

#[test]
fn recovers_facade_floors_and_windows() {
    let s = common::facade(240, 180, 4, 5, 11);
    let truth = truth_labels(&s);
    let (w, h) = (240usize, 180usize);
    // The user's boxes: three windows, three wall patches, the sky and the ground.
    // (`simulate_user` only fills in the structure; every class is replaced below.)
    let mut training = simulate_user(&truth, w, h, 3, 5, 2).unwrap();
    let win = |i: usize| {
        let r = s.windows[i];
        [
            r[0] as f64 + 3.0,
            r[1] as f64 + 3.0,
            r[2] as f64 - 3.0,
            r[3] as f64 - 3.0,
        ]
    };
    training
        .classes
        .insert(Class::Window, vec![win(0), win(7), win(13)]);
    // Wall: beside a window, at the façade's left margin, between two floors.
    training.classes.insert(
        Class::Wall,
        vec![
            [56.0, 50.0, 66.0, 60.0],
            [25.0, 90.0, 31.0, 100.0],
            [100.0, 63.0, 110.0, 73.0],
        ],
    );
    let f = s.facade.map(|v| v as f64);
    training.classes.insert(
        Class::Background,
        vec![
            [5.0, 5.0, 235.0, f[1] - 5.0],
            [5.0, f[3] + 2.0, 235.0, 178.0],
        ],
    );
    let ll = classify(&s.img, &training, &params()).unwrap();
    let gmm_only: Vec<u8> = ll.initial_labels().iter().map(|c| *c as u8).collect();
    let model = parse(&s.img, &ll, &SearchParams::default()).unwrap();
    let pred = model.labels();
    let (acc, iou) = (
        pixel_accuracy(&pred, &truth),
        class_iou(&pred, &truth, Class::Window).unwrap(),
    );
    let (acc0, iou0) = (
        pixel_accuracy(&gmm_only, &truth),
        class_iou(&gmm_only, &truth, Class::Window).unwrap(),
    );
    eprintln!(
        "GMM alone: accuracy {acc0:.3}, window IoU {iou0:.3}; with the façade model: {acc:.3}, {iou:.3}"
    );
    assert_eq!(model.facades.len(), 1, "{model:?}");
    let f = &model.facades[0];
    for (a, b) in f.bbox.iter().zip(s.facade) {
        assert!(
            (a - b as f64).abs() <= 6.0,
            "bbox {:?} vs {:?}",
            f.bbox,
            s.facade
        );
    }
    assert_eq!(f.params.n_w, 5, "{:?}", f.params);
    let windows: usize = f.floors.iter().map(|fl| fl.windows.len()).sum();
    assert_eq!(windows, 20);
    assert!(iou > 0.8 && acc > 0.93, "{acc} {iou}");
    assert!(acc0 > 0.9 && iou0 > 0.8, "{acc0} {iou0}");
    assert!(model.merit.is_finite());
}

#[test]
fn without_background_boxes_the_image_is_one_facade() {
    let s = common::facade(160, 120, 3, 3, 5);
    let truth = truth_labels(&s);
    let mut training = simulate_user(&truth, 160, 120, 2, 4, 3).unwrap();
    training.classes.remove(&Class::Background);
    let ll = classify(&s.img, &training, &params()).unwrap();
    let model = parse(&s.img, &ll, &SearchParams::default()).unwrap();
    assert_eq!(model.facades.len(), 1);
    assert_eq!(model.facades[0].bbox, [0.0, 0.0, 160.0, 120.0]);
}

#[test]
fn odd_shapes_give_results_or_errors_never_panics() {
    use facade::classify::Training;
    for (w, h) in [(2u32, 2u32), (3, 40), (40, 3), (25, 25)] {
        let mut img = image::RgbImage::from_pixel(w, h, image::Rgb([200, 150, 100]));
        img.put_pixel(0, 0, image::Rgb([20, 30, 40]));
        let t: Training = serde_json::from_str(&format!(
            r#"{{"classes": {{"window": [[0, 0, 1, 1]], "wall": [[0, 0, {w}, {h}]], "background": [[{}, {}, {w}, {h}]]}}}}"#,
            w - 1,
            h - 1
        ))
        .unwrap();
        if let Ok(ll) = classify(&img, &t, &params()) {
            let m = parse(&img, &ll, &SearchParams::default()).unwrap();
            assert_eq!(m.labels().len(), (w * h) as usize);
        }
    }
}

/// A façade whose ground floor is a shop (two wide windows in their own columns) and whose
/// second floor lacks one window, with a ±1 log-likelihood map from its layout: the default
/// grammar (`Grammar::Columns`) parses it exactly; the text's grid cannot.
#[test]
fn shop_floor_and_missing_window_are_parsed_exactly() {
    use facade::classify::LogLikelihoods;
    use facade::search::Grammar;
    let (w, h) = (200usize, 200usize);
    // Floors (top to bottom): 0..40, 40..80, 80..120, 120..160 with windows 20 wide at x = 20,
    // 60, 100, 140 (rows +10..+30), the second floor without the one at x = 100; shop floor
    // 160..200 with windows x 15..85 and 115..185, rows 165..195.
    let mut wins: Vec<[usize; 4]> = Vec::new();
    for (f, y0) in [0usize, 40, 80, 120].iter().enumerate() {
        for x0 in [20usize, 60, 100, 140] {
            if !(f == 1 && x0 == 100) {
                wins.push([x0, y0 + 10, x0 + 20, y0 + 30]);
            }
        }
    }
    wins.push([15, 165, 85, 195]);
    wins.push([115, 165, 185, 195]);
    let mut img = image::RgbImage::from_pixel(w as u32, h as u32, image::Rgb([190, 150, 120]));
    let mut truth = vec![1u8; w * h];
    for r in &wins {
        for y in r[1]..r[3] {
            for x in r[0]..r[2] {
                img.put_pixel(x as u32, y as u32, image::Rgb([40, 50, 70]));
                truth[y * w + x] = 2;
            }
        }
    }
    let ll = LogLikelihoods {
        width: w,
        height: h,
        maps: [
            None,
            Some(
                truth
                    .iter()
                    .map(|&t| if t == 1 { 0.0 } else { -1.0 })
                    .collect(),
            ),
            Some(
                truth
                    .iter()
                    .map(|&t| if t == 2 { 0.0 } else { -1.0 })
                    .collect(),
            ),
        ],
    };
    let model = parse(&img, &ll, &SearchParams::default()).unwrap();
    assert_eq!(model.facades.len(), 1);
    let f = &model.facades[0];
    let per_floor: Vec<usize> = f.floors.iter().map(|fl| fl.windows.len()).collect();
    assert_eq!(per_floor, vec![4, 3, 4, 4, 2], "{f:?}");
    let wrong = model
        .labels()
        .iter()
        .zip(&truth)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(wrong, 0, "{f:?}");
    assert_eq!((f.params.n_l, f.params.n_w), (5, 4));
    assert_eq!((f.params.w_w, f.params.w_gap), (20.0, 20.0));
    // The text's grammar: one set of equal columns in every floor, every cell a window.
    let text = parse(&img, &ll, &SearchParams::text()).unwrap();
    assert_eq!(SearchParams::text().grammar, Grammar::Text);
    let acc = pixel_accuracy(&text.labels(), &truth);
    assert!(acc < 1.0, "{acc}");
}
