//! The workspace's layout rule (ARCHITECTURE.md, issue 20): the files of every crate import one
//! way, with no circles, test code included. `scripts/module_cycles.py` finds them; this test
//! runs it so a circle fails the build where it is made.

use std::path::Path;
use std::process::Command;

#[test]
fn no_crate_has_circles_between_its_files() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = match Command::new("python3")
        .arg(root.join("scripts/module_cycles.py"))
        .output()
    {
        Ok(out) => out,
        Err(e) => {
            eprintln!("skipped: python3 is needed to run scripts/module_cycles.py ({e})");
            return;
        }
    };
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{report}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let crates = report.lines().filter(|l| !l.starts_with(' ')).count();
    assert_eq!(crates, 8, "one line per crate: {report}");
    let clean = report.lines().filter(|l| l.trim() == "no circles").count();
    assert_eq!(
        clean, crates,
        "circles, with test code counted too:\n{report}"
    );
}
