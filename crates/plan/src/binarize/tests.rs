//! Tests of §5.1.2's steps and the clean-up before them ([`super`]).

use super::*;
use image::Luma;
use raster::morphology::complement;

fn grey_from(rows: &[&str]) -> GrayImage {
    let h = rows.len() as u32;
    let w = rows[0].len() as u32;
    GrayImage::from_fn(w, h, |x, y| {
        Luma([if rows[y as usize].as_bytes()[x as usize] == b'#' {
            10
        } else {
            240
        }])
    })
}

#[test]
fn threshold_separates_ink_from_paper() {
    let g = grey_from(&["##..", "##.."]);
    let b = binarize(&g, threshold_level(&g));
    assert_eq!(b.get_pixel(0, 0)[0], 255);
    assert_eq!(b.get_pixel(3, 1)[0], 0);
}

#[test]
fn thin_lines_and_specks_go_thick_walls_stay() {
    // A 6-px thick wall, a 1-px line and a speck.
    let mut rows = vec![String::from("..............................."); 20];
    for r in rows.iter_mut().take(10).skip(4) {
        r.replace_range(2..28, &"#".repeat(26));
    }
    rows[15].replace_range(2..28, &"#".repeat(26));
    rows[18].replace_range(29..30, "#");
    let refs: Vec<&str> = rows.iter().map(|s| s.as_str()).collect();
    let (img, stats) = preprocess(&grey_from(&refs), 0.0005);
    assert_eq!(img.get_pixel(10, 6)[0], 255);
    assert_eq!(img.get_pixel(10, 15)[0], 0);
    assert_eq!(img.get_pixel(29, 18)[0], 0);
    assert_eq!(stats.wall_pixels, 26 * 6);
}

#[test]
fn a_door_narrower_than_the_wall_closes_a_wider_passage_stays() {
    // A 6-px wall with a 4-px door and a 14-px passage.
    let mut rows = vec![String::from("........................................"); 12];
    for r in rows.iter_mut().skip(3).take(6) {
        r.replace_range(0..40, &"#".repeat(40));
        r.replace_range(10..14, "....");
        r.replace_range(22..36, &".".repeat(14));
    }
    let refs: Vec<&str> = rows.iter().map(|s| s.as_str()).collect();
    let mut img = binarize(&grey_from(&refs), 128);
    let t = wall_thickness(&img);
    assert!((4.0..=8.0).contains(&t), "{t}");
    let added = close_gaps(&mut img, (t / 2.0).ceil() as u8);
    assert_eq!(img.get_pixel(12, 5)[0], 255);
    assert_eq!(img.get_pixel(29, 5)[0], 0);
    assert!(added >= 4 * 6);
}

#[test]
fn letters_and_arrows_go_the_castle_and_a_free_standing_tower_stay() {
    // The castle (a ring), a free-standing ring tower, a solid "letter" and an "arrow".
    let rows = [
        "....................",
        ".#######.......###..",
        ".#.....#.......#.#..",
        ".#.....#.......###..",
        ".#.....#............",
        ".#######....#.......",
        "...........###......",
        "..##........#.......",
        "..##........#.......",
        "....................",
    ];
    let mut img = binarize(&grey_from(&rows), 128);
    assert_eq!(drop_marks(&mut img, false), 2);
    assert_eq!(img.get_pixel(1, 1)[0], 255);
    assert_eq!(img.get_pixel(16, 1)[0], 255);
    assert_eq!(img.get_pixel(2, 7)[0], 0);
    assert_eq!(img.get_pixel(12, 6)[0], 0);
}

#[test]
fn pieces_of_a_cut_wall_stay_with_the_learned_ink_letters_go() {
    // A 240 × 500 sheet: the castle, a ring with an 8-px wall; the two pieces of an 8-px
    // wall cut by a window, each 236 px long, without a hole; a 2-px line as long as both
    // (thinner than half the walls); a 16 × 36 blob (shorter than 8 squares of the walls).
    let sheet = GrayImage::from_fn(240, 500, |x, y| {
        let ring = (4..84).contains(&x) && (4..84).contains(&y);
        let hole = (12..76).contains(&x) && (12..76).contains(&y);
        let piece = (100..108).contains(&x) && ((4..240).contains(&y) || (260..496).contains(&y));
        let line = (150..152).contains(&x) && (4..496).contains(&y);
        let blob = (200..216).contains(&x) && (4..40).contains(&y);
        Luma([if (ring && !hole) || piece || line || blob {
            255
        } else {
            0
        }])
    });
    let mut learned = sheet.clone();
    assert_eq!(drop_marks(&mut learned, true), 2);
    assert_eq!(learned.get_pixel(104, 100)[0], 255);
    assert_eq!(learned.get_pixel(104, 300)[0], 255);
    assert_eq!(learned.get_pixel(150, 100)[0], 0);
    assert_eq!(learned.get_pixel(205, 20)[0], 0);
    let mut rules = sheet;
    assert_eq!(drop_marks(&mut rules, false), 4);
    assert_eq!(rules.get_pixel(104, 100)[0], 0);
    assert_eq!(rules.get_pixel(6, 6)[0], 255);
}

