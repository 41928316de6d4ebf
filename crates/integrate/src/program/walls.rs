//! Curtain and inner walls in the program (issue 25, after §7.2.2's `curtain_wall.vsg`): each
//! straight piece of a wall run is a box in the axiom, and every curtain piece takes the one
//! `curtain` rule — a wall body, then on top a parapet crenellated on the field side and the wall
//! walk behind it — so a castle's curtain is one rule however many pieces it has. Inner walls
//! are plain masonry.

use std::fmt::Write;

use crate::estimate::{Footprint, Role, Structure};

use super::common::{Part, n};

/// A wall run: one box per straight piece, each end lengthened so that neighbouring pieces
/// meet in a mitre ([`end_extensions`]). Local −z of every piece is the field side (the
/// centreline keeps the field on its left, `Footprint::Wall`), where the `curtain` rule puts
/// the parapet.
/// `textures`: the wall samples' list, when there are any (one of them per shape, tinted by the
/// stone colour, as the library's structures take them).
pub(super) fn run(s: &Structure, textures: Option<&str>) -> Part {
    let mut out = Part::default();
    let Footprint::Wall {
        thickness,
        ref widths,
        ..
    } = s.footprint
    else {
        return out;
    };
    let id = &s.id;
    let _ = writeln!(
        out.params,
        "float[] {id}H = {{{}, {}}}; // height, thickness",
        n(s.height),
        n(thickness)
    );
    // Each piece's own thickness as drawn (issue 25), when the plan measured it.
    if !widths.is_empty() {
        let list: Vec<String> = widths.iter().map(|w| n(*w)).collect();
        let _ = writeln!(
            out.params,
            "float[] {id}W = {{{}}}; // each piece's thickness as drawn",
            list.join(", ")
        );
    }
    let pieces = s.footprint.pieces_with_widths();
    let closed = matches!(s.footprint, Footprint::Wall { closed: true, .. });
    let ends = end_extensions(&pieces, closed);
    for (k, ([a, b], _)) in pieces.into_iter().enumerate() {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        if len < 1e-9 {
            continue;
        }
        // The box's centre moves towards the end lengthened more.
        let [ea, eb] = ends[k];
        let shift = (eb - ea) / 2.0 / len;
        let centre = [
            (a[0] + b[0]) / 2.0 + dx * shift,
            (a[1] + b[1]) / 2.0 + dy * shift,
        ];
        let depth = if widths.is_empty() {
            format!("{id}H[1]")
        } else {
            format!("{id}W[{k}]")
        };
        out.axiom.push((
            format!(
                "T({}, {id}H[0]/2, {}) R(0, {}, 0) I(\"box\", {{{}, {id}H[0], {depth}}})",
                n(centre[0]),
                n(centre[1]),
                n(-dy.atan2(dx)),
                n(len + ea + eb)
            ),
            id.clone(),
        ));
    }
    // The curtain is crenellated and inner walls are not, unless the user said otherwise
    // (`[[structure]] crenellated`, issue 22).
    let body = match (s.role == Role::Curtain, s.crenellated) {
        (_, Some(true)) | (true, None) => "curtain",
        (true, Some(false)) => "curtainPlain",
        (false, _) => "innerWall",
    };
    let appearance = textures
        .map(|list| format!("appearance(\"texture\", {list})"))
        .unwrap_or_default();
    let _ = writeln!(out.rules, "{id} :: {appearance}{{{body}}};");
    out
}

/// How far each piece's box reaches past its start and its end. Where two pieces meet at a
/// turn θ, each reaches half its thickness × tan(θ/2) past the joint, so that their outer
/// sides meet in a mitre: a square end (half the thickness, the rule before session 18) left
/// a corner sticking out of every shallow bend, off the drawn wall (issue 25's precision).
/// Turns sharper than a right angle reach half the thickness, as before: a longer reach built
/// spikes where a chain doubles back (34 shared plans, median plan–model IoU: capped at the
/// thickness 0.792, at half of it 0.804, square ends 0.801). A run's free ends reach half
/// the thickness (the skeleton's chain stops about that short of the drawn wall's end).
fn end_extensions(pieces: &[([[f64; 2]; 2], f64)], closed: bool) -> Vec<[f64; 2]> {
    let dir = |p: &[[f64; 2]; 2]| {
        let (dx, dy) = (p[1][0] - p[0][0], p[1][1] - p[0][1]);
        let l = dx.hypot(dy).max(1e-12);
        [dx / l, dy / l]
    };
    // The mitre reach of a piece `width` thick at a joint turning from `u` to `v`.
    let mitre = |u: [f64; 2], v: [f64; 2], width: f64| {
        let cos = (u[0] * v[0] + u[1] * v[1]).clamp(-1.0, 1.0);
        let half_turn = cos.acos() / 2.0;
        (width / 2.0 * half_turn.tan()).min(width / 2.0)
    };
    let dirs: Vec<[f64; 2]> = pieces.iter().map(|(p, _)| dir(p)).collect();
    let n = pieces.len();
    (0..n)
        .map(|k| {
            let width = pieces[k].1;
            let prev = if k > 0 {
                Some(k - 1)
            } else {
                (closed && n > 2).then(|| n - 1)
            };
            let next = if k + 1 < n {
                Some(k + 1)
            } else {
                (closed && n > 2).then_some(0)
            };
            let start = prev.map_or(width / 2.0, |j| mitre(dirs[j], dirs[k], width));
            let end = next.map_or(width / 2.0, |j| mitre(dirs[k], dirs[j], width));
            [start, end]
        })
        .collect()
}

