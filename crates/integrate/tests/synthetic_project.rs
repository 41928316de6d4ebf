//! Issue 9's integration check: a synthetic plan with a keep and two round towers, and two
//! perspective photos of the keep's south façade at different scales. The model's keep must
//! have the façades' height, floor count and windows per floor after scaling; the towers must
//! match the plan.

use integrate::estimate::{Footprint, Structure};
use integrate::photo::{FacadePhoto, estimate_facade};
use integrate::project::Correspondence;
use integrate::{Inputs, integrate, program, synth::Castle};

fn keep(structures: &[Structure]) -> &Structure {
    structures
        .iter()
        .find(|s| !s.facades.is_empty())
        .expect("a structure carries the façades")
}

#[test]
fn keep_and_towers_match_facades_and_plan() {
    let castle = Castle::default();
    let plan = plan::parse(
        &image::DynamicImage::ImageLuma8(castle.plan()),
        &plan::Options::default(),
    )
    .unwrap();
    let photos = [castle.photo(20.0, 0.12, 1), castle.photo(13.0, 0.08, 2)];
    let names = ["keep_south_near.png", "keep_south_far.png"];
    let estimates: Vec<_> = photos
        .iter()
        .zip(names)
        .map(|(p, name)| {
            estimate_facade(&FacadePhoto {
                name,
                image: &p.image,
                training: &p.training,
                lines: None,
                rectified: false,
                seed: 7,
            })
            .unwrap()
        })
        .collect();
    let correspondences: Vec<Correspondence> = photos
        .iter()
        .zip(names)
        .map(|(p, name)| Correspondence {
            facade: name.into(),
            facade_point: p.facade_point,
            plan_points: vec![castle.keep_south_point()],
        })
        .collect();
    let estimate = integrate(&Inputs {
        plan: &plan,
        plan_image: "plan.png",
        scale: Some(castle.metres_per_pixel),
        facades: &estimates,
        correspondences: &correspondences,
    })
    .unwrap();

    let k = keep(&estimate.structures);
    assert!(matches!(k.footprint, Footprint::Rectangle { .. }), "{k:?}");
    assert_eq!(k.facades.len(), 2);
    for f in &k.facades {
        assert_eq!(f.side, "south");
        assert!(f.joint);
        assert_eq!(f.floors.len() as u32, castle.floors, "{f:?}");
        let windowed: Vec<u32> = f.floors.iter().map(|fl| fl.windows).collect();
        assert_eq!(
            windowed,
            vec![castle.windows; castle.floors as usize],
            "{f:?}"
        );
        assert!(
            (f.width - castle.keep_width()).abs() < 0.05 * castle.keep_width(),
            "{f:?}"
        );
    }
    // Height after scaling by w_p / w_f, within 10 % of the truth (rectification keeps the
    // photo's aspect at its centre only).
    assert!(
        (k.height - castle.keep_height).abs() < 0.1 * castle.keep_height,
        "keep height {} vs {}",
        k.height,
        castle.keep_height
    );
    // Towers from the plan: two circles of outer radius (36 + 5) px × 0.1 m.
    let towers: Vec<&Structure> = estimate
        .structures
        .iter()
        .filter(|s| s.label == "tower_room")
        .collect();
    assert_eq!(towers.len(), 2, "{:?}", estimate.structures);
    for t in towers {
        let Footprint::Circle { radius, .. } = t.footprint else {
            panic!("{t:?}")
        };
        assert!((radius - 4.1).abs() < 0.3, "tower radius {radius}");
    }

    // The program runs, and its keep façade has floors × windows window openings.
    let src = program::generate(&estimate, &program::Options::default());
    let model = vsg::run_with(
        "model.vsg",
        &src,
        &vsg::RunOptions::default(),
        &mut integrate::library::Library,
    )
    .unwrap_or_else(|e| panic!("{}\n{src}", e.render("model.vsg", &src)));
    let windows = model
        .terminals()
        .filter(|n| model.symbol(n) == "glass")
        .count();
    assert_eq!(windows as u32, castle.floors * castle.windows, "{src}");
}
