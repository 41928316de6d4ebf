//! Python tools for the tests (issue 24: cjio, IfcOpenShell), each in its own virtual
//! environment under `tools/NAME/.venv`, installed on first use from `tools/NAME/requirements.txt`
//! (pinned). Outside CI a tool that cannot be had is skipped with a message saying how to get
//! it; in CI (the `CI` variable set) that is a failure. Included through `#[path]` by every test
//! that runs one of these tools (`cjio.rs`, `ifcopenshell.rs`).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{SystemTime, UNIX_EPOCH};

/// `tools/NAME` at the repository root.
pub fn tools(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tools")
        .join(name)
}

/// `tools/NAME/.venv/RELATIVE` once `ready` holds for it, installing the venv and its pinned
/// requirements if it does not yet.
pub fn install(
    name: &str,
    relative: &str,
    ready: impl Fn(&Path) -> bool,
) -> Result<PathBuf, String> {
    let dir = tools(name);
    let venv = dir.join(".venv");
    let wanted = venv.join(relative);
    if ready(&wanted) {
        return Ok(wanted);
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
        Command::new(venv.join("bin/python"))
            .args([
                "-m",
                "pip",
                "install",
                "--quiet",
                "--disable-pip-version-check",
                "-r",
            ])
            .arg(dir.join("requirements.txt")),
        &format!("`pip install -r tools/{name}/requirements.txt`"),
    )?;
    if ready(&wanted) {
        Ok(wanted)
    } else {
        Err(format!(
            "{} is not usable after installing tools/{name}",
            wanted.display()
        ))
    }
}

/// How to install tool `name` by hand.
pub fn how(name: &str) -> String {
    format!(
        "install Python 3 with its venv module (Debian: python3-venv), or run `python3 -m venv \
         tools/{name}/.venv && tools/{name}/.venv/bin/pip install -r tools/{name}/requirements.txt` \
         from the repository root"
    )
}

/// The installed program, or `None` after saying why it is skipped; a failure in CI.
pub fn available(name: &str, installed: &Result<PathBuf, String>) -> Option<PathBuf> {
    match installed {
        Ok(exe) => Some(exe.clone()),
        Err(why) => {
            if std::env::var_os("CI").is_some() {
                panic!("cannot run {name}: {why}; {}", how(name));
            }
            eprintln!("SKIPPED {name} checks: {why}; {}", how(name));
            None
        }
    }
}

/// A fresh path in the temporary folder for a file named after `name`, ending in `extension`.
pub fn temporary(name: &str, extension: &str) -> PathBuf {
    let nanos = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let stem = name.replace(|c: char| !c.is_ascii_alphanumeric(), "_");
    let file = format!(
        "castellan-{stem}-{}-{nanos}.{extension}",
        std::process::id()
    );
    std::env::temp_dir().join(file)
}
