//! What the integration tests share: a bundled example project read into memory. Each test
//! binary compiles this module and uses a part of it.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::Path;

use integrate::pipeline::InMemory;
use integrate::project::Project;

/// Every file of `examples/NAME` (PROJECT.toml and the files it names), by file name.
pub fn example_files(name: &str) -> BTreeMap<String, Vec<u8>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    std::fs::read_dir(&dir)
        .unwrap()
        .map(|entry| {
            let path = entry.unwrap().path();
            let file = path.file_name().unwrap().to_string_lossy().into_owned();
            (file, std::fs::read(&path).unwrap())
        })
        .collect()
}

/// `examples/NAME`'s project and its files.
pub fn example(name: &str) -> (Project, InMemory) {
    let files = example_files(name);
    let text = String::from_utf8(files["PROJECT.toml"].clone()).unwrap();
    (Project::from_toml(&text).unwrap(), InMemory(files))
}
