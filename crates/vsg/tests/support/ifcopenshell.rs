//! IfcOpenShell for the tests (issue 24): installed on first use into `tools/ifcopenshell/.venv`
//! from the pinned requirements, and [`check`], its report on an IFC text (`check.py`: schema,
//! counts, validation with the EXPRESS rules, volumes). Shared by `crates/vsg/tests/ifc.rs` and
//! `crates/integrate/tests/heritage.rs` (the real demo's file) through `#[path]`.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;
use std::time::{SystemTime, UNIX_EPOCH};

use serde_json::Value;

const HOW: &str = "install Python 3.11 with venv, then `python3 -m venv tools/ifcopenshell/.venv \
                   && tools/ifcopenshell/.venv/bin/pip install -r \
                   tools/ifcopenshell/requirements.txt` from the repository root";

pub fn tools() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tools/ifcopenshell")
}

/// The venv's Python with IfcOpenShell, or `None` (after saying why) when it cannot be had
/// outside CI. Installed from the pinned requirements on first use.
fn python() -> Option<PathBuf> {
    static INSTALL: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    let why = match INSTALL.get_or_init(|| install(&tools())) {
        Ok(python) => return Some(python.clone()),
        Err(why) => why.clone(),
    };
    if std::env::var_os("CI").is_some() {
        panic!("cannot run IfcOpenShell: {why}; {HOW}");
    }
    eprintln!("SKIPPED IfcOpenShell checks: {why}; {HOW}");
    None
}

fn install(dir: &Path) -> Result<PathBuf, String> {
    let venv = dir.join(".venv");
    let python = venv.join("bin/python");
    let ready = |p: &Path| {
        Command::new(p)
            .args([
                "-c",
                "import ifcopenshell, ifcopenshell.geom, ifcopenshell.validate, pytest",
            ])
            .output()
            .is_ok_and(|o| o.status.success())
    };
    if ready(&python) {
        return Ok(python);
    }
    let run = |cmd: &mut Command, what: &str| -> Result<(), String> {
        let out = cmd
            .output()
            .map_err(|e| format!("cannot run {what}: {e}"))?;
        if out.status.success() {
            Ok(())
        } else {
            Err(format!(
                "{what} failed: {}",
                String::from_utf8_lossy(&out.stderr).trim()
            ))
        }
    };
    if !venv.join("bin/pip").is_file() {
        run(
            Command::new("python3").args(["-m", "venv"]).arg(&venv),
            "`python3 -m venv`",
        )?;
    }
    run(
        Command::new(venv.join("bin/pip"))
            .args(["install", "--quiet", "--disable-pip-version-check", "-r"])
            .arg(dir.join("requirements.txt")),
        "`pip install -r tools/ifcopenshell/requirements.txt`",
    )?;
    if ready(&python) {
        Ok(python)
    } else {
        Err("ifcopenshell does not import after installing it".into())
    }
}

/// IfcOpenShell's report on `ifc` (see check.py), or `None` when skipped.
pub fn check(name: &str, ifc: &str) -> Option<Value> {
    let python = python()?;
    let nanos = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let file = format!("castellan-{name}-{}-{nanos}.ifc", std::process::id());
    let path = std::env::temp_dir().join(file);
    std::fs::write(&path, ifc).expect("write the temporary .ifc");
    let out = Command::new(python)
        .arg(tools().join("check.py"))
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
