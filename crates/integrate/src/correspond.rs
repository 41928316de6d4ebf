//! Correspondences (§6.1.1): a plan point selects the structure whose footprint contains it
//! (towers first); on a rectangle the façade takes the nearest side, on a circle the arc
//! between the two points (counter-clockwise on the drawing). A photo point selects the façade
//! whose rectified boundary contains it.

use std::f64::consts::{PI, TAU};

use facade::model::FacadeModel;

use crate::estimate::{Footprint, Side, Structure};

/// Where on a structure a façade goes.
#[derive(Debug, Clone, PartialEq)]
pub enum Placement {
    /// `north`, `south`, `east` or `west`, and that side's length (model units).
    Side { side: Side, length: f64 },
    /// Start and end angle (counter-clockwise on the drawing, 0 = +x) and the diameter.
    Arc { start: f64, end: f64, diameter: f64 },
}

/// Coordinates of `p` in a rectangle's frame: along its first side, then across.
fn local(center: [f64; 2], rotation: f64, p: [f64; 2]) -> (f64, f64) {
    let (dx, dy) = (p[0] - center[0], p[1] - center[1]);
    let (c, s) = (rotation.cos(), rotation.sin());
    (dx * c + dy * s, -dx * s + dy * c)
}

/// A footprint's area, model units².
pub(crate) fn area(f: &Footprint) -> f64 {
    match f {
        Footprint::Rectangle { size, .. } => size[0] * size[1],
        Footprint::Circle { radius, .. } => PI * radius * radius,
        Footprint::Wall { thickness, .. } => {
            thickness * f.pieces().iter().map(|[a, b]| length(*a, *b)).sum::<f64>()
        }
        Footprint::Blocks { blocks, .. } => blocks.iter().map(|b| b.size[0] * b.size[1]).sum(),
    }
}

fn length(a: [f64; 2], b: [f64; 2]) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1])
}

