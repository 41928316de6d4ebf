//! Bad input: blank pages, empty and huge images, drawings without a closed outer wall,
//! photos instead of drawings, small drawings. A clear error or a partial result that says
//! what it could not find; never a panic.

use image::{DynamicImage, GrayImage, Luma};
use plan::label::Label;
use plan::{Options, PlanError, parse};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

#[test]
fn blank_page_is_an_error_saying_no_walls() {
    let img = DynamicImage::ImageLuma8(GrayImage::from_pixel(300, 200, Luma([250])));
    let e = parse(&img, &Options::default()).unwrap_err();
    assert!(matches!(e, PlanError::NoLearnedWalls), "{e}");
    assert!(e.to_string().contains("no walls"));
    let rules = Options {
        ink: plan::ink::InkMethod::Rules,
        ..Default::default()
    };
    let e = parse(&img, &rules).unwrap_err();
    assert!(matches!(e, PlanError::NoWalls(_)), "{e}");
    assert!(e.to_string().contains("no walls"));
}

#[test]
fn empty_and_huge_images_are_refused_before_work() {
    let empty = DynamicImage::ImageLuma8(GrayImage::new(0, 5));
    assert!(matches!(
        parse(&empty, &Options::default()),
        Err(PlanError::Empty(0, 5))
    ));
    let opts = Options {
        max_pixels: 10_000,
        ..Default::default()
    };
    let big = DynamicImage::ImageLuma8(GrayImage::new(200, 100));
    let e = parse(&big, &opts).unwrap_err();
    assert!(e.to_string().contains("too large"), "{e}");
}

#[test]
fn open_enclosure_is_a_partial_result_with_a_warning() {
    // A U of thick walls: no closed outer wall.
    let mut c = plan::synth::Canvas::new(300, 300);
    c.wall((60.0, 60.0), (60.0, 240.0), 10.0);
    c.wall((60.0, 240.0), (240.0, 240.0), 10.0);
    c.wall((240.0, 240.0), (240.0, 60.0), 10.0);
    let p = parse(&DynamicImage::ImageLuma8(c.0), &Options::default()).unwrap();
    assert!(
        p.warnings
            .iter()
            .any(|w| w.contains("no closed outer wall")),
        "{:?}",
        p.warnings
    );
    assert!(p.faces.iter().all(|f| f.label != Label::Courtyard));
    assert_eq!(p.label_at(150, 150), Label::CastleSurroundings);
    assert!(Label::ALL[p.labels[240 * 300 + 150] as usize].is_wall());
}

#[test]
fn photo_like_noise_does_not_panic() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    // Smooth random texture: a coarse random grid, enlarged.
    let coarse = GrayImage::from_fn(40, 30, |_, _| Luma([rng.random_range(0..=255u8)]));
    let photo = image::imageops::resize(&coarse, 200, 150, image::imageops::FilterType::Triangle);
    match parse(&DynamicImage::ImageLuma8(photo), &Options::default()) {
        Ok(p) => assert_eq!(p.labels.len(), 200 * 150),
        Err(e) => assert!(!e.to_string().is_empty()),
    }
}

#[test]
fn small_drawing_with_thin_walls_is_enlarged_and_parsed() {
    // The synthetic castle at 40 % (4-px curtain walls, 360 px wide), enlarged ×2 inside. The
    // rule chain's test: the learned wall ink, which reads the drawing at its own resolution,
    // finds 3 of the 6 towers here (docs/plan.md, "Learned wall ink", known gaps).
    let (img, truth) = plan::synth::castle(2, 0.4, 360, 280);
    let img = DynamicImage::ImageLuma8(img);
    let rules = Options {
        ink: plan::ink::InkMethod::Rules,
        ..Default::default()
    };
    let p = parse(&img, &rules).unwrap();
    assert_eq!(p.towers, 6, "{:?}", p.warnings);
    let right = truth
        .iter()
        .filter(|(xy, l)| p.label_at(xy.0, xy.1) == *l)
        .count();
    assert!(right + 3 >= truth.len(), "{right} of {}", truth.len());
}

#[test]
fn a_users_stroke_off_the_drawing_is_an_error_naming_it() {
    let (img, _) = plan::synth::castle(2, 0.4, 360, 280);
    let opts = Options {
        ink_strokes: vec![plan::ink::refine::InkStroke {
            wall: true,
            radius: 2.0,
            points: vec![[10.0, 10.0], [400.0, 10.0]],
        }],
        ..Default::default()
    };
    let e = parse(&DynamicImage::ImageLuma8(img), &opts).unwrap_err();
    assert!(matches!(e, PlanError::Strokes(_)), "{e}");
    assert!(e.to_string().contains("ink stroke 0"), "{e}");
}
