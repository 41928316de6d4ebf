//! The file contracts of docs/formats.md, checked against the JSON Schemas of docs/schemas/
//! (hand-written from the code, so an independent contract): every schema is a valid draft
//! 2020-12 schema; the PROJECT.toml, TRAINING.json and LINES.json files shipped in the
//! repository follow theirs; the outputs of real runs of the binary (`demo`, `plan`, `facade`,
//! `gothic`, `vsg run`) follow theirs; and each schema refuses a file a step away from a real
//! one (a wrong label, side, unit or unknown key), so it has teeth. Each command runs once,
//! shared by the tests that read its outputs.

mod facade_fix;
#[path = "../fixtures/mod.rs"]
mod fixtures;
mod outputs;
mod runs;
mod schemas;
mod shipped;
mod teeth;