/// A 480 × 480 sheet: a round room (ring of radius 40, 10-px wall) with a 3-px cross of
/// ribs at (240, 240) when `round`, else an 80 × 48 rectangular room split there by a 3-px
/// partition.
fn ribbed(round: bool) -> GrayImage {
    GrayImage::from_fn(480, 480, |x, y| {
        let (fx, fy) = (x as f64 - 240.0, y as f64 - 240.0);
        let ink = if round {
            let d = fx.hypot(fy);
            (30.0..=40.0).contains(&d) || (d < 30.0 && (fx.abs() <= 1.0 || fy.abs() <= 1.0))
        } else {
            let outer = fx.abs() <= 48.0 && fy.abs() <= 34.0;
            let inner = fx.abs() < 40.0 && fy.abs() < 24.0;
            (outer && !inner) || (inner && fx.abs() <= 1.0)
        };
        Luma([if ink { 255 } else { 0 }])
    })
}

#[test]
fn ribs_across_a_round_room_go_a_partition_of_a_rectangle_stays() {
    let mut room = ribbed(true);
    assert!(drop_thin_lines(&mut room, 2, 1, 50.0) > 0);
    assert_eq!(room.get_pixel(240, 255)[0], 0, "a rib");
    assert_eq!(room.get_pixel(225, 240)[0], 0, "a rib");
    assert_eq!(room.get_pixel(240, 205)[0], 255, "the ring");
    let mut rooms = ribbed(false);
    assert_eq!(drop_thin_lines(&mut rooms, 2, 1, 50.0), 0);
    assert_eq!(rooms.get_pixel(240, 240)[0], 255, "the partition");
}

#[test]
fn without_dash_linking_a_dashed_line_is_removed_as_specks() {
    // The sheet of `dashes`' tests (a dashed line along rows 20–21), drawn as ink on paper.
    let sheet = crate::dashes::tests::sheet();
    let (clean, _) = preprocess(&complement(&sheet), 0.005);
    assert_eq!(clean.get_pixel(40, 21)[0], 0);
    let mut linked = sheet;
    crate::dashes::link_dashes(&mut linked, 200, 20.0, 4.0, 3.0);
    let (clean, _) = preprocess(&complement(&linked), 0.005);
    assert_eq!(clean.get_pixel(40, 21)[0], 255);
}

#[test]
fn the_forest_ink_keeps_a_small_tower_room_open_and_fills_a_pinhole() {
    // A 1000 × 1000 learned mask: a square enceinte with a 12-px wall, a solid drum of
    // radius 30 on its west wall with a round room of radius 8 (about 200 px: under
    // 0.05 % of the sheet, 500 px, but over half a wall's square), and a 2 × 2 pinhole
    // in the north wall.
    let mask = GrayImage::from_fn(1000, 1000, |x, y| {
        let (x, y) = (x as i32, y as i32);
        let ring = (100..900).contains(&x) && (100..900).contains(&y);
        let court = (112..888).contains(&x) && (112..888).contains(&y);
        let d2 = (x - 106).pow(2) + (y - 500).pow(2);
        let pinhole = (500..502).contains(&x) && (105..107).contains(&y);
        let wall = ((ring && !court) || d2 <= 30 * 30) && d2 > 8 * 8 && !pinhole;
        Luma([if wall { 255 } else { 0 }])
    });
    let t = wall_thickness(&mask);
    let room = (0..1000 * 1000i32)
        .filter(|i| (i % 1000 - 106).pow(2) + (i / 1000 - 500).pow(2) <= 64)
        .count() as f64;
    assert!(
        LEARNED_PAPER_SPECK * t * t < room && room < 500.0,
        "{t} {room}"
    );
    let (kept, stats) = preprocess_learned(mask.clone(), 0.0005, false, true);
    assert_eq!(
        kept.get_pixel(106, 500)[0],
        0,
        "the tower's room stays open"
    );
    assert_eq!(kept.get_pixel(500, 105)[0], 255, "the pinhole is filled");
    assert_eq!(stats.filled_white, 1, "regions filled");
    let (text, stats) = preprocess_learned(mask, 0.0005, false, false);
    assert_eq!(
        text.get_pixel(106, 500)[0],
        255,
        "§5.1.2 (2) fills the room"
    );
    assert_eq!(stats.filled_white, 2);
}

#[test]
fn small_holes_are_filled() {
    let mut rows = vec![String::from("##########"); 10];
    rows[5].replace_range(5..6, ".");
    let refs: Vec<&str> = rows.iter().map(|s| s.as_str()).collect();
    // Region threshold 2 % of 100 px = 2 px: the 1-px hole is filled.
    let (img, stats) = preprocess(&grey_from(&refs), 0.02);
    assert_eq!(img.get_pixel(5, 5)[0], 255);
    assert_eq!(stats.filled_white, 1);
}
