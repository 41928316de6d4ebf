//! The user's corrections (issue 22) honoured by the search, on a generated façade whose
//! classes are known exactly: 4 floors of 40 rows, in each a window row 20 high ending 10 above
//! the floor's bottom, in 4 columns 20 wide at x = 20, 60, 100, 140.

use image::{Rgb, RgbImage};

use super::{Grammar, SearchParams, parse_with};
use crate::classify::{Class, LogLikelihoods};
use crate::error::FacadeError;
use crate::fixes::FacadeFixes;
use crate::model::FacadeModel;

const W: u32 = 180;
const H: u32 = 160;

fn is_window(x: u32, y: u32) -> bool {
    (20..160).contains(&x) && (x - 20) % 40 < 20 && (10..30).contains(&(y % 40))
}

/// The façade's picture and its exact class log-likelihoods (no background: the whole image
/// is the façade).
fn facade() -> (RgbImage, LogLikelihoods) {
    let img = RgbImage::from_fn(W, H, |x, y| {
        if is_window(x, y) {
            Rgb([30, 40, 60])
        } else {
            Rgb([190, 140, 100])
        }
    });
    let map = |class: Class| -> Vec<f32> {
        (0..H)
            .flat_map(|y| (0..W).map(move |x| (x, y)))
            .map(|(x, y)| {
                let here = if is_window(x, y) {
                    Class::Window
                } else {
                    Class::Wall
                };
                if here == class { 0.0 } else { -4.0 }
            })
            .collect()
    };
    let ll = LogLikelihoods {
        width: W as usize,
        height: H as usize,
        maps: [None, Some(map(Class::Wall)), Some(map(Class::Window))],
    };
    (img, ll)
}

fn parse(fixes: &FacadeFixes) -> FacadeModel {
    let (img, ll) = facade();
    parse_with(&img, &ll, &SearchParams::default(), fixes).unwrap()
}

/// (y0, y1) of each floor, top to bottom.
fn floors(m: &FacadeModel) -> Vec<(f64, f64)> {
    m.facades[0].floors.iter().map(|f| (f.y0, f.y1)).collect()
}

fn windows_per_floor(m: &FacadeModel) -> Vec<usize> {
    m.facades[0]
        .floors
        .iter()
        .map(|f| f.windows.len())
        .collect()
}

fn lines(ys: &[f64]) -> FacadeFixes {
    FacadeFixes {
        floor_lines: Some(ys.to_vec()),
        ..Default::default()
    }
}

#[test]
fn without_fixes_every_window_is_found() {
    let m = parse(&FacadeFixes::default());
    assert_eq!(m.facades.len(), 1);
    assert_eq!(windows_per_floor(&m).iter().sum::<usize>(), 16);
}

#[test]
fn fixed_floor_lines_are_the_floors_and_a_moved_line_moves_exactly_there() {
    let m = parse(&lines(&[40.0, 80.0, 120.0]));
    assert_eq!(
        floors(&m),
        vec![(0.0, 40.0), (40.0, 80.0), (80.0, 120.0), (120.0, 160.0)]
    );
    assert_eq!(windows_per_floor(&m), vec![4, 4, 4, 4]);
    assert_eq!(m.facades[0].params.n_l, 4);
    // The line between the second and third floor dragged 7 rows down: the floors follow it,
    // the window rows stay where the windows are.
    let moved = parse(&lines(&[40.0, 87.0, 120.0]));
    assert_eq!(
        floors(&moved),
        vec![(0.0, 40.0), (40.0, 87.0), (87.0, 120.0), (120.0, 160.0)]
    );
    assert_eq!(windows_per_floor(&moved), vec![4, 4, 4, 4]);
    let rows: Vec<(f64, f64)> = moved.facades[0]
        .floors
        .iter()
        .map(|f| (f.windows[0][1], f.windows[0][3]))
        .collect();
    assert_eq!(
        rows,
        vec![(10.0, 30.0), (50.0, 70.0), (90.0, 110.0), (130.0, 150.0)]
    );
    // Two lines only: three floors, whatever the search would have made of the picture.
    let three = parse(&lines(&[40.0, 120.0]));
    assert_eq!(
        floors(&three),
        vec![(0.0, 40.0), (40.0, 120.0), (120.0, 160.0)]
    );
    assert_eq!(three.facades[0].params.n_l, 3);
}

