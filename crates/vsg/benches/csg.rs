//! Speed of unique shapes (§7.1.2) through `boolmesh`: a 20 x 10 x 1 wall minus 100 window
//! boxes, and a cylinder-minus-cylinder ring. `csg_peer.py` times the same solids in Python
//! `manifold3d` in the same run and prints the ratio.
//!
//! `python3 crates/vsg/benches/csg_peer.py` (runs this bench, then the peer), or
//! `cargo bench -p vsg --bench csg` alone.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use vsg::csg::{BoolOp, Manifold, MeshBoolean};
use vsg::mesh::TriMesh;
use vsg::shape::{Primitive, ShapeType, Tessellation};

fn placed(kind: ShapeType, params: &[f64], at: [f64; 3]) -> TriMesh {
    let mut m = Primitive::new(kind, params)
        .unwrap()
        .mesh(&Tessellation { segments: 64 });
    for p in &mut m.positions {
        for k in 0..3 {
            p[k] += at[k];
        }
    }
    m
}

/// The wall first, then a 10 x 10 grid of 1 x 0.6 x 2 windows through it (the peer script
/// builds the same grid).
pub fn wall_and_windows() -> Vec<TriMesh> {
    let mut meshes = vec![placed(ShapeType::Box, &[20.0, 10.0, 1.0], [0.0; 3])];
    for row in 0..10 {
        for col in 0..10 {
            let at = [-9.0 + 2.0 * col as f64, -4.5 + row as f64, 0.0];
            meshes.push(placed(ShapeType::Box, &[1.0, 0.6, 2.0], at));
        }
    }
    meshes
}

/// A radius-2 cylinder of height 1 minus a radius-1.5 cylinder of height 2, 64 segments.
pub fn ring() -> Vec<TriMesh> {
    vec![
        placed(ShapeType::Cylinder, &[2.0, 1.0], [0.0; 3]),
        placed(ShapeType::Cylinder, &[1.5, 2.0], [0.0; 3]),
    ]
}

fn booleans(c: &mut Criterion) {
    let mut group = c.benchmark_group("csg");
    group.sample_size(20);
    let wall = wall_and_windows();
    let r = Manifold.combine(BoolOp::Difference, &wall).unwrap();
    assert!(r.is_closed_oriented());
    assert!((r.signed_volume() - (200.0 - 100.0 * 0.6)).abs() < 1e-9);
    group.bench_function("wall minus 100 windows", |b| {
        b.iter(|| {
            Manifold
                .combine(BoolOp::Difference, black_box(&wall))
                .unwrap()
        })
    });
    let ring = ring();
    assert!(
        Manifold
            .combine(BoolOp::Difference, &ring)
            .unwrap()
            .is_closed_oriented()
    );
    group.bench_function("cylinder minus cylinder", |b| {
        b.iter(|| {
            Manifold
                .combine(BoolOp::Difference, black_box(&ring))
                .unwrap()
        })
    });
    group.finish();
}

criterion_group!(benches, booleans);
criterion_main!(benches);
