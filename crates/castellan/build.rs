//! Builds castellan's browser code (web/: the report's model viewer and the `castellan serve`
//! app, three.js from the npm registry) into two scripts, OUT_DIR/viewer.js and OUT_DIR/app.js,
//! that the binary embeds — so the installed binary needs nothing at run time. The build needs
//! Node.js and npm (`npm ci` against web/package-lock.json, then esbuild); set
//! CASTELLAN_VIEWER_JS and CASTELLAN_APP_JS to scripts built elsewhere to skip them.

use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets it"));
    let web = manifest.join("web");
    println!("cargo:rerun-if-env-changed=CASTELLAN_VIEWER_JS");
    println!("cargo:rerun-if-env-changed=CASTELLAN_APP_JS");
    for f in ["package.json", "package-lock.json", "src"] {
        println!("cargo:rerun-if-changed=web/{f}");
    }
    let prebuilt = [
        ("CASTELLAN_VIEWER_JS", "viewer.js"),
        ("CASTELLAN_APP_JS", "app.js"),
    ]
    .map(|(var, file)| (var, file, std::env::var_os(var)));
    if prebuilt.iter().any(|(_, _, p)| p.is_some()) {
        for (var, file, path) in prebuilt {
            let path = path.unwrap_or_else(|| {
                panic!("{var} is not set: set both CASTELLAN_VIEWER_JS and CASTELLAN_APP_JS, or neither")
            });
            std::fs::copy(&path, out.join(file))
                .unwrap_or_else(|e| panic!("{var}={}: {e}", Path::new(&path).display()));
        }
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
                "castellan's build runs npm to build its web viewer (crates/castellan/web) and could not start it ({e}). Install Node.js 18+ and npm (Debian: apt-get install nodejs npm), or set CASTELLAN_VIEWER_JS and CASTELLAN_APP_JS to scripts built elsewhere."
            )
        });
    assert!(
        status.success(),
        "npm {} failed in {} ({status})",
        args.join(" "),
        dir.display()
    );
}