#[test]
fn the_text_grammar_honours_fixed_floor_lines_too() {
    let (img, ll) = facade();
    let p = SearchParams {
        grammar: Grammar::Text,
        ..SearchParams::default()
    };
    let m = parse_with(&img, &ll, &p, &lines(&[40.0, 80.0, 120.0])).unwrap();
    assert_eq!(
        floors(&m),
        vec![(0.0, 40.0), (40.0, 80.0), (80.0, 120.0), (120.0, 160.0)]
    );
}

#[test]
fn a_blind_floor_has_no_windows() {
    let mut fixes = lines(&[40.0, 80.0, 120.0]);
    fixes.blind_floors = vec![1];
    let m = parse(&fixes);
    assert_eq!(windows_per_floor(&m), vec![4, 4, 4, 0]);
    // A middle floor (the third from the ground) and the top floor.
    fixes.blind_floors = vec![3, 4];
    assert_eq!(windows_per_floor(&parse(&fixes)), vec![0, 0, 4, 4]);
    // Without floor lines the search keeps the ground floor blind, and the windows above.
    let free = parse(&FacadeFixes {
        blind_floors: vec![1],
        ..Default::default()
    });
    let per_floor = windows_per_floor(&free);
    assert_eq!(per_floor.last(), Some(&0), "{per_floor:?}");
    assert!(per_floor.len() >= 2, "{per_floor:?}");
    assert!(
        per_floor.iter().sum::<usize>() >= 8,
        "the windows above the ground floor stay: {per_floor:?}"
    );
}

#[test]
fn a_removed_window_is_gone_and_an_added_one_is_there() {
    let base = lines(&[40.0, 80.0, 120.0]);
    let removed = parse(&FacadeFixes {
        remove_windows: vec![[70.0, 60.0]],
        ..base.clone()
    });
    assert_eq!(windows_per_floor(&removed), vec![4, 3, 4, 4]);
    assert!(
        removed
            .facades
            .iter()
            .flat_map(|f| &f.floors)
            .flat_map(|f| &f.windows)
            .all(|w| !(w[0] <= 70.0 && 70.0 <= w[2] && w[1] <= 60.0 && 60.0 <= w[3]))
    );
    // The labels follow: the removed window's pixels are wall.
    let labels = removed.labels();
    assert_eq!(labels[60 * W as usize + 70], Class::Wall as u8);
    let added = parse(&FacadeFixes {
        add_windows: vec![[162.0, 90.0, 175.0, 115.0]],
        ..base
    });
    assert_eq!(windows_per_floor(&added), vec![4, 4, 5, 4]);
    assert!(
        added.facades[0].floors[2]
            .windows
            .contains(&[162.0, 90.0, 175.0, 115.0])
    );
}

#[test]
fn fixed_columns_are_every_floors_columns() {
    let m = parse(&FacadeFixes {
        columns: Some(vec![[18.0, 42.0], [60.0, 80.0]]),
        ..lines(&[40.0, 80.0, 120.0])
    });
    assert_eq!(windows_per_floor(&m), vec![2, 2, 2, 2]);
    for f in &m.facades[0].floors {
        let xs: Vec<(f64, f64)> = f.windows.iter().map(|w| (w[0], w[2])).collect();
        assert_eq!(xs, vec![(18.0, 42.0), (60.0, 80.0)]);
    }
    assert_eq!(m.facades[0].params.n_w, 2);
}

#[test]
fn bad_fixes_are_refused_by_name() {
    let (img, ll) = facade();
    let e = parse_with(&img, &ll, &SearchParams::default(), &lines(&[40.0, 1200.0])).unwrap_err();
    assert!(matches!(e, FacadeError::BadFixes(_)));
    assert_eq!(
        e.to_string(),
        "bad façade corrections: floor line 1200 is below the façade (rectified height 160)"
    );
}
