//! Invariants every primitive must satisfy: closed oriented meshes whose volume converges to the
//! analytic one, and splits along every allowed axis that conserve volume and stay inside.

use super::{Axis, Piece, Primitive, ShapeError, ShapeType, Tessellation};
use std::f64::consts::{PI, TAU};

/// One representative of each type, with asymmetric parameters so mixed-up axes show.
fn samples() -> Vec<Primitive> {
    use ShapeType::*;
    let p = |k, v: &[f64]| Primitive::new(k, v).unwrap_or_else(|e| panic!("{k}: {e}"));
    vec![
        p(Box, &[4.0, 3.0, 2.0]),
        p(Ramp, &[4.0, 3.0, 2.0]),
        p(RampFrustum, &[4.0, 3.0, 2.0, 1.2]),
        p(Parallelepiped, &[4.0, 3.0, 2.0, 0.5, 0.3, -0.4]),
        p(Cylinder, &[2.0, 3.0]),
        p(ExtrudedRing, &[2.0, 3.0, 1.2]),
        p(ExtrudedFan, &[2.0, 3.0, 2.0]),
        p(CylindricalSector, &[2.0, 3.0, 1.2, 2.0]),
        p(Cone, &[2.0, 3.0]),
        p(ConicFrustum, &[2.0, 3.0, 1.0]),
        p(ConicRing, &[2.0, 3.0, 1.0, 1.5]),
        p(ConicFan, &[2.0, 3.0, 2.0]),
        p(ConicSector, &[2.0, 3.0, 2.0, 1.0, 0.8]),
        p(Tetrahedron, &[3.0, 2.0, 2.5, 1.2]),
        p(TetrahedronFrustum, &[3.0, 2.0, 2.5, 1.2, 1.5]),
        p(TetrahedronSector, &[3.0, 2.0, 2.5, 1.2, 1.5, 1.0]),
        p(Sphere, &[2.0]),
        p(SphericalSector, &[2.0, 2.0, 1.2]),
    ]
}

fn is_curved(kind: ShapeType) -> bool {
    !matches!(
        kind,
        ShapeType::Box
            | ShapeType::Ramp
            | ShapeType::RampFrustum
            | ShapeType::Parallelepiped
            | ShapeType::Tetrahedron
            | ShapeType::TetrahedronFrustum
            | ShapeType::TetrahedronSector
    )
}

#[test]
fn samples_cover_every_type() {
    let kinds: Vec<_> = samples().iter().map(|p| p.kind).collect();
    assert_eq!(kinds, ShapeType::ALL.to_vec());
}

#[test]
fn every_type_name_round_trips() {
    for k in ShapeType::ALL {
        assert_eq!(ShapeType::parse(k.name()), Some(k));
    }
    assert_eq!(
        ShapeType::parse("Conic Frustum"),
        Some(ShapeType::ConicFrustum)
    );
    assert_eq!(
        ShapeType::parse("extruded_ring"),
        Some(ShapeType::ExtrudedRing)
    );
    assert_eq!(ShapeType::parse("pyramid"), None);
}

#[test]
fn meshes_are_closed_and_oriented() {
    for p in samples() {
        let m = p.mesh(&Tessellation { segments: 24 });
        assert!(
            m.is_closed_oriented(),
            "{} mesh is not closed and oriented",
            p.kind
        );
        assert!(m.signed_volume() > 0.0, "{} mesh is inside out", p.kind);
    }
}

#[test]
fn mesh_volume_matches_analytic_volume() {
    for p in samples() {
        let exact = p.volume();
        let m = p.mesh(&Tessellation { segments: 512 });
        let rel = (m.signed_volume() - exact).abs() / exact;
        let tol = if is_curved(p.kind) { 2e-3 } else { 1e-9 };
        assert!(
            rel < tol,
            "{}: mesh {} vs exact {exact}",
            p.kind,
            m.signed_volume()
        );
    }
}

#[test]
fn mesh_fits_the_reported_size() {
    for p in samples() {
        let (lo, hi) = p.mesh(&Tessellation { segments: 512 }).bounds().unwrap();
        let size = p.size();
        for k in 0..3 {
            assert!(
                ((hi[k] - lo[k]) - size[k]).abs() < 1e-3 * size[k].max(1.0),
                "{} size[{k}] = {} but mesh spans {}",
                p.kind,
                size[k],
                hi[k] - lo[k]
            );
        }
    }
}

fn split_fractions(axis: Axis) -> &'static [f64] {
    match axis {
        Axis::Theta | Axis::Phi => &[0.2, 0.5, 0.3],
        _ => &[0.25, 0.45, 0.3],
    }
}

