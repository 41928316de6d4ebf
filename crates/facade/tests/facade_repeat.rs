//! Windows found as repeats of one drawn window (`facade::repeat`) on generated façades.

mod common;

use facade::repeat::{RepeatParams, find_repeats};

fn matched(found: &[[f64; 4]], truth: &[[u32; 4]], tol: f64) -> usize {
    truth
        .iter()
        .filter(|t| {
            found.iter().any(|f| {
                f.iter()
                    .zip(t.iter())
                    .all(|(a, b)| (a - *b as f64).abs() <= tol)
            })
        })
        .count()
}

#[test]
fn one_window_finds_the_other_eleven_of_a_4_by_3_grid() {
    // 3 floors × 4 columns of windows on a brick-coursed wall, ±8 grey-level noise.
    let s = common::facade(320, 240, 3, 4, 7);
    assert_eq!(s.windows.len(), 12);
    let w0 = s.windows[5].map(|v| v as f64);
    let r = find_repeats(&s.img, &[w0], &RepeatParams::default());
    assert_eq!(r.windows.len(), 12, "{:?}", r.windows);
    // Every window found within 2 px (the brick courses repeat every 8 rows, so a window
    // matches best where the courses line up — the windows do sit on the same phase here).
    assert_eq!(matched(&r.windows, &s.windows, 2.0), 12, "{:?}", r.windows);
    assert_eq!(r.columns.len(), 4, "{:?}", r.columns);
    assert_eq!(r.rows.len(), 3, "{:?}", r.rows);
    // The template itself is kept with score 1, the others below.
    assert!(r.scores.iter().all(|v| (0.6..=1.0).contains(v)));
}

#[test]
fn nothing_repeats_on_a_plain_wall() {
    let s = common::facade(200, 150, 1, 1, 3);
    let w0 = s.windows[0].map(|v| v as f64);
    let r = find_repeats(&s.img, &[w0], &RepeatParams::default());
    assert_eq!(r.windows.len(), 1, "{:?}", r.windows);
    assert_eq!((r.columns.len(), r.rows.len()), (1, 1));
    // A degenerate box is ignored.
    let none = find_repeats(&s.img, &[[5.0, 5.0, 6.0, 6.0]], &RepeatParams::default());
    assert!(none.windows.is_empty());
}
