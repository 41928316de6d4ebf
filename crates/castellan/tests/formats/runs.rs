//! Real runs of the binary, once each, shared by the tests that read their outputs.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::OnceLock;

use serde_json::Value;

use crate::fixtures;
use crate::schemas::*;

/// A command's JSON outputs (file name → document), read before its folder is removed.
pub struct Run {
    pub files: BTreeMap<String, Value>,
}

impl Run {
    pub fn get(&self, name: &str) -> &Value {
        self.files
            .get(name)
            .unwrap_or_else(|| panic!("the run wrote no {name}"))
    }
}

/// The JSON outputs of a reconstruction in `out`: estimate.json, stats.json and, when there,
/// the project copy in out/project (PROJECT.toml as JSON, its TRAINING.json files).
pub fn reconstruction_outputs(out: &Path) -> Run {
    let mut files = BTreeMap::new();
    for name in ["estimate.json", "stats.json"] {
        files.insert(name.to_string(), read_json(&out.join(name)));
    }
    if let Ok(entries) = std::fs::read_dir(out.join("project")) {
        for entry in entries {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().to_string();
            if name == "PROJECT.toml" {
                let text = std::fs::read_to_string(&path).unwrap();
                files.insert(format!("project/{name}"), toml_to_json(&text, &name));
            } else if name.ends_with(".training.json") {
                files.insert(format!("project/{name}"), read_json(&path));
            }
        }
    }
    Run { files }
}

/// `castellan demo --example NAME -o DIR`.
pub fn run_demo(example: &str) -> Run {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("demo");
    castellan()
        .args(["demo", "--example", example, "-o"])
        .arg(&out)
        .assert()
        .success();
    reconstruction_outputs(&out)
}

/// `castellan demo --example synthetic`: a metric model (`scale`), two photos of one wall
/// re-estimated jointly.
pub fn demo() -> &'static Run {
    static RUN: OnceLock<Run> = OnceLock::new();
    RUN.get_or_init(|| run_demo("synthetic"))
}

/// `castellan demo --example coucy`: a scale bar, inline training boxes, a measured elevation
/// (`bbox`, `scale`) on the arc of a round tower.
pub fn coucy() -> &'static Run {
    static RUN: OnceLock<Run> = OnceLock::new();
    RUN.get_or_init(|| run_demo("coucy"))
}

/// `castellan reconstruct` on examples/demo without its `scale`: a model in plan pixels.
pub fn unscaled() -> &'static Run {
    static RUN: OnceLock<Run> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let project = dir.path().join("project");
        std::fs::create_dir(&project).unwrap();
        for entry in std::fs::read_dir(repo().join("examples/demo")).unwrap() {
            let path = entry.unwrap().path();
            std::fs::copy(&path, project.join(path.file_name().unwrap())).unwrap();
        }
        let toml = project.join("PROJECT.toml");
        let text = std::fs::read_to_string(&toml).unwrap();
        let unscaled: String = text
            .lines()
            .filter(|l| !l.starts_with("scale ="))
            .map(|l| format!("{l}\n"))
            .collect();
        assert_ne!(
            unscaled, text,
            "examples/demo/PROJECT.toml has no scale line"
        );
        std::fs::write(&toml, unscaled).unwrap();
        let out = dir.path().join("out");
        castellan()
            .arg("reconstruct")
            .arg(&toml)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        reconstruction_outputs(&out)
    })
}

/// `castellan plan IMAGE -o PLAN.json [ARGS]`.
pub fn run_plan(image: &str, args: &[&str]) -> Value {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("plan.json");
    castellan()
        .arg("plan")
        .arg(repo().join(image))
        .arg("-o")
        .arg(&out)
        .args(args)
        .assert()
        .success();
    read_json(&out)
}

/// `castellan plan examples/plans/sully-sur-loire.png -o PLAN.json`.
pub fn plan() -> &'static Value {
    static RUN: OnceLock<Value> = OnceLock::new();
    RUN.get_or_init(|| run_plan("examples/plans/sully-sur-loire.png", &[]))
}

/// `castellan plan examples/coucy/plan.png --scale-bar 50 --thin-lines 0.3`: a scale bar found,
/// a scale recorded.
pub fn coucy_plan() -> &'static Value {
    static RUN: OnceLock<Value> = OnceLock::new();
    RUN.get_or_init(|| {
        run_plan(
            "examples/coucy/plan.png",
            &["--scale-bar", "50", "--thin-lines", "0.3"],
        )
    })
}

/// The training boxes the façade run uses (in [`facade_image`]'s pixels).
pub const FACADE_TRAINING: &str = r#"{"classes": {"window": [[14, 27, 30, 43], [52, 62, 68, 78]], "wall": [[2, 50, 10, 58], [40, 17, 100, 23]], "background": [[5, 2, 115, 12]]}}"#;

/// `castellan facade f.png --training t.json -o FACADE.json` on [`facade_image`].
pub fn facade() -> &'static Value {
    static RUN: OnceLock<Value> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let (img, training, out) = (
            dir.path().join("f.png"),
            dir.path().join("t.json"),
            dir.path().join("facade.json"),
        );
        fixtures::facade_image().save(&img).unwrap();
        std::fs::write(&training, FACADE_TRAINING).unwrap();
        castellan()
            .arg("facade")
            .arg(&img)
            .arg("--training")
            .arg(&training)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        read_json(&out)
    })
}

/// `castellan gothic g.png -o GOTHIC.json --masonry m.png` on a synthetic Gothic bay (two
/// pointed windows under an enclosing arch, as in tests/gothic_cli.rs): elements, a group,
/// nesting and stones.
pub fn gothic() -> &'static Value {
    use facade::gothic::synth::synthetic_facade;
    static RUN: OnceLock<Value> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let spec = fixtures::gothic_bay();
        let (img, out) = (dir.path().join("g.png"), dir.path().join("gothic.json"));
        synthetic_facade(&spec, 4).image.save(&img).unwrap();
        castellan()
            .arg("gothic")
            .arg(&img)
            .arg("-o")
            .arg(&out)
            .arg("--masonry")
            .arg(dir.path().join("masonry.png"))
            .assert()
            .success();
        read_json(&out)
    })
}

/// `castellan vsg run examples/rules_7_1.vsg -o M.glb --stats STATS.json`.
pub fn vsg_stats() -> &'static Value {
    static RUN: OnceLock<Value> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("stats.json");
        castellan()
            .args(["vsg", "run"])
            .arg(repo().join("examples/rules_7_1.vsg"))
            .arg("-o")
            .arg(dir.path().join("m.glb"))
            .arg("--stats")
            .arg(&out)
            .assert()
            .success();
        read_json(&out)
    })
}
