//! cjio, 3D-GIS's CityJSON tool, for the tests (issue 24): [`assert_cjio_reads`] checks that it
//! reads a document as one Building with the given parts and vertices. Installed on first use
//! into `tools/cjio/.venv` ([`super::venv`]); the including test declares `mod venv` beside it.

use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

use super::venv;

/// The cjio program, or `None` (after saying why) when it cannot run outside CI.
fn cjio() -> Option<PathBuf> {
    static INSTALL: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    let installed = INSTALL.get_or_init(|| venv::install("cjio", "bin/cjio", |exe| exe.is_file()));
    venv::available("cjio", installed)
}

/// `cjio FILE info --long` on `text`, or `None` when cjio cannot run here.
fn cjio_info(name: &str, text: &str) -> Option<String> {
    let exe = cjio()?;
    let path = venv::temporary(name, "city.json");
    std::fs::write(&path, text).expect("write the temporary file");
    let out = Command::new(&exe)
        .arg(&path)
        .args(["info", "--long"])
        .output()
        .expect("run cjio");
    let _ = std::fs::remove_file(&path);
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "cjio cannot read {name}:\n{stdout}\n{stderr}"
    );
    assert!(
        !stderr.contains("Error") && !stdout.contains("Error"),
        "cjio: {name}:\n{stdout}\n{stderr}"
    );
    eprintln!("cjio info --long: {name}:\n{stdout}");
    Some(stdout)
}

/// Asserts that cjio reads the file as one Building with `parts` BuildingParts and
/// `vertices` vertices, in CityJSON 2.0.
pub fn assert_cjio_reads(name: &str, text: &str, parts: usize, vertices: usize) {
    let Some(info) = cjio_info(name, text) else {
        return;
    };
    let lines: Vec<&str> = info.lines().map(str::trim).collect();
    for expected in [
        "CityJSON version = 2.0".to_string(),
        "|-- Building (1)".to_string(),
        format!("|-- BuildingPart ({parts})"),
        format!("vertices_total = {vertices}"),
    ] {
        assert!(
            lines.contains(&expected.as_str()),
            "{expected:?} in\n{info}"
        );
    }
}
