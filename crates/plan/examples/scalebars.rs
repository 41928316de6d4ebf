//! Runs the scale-bar finder (`plan::scalebar`, issue 11) over every plan of
//! `../shared/data/castle_drawings_pd` and prints one line per drawing: the bar found (ends
//! and length in pixels) or `-`, then how many were found. docs/plan.md has these bars checked
//! by eye. Run: `cargo run --release -p plan --example scalebars`.

#[path = "../tests/common/mod.rs"]
mod common;

fn main() {
    let Some(data) = common::castle_drawings() else {
        return;
    };
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(data.join("manifest.json")).unwrap())
            .unwrap();
    let mut found = 0;
    let mut total = 0;
    for item in manifest.as_array().unwrap() {
        if item["kind"] != "plan" {
            continue;
        }
        let file = item["file"].as_str().unwrap();
        let grey = image::open(data.join(file)).unwrap().to_luma8();
        total += 1;
        match plan::scalebar::find(&grey) {
            Some(b) => {
                found += 1;
                println!(
                    "{file}\t{} {} {} {}\t{}",
                    b.x0, b.y0, b.x1, b.y1, b.length_px
                );
            }
            None => println!("{file}\t-"),
        }
    }
    eprintln!("bars found on {found} of {total} plans");
}
