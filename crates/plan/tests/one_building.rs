//! One building on the sheet (`Options::one_building`): a survey whose walls windows and doors
//! cut into pieces farther apart than the castle's usual reach (3 % of the sheet) keeps every
//! piece within six wall thicknesses, and a figure farther away still goes.

use image::{DynamicImage, GrayImage, Luma};

/// 1000 × 700 sheet. A: a building (100..=499) × (100..=599) with 12-px walls, each wall cut
/// by one 48-px opening (4.8 % of the sheet, four thicknesses), so its outline is four
/// pieces. B: a smaller square outline (640..=719) × (200..=279), 140 px from A.
fn in_a(x: u32, y: u32) -> bool {
    let outline = (100..=499).contains(&x)
        && (100..=599).contains(&y)
        && !((112..=487).contains(&x) && (112..=587).contains(&y));
    let opening = ((250..298).contains(&x) && y < 112)
        || ((300..348).contains(&x) && y > 587)
        || ((300..348).contains(&y) && x < 112)
        || ((250..298).contains(&y) && x > 487);
    outline && !opening
}

fn in_b(x: u32, y: u32) -> bool {
    (640..=719).contains(&x)
        && (200..=279).contains(&y)
        && !((652..=707).contains(&x) && (212..=267).contains(&y))
}

fn sheet() -> GrayImage {
    GrayImage::from_fn(1000, 700, |x, y| {
        Luma([if in_a(x, y) || in_b(x, y) { 0 } else { 255 }])
    })
}

/// The shares of A's and of B's drawn pixels that the parse keeps as wall.
fn kept(one_building: bool) -> (f64, f64) {
    let opts = plan::Options {
        one_building,
        ..Default::default()
    };
    let p = plan::parse(&DynamicImage::ImageLuma8(sheet()), &opts).unwrap();
    let (mut a, mut a_kept, mut b, mut b_kept) = (0, 0, 0, 0);
    for y in 0..700 {
        for x in 0..1000 {
            let wall = p.walls.get(x as i32, y as i32) != 0;
            if in_a(x, y) {
                a += 1;
                a_kept += usize::from(wall);
            } else if in_b(x, y) {
                b += 1;
                b_kept += usize::from(wall);
            }
        }
    }
    (a_kept as f64 / a as f64, b_kept as f64 / b as f64)
}

#[test]
fn one_building_keeps_the_walls_that_openings_cut_and_not_the_figure_beside_it() {
    // By default the largest piece is the castle and the others, 48 px away, go.
    let (a, b) = kept(false);
    assert!(a < 0.4, "by default {a:.3} of the building's walls kept");
    assert_eq!(b, 0.0);
    // As one building every piece stays; the figure 140 px away (about 12 thicknesses) goes.
    let (a, b) = kept(true);
    assert!(a > 0.95, "as one building {a:.3} of its walls kept");
    assert_eq!(b, 0.0);
}
