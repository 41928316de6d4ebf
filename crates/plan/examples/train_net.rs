//! Trains the wall-ink network that ships with castellan (issue 26), from a seed: the same
//! synthetic plans and painted public-domain plans as the forest (`train_ink`; needs
//! `../shared/data/castle_drawings_pd`). With `--hold SOURCE` (repeatable; a part of the
//! book's name) that book's painted plans are left out of training and the network's wall
//! IoU on them is printed beside Otsu's threshold, per drawing and per book; `--evaluate FILE`
//! reads a network written before instead of training one.
//!
//! `cargo run --release -p plan --example train_net -- [--seed 1] [--steps 600]
//! [--synthetic 60] [--hold SOURCE]… [--evaluate FILE] [--out crates/plan/models/wall_net.safetensors]`

#[path = "common/ink_data.rs"]
mod ink_data;

use std::path::PathBuf;

use plan::ink::net_train::{NetParams, train_net};
use plan::ink::train::{confusion, source_of};

fn main() {
    let mut np = NetParams::default();
    let mut synthetic = 60usize;
    let mut hold: Vec<String> = Vec::new();
    let mut evaluate: Option<PathBuf> = None;
    let mut out = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("models/wall_net.safetensors");
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut k = 0;
    while k < args.len() {
        let flag = args[k].as_str();
        const FLAGS: [&str; 6] = [
            "--seed",
            "--steps",
            "--synthetic",
            "--hold",
            "--evaluate",
            "--out",
        ];
        if !FLAGS.contains(&flag) {
            ink_data::fail(flag, format!("unknown argument ({})", FLAGS.join(", ")));
        }
        let Some(value) = args.get(k + 1).cloned() else {
            ink_data::fail(flag, "needs a value")
        };
        match flag {
            "--seed" => np.seed = parse(&value, flag),
            "--steps" => np.steps = parse(&value, flag),
            "--synthetic" => synthetic = parse(&value, flag),
            "--hold" => hold.push(value),
            "--evaluate" => evaluate = Some(PathBuf::from(value)),
            _ => out = PathBuf::from(value),
        }
        k += 2;
    }
    let data = ink_data::painted_data_dir();
    let (mut painted, mut held) = (Vec::new(), Vec::new());
    for r in ink_data::recipes() {
        let source = source_of(&r.book);
        let sheet = ink_data::painted_sheet(&data, &r);
        if hold.iter().any(|h| source.contains(h.as_str())) {
            held.push((r.file.clone(), source, sheet));
        } else {
            painted.push(sheet);
        }
    }
    if let Some(f) = evaluate {
        let bytes =
            std::fs::read(&f).unwrap_or_else(|e| ink_data::fail(&f.display().to_string(), e));
        let net = plan::ink::net::WallNet::from_bytes(&bytes)
            .unwrap_or_else(|e| ink_data::fail(&f.display().to_string(), e));
        println!("{}: {}", f.display(), net.provenance);
        report(&net, &held);
        return;
    }
    let synth = ink_data::synthetic(synthetic, np.seed);
    let provenance = format!(
        "seed {}; {} steps of {} crops of {} px; {synthetic} synthetic plans; {} painted plans (crates/plan/data/wall_masks*.json){}",
        np.seed,
        np.steps,
        np.batch,
        np.crop,
        painted.len(),
        if hold.is_empty() {
            String::new()
        } else {
            format!(", without {}", hold.join(", "))
        }
    );
    let t = std::time::Instant::now();
    let (net, bytes) = train_net(&painted, &synth, &np, &provenance, &mut |step, loss| {
        eprintln!(
            "step {step}: loss {loss:.4} ({:.0} s)",
            t.elapsed().as_secs_f64()
        )
    })
    .unwrap_or_else(|e| ink_data::fail("training", e));
    std::fs::write(&out, &bytes).unwrap_or_else(|e| ink_data::fail(&out.display().to_string(), e));
    println!(
        "{}: {} bytes, trained in {:.0} s ({provenance})",
        out.display(),
        bytes.len(),
        t.elapsed().as_secs_f64()
    );
    report(&net, &held);
}

/// Wall IoU (P > 0.5) of `net` and of Otsu's threshold on the held-out painted drawings: per
/// drawing, per book (pooled, as `ink_eval` reports the forest's) and over all.
fn report(net: &plan::ink::net::WallNet, held: &[(String, String, plan::ink::train::Sheet)]) {
    if held.is_empty() {
        return;
    }
    println!("| held-out drawing | wall IoU, network | Otsu |");
    println!("| --- | --- | --- |");
    // Per book: the network's sums, then Otsu's.
    let mut by_source: std::collections::BTreeMap<&str, [[usize; 3]; 2]> = Default::default();
    for (file, source, sheet) in held {
        let (w, h) = sheet.grey.dimensions();
        let p = net.wall_probability(&sheet.grey, w, h);
        let (a, b) = (
            confusion(&p, &sheet.truth),
            confusion(&ink_data::otsu_map(&sheet.grey), &sheet.truth),
        );
        println!(
            "| {file} | {} | {} |",
            ink_data::iou([a.0, a.1, a.2]),
            ink_data::iou([b.0, b.1, b.2])
        );
        let sum = by_source.entry(source).or_default();
        ink_data::add(&mut sum[0], a);
        ink_data::add(&mut sum[1], b);
    }
    let mut all = [[0usize; 3]; 2];
    for (source, [n, o]) in &by_source {
        println!(
            "| {source} | {} | {} |",
            ink_data::iou(*n),
            ink_data::iou(*o)
        );
        ink_data::add(&mut all[0], (n[0], n[1], n[2]));
        ink_data::add(&mut all[1], (o[0], o[1], o[2]));
    }
    println!(
        "| all held out | {} | {} |",
        ink_data::iou(all[0]),
        ink_data::iou(all[1])
    );
}

fn parse<T: std::str::FromStr>(v: &str, name: &str) -> T
where
    T::Err: std::fmt::Display,
{
    v.parse().unwrap_or_else(|e| ink_data::fail(name, e))
}
