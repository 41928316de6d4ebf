//! Prints what the clean-up steps added to §5.1.2 did on given drawings (hatch pixels
//! filled, hachure pixels removed, dash links drawn) and, with `--overlay DIR`, writes each
//! drawing's label overlay. Run: `cargo run --release -p plan --example cleanup -- [--hatching]
//! [--hachures] [--no-dashes] [--overlay DIR] FILE...`.

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let has = |f: &str| args.iter().any(|a| a == f);
    let opts = plan::Options {
        hatching: has("--hatching"),
        hachures: has("--hachures"),
        dashes: !has("--no-dashes"),
        ..Default::default()
    };
    let dir = args
        .iter()
        .position(|a| a == "--overlay")
        .and_then(|i| args.get(i + 1).cloned());
    for file in args
        .iter()
        .filter(|a| !a.starts_with("--") && Some(*a) != dir.as_ref())
    {
        let img = match image::open(file) {
            Ok(i) => i,
            Err(e) => {
                eprintln!("{file}: {e}");
                continue;
            }
        };
        match plan::parse(&img, &opts) {
            Ok(p) => {
                println!(
                    "{file}: hatching {} px, hachures {} px, dash links {}, towers {}",
                    p.pre.hatching_pixels, p.pre.hachure_pixels, p.pre.dash_links, p.towers
                );
                if let Some(d) = &dir {
                    let name = file.rsplit('/').next().unwrap_or(file);
                    let out = std::path::Path::new(d).join(format!("{name}.overlay.png"));
                    if let Err(e) = plan::output::overlay(&p, &img.to_luma8()).save(&out) {
                        eprintln!("{}: {e}", out.display());
                    }
                }
            }
            Err(e) => println!("{file}: {e}"),
        }
    }
}
