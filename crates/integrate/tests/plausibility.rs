//! Issue 22: the pipeline's plausibility warnings on generated projects — none on the bundled
//! synthetic castle, each on an input made to trip it — and the run still succeeds.

use std::collections::BTreeMap;

use integrate::pipeline::{self, InMemory};
use integrate::plausibility::Warning;
use integrate::project::Project;

mod common;

/// The warnings of reconstructing the project `toml` from `files`, held in memory.
fn run(toml: &str, files: BTreeMap<String, Vec<u8>>) -> Vec<Warning> {
    let project = Project::from_toml(toml).unwrap();
    pipeline::reconstruct(&project, &InMemory(files), &Default::default(), &|_| {})
        .unwrap()
        .warnings
}

fn png(image: &image::GrayImage) -> Vec<u8> {
    pipeline::encode_png(image).unwrap()
}

#[test]
fn the_synthetic_demo_raises_no_warning() {
    let files = common::example_files("demo");
    let toml = String::from_utf8(files["PROJECT.toml"].clone()).unwrap();
    assert_eq!(run(&toml, files), vec![]);
}

/// A drawing whose ink makes no wall graph (as Rochester's did): one black disc. A blank page
/// is an error of the parser already.
#[test]
fn a_drawing_without_a_wall_graph_warns_that_no_walls_were_read() {
    let disc = image::GrayImage::from_fn(300, 200, |x, y| {
        let (dx, dy) = (x as f64 - 150.0, y as f64 - 100.0);
        image::Luma([if dx * dx + dy * dy < 900.0 { 0 } else { 255 }])
    });
    let mut files = BTreeMap::new();
    files.insert("disc.png".to_string(), png(&disc));
    let w = run("plan = \"disc.png\"\n", files);
    assert_eq!(
        w,
        vec![Warning::NoWalls {
            plan: "disc.png".into()
        }]
    );
    assert!(
        w[0].to_string()
            .starts_with("no walls were read from disc.png")
    );
}

#[test]
fn a_scale_that_makes_the_demo_castle_a_toy_warns() {
    // The synthetic plan at 1 mm a pixel instead of 0.1 m: well under a metre across.
    let files = common::example_files("demo");
    let plan_only = "plan = \"plan.png\"\nscale = 0.001\n";
    let w = run(plan_only, files);
    assert!(
        matches!(&w[..], [Warning::ImplausibleSize { metres_across, .. }] if *metres_across < 1.0),
        "{w:?}"
    );
    assert!(w[0].to_string().contains("check scale (metres per pixel"));
}

#[test]
fn a_scale_bar_missing_from_the_drawing_warns_and_the_model_is_in_pixels() {
    let files = common::example_files("demo");
    let project = Project::from_toml("plan = \"plan.png\"\nscale_bar = 30\n").unwrap();
    let r =
        pipeline::reconstruct(&project, &InMemory(files), &Default::default(), &|_| {}).unwrap();
    assert_eq!(
        r.warnings,
        vec![Warning::ScaleBarNotFound {
            plan: "plan.png".into(),
            metres: 30.0
        }]
    );
    assert_eq!(r.estimate.scale.units, plan::scale::Units::Pixels);
    assert_eq!(
        r.estimate.assumptions.len(),
        1,
        "{:?}",
        r.estimate.assumptions
    );
}
