//! The schemas of docs/schemas/, compiled with their cross-file references, and the
//! assertions and document edits the tests use.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use assert_cmd::Command;
use jsonschema::{Registry, Resource, Validator};
use serde_json::Value;

/// Every schema: the file contract it checks.
pub const SCHEMAS: [&str; 8] = [
    "project", "training", "lines", "plan", "facade", "gothic", "estimate", "stats",
];

/// Schemas refer to each other by relative file name (`training.schema.json`); they are
/// registered under this base so no reference leaves the test.
pub const BASE: &str = "file:///castellan/docs/schemas/";

pub fn castellan() -> Command {
    Command::cargo_bin("castellan").unwrap()
}

pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

pub fn schema_file(name: &str) -> PathBuf {
    repo().join(format!("docs/schemas/{name}.schema.json"))
}

pub fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: not JSON: {e}", path.display()))
}

/// PROJECT.toml as the JSON document its schema describes.
pub fn toml_to_json(text: &str, what: &str) -> Value {
    let doc: toml::Value = toml::from_str(text).unwrap_or_else(|e| panic!("{what}: {e}"));
    serde_json::to_value(doc).unwrap()
}

/// The schemas, parsed, by name.
pub fn schema_documents() -> &'static BTreeMap<&'static str, Value> {
    static DOCS: OnceLock<BTreeMap<&'static str, Value>> = OnceLock::new();
    DOCS.get_or_init(|| {
        SCHEMAS
            .iter()
            .map(|&name| (name, read_json(&schema_file(name))))
            .collect()
    })
}

/// The registry every validator resolves `$ref`s in: all schemas, under [`BASE`].
pub fn registry() -> &'static Registry<'static> {
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
pub fn validator(name: &str) -> Validator {
    let doc = &schema_documents()[name];
    jsonschema::options()
        .with_registry(registry())
        .with_base_uri(format!("{BASE}{name}.schema.json"))
        .build(doc)
        .unwrap_or_else(|e| panic!("docs/schemas/{name}.schema.json does not compile: {e}"))
}

/// Every way `doc` (the file `file`) breaks schema `name`, one line each: the file, the path in
/// the document, the message and the path in the schema.
pub fn violations(name: &str, file: &str, doc: &Value) -> Vec<String> {
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
pub fn assert_valid(name: &str, file: &str, doc: &Value) {
    let errors = violations(name, file, doc);
    assert!(
        errors.is_empty(),
        "{file} breaks docs/schemas/{name}.schema.json:\n{}",
        errors.join("\n")
    );
}

/// Fails unless `doc` breaks schema `name` (a schema with teeth); `why` says what is wrong.
pub fn assert_refused(name: &str, why: &str, doc: &Value) {
    assert!(
        !validator(name).is_valid(doc),
        "docs/schemas/{name}.schema.json accepts {why}: {doc}"
    );
}

/// A copy of `doc` with the value at the JSON pointer `at` replaced by `value`.
pub fn with(doc: &Value, at: &str, value: Value) -> Value {
    let mut out = doc.clone();
    *out.pointer_mut(at)
        .unwrap_or_else(|| panic!("no {at} in the document")) = value;
    out
}

/// A copy of `doc` without the key `key` of the object at the JSON pointer `parent`.
pub fn without(doc: &Value, parent: &str, key: &str) -> Value {
    let mut out = doc.clone();
    out.pointer_mut(parent)
        .and_then(Value::as_object_mut)
        .unwrap_or_else(|| panic!("no object {parent} in the document"))
        .remove(key)
        .unwrap_or_else(|| panic!("no {parent}/{key} in the document"));
    out
}

/// A copy of `doc` with `key = value` added to (or replaced in) the object at `parent`.
pub fn with_key(doc: &Value, parent: &str, key: &str, value: Value) -> Value {
    let mut out = doc.clone();
    out.pointer_mut(parent)
        .and_then(Value::as_object_mut)
        .unwrap_or_else(|| panic!("no object {parent} in the document"))
        .insert(key.to_string(), value);
    out
}

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
