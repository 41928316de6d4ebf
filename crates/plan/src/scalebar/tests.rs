//! Unit tests of the scale-bar finder on synthetic sheets and the demo's Coucy plan.

use super::*;
use image::Luma;

/// A 300 × 200 sheet: a square "castle" at the top left and whatever `extra` inks.
fn sheet(extra: impl Fn(u32, u32) -> bool) -> GrayImage {
    GrayImage::from_fn(300, 200, |x, y| {
        let castle = (20..=120).contains(&x)
            && (20..=120).contains(&y)
            && !((30..=110).contains(&x) && (30..=110).contains(&y));
        Luma([if castle || extra(x, y) { 0 } else { 255 }])
    })
}

/// A 1-px line on row 170 from x = 150 to 270 with 7-px ticks every 20 px above it.
fn bar(x: u32, y: u32) -> bool {
    let line = (150..=270).contains(&x) && y == 170;
    let tick = (150..=270).contains(&x) && (x - 150).is_multiple_of(20) && (164..=170).contains(&y);
    line || tick
}

#[test]
fn finds_a_ruled_bar_with_ticks_and_its_length() {
    let b = find(&sheet(bar)).unwrap();
    assert_eq!(
        (b.x0, b.y0, b.x1, b.y1, b.length_px),
        (150, 170, 270, 170, 121)
    );
    assert!((b.metres_per_pixel(30.25) - 0.25).abs() < 1e-12);
    assert_eq!(b.describe(), "from (150, 170) to (270, 170), 121 px");
}

#[test]
fn no_bar_no_answer_and_the_castle_is_never_the_bar() {
    assert_eq!(find(&sheet(|_, _| false)), None);
    assert_eq!(find(&GrayImage::from_pixel(50, 40, Luma([255]))), None);
}

#[test]
fn breaks_numerals_and_a_line_running_on_under_a_word_keep_the_bar_whole() {
    let engraved = |x: u32, y: u32| {
        let broken = bar(x, y) && !(203..=207).contains(&x);
        // "25" and "50" above ticks 190 and 250: 5 × 6-px blocks touching nothing.
        let numeral = |c: u32| (c + 2..=c + 6).contains(&x) && (154..=159).contains(&y);
        // The line runs on 7 px past the last tick under a word with 3-px letter stems.
        let run_on = (271..=277).contains(&x) && y == 170;
        let letters = (272..=277).contains(&x) && x.is_multiple_of(2) && (167..=169).contains(&y);
        broken || numeral(190) || numeral(250) || run_on || letters
    };
    let b = find(&sheet(engraved)).unwrap();
    assert_eq!((b.x0, b.x1, b.y0), (150, 270, 170));
}

#[test]
fn a_bar_lettered_above_and_below_is_found() {
    // Armitage's style: "0 100 200 300" close above, "Feet" close below, paper beyond.
    let lettered = |x: u32, y: u32| {
        let along = x.wrapping_sub(150) % 20;
        let numerals = (4..14).contains(&along) && (160..=165).contains(&y);
        let word = (180..=230).contains(&x) && !x.is_multiple_of(3) && (174..=179).contains(&y);
        bar(x, y) || (150..=270).contains(&x) && (numerals || word)
    };
    let b = find(&sheet(lettered)).unwrap();
    assert_eq!((b.x0, b.x1, b.y0), (150, 270, 170));
}

#[test]
fn a_bar_inside_the_moats_bounding_box_is_found() {
    // Coucy's bar sits beside a wall that runs down to the sheet's bottom edge.
    let wall = |x: u32, y: u32| (285..=290).contains(&x) && y >= 100;
    let with_wall =
        |x, y| bar(x, y) || wall(x, y) || (120..=285).contains(&x) && (100..=104).contains(&y);
    let b = find(&sheet(with_wall)).unwrap();
    assert_eq!((b.x0, b.x1), (150, 270));
}

#[test]
fn a_line_without_even_ticks_is_not_a_bar() {
    let plain = |x: u32, y: u32| (150..=270).contains(&x) && y == 170;
    assert_eq!(find(&sheet(plain)), None);
    // Stubs of walls at uneven places along an outline.
    let stubs = |x: u32, y: u32| {
        plain(x, y) || [150, 157, 201, 230, 270].contains(&x) && (164..=170).contains(&y)
    };
    assert_eq!(find(&sheet(stubs)), None);
}

#[test]
fn the_edge_of_hachures_is_not_a_bar() {
    let hachured = |x: u32, y: u32| {
        (150..=270).contains(&x) && (y == 170 || x.is_multiple_of(3) && (160..=170).contains(&y))
    };
    assert_eq!(find(&sheet(hachured)), None);
}

