//! Export of the heritage formats (issue 24) against plain glTF, on a 100 000-terminal program
//! of 100 parts (a wall of 100 rows of 1 000 bricks, each row a part): GLB, GLB with
//! structural metadata, CityJSON 2.0 and IFC4. Sizes are printed once before the timings.
//!
//! `cargo bench -p vsg --bench heritage`

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use vsg::RunOptions;
use vsg::export::semantics::{Heritage, Part};
use vsg::export::{ExportOptions, Textures, to_cityjson, to_glb, to_glb_with_metadata, to_ifc};

/// 100 rows of 1 000 unit bricks, the rows (the root's children's children) as parts.
fn wall() -> (vsg::Model, Heritage) {
    let src = "Axiom :: I(\"box\", {1000, 100, 1}){wall};\n\
               wall :: repeat(\"Y\", {1}){row};\n\
               row :: repeat(\"X\", {1}){brick};\n\
               brick :: {j3d.terminal};\n";
    let options = RunOptions {
        limits: vsg::Limits {
            max_depth: 100,
            max_shapes: 3_000_000,
            ..Default::default()
        },
        ..Default::default()
    };
    let model = vsg::run(src, &options).expect("the wall runs");
    let parts: Vec<Part> = model
        .nodes
        .iter()
        .enumerate()
        .filter(|(_, n)| model.symbol(n) == "row")
        .map(|(i, _)| Part {
            node: i as u32,
            more_nodes: Vec::new(),
            name: format!("row{i}"),
            kind: "row".into(),
            attributes: Default::default(),
        })
        .collect();
    assert_eq!(parts.len(), 100);
    assert_eq!(model.terminals().count(), 100_000);
    let heritage = Heritage {
        name: "wall".into(),
        parts,
        ..Default::default()
    };
    (model, heritage)
}

fn export(c: &mut Criterion) {
    let (model, heritage) = wall();
    let o = ExportOptions::default();
    let t = Textures::new();
    let mb = |n: usize| n as f64 / 1e6;
    eprintln!(
        "100k terminals, 100 parts: glb {:.1} MB, glb + metadata {:.1} MB, CityJSON {:.1} MB, IFC {:.1} MB",
        mb(to_glb(&model, &o).unwrap().len()),
        mb(to_glb_with_metadata(&model, &o, &t, &heritage)
            .unwrap()
            .len()),
        mb(to_cityjson(&model, &heritage, &o).unwrap().len()),
        mb(to_ifc(&model, &heritage, &o).unwrap().len()),
    );
    let mut group = c.benchmark_group("heritage export, 100k terminals");
    group.sample_size(10);
    group.bench_function("glb", |b| b.iter(|| to_glb(black_box(&model), &o).unwrap()));
    group.bench_function("glb + structural metadata", |b| {
        b.iter(|| to_glb_with_metadata(black_box(&model), &o, &t, &heritage).unwrap())
    });
    group.bench_function("CityJSON", |b| {
        b.iter(|| to_cityjson(black_box(&model), &heritage, &o).unwrap())
    });
    group.bench_function("IFC", |b| {
        b.iter(|| to_ifc(black_box(&model), &heritage, &o).unwrap())
    });
    group.finish();
}

criterion_group!(benches, export);
criterion_main!(benches);
