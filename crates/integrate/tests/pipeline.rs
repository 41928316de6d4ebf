//! `integrate::pipeline` on the bundled synthetic project, its files served from memory: every
//! stage reports, the progress steps add up, the products and overlays are named as the
//! commands write them, and a missing or bad file is an error naming its PROJECT.toml entry.

use std::sync::Mutex;

use integrate::pipeline::{self, PipelineError, Progress, Stage};

mod common;

#[test]
fn the_synthetic_project_runs_from_memory_with_every_stage_and_step_reported() {
    let (project, files) = common::example("demo");
    let heard = Mutex::new(Vec::new());
    let r = pipeline::reconstruct(&project, &files, &pipeline::Options::default(), &|p| {
        heard.lock().unwrap().push(p)
    })
    .unwrap();
    let heard = heard.into_inner().unwrap();
    let steps = heard.iter().filter(|p| **p == Progress::Step).count() as u64;
    assert_eq!(steps, pipeline::steps(&project));
    let started: Vec<Stage> = heard
        .iter()
        .filter_map(|p| match p {
            Progress::Started(s) => Some(*s),
            Progress::Step => None,
        })
        .collect();
    let order = [
        Stage::Plan,
        Stage::Facades,
        Stage::Integrate,
        Stage::Vsg,
        Stage::Export,
    ];
    assert_eq!(started, order);
    assert_eq!(r.stages.iter().map(|(s, _)| *s).collect::<Vec<_>>(), order);
    for (stage, _) in &r.stages {
        assert!(
            r.exports.stats["stages_ms"][stage.name()].is_number(),
            "{stage:?}"
        );
    }

    // The keep received both photos, and the estimate names the crop of each.
    let mapped: Vec<_> = r
        .estimate
        .structures
        .iter()
        .flat_map(|s| &s.facades)
        .collect();
    assert_eq!(mapped.len(), 2);
    for f in &mapped {
        let texture = f.texture.as_ref().unwrap();
        assert!(r.textures.iter().any(|t| &t.name == texture), "{texture}");
    }
    // Every texture mipmaps in any viewer (power-of-two sides), and each photo's wall sample
    // knows its real size: metres, a few of them, not a crop tiled once a metre (issue 25).
    for t in &r.textures {
        let (w, h) = t.image.dimensions();
        assert!(
            w.is_power_of_two() && h.is_power_of_two(),
            "{}: {w} × {h}",
            t.name
        );
    }
    let samples: Vec<_> = r
        .textures
        .iter()
        .filter(|t| t.name.starts_with("textures/wall_"))
        .collect();
    assert_eq!(samples.len(), 2, "one sample a photo");
    let per_metre = r.estimate.scale.units_per_metre;
    for t in samples {
        let [w, h] = t
            .size
            .expect("a mapped photo's sample has a real size")
            .map(|v| v / per_metre);
        assert!(
            (1.0..40.0).contains(&w) && (1.0..40.0).contains(&h),
            "{}: {w} × {h} m",
            t.name
        );
    }

    let names: Vec<String> = r.files().unwrap().into_iter().map(|(n, _)| n).collect();
    for expected in [
        "overlays/plan_labels.png",
        "overlays/keep_south_near_lines.png",
        "overlays/keep_south_near_pixels.png",
        "overlays/keep_south_near_facade.png",
        "overlays/keep_south_near_labels.png",
        "overlays/keep_south_near_labels.view.png",
        "overlays/keep_south_far_facade.png",
        "plan.svg",
        "model.vsg",
        "model.glb",
        "model.obj",
        "model.mtl",
        "preview.png",
        "stats.json",
        "estimate.json",
    ] {
        assert!(
            names.iter().any(|n| n == expected),
            "{expected} in {names:?}"
        );
    }
    // Every overlay the report shows has a legend naming its photo; the label image and its
    // view (issue 22: the classes in colour with a key, linked from the report) have none.
    for o in &r.overlays {
        match &o.caption {
            Some(c) if o.name.contains("keep_south_far") => {
                assert!(c.starts_with("keep_south_far.png: "), "{c}")
            }
            Some(_) => {}
            None => assert!(
                o.name.ends_with("_labels.png") || o.name.ends_with("_labels.view.png"),
                "{}",
                o.name
            ),
        }
        // The colour overlays of the façade stage say which colour is which class.
        if o.name.ends_with("_pixels.png") || o.name.ends_with("_facade.png") {
            let c = o.caption.as_deref().unwrap_or_default();
            assert!(c.contains(facade::draw::LEGEND), "{c}");
        }
        // Issue 22: so do the line and plan overlays.
        let c = o.caption.as_deref().unwrap_or_default();
        if o.name.ends_with("_lines.png") {
            assert!(c.contains(facade::rectify::OVERLAY_LEGEND), "{c}");
        }
        if o.name == "overlays/plan_labels.png" {
            assert!(
                c.contains("courtyard blue") && c.contains("tower room green"),
                "{c}"
            );
        }
    }
    assert_eq!(
        r.exports.terminals,
        r.exports.stats["terminals"].as_u64().unwrap() as usize
    );
}

#[test]
fn a_missing_or_bad_file_names_its_entry() {
    let (project, mut files) = common::example("demo");
    files.0.remove("keep_south_far.training.json");
    let e = pipeline::reconstruct(&project, &files, &pipeline::Options::default(), &|_| {})
        .err()
        .unwrap();
    assert!(matches!(e, PipelineError::Entry { .. }), "{e}");
    assert_eq!(
        e.to_string(),
        "[[facade]] #2 (image = \"keep_south_far.png\"): keep_south_far.training.json: no such file"
    );

    let (project, mut files) = common::example("demo");
    files.0.insert("plan.png".into(), b"not a png".to_vec());
    let e = pipeline::parse_plan(&project, &files).err().unwrap();
    assert!(
        e.to_string().starts_with("plan = \"plan.png\": plan.png: "),
        "{e}"
    );
}

#[test]
fn training_boxes_have_one_rule_inline_or_from_their_file() {
    let (project, files) = common::example("demo");
    let from_file = pipeline::training(&project.facades[0], &files).unwrap();
    let mut inline = project.facades[0].clone();
    inline.training = integrate::project::TrainingSource::Inline(from_file.clone());
    assert_eq!(pipeline::training(&inline, &files).unwrap(), from_file);
    let mut missing = project.facades[0].clone();
    missing.training = integrate::project::TrainingSource::File("gone.json".into());
    assert!(pipeline::training(&missing, &files).is_err());
}
