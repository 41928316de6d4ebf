//! The 3D model of §5.3 as a VSG program: every labelled wall is extruded along its
//! simplified chain to its class height, and rooms with a circle or rectangle fit are extruded
//! as cylinders or boxes; towers highest, the surroundings at ground level (not emitted).

use std::fmt::Write;

use crate::ParsedPlan;
use crate::fit::Fit;
use crate::label::Label;
use crate::scale::ModelScale;

/// Extrusion heights by label, in output units (§5.3 order: tower walls > tower rooms >
/// outer walls > great hall wall > great hall > chapel wall > chapel > unknown wall >
/// unknown room > courtyard > surroundings = 0).
#[derive(Debug, Clone)]
pub struct Heights(pub [f64; 11]);

impl Heights {
    /// Heights in metres for a typical medieval castle.
    pub fn metres() -> Heights {
        let mut h = [0.0; 11];
        for (l, v) in [
            (Label::TowerWall, 20.0),
            (Label::TowerRoom, 18.0),
            (Label::CastleOuterWall, 12.0),
            (Label::GreatHallWall, 10.0),
            (Label::GreatHall, 9.0),
            (Label::ChapelWall, 8.0),
            (Label::Chapel, 7.0),
            (Label::UnknownWall, 6.0),
            (Label::UnknownRoom, 5.0),
            (Label::Courtyard, 0.2),
        ] {
            h[l as usize] = v;
        }
        Heights(h)
    }

    /// The metre heights scaled by `units_per_metre` (e.g. pixels when no scale is known).
    pub fn scaled(units_per_metre: f64) -> Heights {
        Heights(Heights::metres().0.map(|v| v * units_per_metre))
    }

    pub fn of(&self, l: Label) -> f64 {
        self.0[l as usize]
    }
}

