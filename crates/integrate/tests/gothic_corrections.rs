//! Issue 22's Gothic corrections through the whole pipeline: a project with the synthetic
//! castle's plan and a synthetic Gothic photo on the keep's north wall, whose PROJECT.toml
//! deletes one window and moves another's apex (`[[gothic.element]]`). The estimate follows,
//! estimate.json names the corrections with source "user", and a correction that cannot be
//! applied is an error naming its entry.

use std::collections::BTreeMap;

use facade::gothic::Theta;
use facade::gothic::synth::{SynthSpec, Synthetic, synthetic_facade};
use integrate::estimate::Source;
use integrate::pipeline::{self, InMemory};
use integrate::project::Project;
use integrate::synth::Castle;

fn png(img: impl Into<image::DynamicImage>) -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    img.into()
        .write_to(&mut out, image::ImageFormat::Png)
        .unwrap();
    out.into_inner()
}

/// The castle's plan and a Gothic photo of its keep's north wall; `elements` is the text of
/// the `[[gothic.element]]` tables.
fn project(elements: &str) -> (Project, InMemory, Synthetic) {
    let castle = Castle::default();
    let synth = synthetic_facade(&SynthSpec::small(), 1);
    let (w, h) = synth.image.dimensions();
    let north = [
        castle.keep_center[0],
        castle.keep_center[1] - castle.keep_size[1] / 2.0 + 12.0,
    ];
    let text = format!(
        "plan = \"plan.png\"\nscale = {}\n\n[[gothic]]\nimage = \"gothic.png\"\nrectified = true\n\
         {elements}\n[[correspondence]]\nfacade = \"gothic.png\"\nfacade_point = [{}, {}]\n\
         plan_points = [[{}, {}]]\n",
        castle.metres_per_pixel,
        w / 2,
        h / 2,
        north[0],
        north[1]
    );
    let project = Project::from_toml(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let files = InMemory(BTreeMap::from([
        ("plan.png".to_string(), png(castle.plan())),
        ("gothic.png".to_string(), png(synth.image.clone())),
    ]));
    (project, files, synth)
}

fn centre(t: &Theta) -> [f64; 2] {
    [t.x0 + t.w / 2.0, t.y0 - t.h / 2.0]
}

/// The element of `shapes` within 3 px of a true one (corners and apex).
fn matching(shapes: &[Theta], t: &Theta) -> Option<usize> {
    shapes.iter().position(|a| {
        [a.x0 - t.x0, a.y0 - t.y0, a.w - t.w, a.apex() - t.apex()]
            .iter()
            .all(|d| d.abs() <= 3.0)
    })
}

#[test]
fn a_project_with_gothic_corrections_reconstructs_with_them() {
    let truth = synthetic_facade(&SynthSpec::small(), 1).elements;
    let (deleted, moved) = (truth[1].theta, truth[4].theta);
    let apex = moved.apex() + 6.5;
    let [dx, dy] = centre(&deleted);
    let [mx, my] = centre(&moved);
    let elements = format!(
        "[[gothic.element]]\npoint = [{dx}, {dy}]\ndelete = true\n\n\
         [[gothic.element]]\npoint = [{mx}, {my}]\napex = {apex}\n"
    );
    let (plain, plain_files, synth) = project("");
    let (corrected, files, _) = project(&elements);
    assert_eq!(corrected.gothics[0].elements.len(), 2);

    let (before, _) = pipeline::estimate_gothic_photo(&plain, 0, &plain_files).unwrap();
    let (after, _) = pipeline::estimate_gothic_photo(&corrected, 0, &files).unwrap();
    let shapes = |e: &integrate::gothic::GothicFacadeEstimate| -> Vec<Theta> {
        e.estimate.elements.iter().map(|e| e.theta()).collect()
    };
    assert_eq!(before.estimate.elements.len(), synth.elements.len());
    assert_eq!(
        after.estimate.elements.len(),
        before.estimate.elements.len() - 1
    );
    assert!(matching(&shapes(&before), &deleted).is_some());
    assert_eq!(matching(&shapes(&after), &deleted), None);
    let id = after.applied[1].element.expect("the moved window");
    assert!((after.estimate.elements[id].theta().apex() - apex).abs() <= 0.5);
    assert!(
        after.estimate.elements[id].parent.is_some(),
        "still in its arch"
    );

    // The whole reconstruction: the keep's Gothic façade holds one element less, its program
    // has one element less, and estimate.json says who set what.
    let r =
        pipeline::reconstruct(&corrected, &files, &pipeline::Options::default(), &|_| {}).unwrap();
    let gothic_facade = r
        .estimate
        .structures
        .iter()
        .flat_map(|s| s.facades.iter().map(move |f| (s, f)))
        .find(|(_, f)| f.gothic.is_some())
        .expect("the Gothic façade is mapped");
    let (structure, f) = gothic_facade;
    let g = f.gothic.as_ref().unwrap();
    assert_eq!(g.elements, after.estimate.elements.len());
    let program = &r
        .gothic_programs
        .iter()
        .find(|(name, _)| *name == g.program)
        .unwrap()
        .1;
    let declared = program.lines().filter(|l| l.starts_with("float e")).count();
    assert_eq!(declared, after.estimate.elements.len());
    let user: Vec<(&String, &String)> = structure
        .provenance
        .iter()
        .filter(|(_, p)| p.source() == Source::User)
        .map(|(k, p)| (k, &p.step))
        .collect();
    assert_eq!(user.len(), 2, "{user:?}");
    let deleted_key = "gothic.gothic.png.deleted.1".to_string();
    let moved_key = format!("gothic.gothic.png.element.{id}");
    assert!(user.iter().any(|(k, step)| **k == deleted_key
        && step.as_str() == "[[gothic]] #1 element #1 (image = \"gothic.png\")"));
    assert!(user.iter().any(|(k, step)| **k == moved_key
        && step.as_str() == "[[gothic]] #1 element #2 (image = \"gothic.png\")"));
}

#[test]
fn a_correction_that_cannot_apply_names_its_entry() {
    let window = synthetic_facade(&SynthSpec::small(), 1).elements[1].theta;
    let [x, y] = centre(&window);
    let (p, files, _) = project(&format!(
        "[[gothic.element]]\npoint = [{x}, {y}]\ndelete = true\n\n\
         [[gothic.element]]\npoint = [900, 20]\ndelete = true\n"
    ));
    let e = pipeline::estimate_gothic_photo(&p, 0, &files)
        .err()
        .expect("refused")
        .to_string();
    assert!(
        e.starts_with("[[gothic]] #1 element #2 (image = \"gothic.png\"): point [900, 20]"),
        "{e}"
    );
    // Values wrong on their own are refused when PROJECT.toml is read.
    let text = "plan = \"p.png\"\n[[gothic]]\nimage = \"g.png\"\n[[gothic.element]]\n\
                point = [1, 2]\nwidth = 0\n[[correspondence]]\nfacade = \"g.png\"\n\
                facade_point = [1, 1]\nplan_points = [[1, 1]]\n";
    let e = Project::from_toml(text).unwrap_err().to_string();
    assert_eq!(
        e,
        "[[gothic]] #1 element #1 (image = \"g.png\"): width = 0: must be more than 0 px"
    );
    let text = text.replace("width = 0", "springing = 50\napex = 60");
    let e = Project::from_toml(&text).unwrap_err().to_string();
    assert!(
        e.contains("apex = 60 is below the springing line (50)"),
        "{e}"
    );
}

/// Issue 23: what the learned check drops reaches estimate.json and the overlay's caption. The
/// bundled Coucy elevation (an engraving) as the keep's Gothic photo: the fit finds one
/// element, an arch over the roof's finial, and the check drops it (as
/// `facade/tests/gothic_corrections.rs` finds on the image alone).
#[test]
fn what_the_learned_check_drops_is_counted_in_the_estimate() {
    let (mut p, mut files, _) = project("");
    let elevation = std::fs::read(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/coucy/tower_elevation.png"),
    )
    .unwrap();
    files.0.insert("gothic.png".to_string(), elevation);
    p.correspondences[0].facade_point = [116.0, 330.0];
    let (gothic, overlays) = pipeline::estimate_gothic_photo(&p, 0, &files).unwrap();
    assert_eq!((gothic.estimate.elements.len(), gothic.dropped), (0, 1));
    let caption = overlays
        .iter()
        .find(|o| o.name.ends_with("_gothic.png"))
        .and_then(|o| o.caption.clone())
        .unwrap();
    assert!(
        caption.contains("the learned check dropped 1 element(s)"),
        "{caption}"
    );
    let r = pipeline::reconstruct(&p, &files, &pipeline::Options::default(), &|_| {}).unwrap();
    let g = r
        .estimate
        .structures
        .iter()
        .flat_map(|s| s.facades.iter())
        .find_map(|f| f.gothic.as_ref())
        .expect("the Gothic façade is mapped");
    assert_eq!((g.elements, g.dropped), (0, 1));
    let json = serde_json::to_value(g).unwrap();
    assert_eq!(json["dropped"], 1);
}
