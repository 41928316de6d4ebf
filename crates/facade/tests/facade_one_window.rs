//! Issue 21: a user who draws ONE whole window (frame, bars and all) and two wall boxes gets
//! every window of a generated façade, through `facade::parse_photo` (classify with the
//! whole-window sampling rule → repeats as window evidence → search).

use facade::classify::{Class, ClassifyParams, Training};
use facade::parse_photo;
use facade::repeat::RepeatParams;
use facade::search::SearchParams;
use image::{Rgb, RgbImage};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A façade filling the image: brick-coursed wall, `floors` × `cols` windows, each a light
/// frame (3 px) round dark glass with a light mullion and transom and a reflection gradient,
/// ±8 grey-level noise. Returns the image and the windows' boxes (frames included).
fn framed_facade(w: u32, h: u32, floors: u32, cols: u32, seed: u64) -> (RgbImage, Vec<[u32; 4]>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (fl_h, pitch) = (h / floors, w / cols);
    let mut windows = Vec::new();
    for f in 0..floors {
        for c in 0..cols {
            let x0 = c * pitch + pitch / 4;
            let y0 = f * fl_h + fl_h / 4;
            windows.push([x0, y0, x0 + pitch / 2, y0 + fl_h / 2]);
        }
    }
    let img = RgbImage::from_fn(w, h, |x, y| {
        let base: [f64; 3] = match windows
            .iter()
            .find(|r| x >= r[0] && x < r[2] && y >= r[1] && y < r[3])
        {
            Some(r) => {
                let (mx, my) = ((r[0] + r[2]) / 2, (r[1] + r[3]) / 2);
                let frame = x < r[0] + 3 || x >= r[2] - 3 || y < r[1] + 3 || y >= r[3] - 3;
                let bar = x.abs_diff(mx) <= 1 || y.abs_diff(my) <= 1;
                if frame || bar {
                    [225.0, 225.0, 215.0]
                } else {
                    // Sky reflected in the upper panes.
                    let t = (y - r[1]) as f64 / (r[3] - r[1]) as f64;
                    [
                        40.0 + 60.0 * (1.0 - t),
                        50.0 + 70.0 * (1.0 - t),
                        70.0 + 80.0 * (1.0 - t),
                    ]
                }
            }
            None => {
                let course = if (y / 4) % 2 == 0 { 0.0 } else { 12.0 };
                [170.0 + course, 120.0 + course, 90.0]
            }
        };
        let n: f64 = rng.random_range(-8.0..8.0);
        Rgb(base.map(|b| (b + n).clamp(0.0, 255.0) as u8))
    });
    (img, windows)
}

fn iou(a: &[f64; 4], b: &[u32; 4]) -> f64 {
    let ix = (a[2].min(b[2] as f64) - a[0].max(b[0] as f64)).max(0.0);
    let iy = (a[3].min(b[3] as f64) - a[1].max(b[1] as f64)).max(0.0);
    let inter = ix * iy;
    let area = |v: [f64; 4]| (v[2] - v[0]) * (v[3] - v[1]);
    inter / (area(*a) + area(b.map(|v| v as f64)) - inter)
}

fn one_window_user(windows: &[[u32; 4]], pick: usize, walls: Vec<[f64; 4]>) -> Training {
    let mut t = Training {
        whole_windows: vec![windows[pick].map(|v| v as f64)],
        ..Default::default()
    };
    t.classes.insert(Class::Wall, walls);
    t
}

fn check(img: &RgbImage, windows: &[[u32; 4]], training: &Training) {
    let (_, model, repeats) = parse_photo(
        img,
        training,
        &ClassifyParams::default(),
        &SearchParams::default(),
        &RepeatParams::default(),
    )
    .unwrap();
    assert!(repeats.is_some(), "a whole-window box runs the repeat step");
    let found: Vec<[f64; 4]> = model
        .facades
        .iter()
        .flat_map(|f| f.floors.iter().flat_map(|fl| fl.windows.iter().copied()))
        .collect();
    assert_eq!(found.len(), windows.len(), "{found:?}");
    for t in windows {
        let best = found.iter().map(|f| iou(f, t)).fold(0.0, f64::max);
        assert!(best >= 0.8, "window {t:?}: best IoU {best:.3} in {found:?}");
    }
}

#[test]
fn one_whole_window_and_two_wall_boxes_give_every_window_of_a_4_by_3_grid() {
    let (img, windows) = framed_facade(320, 240, 3, 4, 7);
    let training = one_window_user(
        &windows,
        5,
        vec![[2.0, 2.0, 14.0, 14.0], [150.0, 200.0, 170.0, 212.0]],
    );
    check(&img, &windows, &training);
}

#[test]
fn one_whole_window_and_two_wall_boxes_give_every_window_of_a_5_by_4_grid() {
    let (img, windows) = framed_facade(400, 320, 4, 5, 3);
    let training = one_window_user(
        &windows,
        0,
        vec![[70.0, 150.0, 80.0, 160.0], [300.0, 300.0, 315.0, 315.0]],
    );
    check(&img, &windows, &training);
}
