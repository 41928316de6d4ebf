//! Builds castellan's browser code (web/: the model viewer, three.js from the npm registry) into
//! one script, OUT_DIR/viewer.js, that the binary embeds — so the installed binary needs
//! nothing at run time. The build needs Node.js and npm (`npm ci` against web/package-lock.json,
//! then esbuild); set CASTELLAN_VIEWER_JS to a viewer.js built elsewhere to skip them.

use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets it"));
    let web = manifest.join("web");
    println!("cargo:rerun-if-env-changed=CASTELLAN_VIEWER_JS");
    for f in ["package.json", "package-lock.json", "src"] {
        println!("cargo:rerun-if-changed=web/{f}");
    }
    if let Some(prebuilt) = std::env::var_os("CASTELLAN_VIEWER_JS") {
        std::fs::copy(&prebuilt, out.join("viewer.js")).unwrap_or_else(|e| {
            panic!(
                "CASTELLAN_VIEWER_JS={}: {e}",
                Path::new(&prebuilt).display()
            )
        });
        return;
    }
    let work = out.join("web");
    std::fs::create_dir_all(work.join("src")).expect("OUT_DIR is writable");
    let lock = std::fs::read(web.join("package-lock.json")).expect("web/package-lock.json");
    let installed = std::fs::read(work.join("package-lock.json")).ok();
    std::fs::copy(web.join("package.json"), work.join("package.json")).expect("web/package.json");
    for entry in std::fs::read_dir(web.join("src")).expect("web/src") {
        let p = entry.expect("web/src entry").path();
        std::fs::copy(&p, work.join("src").join(p.file_name().expect("a file")))
            .expect("copy web/src");
    }
    if installed.as_deref() != Some(&lock[..]) || !work.join("node_modules").is_dir() {
        std::fs::write(work.join("package-lock.json"), &lock).expect("OUT_DIR is writable");
        npm(
            &work,
            &["ci", "--no-audit", "--no-fund", "--ignore-scripts"],
            &out,
        );
    }
    npm(&work, &["run", "build"], &out);
}

fn npm(dir: &Path, args: &[&str], out: &Path) {
    let status = Command::new("npm")
        .args(args)
        .current_dir(dir)
        .env("OUT", out)
        .status()
        .unwrap_or_else(|e| {
            panic!(
                "castellan's build runs npm to build its web viewer (crates/castellan/web) and could not start it ({e}). Install Node.js 18+ and npm (Debian: apt-get install nodejs npm), or set CASTELLAN_VIEWER_JS to a viewer.js built elsewhere."
            )
        });
    assert!(
        status.success(),
        "npm {} failed in {} ({status})",
        args.join(" "),
        dir.display()
    );
}