#[test]
fn an_outline_along_a_wall_is_not_a_bar() {
    // A building's edge: ticks where cross walls meet it, the wall 5 px below.
    let outline =
        |x: u32, y: u32| bar(x, y) || (150..=270).contains(&x) && (175..=180).contains(&y);
    assert_eq!(find(&sheet(outline)), None);
}

/// A 1-px vertical line on column 200 from y = 40 to 160 with 7-px ticks every 20 px to its
/// right, and, when `numerals`, a 4 × 5 block 4 px beyond each tick.
fn vertical(numerals: bool) -> impl Fn(u32, u32) -> bool {
    move |x, y| {
        let on = (40..=160).contains(&y);
        let at_tick = on && (y - 40).is_multiple_of(20);
        let line = on && x == 200;
        let tick = at_tick && (200..=206).contains(&x);
        let near_tick = on
            && [0, 20, 40, 60, 80, 100, 120]
                .iter()
                .any(|&t| y.abs_diff(40 + t) <= 2);
        let numeral = numerals && near_tick && (211..=214).contains(&x);
        line || tick || numeral
    }
}

#[test]
fn a_vertical_bar_with_numerals_beside_its_ticks_is_found() {
    let b = find(&sheet(vertical(true))).unwrap();
    assert_eq!(
        (b.x0, b.y0, b.x1, b.y1, b.length_px),
        (200, 40, 200, 160, 121)
    );
}

#[test]
fn a_vertical_ticked_line_without_numerals_is_not_a_bar() {
    // Section lines and walls' outlines with stubs: the horizontal tests alone pass them.
    assert_eq!(find(&sheet(vertical(false))), None);
}

#[test]
fn a_horizontal_bar_wins_over_a_vertical_one() {
    let both = |x, y| bar(x, y) || vertical(true)(x + 60, y);
    let b = find(&sheet(both)).unwrap();
    assert_eq!((b.x0, b.x1, b.y0, b.y1), (150, 270, 170, 170));
}

#[test]
fn a_bar_whose_second_half_is_a_plain_line_runs_to_its_end() {
    // Armitage's 0–1000 ft bars: ticks every 20 px up to x = 210, then a plain line to 270
    // (three units) with no end tick.
    let half_plain = |x: u32, y: u32| {
        let line = (150..=270).contains(&x) && y == 170;
        let tick =
            (150..=210).contains(&x) && (x - 150).is_multiple_of(20) && (164..=170).contains(&y);
        line || tick
    };
    let b = find(&sheet(half_plain)).unwrap();
    assert_eq!((b.x0, b.x1, b.y0), (150, 270, 170));
    // A plain run-on of 1.55 units is not a bar's end: the line runs on like a wall's outline.
    let run_on = |x: u32, y: u32| half_plain(x, y) && x <= 241;
    assert_eq!(find(&sheet(run_on)), None);
}

/// A checkered bar: a 4-px-tall strip from x = 150 to 270 outlined top and bottom, its 20-px
/// boxes filled black from the zero on (four black boxes of six, the last box white).
fn checkered(x: u32, y: u32) -> bool {
    let along = (150..=270).contains(&x);
    let edge = along && (y == 167 || y == 170);
    let filled = along && x < 270 && ((x - 150) / 20).is_multiple_of(2) && (167..=170).contains(&y);
    let ends = (x == 150 || x == 270) && (167..=170).contains(&y);
    edge || filled || ends
}

#[test]
fn a_checkered_bar_is_found_end_to_end() {
    let b = find(&sheet(checkered)).unwrap();
    assert!(b.x0.abs_diff(150) <= 1 && b.x1.abs_diff(270) <= 1, "{b:?}");
    assert!((167..=170).contains(&b.y0), "{b:?}");
}

#[test]
fn a_line_filled_along_one_stretch_is_not_a_checkered_bar() {
    // One long black box and a plain line: read as a checkered bar it has one box, two
    // graduations, and no unit.
    let half_filled = |x: u32, y: u32| {
        (150..=270).contains(&x) && y == 167 || (150..=219).contains(&x) && (167..=170).contains(&y)
    };
    assert_eq!(find(&sheet(half_filled)), None);
}

/// Issue 11: the Coucy plan shipped with the demo (Viollet-le-Duc, tome 3, fig. 16) has a
/// 50-m bar whose ticks were read by hand at x = 160 and 317 on row 580.
#[test]
fn issue_11_coucy_scale_bar_is_found_on_the_real_drawing() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/coucy/plan.png");
    let grey = image::open(path).unwrap().to_luma8();
    let b = find(&grey).unwrap();
    assert!(
        (159..=162).contains(&b.x0) && (316..=318).contains(&b.x1),
        "{b:?}"
    );
    assert!((578..=582).contains(&b.y0), "{b:?}");
    assert!(
        (b.metres_per_pixel(50.0) - 0.32).abs() < 0.01,
        "{}",
        b.metres_per_pixel(50.0)
    );
}
