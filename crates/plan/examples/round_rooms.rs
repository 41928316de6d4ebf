//! Prints the rooms of one drawing that fit a circle, with their labels and the tower count:
//! the measure of vault-rib removal on Coucy (issue 11; 5 round towers drawn). Run:
//! `cargo run --release -p plan --example round_rooms -- IMAGE [--thin-lines F]`.

use plan::fit::Fit;
use plan::label::Label;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let Some(path) = args.get(1) else {
        eprintln!("usage: round_rooms IMAGE [--thin-lines F]");
        std::process::exit(2);
    };
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .map(|v| v.parse::<f64>().expect("a number"))
    };
    let opts = plan::Options {
        thin_lines: value("--thin-lines").unwrap_or(plan::Options::default().thin_lines),
        ..Default::default()
    };
    let img = image::open(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let p = plan::parse(&img, &opts).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut round = 0;
    let mut round_towers = 0;
    for f in &p.faces {
        if let Some(Fit::Circle { center, radius, .. }) = f.shape {
            if f.label == Label::CastleSurroundings {
                continue;
            }
            round += 1;
            round_towers += usize::from(f.label == Label::TowerRoom);
            println!(
                "circle at ({:.0}, {:.0}) r {:.1}: {:?}",
                center[0], center[1], radius, f.label
            );
        }
    }
    println!(
        "{path}: {round} round rooms ({round_towers} tower rooms), {} towers, {} thin-line pixels removed",
        p.towers, p.pre.thin_line_pixels
    );
    if let Some(dir) = args
        .iter()
        .position(|a| a == "--overlay")
        .and_then(|i| args.get(i + 1))
    {
        plan::output::overlay(&p, &img.to_luma8())
            .save(dir)
            .unwrap();
    }
}