/// The piece of a wall's centreline nearest to `p`.
fn nearest_piece(f: &Footprint, p: [f64; 2]) -> Option<([[f64; 2]; 2], f64)> {
    f.pieces()
        .into_iter()
        .map(|s| (s, plan::fit::segment_distance(p, s[0], s[1])))
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// Whether a point (model units, plan frame) lies inside a footprint.
pub fn contains(f: &Footprint, p: [f64; 2]) -> bool {
    match f {
        Footprint::Rectangle {
            center,
            size,
            rotation,
        } => {
            let (u, v) = local(*center, *rotation, p);
            u.abs() <= size[0] / 2.0 && v.abs() <= size[1] / 2.0
        }
        Footprint::Circle { center, radius } => {
            (p[0] - center[0]).hypot(p[1] - center[1]) <= *radius
        }
        Footprint::Wall { thickness, .. } => {
            nearest_piece(f, p).is_some_and(|(_, d)| d <= thickness / 2.0)
        }
        Footprint::Blocks { rotation, blocks } => blocks.iter().any(|b| {
            let (u, v) = local(b.center, *rotation, p);
            u.abs() <= b.size[0] / 2.0 && v.abs() <= b.size[1] / 2.0
        }),
    }
}

/// The smallest tower containing `p`, else the smallest structure: a tower wins over the
/// curtain wall it sits on, even where a segment of the curtain is the smaller (a small tower
/// drawn solid on the curtain's line, `Kind::SolidCylindrical`).
pub fn structure_at(structures: &[Structure], p: [f64; 2]) -> Option<usize> {
    structures
        .iter()
        .enumerate()
        .filter(|(_, s)| contains(&s.footprint, p))
        .min_by(|a, b| {
            (!a.1.is_tower())
                .cmp(&!b.1.is_tower())
                .then(area(&a.1.footprint).total_cmp(&area(&b.1.footprint)))
        })
        .map(|(i, _)| i)
}

/// The angle of `p` about `c`, counter-clockwise as the drawing is seen (image y is down).
fn drawing_angle(c: [f64; 2], p: [f64; 2]) -> f64 {
    (-(p[1] - c[1])).atan2(p[0] - c[0])
}

/// Where the façade goes on `footprint`, given the plan points (model units).
pub fn place(footprint: &Footprint, points: &[[f64; 2]]) -> Placement {
    match footprint {
        Footprint::Rectangle {
            center,
            size,
            rotation,
        } => {
            let (u, v) = local(*center, *rotation, points[0]);
            let (a, b) = (size[0] / 2.0, size[1] / 2.0);
            let sides = [
                (Side::North, (v + b).abs(), size[0]),
                (Side::South, (v - b).abs(), size[0]),
                (Side::East, (u - a).abs(), size[1]),
                (Side::West, (u + a).abs(), size[1]),
            ];
            let (side, _, length) = sides
                .into_iter()
                .min_by(|x, y| x.1.total_cmp(&y.1))
                .expect("four sides");
            Placement::Side { side, length }
        }
        Footprint::Circle { center, radius } => {
            let (start, end) = match points {
                [p] => {
                    // One point: the half of the tower a photo of it can show, centred there.
                    let mid = drawing_angle(*center, *p);
                    (mid - PI / 2.0, mid + PI / 2.0)
                }
                [p, q, ..] => {
                    let a = drawing_angle(*center, *p);
                    let mut b = drawing_angle(*center, *q);
                    while b <= a {
                        b += TAU;
                    }
                    (a, b)
                }
                [] => (0.0, TAU),
            };
            Placement::Arc {
                start,
                end,
                diameter: 2.0 * radius,
            }
        }
        // A façade on a room of blocks covers the room's length along its long axis.
        Footprint::Blocks { rotation, blocks } => {
            let along = |b: &crate::estimate::Block, sign: f64| {
                local([0.0, 0.0], *rotation, b.center).0 + sign * b.size[0] / 2.0
            };
            let lo = blocks
                .iter()
                .map(|b| along(b, -1.0))
                .fold(f64::MAX, f64::min);
            let hi = blocks
                .iter()
                .map(|b| along(b, 1.0))
                .fold(f64::MIN, f64::max);
            Placement::Side {
                side: Side::North,
                length: (hi - lo).max(0.0),
            }
        }
        // A façade on a wall covers the straight piece it was pointed at; its outer face is
        // the wall's field face.
        Footprint::Wall { .. } => Placement::Side {
            side: Side::North,
            length: points
                .first()
                .and_then(|p| nearest_piece(footprint, *p))
                .map_or(0.0, |([a, b], _)| length(a, b)),
        },
    }
}

/// Index of the façade whose bounding box contains `p` (rectified pixels).
pub fn facade_at(model: &FacadeModel, p: [f64; 2]) -> Option<usize> {
    model.facades.iter().position(|f| {
        let [x0, y0, x1, y1] = f.bbox;
        (x0..=x1).contains(&p[0]) && (y0..=y1).contains(&p[1])
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect() -> Footprint {
        Footprint::Rectangle {
            center: [100.0, 50.0],
            size: [40.0, 20.0],
            rotation: 0.0,
        }
    }

    #[test]
    fn a_point_selects_the_nearest_side() {
        let f = rect();
        let side = |p| match place(&f, &[p]) {
            Placement::Side { side, length } => (side, length),
            other => panic!("{other:?}"),
        };
        // Image y is down: north is the top edge (smaller y).
        assert_eq!(side([100.0, 42.0]), (Side::North, 40.0));
        assert_eq!(side([100.0, 58.0]), (Side::South, 40.0));
        assert_eq!(side([118.0, 50.0]), (Side::East, 20.0));
        assert_eq!(side([82.0, 50.0]), (Side::West, 20.0));
    }

    #[test]
    fn a_rotated_rectangle_turns_its_sides() {
        let f = Footprint::Rectangle {
            center: [0.0, 0.0],
            size: [40.0, 20.0],
            rotation: PI / 2.0,
        };
        // The first side now runs along +y (down the image): "east" is at +y.
        assert!(contains(&f, [0.0, 19.0]) && !contains(&f, [19.0, 0.0]));
        assert_eq!(
            place(&f, &[[0.0, 18.0]]),
            Placement::Side {
                side: Side::East,
                length: 20.0
            }
        );
    }

    #[test]
    fn arcs_run_counter_clockwise_between_the_points() {
        let f = Footprint::Circle {
            center: [0.0, 0.0],
            radius: 10.0,
        };
        // East (+x) then north (−y on the image): a quarter turn counter-clockwise.
        let Placement::Arc {
            start,
            end,
            diameter,
        } = place(&f, &[[5.0, 0.0], [0.0, -5.0]])
        else {
            panic!()
        };
        assert!((start - 0.0).abs() < 1e-12 && (end - PI / 2.0).abs() < 1e-12);
        assert_eq!(diameter, 20.0);
        // The reverse order goes the long way round.
        let Placement::Arc { start, end, .. } = place(&f, &[[0.0, -5.0], [5.0, 0.0]]) else {
            panic!()
        };
        assert!((end - start - 1.5 * PI).abs() < 1e-12);
    }

    #[test]
    fn the_smallest_containing_structure_wins() {
        use crate::estimate::Kind;
        let mk = |footprint| Structure {
            id: String::new(),
            label: plan::label::Label::UnknownRoom,
            role: crate::estimate::Role::Room,
            kind: Kind::Solid,
            footprint,
            height: 1.0,
            wall_thickness: 1.0,
            facades: vec![],
            children: vec![],
            roof: None,
            crenellated: None,
            provenance: Default::default(),
        };
        let big = mk(rect());
        let small = mk(Footprint::Circle {
            center: [100.0, 50.0],
            radius: 5.0,
        });
        assert_eq!(structure_at(&[big.clone(), small], [101.0, 50.0]), Some(1));
        assert_eq!(structure_at(&[big], [0.0, 0.0]), None);
    }

    #[test]
    fn a_solid_tower_wins_over_the_smaller_curtain_segment_it_sits_on() {
        use crate::estimate::Kind;
        let segment = Structure {
            id: "wall1".into(),
            label: plan::label::Label::CastleOuterWall,
            role: crate::estimate::Role::Curtain,
            kind: Kind::Solid,
            footprint: Footprint::Rectangle {
                center: [0.0, 0.0],
                size: [6.0, 2.0],
                rotation: 0.0,
            },
            height: 12.0,
            wall_thickness: 2.0,
            facades: vec![],
            children: vec![],
            roof: None,
            crenellated: None,
            provenance: Default::default(),
        };
        let tower = Structure {
            id: "tower1".into(),
            label: plan::label::Label::TowerWall,
            role: crate::estimate::Role::Tower,
            kind: Kind::SolidCylindrical,
            footprint: Footprint::Circle {
                center: [0.0, 1.0],
                radius: 3.0,
            },
            ..segment.clone()
        };
        assert!(area(&segment.footprint) < area(&tower.footprint));
        assert_eq!(structure_at(&[segment.clone(), tower], [0.5, 0.5]), Some(1));
        assert_eq!(structure_at(&[segment], [0.5, 0.5]), Some(0));
    }
}
