//! Tests of the volumetric Booleans of unique shapes (§7.1.2, figure 7.3) on box meshes of
//! Table 7.1: difference, union, intersection, batched unions, empty results and refused
//! input. In a file of their own because they build their inputs with `crate::shape`, which
//! `csg.rs` itself does not use.

use super::*;
use crate::shape::{Primitive, ShapeType, Tessellation};

fn boxed(size: [f64; 3], at: [f64; 3]) -> TriMesh {
    let mut m = Primitive::new(ShapeType::Box, &size)
        .unwrap()
        .mesh(&Tessellation::default());
    for p in &mut m.positions {
        for k in 0..3 {
            p[k] += at[k];
        }
    }
    m
}

#[test]
fn box_minus_inner_box_is_a_closed_shell() {
    let outer = boxed([4.0, 4.0, 4.0], [0.0; 3]);
    let through = boxed([2.0, 2.0, 6.0], [0.0; 3]);
    let r = Manifold
        .combine(BoolOp::Difference, &[outer, through])
        .unwrap();
    assert!(r.is_closed_oriented());
    assert!((r.signed_volume() - (64.0 - 16.0)).abs() < 1e-9);
}

#[test]
fn union_and_intersection_of_overlapping_boxes() {
    let a = boxed([2.0, 2.0, 2.0], [0.0; 3]);
    let b = boxed([2.0, 2.0, 2.0], [1.0, 0.0, 0.0]);
    let u = Manifold
        .combine(BoolOp::Union, &[a.clone(), b.clone()])
        .unwrap();
    let i = Manifold.combine(BoolOp::Intersection, &[a, b]).unwrap();
    assert!(u.is_closed_oriented() && i.is_closed_oriented());
    assert!((u.signed_volume() - 12.0).abs() < 1e-9);
    assert!((i.signed_volume() - 4.0).abs() < 1e-9);
}

#[test]
fn batched_union_keeps_disjoint_groups_apart_and_merges_overlaps() {
    let meshes = [
        boxed([2.0; 3], [0.0; 3]),
        boxed([2.0; 3], [1.0, 0.0, 0.0]),
        boxed([2.0; 3], [0.0, 1.0, 0.0]),
        boxed([1.0; 3], [10.0, 0.0, 0.0]),
    ];
    let u = Manifold.combine(BoolOp::Union, &meshes).unwrap();
    assert!(u.is_closed_oriented());
    // Three overlapping 2-cubes, by inclusion-exclusion 24 - 4 - 4 - 2 + 2 = 16, plus the
    // far unit cube.
    assert!(
        (u.signed_volume() - 17.0).abs() < 1e-9,
        "{}",
        u.signed_volume()
    );
    let wall = boxed([10.0, 4.0, 1.0], [0.0; 3]);
    let windows: Vec<_> = (0..4)
        .map(|i| boxed([1.0, 1.0, 2.0], [-3.0 + 2.0 * i as f64, 0.0, 0.0]))
        .collect();
    let mut all = vec![wall];
    all.extend(windows);
    let d = Manifold.combine(BoolOp::Difference, &all).unwrap();
    assert!(d.is_closed_oriented());
    assert!((d.signed_volume() - 36.0).abs() < 1e-9);
}

#[test]
fn disjoint_intersection_is_empty() {
    let a = boxed([1.0; 3], [0.0; 3]);
    let b = boxed([1.0; 3], [5.0, 0.0, 0.0]);
    let i = Manifold.combine(BoolOp::Intersection, &[a, b]).unwrap();
    assert!(i.triangles.is_empty());
}

#[test]
fn open_input_is_refused_with_its_index() {
    let a = boxed([1.0; 3], [0.0; 3]);
    let mut b = a.clone();
    b.triangles.pop();
    let e = Manifold.combine(BoolOp::Union, &[a, b]).unwrap_err();
    assert!(matches!(e, CsgError::BadInput { index: 1, .. }), "{e}");
}
