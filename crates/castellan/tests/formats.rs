//! The file contracts of docs/formats.md, checked against the JSON Schemas of docs/schemas/
//! (hand-written from the code, so an independent contract): every schema is a valid draft
//! 2020-12 schema; the PROJECT.toml, TRAINING.json and LINES.json files shipped in the
//! repository follow theirs; the outputs of real runs of the binary (`demo`, `plan`, `facade`,
//! `gothic`, `vsg run`) follow theirs; and each schema refuses a file a step away from a real
//! one (a wrong label, side, unit or unknown key), so it has teeth. Each command runs once,
//! shared by the tests that read its outputs.

mod fixtures;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use assert_cmd::Command;

use jsonschema::{Registry, Resource, Validator};
use serde_json::{Value, json};

/// Every schema: the file contract it checks.
const SCHEMAS: [&str; 8] = [
    "project", "training", "lines", "plan", "facade", "gothic", "estimate", "stats",
];

/// Schemas refer to each other by relative file name (`training.schema.json`); they are
/// registered under this base so no reference leaves the test.
const BASE: &str = "file:///castellan/docs/schemas/";

fn castellan() -> Command {
    Command::cargo_bin("castellan").unwrap()
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn schema_file(name: &str) -> PathBuf {
    repo().join(format!("docs/schemas/{name}.schema.json"))
}

fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: not JSON: {e}", path.display()))
}

/// PROJECT.toml as the JSON document its schema describes.
fn toml_to_json(text: &str, what: &str) -> Value {
    let doc: toml::Value = toml::from_str(text).unwrap_or_else(|e| panic!("{what}: {e}"));
    serde_json::to_value(doc).unwrap()
}

/// The schemas, parsed, by name.
fn schema_documents() -> &'static BTreeMap<&'static str, Value> {
    static DOCS: OnceLock<BTreeMap<&'static str, Value>> = OnceLock::new();
    DOCS.get_or_init(|| {
        SCHEMAS
            .iter()
            .map(|&name| (name, read_json(&schema_file(name))))
            .collect()
    })
}

/// The registry every validator resolves `$ref`s in: all schemas, under [`BASE`].
fn registry() -> &'static Registry<'static> {
    static REGISTRY: OnceLock<Registry<'static>> = OnceLock::new();
    REGISTRY.get_or_init(|| {
        Registry::new()
            .extend(schema_documents().iter().map(|(name, doc)| {
                (
                    format!("{BASE}{name}.schema.json"),
                    Resource::from_contents(doc.clone()),
                )
            }))
            .expect("schema URIs")
            .prepare()
            .expect("the schemas' references resolve")
    })
}

/// The compiled schema `name` (docs/schemas/NAME.schema.json).
fn validator(name: &str) -> Validator {
    let doc = &schema_documents()[name];
    jsonschema::options()
        .with_registry(registry())
        .with_base_uri(format!("{BASE}{name}.schema.json"))
        .build(doc)
        .unwrap_or_else(|e| panic!("docs/schemas/{name}.schema.json does not compile: {e}"))
}

/// Every way `doc` (the file `file`) breaks schema `name`, one line each: the file, the path in
/// the document, the message and the path in the schema.
fn violations(name: &str, file: &str, doc: &Value) -> Vec<String> {
    validator(name)
        .iter_errors(doc)
        .map(|e| {
            format!(
                "{file}: at '{}': {e} (schema {name}.schema.json at '{}')",
                e.instance_path(),
                e.schema_path()
            )
        })
        .collect()
}

/// Fails naming the file and each error's paths unless `doc` follows schema `name`.
fn assert_valid(name: &str, file: &str, doc: &Value) {
    let errors = violations(name, file, doc);
    assert!(
        errors.is_empty(),
        "{file} breaks docs/schemas/{name}.schema.json:\n{}",
        errors.join("\n")
    );
}

/// Fails unless `doc` breaks schema `name` (a schema with teeth); `why` says what is wrong.
fn assert_refused(name: &str, why: &str, doc: &Value) {
    assert!(
        !validator(name).is_valid(doc),
        "docs/schemas/{name}.schema.json accepts {why}: {doc}"
    );
}

