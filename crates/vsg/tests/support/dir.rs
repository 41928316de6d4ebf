//! Imports resolved inside one directory (`library/`, or a demo's output folder), as
//! `castellan vsg run` resolves them beside the importing file: the one resolver the tests that
//! run real programs share.

use std::path::PathBuf;

/// Imports resolve inside this directory.
pub struct Dir(pub PathBuf);

impl vsg::import::Resolver for Dir {
    fn load(&mut self, _from: &str, path: &str) -> Result<(String, String), String> {
        std::fs::read_to_string(self.0.join(path))
            .map(|t| (path.to_string(), t))
            .map_err(|e| e.to_string())
    }
}