/// Douglas–Peucker simplification of a chain to within `eps` pixels.
pub fn simplify(pts: &[[f64; 2]], eps: f64) -> Vec<[f64; 2]> {
    if pts.len() < 3 {
        return pts.to_vec();
    }
    let mut keep = vec![false; pts.len()];
    keep[0] = true;
    keep[pts.len() - 1] = true;
    let mut stack = vec![(0, pts.len() - 1)];
    while let Some((i, j)) = stack.pop() {
        let (a, b) = (pts[i], pts[j]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        let mut best = (0.0, i);
        for (k, p) in pts.iter().enumerate().take(j).skip(i + 1) {
            let d = if len < 1e-9 {
                (p[0] - a[0]).hypot(p[1] - a[1])
            } else {
                ((p[0] - a[0]) * dy - (p[1] - a[1]) * dx).abs() / len
            };
            if d > best.0 {
                best = (d, k);
            }
        }
        if best.0 > eps {
            keep[best.1] = true;
            stack.push((i, best.1));
            stack.push((best.1, j));
        }
    }
    pts.iter()
        .zip(keep)
        .filter_map(|(p, k)| k.then_some(*p))
        .collect()
}

fn symbol(l: Label) -> String {
    l.name().to_string()
}

/// The VSG program extruding `plan` (§5.3) in the model frame `frame` (decided by
/// [`ModelScale::decide`]): plan pixel (x, y) goes to (x·s, z = y·s), s = `units_per_pixel`,
/// and the class heights are [`Heights::metres`] in model units;
/// y is up. Each instance is a terminal named after its label, coloured as in the overlay.
pub fn to_vsg(plan: &ParsedPlan, frame: &ModelScale) -> String {
    let scale = frame.units_per_pixel;
    let heights = &Heights::scaled(frame.units_per_metre);
    let mut shapes: Vec<(String, Label)> = Vec::new();
    let f = |v: f64| format!("{:.4}", v);
    for e in &plan.edges {
        let h = heights.of(e.label);
        if h <= 0.0 {
            continue;
        }
        let t = e.thickness.max(1.0) * scale;
        let pts: Vec<[f64; 2]> = e
            .points
            .iter()
            .map(|&(x, y)| [x as f64, y as f64])
            .collect();
        for w in simplify(&pts, 1.5).windows(2) {
            let (dx, dy) = (w[1][0] - w[0][0], w[1][1] - w[0][1]);
            let len = dx.hypot(dy) * scale;
            if len < 1e-9 {
                continue;
            }
            let (cx, cz) = (
                (w[0][0] + w[1][0]) / 2.0 * scale,
                (w[0][1] + w[1][1]) / 2.0 * scale,
            );
            // Rotation about y by θ takes x to (cos θ, 0, -sin θ): θ = -atan2(dz, dx).
            let theta = -dy.atan2(dx);
            shapes.push((
                format!(
                    "T({}, {}, {}) R(0, {}, 0) I(\"box\", {{{}, {}, {}}})",
                    f(cx),
                    f(h / 2.0),
                    f(cz),
                    f(theta),
                    f(len + t),
                    f(h),
                    f(t)
                ),
                e.label,
            ));
        }
    }
    for face in &plan.faces {
        let h = heights.of(face.label);
        if h <= 0.0 {
            continue;
        }
        match &face.shape {
            Some(Fit::Circle { center, radius, .. }) if *radius > 0.5 => shapes.push((
                format!(
                    "T({}, {}, {}) I(\"cylinder\", {{{}, {}}})",
                    f(center[0] * scale),
                    f(h / 2.0),
                    f(center[1] * scale),
                    f(radius * scale),
                    f(h)
                ),
                face.label,
            )),
            Some(Fit::Rectangle {
                center,
                size,
                angle,
                ..
            }) if size[0] > 0.5 && size[1] > 0.5 => shapes.push((
                format!(
                    "T({}, {}, {}) R(0, {}, 0) I(\"box\", {{{}, {}, {}}})",
                    f(center[0] * scale),
                    f(h / 2.0),
                    f(center[1] * scale),
                    f(-angle),
                    f(size[0] * scale),
                    f(h),
                    f(size[1] * scale)
                ),
                face.label,
            )),
            _ => {}
        }
    }
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// §5.3 extrusion of a parsed plan drawing, written by castellan plan.\n// {} walls, {} rooms; units per plan pixel: {}.",
        plan.edges.len(),
        plan.faces.len(),
        scale
    );
    if shapes.is_empty() {
        // Nothing to extrude: an empty marker keeps the program valid.
        let _ = writeln!(
            s,
            "Axiom :: I(\"box\", {{0.001, 0.001, 0.001}}){{empty}};\nempty :: void(){{j3d.terminal}};"
        );
        return s;
    }
    let _ = writeln!(s, "Axiom ::");
    for (inst, _) in &shapes {
        let _ = writeln!(s, "    {inst}");
    }
    let names: Vec<String> = shapes.iter().map(|(_, l)| symbol(*l)).collect();
    let _ = writeln!(s, "    {{{}}};", names.join(", "));
    let mut used: Vec<Label> = shapes.iter().map(|(_, l)| *l).collect();
    used.sort_by_key(|l| *l as u8);
    used.dedup();
    for l in used {
        let [r, g, b] = l.color();
        let _ = writeln!(
            s,
            "{} :: appearance(\"color\", {{{:.3}, {:.3}, {:.3}}}){{j3d.terminal}};",
            symbol(l),
            f64::from(r) / 255.0,
            f64::from(g) / 255.0,
            f64::from(b) / 255.0
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn douglas_peucker_keeps_corners() {
        let mut pts: Vec<[f64; 2]> = (0..20).map(|i| [i as f64, 0.0]).collect();
        pts.extend((1..20).map(|j| [19.0, j as f64]));
        let s = simplify(&pts, 1.0);
        assert_eq!(s, vec![[0.0, 0.0], [19.0, 0.0], [19.0, 19.0]]);
    }

    #[test]
    fn heights_follow_section_5_3_order() {
        let h = Heights::metres();
        let order = [
            Label::TowerWall,
            Label::TowerRoom,
            Label::CastleOuterWall,
            Label::GreatHallWall,
            Label::GreatHall,
            Label::ChapelWall,
            Label::Chapel,
            Label::UnknownWall,
            Label::UnknownRoom,
            Label::Courtyard,
            Label::CastleSurroundings,
        ];
        for w in order.windows(2) {
            assert!(h.of(w[0]) > h.of(w[1]), "{:?} {:?}", w[0], w[1]);
        }
    }
}