/// A copy of `doc` with the value at the JSON pointer `at` replaced by `value`.
fn with(doc: &Value, at: &str, value: Value) -> Value {
    let mut out = doc.clone();
    *out.pointer_mut(at)
        .unwrap_or_else(|| panic!("no {at} in the document")) = value;
    out
}

/// A copy of `doc` without the key `key` of the object at the JSON pointer `parent`.
fn without(doc: &Value, parent: &str, key: &str) -> Value {
    let mut out = doc.clone();
    out.pointer_mut(parent)
        .and_then(Value::as_object_mut)
        .unwrap_or_else(|| panic!("no object {parent} in the document"))
        .remove(key)
        .unwrap_or_else(|| panic!("no {parent}/{key} in the document"));
    out
}

/// A copy of `doc` with `key = value` added to (or replaced in) the object at `parent`.
fn with_key(doc: &Value, parent: &str, key: &str, value: Value) -> Value {
    let mut out = doc.clone();
    out.pointer_mut(parent)
        .and_then(Value::as_object_mut)
        .unwrap_or_else(|| panic!("no object {parent} in the document"))
        .insert(key.to_string(), value);
    out
}

// ---------------------------------------------------------------------------------------------
// Real runs of the binary, once each.

/// A command's JSON outputs (file name → document), read before its folder is removed.
struct Run {
    files: BTreeMap<String, Value>,
}

impl Run {
    fn get(&self, name: &str) -> &Value {
        self.files
            .get(name)
            .unwrap_or_else(|| panic!("the run wrote no {name}"))
    }
}

/// The JSON outputs of a reconstruction in `out`: estimate.json, stats.json and, when there,
/// the project copy in out/project (PROJECT.toml as JSON, its TRAINING.json files).
fn reconstruction_outputs(out: &Path) -> Run {
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
fn run_demo(example: &str) -> Run {
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
fn demo() -> &'static Run {
    static RUN: OnceLock<Run> = OnceLock::new();
    RUN.get_or_init(|| run_demo("synthetic"))
}

/// `castellan demo --example coucy`: a scale bar, inline training boxes, a measured elevation
/// (`bbox`, `scale`) on the arc of a round tower.
fn coucy() -> &'static Run {
    static RUN: OnceLock<Run> = OnceLock::new();
    RUN.get_or_init(|| run_demo("coucy"))
}

/// `castellan reconstruct` on examples/demo without its `scale`: a model in plan pixels.
fn unscaled() -> &'static Run {
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
fn run_plan(image: &str, args: &[&str]) -> Value {
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
fn plan() -> &'static Value {
    static RUN: OnceLock<Value> = OnceLock::new();
    RUN.get_or_init(|| run_plan("examples/plans/sully-sur-loire.png", &[]))
}

/// `castellan plan examples/coucy/plan.png --scale-bar 50 --thin-lines 0.3`: a scale bar found,
/// a scale recorded.
fn coucy_plan() -> &'static Value {
    static RUN: OnceLock<Value> = OnceLock::new();
    RUN.get_or_init(|| {
        run_plan(
            "examples/coucy/plan.png",
            &["--scale-bar", "50", "--thin-lines", "0.3"],
        )
    })
}

/// The training boxes the façade run uses (in [`facade_image`]'s pixels).
const FACADE_TRAINING: &str = r#"{"classes": {"window": [[14, 27, 30, 43], [52, 62, 68, 78]], "wall": [[2, 50, 10, 58], [40, 17, 100, 23]], "background": [[5, 2, 115, 12]]}}"#;

/// `castellan facade f.png --training t.json -o FACADE.json` on [`facade_image`].
fn facade() -> &'static Value {
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
fn gothic() -> &'static Value {
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
fn vsg_stats() -> &'static Value {
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

// ---------------------------------------------------------------------------------------------
// The schemas themselves.

