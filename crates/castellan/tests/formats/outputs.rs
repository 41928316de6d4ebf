//! Outputs of real runs follow their schemas.

use serde_json::Value;

use crate::runs::*;
use crate::schemas::*;

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
        assert!(stats["agreement"]["iou"].is_number(), "{stats}");
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
    assert!(stats.get("agreement").is_none(), "{stats}");
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