/// The parameters and rules every curtain piece and inner wall shares; `lowest` is the lowest
/// curtain (model units), so that the parapet always fits, `u` the units per metre.
pub(super) fn shared(lowest: f64, u: f64) -> Part {
    let parapet = (1.8 * u).min(0.3 * lowest);
    Part {
        params: format!(
            "\n// The curtain's parapet (§7.2.2's curtain_wall.vsg): height, merlon width, wall-walk paving.\nfloat curtainParapetH = {};\nfloat curtainMerlon = {};\nfloat curtainWalkT = {};\n",
            n(parapet),
            n(1.2 * u),
            n((0.2 * u).min(parapet * 0.3))
        ),
        axiom: Vec::new(),
        rules: "\n// Curtain walls (curtain_wall.vsg as one rule for every piece): the body, then a parapet\n// on the field side (local −z, a fifth of the wall) crenellated once, and the wall walk behind it.\ncurtain :: split(\"Y\", {~1, curtainParapetH}){wallStone, curtainTop};\ncurtainTop :: split(\"Z\", {~1, ~4}){curtainParapet, curtainWalkZone};\ncurtainParapet :: repeat(\"X\", {~curtainMerlon, ~curtainMerlon}){wallStone, curtainCrenel};\ncurtainCrenel :: split(\"Y\", {~4, ~5}){wallStone, opening};\ncurtainWalkZone :: split(\"Y\", {curtainWalkT, ~1}){curtainWalk, opening};\ncurtainWalk :: appearance(\"color\", {0.5, 0.47, 0.42}){j3d.terminal};\n// A curtain the user wants without crenels: the parapet whole.\ncurtainPlain :: split(\"Y\", {~1, curtainParapetH}){wallStone, curtainPlainTop};\ncurtainPlainTop :: split(\"Z\", {~1, ~4}){wallStone, curtainWalkZone};\ninnerWall :: {wallStone};\n".to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn pieces_meet_in_a_mitre_and_free_ends_reach_half_the_thickness() {
        // An open run 2 thick: straight on, then a 45° turn, then a right angle.
        let pieces = [
            ([[0.0, 0.0], [10.0, 0.0]], 2.0),
            ([[10.0, 0.0], [20.0, 0.0]], 2.0),
            ([[20.0, 0.0], [30.0, 10.0]], 2.0),
            ([[30.0, 10.0], [20.0, 20.0]], 2.0),
        ];
        let e = end_extensions(&pieces, false);
        let t = (std::f64::consts::PI / 8.0).tan();
        assert!(close(e[0][0], 1.0) && close(e[0][1], 0.0), "{e:?}");
        assert!(close(e[1][0], 0.0) && close(e[1][1], t), "{e:?}");
        assert!(close(e[2][0], t) && close(e[2][1], 1.0), "{e:?}");
        assert!(close(e[3][0], 1.0) && close(e[3][1], 1.0), "{e:?}");
        // A square ring: every corner a right angle, closing piece included.
        let ring = [
            ([[0.0, 0.0], [10.0, 0.0]], 2.0),
            ([[10.0, 0.0], [10.0, 10.0]], 2.0),
            ([[10.0, 10.0], [0.0, 10.0]], 2.0),
            ([[0.0, 10.0], [0.0, 0.0]], 2.0),
        ];
        let e = end_extensions(&ring, true);
        assert!(e.iter().flatten().all(|&v| close(v, 1.0)), "{e:?}");
        // A chain that doubles back reaches no further than a right angle's.
        let back = [
            ([[0.0, 0.0], [10.0, 0.0]], 2.0),
            ([[10.0, 0.0], [0.0, 0.5]], 2.0),
        ];
        assert!(close(end_extensions(&back, false)[0][1], 1.0));
    }
}
