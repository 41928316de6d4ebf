//! IfcOpenShell for the tests (issue 24): installed on first use into `tools/ifcopenshell/.venv`
//! ([`super::venv`]; the including test declares `mod venv` beside it), and [`check`], its
//! report on an IFC text (`check.py`: schema, counts, validation with the EXPRESS rules,
//! volumes). Shared by `crates/vsg/tests/ifc.rs` and
//! `crates/integrate/tests/heritage.rs` (the real demo's file) through `#[path]`.

use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

use serde_json::Value;

use super::venv;

/// The venv's Python with IfcOpenShell, or `None` (after saying why) when it cannot be had
/// outside CI.
fn python() -> Option<PathBuf> {
    static INSTALL: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    let installed = INSTALL.get_or_init(|| {
        venv::install("ifcopenshell", "bin/python", |python| {
            Command::new(python)
                .args([
                    "-c",
                    "import ifcopenshell, ifcopenshell.geom, ifcopenshell.validate, pytest",
                ])
                .output()
                .is_ok_and(|o| o.status.success())
        })
    });
    venv::available("ifcopenshell", installed)
}

/// IfcOpenShell's report on `ifc` (see check.py), or `None` when skipped.
pub fn check(name: &str, ifc: &str) -> Option<Value> {
    let python = python()?;
    let path = venv::temporary(name, "ifc");
    std::fs::write(&path, ifc).expect("write the temporary .ifc");
    let out = Command::new(python)
        .arg(venv::tools("ifcopenshell").join("check.py"))
        .arg(&path)
        .arg("--express")
        .output()
        .expect("run check.py");
    let _ = std::fs::remove_file(&path);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "check.py fails on {name}:\n{stderr}");
    let report: Value = serde_json::from_slice(&out.stdout).expect("a JSON report");
    assert_eq!(report["schema"], "IFC4", "{name}");
    assert_eq!(report["errors"], serde_json::json!([]), "{name}: {stderr}");
    assert_eq!(report["duplicate_guids"], serde_json::json!([]), "{name}");
    Some(report)
}
