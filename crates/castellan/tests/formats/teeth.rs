//! Teeth: each schema refuses a document one step away from a real one.

use serde_json::{Value, json};

use crate::runs::*;
use crate::schemas::*;

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
fn stats_schema_refuses_negative_counts_unknown_stages_and_bad_agreements() {
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
    assert_refused(
        "stats",
        "an IoU above 1",
        &with(doc, "/agreement/iou", json!(1.5)),
    );
    assert_refused(
        "stats",
        "an agreement without its tower count",
        &without(doc, "/agreement", "towers"),
    );
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

#[test]
fn project_schema_takes_gothic_element_corrections_and_refuses_bad_ones() {
    let text = "plan = \"plan.png\"\n[[gothic]]\nimage = \"portal.png\"\n\
                [[gothic.element]]\npoint = [412, 300]\napex = 210.0\nwidth = 96.0\n\
                [[gothic.element]]\npoint = [130, 320]\ndelete = true\n\
                [[correspondence]]\nfacade = \"portal.png\"\nfacade_point = [1, 1]\n\
                plan_points = [[1, 1]]\n";
    let doc = toml_to_json(text, "a Gothic project");
    assert_valid("project", "a Gothic project", &doc);
    assert!(integrate::project::Project::from_toml(text).is_ok());
    for (why, bad) in [
        (
            "an unknown key in [[gothic.element]]",
            with_key(&doc, "/gothic/0/element/0", "top", json!(3)),
        ),
        (
            "a width of 0",
            with(&doc, "/gothic/0/element/0/width", json!(0)),
        ),
        ("no point", without(&doc, "/gothic/0/element/1", "point")),
    ] {
        assert_refused("project", why, &bad);
    }
    // The program refuses them too.
    assert!(
        integrate::project::Project::from_toml(&text.replace("width = 96.0", "top = 3")).is_err()
    );
    assert!(
        integrate::project::Project::from_toml(&text.replace("width = 96.0", "width = 0")).is_err()
    );
}
