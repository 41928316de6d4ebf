//! Production and export speed (issue: 1 M terminals produced < 1 s, 100 k exported < 1 s on
//! 2 cores), a peer comparison against the `symbios-shape` CGA engine on the same program, and
//! compile time against the number of rules (issue 19: it was quadratic, each rule's line found
//! by rescanning the text; 32 k rules took 10 s).
//!
//! `cargo bench -p vsg --bench vsg`

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use vsg::RunOptions;
use vsg::export::{ExportOptions, to_glb};

/// A `rows` x `cols` wall of 1 x 1 x 1 bricks from two nested repeats.
fn brick_wall(rows: u32, cols: u32) -> String {
    format!(
        "Axiom :: I(\"box\", {{{cols}, {rows}, 1}}){{wall}};\n\
         wall :: repeat(\"Y\", {{1}}){{row}};\n\
         row :: repeat(\"X\", {{1}}){{brick}};\n\
         brick :: {{j3d.terminal}};\n"
    )
}

fn options() -> RunOptions {
    RunOptions {
        limits: vsg::Limits {
            max_depth: 100,
            max_shapes: 3_000_000,
            ..Default::default()
        },
        ..Default::default()
    }
}

fn production(c: &mut Criterion) {
    let mut group = c.benchmark_group("produce");
    group.sample_size(10);
    let million = brick_wall(1000, 1000);
    group.bench_function("1M bricks, nested repeat", |b| {
        b.iter(|| vsg::run(black_box(&million), &options()).unwrap())
    });
    let peer_size = brick_wall(99, 1000);
    group.bench_function("99k bricks, nested repeat (vsg)", |b| {
        b.iter(|| vsg::run(black_box(&peer_size), &options()).unwrap())
    });
    group.bench_function("99k bricks, nested repeat (symbios-shape)", |b| {
        b.iter(|| symbios_brick_wall(99, 1000))
    });
    group.finish();
}

/// The same program through `symbios-shape` (a CGA engine whose derivations are capped at
/// 100 000 queued shapes, hence the 99 k size for the comparison).
fn symbios_brick_wall(rows: u32, cols: u32) -> usize {
    use symbios_shape::grammar::parse_statement;
    use symbios_shape::{Interpreter, Quat, Scope, Vec3};
    let mut interp = Interpreter::new();
    interp.max_terminals = 2_000_000;
    for line in [
        "Wall --> Repeat(Y, 1) { Row }",
        "Row --> Repeat(X, 1) { Brick }",
        "Brick --> I(\"brick\")",
    ] {
        interp
            .add_statement(parse_statement(line).unwrap())
            .unwrap();
    }
    let scope = Scope::new(
        Vec3::ZERO,
        Quat::IDENTITY,
        Vec3::new(cols as f64, rows as f64, 1.0),
    );
    let model = interp.derive(scope, "Wall").unwrap();
    model.terminals.len()
}

fn export(c: &mut Criterion) {
    let mut group = c.benchmark_group("export");
    group.sample_size(10);
    let model = vsg::run(&brick_wall(100, 1000), &options()).unwrap();
    group.bench_function("100k terminals to glb", |b| {
        b.iter(|| to_glb(black_box(&model), &ExportOptions::default()).unwrap())
    });
    group.finish();
}

/// `n` one-line rules (about 38 bytes each) after an axiom that uses the first: the program
/// of issue 19, 32 k rules in 1.2 MB.
pub fn many_rules(n: usize) -> String {
    let mut src = String::from("Axiom :: I(\"box\", {1, 1, 1}){s0};\n");
    for i in 0..n {
        src += &format!("s{i} :: T(0, 0.{}, 0) {{j3d.terminal}};\n", i % 10);
    }
    src
}

fn compile(c: &mut Criterion) {
    let mut group = c.benchmark_group("compile");
    group.sample_size(10);
    for n in [4_000, 32_000] {
        let src = many_rules(n);
        group.bench_function(format!("{n} rules ({} KB)", src.len() >> 10), |b| {
            b.iter(|| vsg::run(black_box(&src), &options()).unwrap())
        });
    }
    group.finish();
}

fn check_sizes(_: &mut Criterion) {
    assert_eq!(symbios_brick_wall(99, 1000), 99_000);
    let m = vsg::run(&brick_wall(99, 1000), &options()).unwrap();
    assert_eq!(m.terminals().count(), 99_000);
}

criterion_group!(benches, check_sizes, production, export, compile);
criterion_main!(benches);