#[test]
fn every_allowed_split_conserves_volume_and_stays_inside() {
    for p in samples() {
        let parent_mesh = p.mesh(&Tessellation { segments: 256 });
        let (plo, phi) = parent_mesh.bounds().unwrap();
        for &axis in p.kind.split_axes() {
            let extent = p.extent(axis).unwrap();
            let lengths: Vec<f64> = split_fractions(axis).iter().map(|f| f * extent).collect();
            let pieces = p
                .split(axis, &lengths)
                .unwrap_or_else(|e| panic!("{} split {axis}: {e}", p.kind));
            assert_eq!(pieces.len(), 3, "{} split {axis}", p.kind);
            let sum: f64 = pieces.iter().map(|q| q.primitive.volume()).sum();
            assert!(
                (sum - p.volume()).abs() < 1e-9 * p.volume(),
                "{} split {axis}: pieces {sum} vs whole {}",
                p.kind,
                p.volume()
            );
            for q in &pieces {
                let m = q.primitive.mesh(&Tessellation { segments: 256 });
                assert!(
                    m.is_closed_oriented(),
                    "{} split {axis}: piece {} open",
                    p.kind,
                    q.primitive.kind
                );
                for v in &m.positions {
                    let w = q.transform * nalgebra::Point3::new(v[0], v[1], v[2]);
                    for k in 0..3 {
                        assert!(
                            w[k] >= plo[k] - 1e-2 && w[k] <= phi[k] + 1e-2,
                            "{} split {axis}: piece {} leaves the parent at {w}",
                            p.kind,
                            q.primitive.kind
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn disallowed_axes_are_errors() {
    for p in samples() {
        for axis in [Axis::X, Axis::Y, Axis::Z, Axis::R, Axis::Theta, Axis::Phi] {
            if !p.kind.split_axes().contains(&axis) {
                assert!(matches!(
                    p.split(axis, &[1.0]),
                    Err(ShapeError::AxisNotAllowed { .. })
                ));
            }
        }
    }
}

#[test]
fn lengths_that_do_not_fit_are_errors() {
    let b = Primitive::new(ShapeType::Box, &[6.0, 1.0, 1.0]).unwrap();
    assert!(matches!(
        b.split(Axis::X, &[1.0, 3.0]),
        Err(ShapeError::LengthsDontFit { .. })
    ));
    assert!(matches!(
        b.split(Axis::X, &[1.0, -3.0, 8.0]),
        Err(ShapeError::BadLength { .. })
    ));
    assert_eq!(b.split(Axis::X, &[1.0, 3.0, 2.0 + 1e-9]).unwrap().len(), 3);
}

#[test]
fn wrong_parameter_counts_and_values_are_errors() {
    assert!(matches!(
        Primitive::new(ShapeType::Box, &[1.0, 2.0]),
        Err(ShapeError::ParamCount { .. })
    ));
    assert!(matches!(
        Primitive::new(ShapeType::Cylinder, &[-1.0, 2.0]),
        Err(ShapeError::BadParam { .. })
    ));
    assert!(matches!(
        Primitive::new(ShapeType::Sphere, &[f64::NAN]),
        Err(ShapeError::BadParam { .. })
    ));
    assert!(Primitive::new(ShapeType::SphericalSector, &[1.0, PI, TAU / 4.0]).is_ok());
}

/// Closed meshes with the exact volume and size; splits that conserve volume and give valid
/// pieces whose vertices lie in the parent solid, as `contains` decides. Shared by the
/// planar families (prism, wedge), whose meshes are exact.
pub(super) fn check_planar_split(
    p: &Primitive,
    axis: Axis,
    fractions: &[f64],
    contains: impl Fn(&Primitive, [f64; 3]) -> bool,
) -> Vec<Piece> {
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0);
    let m = p.mesh(&Tessellation::default());
    assert!(m.is_closed_oriented(), "{} mesh", p.kind);
    assert!(
        m.positions.iter().all(|&v| contains(p, v)),
        "{} mesh outside",
        p.kind
    );
    assert!(
        close(m.signed_volume(), p.volume()),
        "{}: {}",
        p.kind,
        m.signed_volume()
    );
    let (lo, hi) = m.bounds().unwrap();
    let size = p.size();
    assert!(
        (0..3).all(|k| close(hi[k] - lo[k], size[k])),
        "{} size",
        p.kind
    );
    let extent = p.extent(axis).unwrap();
    let lengths: Vec<f64> = fractions.iter().map(|f| f * extent).collect();
    let pieces = p.split(axis, &lengths).unwrap();
    let sum: f64 = pieces.iter().map(|q| q.primitive.volume()).sum();
    assert!(
        (sum - p.volume()).abs() <= 1e-9 * p.volume(),
        "{} {axis}",
        p.kind
    );
    for q in &pieces {
        let r = Primitive::new(q.primitive.kind, q.primitive.params());
        assert_eq!(
            r.as_ref(),
            Ok(&q.primitive),
            "{} {axis}: invalid piece",
            p.kind
        );
        let qm = q.primitive.mesh(&Tessellation::default());
        assert!(
            qm.is_closed_oriented(),
            "{} {axis}: {:?}",
            p.kind,
            q.primitive
        );
        assert!(close(qm.signed_volume(), q.primitive.volume()));
        for v in &qm.positions {
            let x = q.transform * nalgebra::Point3::new(v[0], v[1], v[2]);
            assert!(
                contains(p, [x.x, x.y, x.z]),
                "{} {axis}: {x} outside",
                p.kind
            );
        }
    }
    pieces
}