#[test]
fn every_schema_is_a_valid_draft_2020_12_schema_and_compiles() {
    for name in SCHEMAS {
        let doc = &schema_documents()[name];
        assert_eq!(
            doc["$schema"], "https://json-schema.org/draft/2020-12/schema",
            "docs/schemas/{name}.schema.json: $schema"
        );
        if let Err(e) = jsonschema::meta::validate(doc) {
            panic!(
                "docs/schemas/{name}.schema.json is not a valid schema: at '{}': {e}",
                e.instance_path()
            );
        }
        validator(name);
    }
    let listed: Vec<String> = std::fs::read_dir(repo().join("docs/schemas"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    for file in &listed {
        let name = file.trim_end_matches(".schema.json");
        assert!(
            SCHEMAS.contains(&name),
            "docs/schemas/{file} is not checked by this test"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Inputs shipped in the repository.

/// Files under `dir` (recursively) whose name `keep` accepts.
fn files_under(dir: &Path, keep: &dyn Fn(&str) -> bool, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files_under(&path, keep, out);
        } else if keep(&path.file_name().unwrap().to_string_lossy()) {
            out.push(path);
        }
    }
}

/// `examples/` and every `crates/*/tests/data`.
fn shipped(keep: &dyn Fn(&str) -> bool) -> Vec<PathBuf> {
    let mut out = Vec::new();
    files_under(&repo().join("examples"), keep, &mut out);
    for krate in std::fs::read_dir(repo().join("crates")).unwrap() {
        files_under(&krate.unwrap().path().join("tests/data"), keep, &mut out);
    }
    out.sort();
    out
}

fn shown(path: &Path) -> String {
    path.strip_prefix(repo())
        .unwrap_or(path)
        .display()
        .to_string()
}

#[test]
fn shipped_projects_follow_the_project_schema() {
    let projects = shipped(&|n| n == "PROJECT.toml" || n.ends_with(".project.toml"));
    assert!(
        projects.len() >= 2,
        "examples/coucy and examples/demo: {projects:?}"
    );
    for path in &projects {
        let text = std::fs::read_to_string(path).unwrap();
        let doc = toml_to_json(&text, &shown(path));
        assert_valid("project", &shown(path), &doc);
        // Inline training boxes follow the TRAINING.json contract too.
        for (i, f) in doc["facade"].as_array().into_iter().flatten().enumerate() {
            if f["training"].is_object() {
                let at = format!("{} [[facade]] #{} training", shown(path), i + 1);
                assert_valid("training", &at, &f["training"]);
            }
        }
    }
}

#[test]
fn shipped_training_and_lines_files_follow_their_schemas() {
    let training = shipped(&|n| n == "TRAINING.json" || n.ends_with(".training.json"));
    assert!(training.len() >= 2, "examples/demo: {training:?}");
    for path in &training {
        assert_valid("training", &shown(path), &read_json(path));
    }
    // No LINES.json ships today; any that does is checked.
    for path in shipped(&|n| n == "LINES.json" || n.ends_with(".lines.json")) {
        assert_valid("lines", &shown(&path), &read_json(&path));
    }
}

/// LINES.json has no shipped example: the file `castellan rectify --lines` accepts (as in
/// tests/rectify_facade.rs) follows the schema, and one it refuses breaks it.
#[test]
fn lines_json_the_binary_accepts_follows_the_schema_and_one_it_refuses_breaks_it() {
    let dir = tempfile::tempdir().unwrap();
    let img = dir.path().join("photo.png");
    fixtures::facade_image().save(&img).unwrap();
    let good = json!({
        "horizontal": [[10, 20, 110, 25], [10, 70, 110, 68]],
        "vertical": [[20, 10, 22, 80], [100, 10, 98, 80]]
    });
    let one = with(&good, "/vertical", json!([[20, 10, 22, 80]]));
    for (doc, ok) in [(&good, true), (&one, false)] {
        let lines = dir.path().join("lines.json");
        std::fs::write(&lines, doc.to_string()).unwrap();
        let run = castellan()
            .arg("rectify")
            .arg(&img)
            .arg("-o")
            .arg(dir.path().join("r.png"))
            .arg("--lines")
            .arg(&lines)
            .assert();
        if ok {
            run.success();
            assert_valid("lines", "lines.json (accepted by rectify)", doc);
        } else {
            run.failure();
            assert_refused("lines", "a single vertical segment", doc);
        }
    }
    assert_refused(
        "lines",
        "a segment of three numbers",
        &with(&good, "/horizontal/0", json!([1, 2, 3])),
    );
    assert_refused(
        "lines",
        "no vertical family",
        &without(&good, "", "vertical"),
    );
}

// ---------------------------------------------------------------------------------------------
// Outputs of real runs.

/// The façades mapped in an estimate.json.
fn mapped_facades(estimate: &Value) -> Vec<&Value> {
    estimate["structures"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|s| s["facades"].as_array().unwrap())
        .collect()
}

#[test]
fn demo_estimate_json_follows_its_schema() {
    let estimate = demo().get("estimate.json");
    assert_valid(
        "estimate",
        "demo --example synthetic: estimate.json",
        estimate,
    );
    // The run exercises what the schema is about: a metric model with façades on a side.
    assert_eq!(estimate["units"], "m");
    assert!(
        mapped_facades(estimate)
            .iter()
            .any(|f| f["side"] == "south"),
        "{estimate}"
    );
}

#[test]
fn coucy_estimate_json_follows_its_schema() {
    let estimate = coucy().get("estimate.json");
    assert_valid("estimate", "demo --example coucy: estimate.json", estimate);
    // A façade on the arc of a round tower, with its angles.
    assert!(
        mapped_facades(estimate)
            .iter()
            .any(|f| f["side"] == "arc" && f["arc"].is_array()),
        "{estimate}"
    );
}

#[test]
fn unscaled_estimate_json_follows_its_schema() {
    let estimate = unscaled().get("estimate.json");
    assert_valid(
        "estimate",
        "reconstruct without a scale: estimate.json",
        estimate,
    );
    assert_eq!(estimate["units"], "px");
    assert_eq!(estimate["scale"], 1.0);
    assert_valid(
        "stats",
        "reconstruct without a scale: stats.json",
        unscaled().get("stats.json"),
    );
}

#[test]
fn demo_stats_json_follows_its_schema() {
    for (run, what) in [(demo(), "synthetic"), (coucy(), "coucy")] {
        let stats = run.get("stats.json");
        assert_valid(
            "stats",
            &format!("demo --example {what}: stats.json"),
            stats,
        );
        assert!(stats["stages_ms"].is_object(), "{stats}");
    }
}

#[test]
fn demo_project_copies_follow_the_project_and_training_schemas() {
    for (run, what) in [(demo(), "synthetic"), (coucy(), "coucy")] {
        let project = run.get("project/PROJECT.toml");
        let file = format!("demo --example {what}: project/PROJECT.toml");
        assert_valid("project", &file, project);
        for (i, f) in project["facade"].as_array().unwrap().iter().enumerate() {
            if f["training"].is_object() {
                let at = format!("{file} [[facade]] #{} training", i + 1);
                assert_valid("training", &at, &f["training"]);
            }
        }
        for (name, doc) in &run.files {
            if name.ends_with(".training.json") {
                assert_valid("training", &format!("demo --example {what}: {name}"), doc);
            }
        }
    }
    let files = &demo().files;
    assert!(
        files
            .keys()
            .filter(|n| n.ends_with(".training.json"))
            .count()
            >= 2,
        "{:?}",
        files.keys()
    );
}

#[test]
fn vsg_run_stats_json_follows_its_schema() {
    let stats = vsg_stats();
    assert_valid("stats", "vsg run --stats STATS.json", stats);
    assert!(stats.get("stages_ms").is_none(), "{stats}");
}

#[test]
fn plan_json_follows_its_schema() {
    let doc = plan();
    assert_valid("plan", "sully-sur-loire.png: PLAN.json", doc);
    assert!(!doc["faces"].as_array().unwrap().is_empty());
    assert!(doc["scale"].is_null(), "no scale given: {}", doc["scale"]);
}

#[test]
fn plan_json_with_a_scale_bar_follows_its_schema() {
    let doc = coucy_plan();
    assert_valid("plan", "coucy/plan.png --scale-bar 50: PLAN.json", doc);
    assert!(doc["scale_bar"].is_object(), "{}", doc["scale_bar"]);
    assert!(doc["scale"].as_f64().unwrap() > 0.0);
}

#[test]
fn facade_json_follows_its_schema() {
    let doc = facade();
    assert_valid("facade", "FACADE.json", doc);
    assert!(!doc["facades"].as_array().unwrap().is_empty());
    assert_valid(
        "training",
        "the façade run's TRAINING.json",
        &serde_json::from_str(FACADE_TRAINING).unwrap(),
    );
}

#[test]
fn gothic_json_follows_its_schema() {
    let doc = gothic();
    assert_valid("gothic", "GOTHIC.json", doc);
    // The run exercises groups, nesting and stones.
    assert!(!doc["groups"].as_array().unwrap().is_empty(), "{doc}");
    assert!(
        doc["elements"]
            .as_array()
            .unwrap()
            .iter()
            .any(|e| !e["parent"].is_null()),
        "{doc}"
    );
    assert!(!doc["stones"].as_array().unwrap().is_empty(), "{doc}");
}

// ---------------------------------------------------------------------------------------------
// Teeth: each schema refuses a document one step away from a real one.

#[test]
fn project_schema_refuses_unknown_keys_and_bad_values() {
    let demo_project = || {
        let text = std::fs::read_to_string(repo().join("examples/demo/PROJECT.toml")).unwrap();
        toml_to_json(&text, "examples/demo/PROJECT.toml")
    };
    let doc = demo_project();
    assert_valid("project", "examples/demo/PROJECT.toml", &doc);
    for (why, bad) in [
        (
            "an unknown top-level key",
            with_key(&doc, "", "scael", json!(1)),
        ),
        (
            "an unknown key in [[facade]]",
            with_key(&doc, "/facade/0", "rectify", json!(true)),
        ),
        (
            "an unknown key in [[correspondence]]",
            with_key(&doc, "/correspondence/0", "plan_point", json!([1, 2])),
        ),
        (
            "scale and scale_bar together",
            with_key(&doc, "", "scale_bar", json!(50)),
        ),
        ("a negative scale", with(&doc, "/scale", json!(-0.1))),
        ("no plan", without(&doc, "", "plan")),
        (
            "three plan points",
            with(
                &doc,
                "/correspondence/0/plan_points",
                json!([[1, 2], [3, 4], [5, 6]]),
            ),
        ),
        (
            "a texture class other than wall",
            with_key(
                &doc,
                "",
                "texture",
                json!([{"class": "roof", "image": "a.png", "boxes": [[0, 0, 5, 5]]}]),
            ),
        ),
        (
            "an inline training class other than window, wall, background",
            with(
                &doc,
                "/facade/0/training",
                json!({"classes": {"sky": [[0, 0, 5, 5]]}}),
            ),
        ),
    ] {
        assert_refused("project", why, &bad);
    }
    // The program refuses the unknown key too (deny_unknown_fields): schema and code agree.
    let text = std::fs::read_to_string(repo().join("examples/demo/PROJECT.toml")).unwrap();
    assert!(integrate::project::Project::from_toml(&format!("scael = 1\n{text}")).is_err());
}

#[test]
fn training_schema_refuses_unknown_classes_and_short_boxes() {
    let doc: Value = serde_json::from_str(FACADE_TRAINING).unwrap();
    assert_refused(
        "training",
        "a class 'sky'",
        &with_key(&doc, "/classes", "sky", json!([[0, 0, 5, 5]])),
    );
    assert_refused(
        "training",
        "a box of three numbers",
        &with(&doc, "/classes/window/0", json!([1, 2, 3])),
    );
    assert_refused("training", "no classes", &json!({"window": [[0, 0, 5, 5]]}));
}

#[test]
fn estimate_schema_refuses_unknown_sides_units_and_labels() {
    let doc = demo().get("estimate.json");
    let (s, f) = facade_at(doc);
    let structure = format!("/structures/{s}");
    let facade = format!("{structure}/facades/{f}");
    for (why, bad) in [
        (
            "side = \"up\"",
            with(doc, &format!("{facade}/side"), json!("up")),
        ),
        ("units = \"ft\"", with(doc, "/units", json!("ft"))),
        (
            "a label 'moat'",
            with(doc, &format!("{structure}/label"), json!("moat")),
        ),
        (
            "a label in CamelCase",
            with(doc, &format!("{structure}/label"), json!("TowerRoom")),
        ),
        (
            "a negative height",
            with(doc, &format!("{structure}/height"), json!(-3.0)),
        ),
        ("a scale of zero", with(doc, "/scale", json!(0))),
        (
            "units \"m\" with 2 units per metre",
            with(doc, "/units_per_metre", json!(2.0)),
        ),
        (
            "an arc on a side that is not \"arc\"",
            with_key(doc, &facade, "arc", json!([0.0, 1.0])),
        ),
        (
            "a footprint of type 'hexagon'",
            with(
                doc,
                &format!("{structure}/footprint/type"),
                json!("hexagon"),
            ),
        ),
        ("no units", without(doc, "", "units")),
    ] {
        assert_refused("estimate", why, &bad);
    }
    // An arc façade needs its angles.
    let arc = with(doc, &format!("{facade}/side"), json!("arc"));
    assert_refused("estimate", "side \"arc\" without `arc`", &arc);
    assert_valid(
        "estimate",
        "estimate.json with an arc façade",
        &with_key(&arc, &facade, "arc", json!([0.5, 1.5])),
    );
    // Plan pixels: the scale is 1.
    let px = with(
        &with(doc, "/units", json!("px")),
        "/units_per_metre",
        json!(4.0),
    );
    assert_refused("estimate", "units \"px\" with a scale of 0.1", &px);
    assert_valid(
        "estimate",
        "estimate.json in plan pixels",
        &with(&px, "/scale", json!(1.0)),
    );
}

/// The first mapped façade of the demo's estimate: (structure index, façade index).
fn facade_at(doc: &Value) -> (usize, usize) {
    for (s, structure) in doc["structures"].as_array().unwrap().iter().enumerate() {
        if !structure["facades"].as_array().unwrap().is_empty() {
            return (s, 0);
        }
    }
    panic!("no façade mapped in the demo's estimate.json");
}

#[test]
fn stats_schema_refuses_negative_counts_and_unknown_stages() {
    let doc = demo().get("stats.json");
    assert_refused(
        "stats",
        "terminals = -1",
        &with(doc, "/terminals", json!(-1)),
    );
    assert_refused(
        "stats",
        "a fractional triangle count",
        &with(doc, "/triangles", json!(1.5)),
    );
    assert_refused(
        "stats",
        "a stage 'render'",
        &with_key(doc, "/stages_ms", "render", json!(3.0)),
    );
    assert_refused("stats", "no volume", &without(doc, "", "volume"));
}

#[test]
fn plan_schema_refuses_unknown_labels_and_fits() {
    let doc = plan();
    assert_refused(
        "plan",
        "an edge label 'moat'",
        &with(doc, "/edges/0/label", json!("moat")),
    );
    assert_refused(
        "plan",
        "a face label 'keep'",
        &with(doc, "/faces/0/label", json!("keep")),
    );
    assert_refused(
        "plan",
        "a legend that renames label 4",
        &with(doc, "/legend/4", json!("tower")),
    );
    assert_refused(
        "plan",
        "an edge fitted with a circle",
        &with(
            doc,
            "/edges/0/fit",
            json!({"type": "circle", "center": [0, 0], "radius": 1, "error": 0}),
        ),
    );
    assert_refused("plan", "a negative width", &with(doc, "/width", json!(-5)));
}

#[test]
fn facade_schema_refuses_missing_parameters() {
    let doc = facade();
    assert_refused(
        "facade",
        "no n_w",
        &without(doc, "/facades/0/params", "n_w"),
    );
    assert_refused(
        "facade",
        "n_l = 0",
        &with(doc, "/facades/0/params/n_l", json!(0)),
    );
    assert_refused(
        "facade",
        "a 19th parameter",
        &with_key(doc, "/facades/0/params", "w_extra", json!(1.0)),
    );
    assert_refused(
        "facade",
        "a bbox of two numbers",
        &with(doc, "/facades/0/bbox", json!([1, 2])),
    );
}

#[test]
fn gothic_schema_refuses_unknown_kinds_and_bad_references() {
    let doc = gothic();
    assert_refused(
        "gothic",
        "kind 'ogee'",
        &with(doc, "/elements/0/kind", json!("ogee")),
    );
    assert_refused(
        "gothic",
        "parent = \"none\"",
        &with(doc, "/elements/0/parent", json!("none")),
    );
    assert_refused(
        "gothic",
        "support = 1.5",
        &with(doc, "/elements/0/support", json!(1.5)),
    );
    assert_refused(
        "gothic",
        "an element without v",
        &without(doc, "/elements/0", "v"),
    );
}
