//! Time of each stage on the 3000 × 2000 synthetic scan (what the benchmark spends where),
//! and of the whole parse with the learned wall ink and with the rules.
//! Run: `cargo run --release -p plan --example stage_times`.

use std::time::Instant;

fn main() {
    let (img, _) = plan::synth::castle(1, 2.8, 3000, 2000);
    let t = Instant::now();
    let level = plan::binarize::threshold_level(&img);
    let b = plan::binarize::binarize(&img, level);
    println!("  threshold {:?}", t.elapsed());
    let t2 = Instant::now();
    let oc = imageproc::morphology::close(
        &imageproc::morphology::open(&b, imageproc::distance_transform::Norm::LInf, 1),
        imageproc::distance_transform::Norm::LInf,
        1,
    );
    println!("  open + close {:?}", t2.elapsed());
    let t2 = Instant::now();
    let _ = imageproc::region_labelling::connected_components(
        &oc,
        imageproc::region_labelling::Connectivity::Eight,
        image::Luma([0u8]),
    );
    println!(
        "  one imageproc connected-components pass (flood fill used instead) {:?}",
        t2.elapsed()
    );
    let t = Instant::now();
    let (bin, _) = plan::binarize::preprocess(&img, 0.0005);
    println!("preprocess {:?}", t.elapsed());
    let t = Instant::now();
    let mut skel = plan::thin::Mask::from_gray(&bin);
    let passes = plan::thin::thin(&mut skel);
    println!("thin {:?} ({passes} rounds)", t.elapsed());
    let t = Instant::now();
    let g = plan::graph::vectorise(&skel);
    println!("vectorise {:?} ({} edges)", t.elapsed(), g.edges.len());
    let t = Instant::now();
    let _ = plan::graph::faces(&skel);
    println!("faces {:?}", t.elapsed());
    let t = Instant::now();
    let model = plan::ink::shipped();
    let _ = model.wall_probability(&img, img.width(), img.height());
    println!("learned wall ink alone {:?}", t.elapsed());
    let drawing = image::DynamicImage::ImageLuma8(img);
    for ink in [plan::ink::InkMethod::Learned, plan::ink::InkMethod::Rules] {
        let t = Instant::now();
        let opts = plan::Options {
            ink,
            ..Default::default()
        };
        let p = plan::parse(&drawing, &opts).unwrap();
        println!(
            "whole parse, {ink:?} ink {:?} ({} towers)",
            t.elapsed(),
            p.towers
        );
    }
}
