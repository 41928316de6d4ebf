//! The block-level 3D estimate of §4.2 / figure 4.4(c) as a VSG program (ch. 7): a wall block
//! with the top-level elements cut out, each element rebuilt with the construction of
//! `library/gothic_window.vsg` (spandrels = half-boxes minus the discs of the arcs, the light
//! above the springing line = box ∩ both discs) from the same x0, y0, h, w, v, and each stone
//! extruded by a user depth in front of the wall. An element others nest in keeps a solid
//! tympanum slab with its children's boxes cut through it (issue 23).

use std::fmt::Write;

use super::masonry::Masonry;
use super::{ArchKind, Element, GothicEstimate};

/// Units and depths of the generated program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VsgOptions {
    /// Image pixels per model unit (e.g. 100 px per metre).
    pub px_per_unit: f64,
    /// Wall thickness (model units).
    pub wall_depth: f64,
    /// How far each stone block stands out of the wall (the user depth of §4.2).
    pub stone_depth: f64,
}

impl Default for VsgOptions {
    fn default() -> Self {
        VsgOptions {
            px_per_unit: 100.0,
            wall_depth: 0.8,
            stone_depth: 0.05,
        }
    }
}

/// The VSG program text for an estimate, with stone blocks when `masonry` is given.
/// Model x is image x, model y is up (image height − y), z points out of the wall; one model
/// unit is `px_per_unit` pixels. Every element `e<ID>` declares `e<ID>_x0, _y0, _h, _w, _v`
/// with the meaning of `library/gothic_window.vsg` (y0 measured up from the wall's foot).
pub fn to_vsg(est: &GothicEstimate, masonry: Option<&Masonry>, opt: &VsgOptions) -> String {
    let s = opt.px_per_unit.max(1e-9);
    let img_h = est.height as f64;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "// Gothic façade estimate (castellan gothic, dissertation ch. 4): {} elements, {} stones.",
        est.elements.len(),
        masonry.map_or(0, |m| m.stones.len())
    );
    let _ = writeln!(out, "float W = {:.4};", est.width as f64 / s);
    let _ = writeln!(out, "float H = {:.4};", img_h / s);
    let _ = writeln!(out, "float depth = {:.4};", opt.wall_depth);
    let _ = writeln!(out, "float stoneDepth = {:.4};", opt.stone_depth);
    for e in &est.elements {
        let n = format!("e{}", e.id);
        let _ = writeln!(
            out,
            "float {n}_x0 = {:.4}; float {n}_y0 = {:.4}; float {n}_h = {:.4}; float {n}_w = {:.4}; float {n}_v = {:.4};",
            e.x0 / s,
            (img_h - e.y0) / s,
            e.h.max(0.0) / s,
            e.w / s,
            e.v.max(0.0) / s
        );
    }
    let has_children: Vec<bool> = est
        .elements
        .iter()
        .map(|e| est.elements.iter().any(|c| c.parent == Some(e.id)))
        .collect();

    // Axiom: the wall, every element's bounding box, every stone.
    let mut shapes = vec!["T(W/2, H/2, 0) I(\"box\", {W, H, depth})".to_string()];
    let mut successors = vec!["wall".to_string()];
    for e in &est.elements {
        let n = format!("e{}", e.id);
        shapes.push(format!(
            "T({n}_x0 + {n}_w/2, {n}_y0 + ({n}_h + {n}_v)/2, 0) I(\"box\", {{{n}_w, {n}_h + {n}_v, depth}})"
        ));
        successors.push(n);
    }
    if let Some(m) = masonry {
        for st in &m.stones {
            let [x0, y0, x1, y1] = st.bbox.map(f64::from);
            let (w, h) = ((x1 - x0 + 1.0) / s, (y1 - y0 + 1.0) / s);
            let (cx, cy) = (
                (x0 + x1 + 1.0) / 2.0 / s,
                (img_h - (y0 + y1 + 1.0) / 2.0) / s,
            );
            shapes.push(format!(
                "T({cx:.4}, {cy:.4}, depth/2 + stoneDepth/2) I(\"box\", {{{w:.4}, {h:.4}, stoneDepth}})"
            ));
            successors.push("stone".into());
        }
    }
    let _ = writeln!(
        out,
        "\nAxiom :: {}\n  {{{}}};",
        shapes.join("\n  "),
        successors.join(", ")
    );

    // The wall minus the boxes of the top-level elements (the nested ones sit inside them).
    let holes: Vec<String> = est
        .elements
        .iter()
        .filter(|e| e.parent.is_none())
        .map(|e| {
            let n = format!("e{}", e.id);
            format!(
                "T({n}_x0 + {n}_w/2 - W/2, {n}_y0 + ({n}_h + {n}_v)/2 - H/2, 0) I(\"box\", {{{n}_w, {n}_h + {n}_v, depth + 1}})"
            )
        })
        .collect();
    if holes.is_empty() {
        let _ = writeln!(out, "wall :: {{masonry}};");
    } else {
        let _ = writeln!(
            out,
            "wall :: I(\"box\", {{W, H, depth}})\n  {}\n  difference(){{masonry}};",
            holes.join("\n  ")
        );
    }
    for (e, &parent) in est.elements.iter().zip(&has_children) {
        let children: Vec<&Element> = if parent {
            est.elements
                .iter()
                .filter(|c| c.parent == Some(e.id))
                .collect()
        } else {
            Vec::new()
        };
        element_rules(&mut out, e, &children);
    }
    let _ = writeln!(
        out,
        "masonry :: appearance(\"color\", {{0.76, 0.72, 0.64}}){{j3d.terminal}};"
    );
    let _ = writeln!(
        out,
        "spandrel :: appearance(\"color\", {{0.76, 0.72, 0.64}}){{j3d.terminal}};"
    );
    let _ = writeln!(
        out,
        "tympanum :: appearance(\"color\", {{0.62, 0.58, 0.52}}){{j3d.terminal}};"
    );
    let _ = writeln!(
        out,
        "glass :: appearance(\"color\", {{0.3, 0.4, 0.5}}, \"transparency\", 0.5){{j3d.terminal}};"
    );
    let stone = masonry.map_or([0.6, 0.4, 0.3], |m| m.class_colours[1].map(|c| c / 255.0));
    let _ = writeln!(
        out,
        "stone :: appearance(\"color\", {{{:.3}, {:.3}, {:.3}}}){{j3d.terminal}};",
        stone[0], stone[1], stone[2]
    );
    out
}

/// The rules of one element, in its bounding box's frame: jambs and arch zone (split as in
/// gothic_window.vsg), full-depth spandrels, and a recessed fill: glass for a leaf; for an
/// element others nest in (`children`, figure 4.4(c)), a tympanum slab — the wall between the
/// arch and the lights, kept solid — with each child's bounding box cut through it, so the
/// child's own full-depth spandrels and glass stand in the hole and its light opens through
/// the tympanum. The slab is then its zone's box rather than box ∩ discs (a rule has one
/// boolean); where it leaves the arched outline it lies inside the full-depth spandrels.
fn element_rules(out: &mut String, e: &Element, children: &[&Element]) {
    let n = format!("e{}", e.id);
    let nested = !children.is_empty();
    let (z, t, fill) = if nested {
        ("-depth*0.35", "depth*0.3", "tympanum")
    } else {
        ("-depth*0.25", "depth*0.1", "glass")
    };
    // The slab of a zone of height `zh` whose centre is at model height `cy`, at depth `dz`
    // in the rule's frame, minus every child's box.
    // Departure from §4.2 / figure 4.4(c), whose blocks are the elements' boxes: the parent's
    // slab is its zone's box less its children's boxes (issue 23).
    let slab = |zh: &str, cy: &str, dz: &str| -> String {
        let holes: String = children
            .iter()
            .map(|c| {
                let m = format!("e{}", c.id);
                format!(
                    " T({m}_x0 + {m}_w/2 - ({n}_x0 + {n}_w/2), {m}_y0 + ({m}_h + {m}_v)/2 - ({cy}), {dz}) I(\"box\", {{{m}_w, {m}_h + {m}_v, {t} + 1}})"
                )
            })
            .collect();
        format!("T(0, 0, {dz}) I(\"box\", {{{n}_w, {zh}, {t}}}){holes} difference(){{{fill}}}")
    };
    let jamb = if nested {
        slab(&format!("{n}_h"), &format!("{n}_y0 + {n}_h/2"), z)
    } else {
        format!("T(0, 0, {z}) I(\"box\", {{{n}_w, {n}_h, {t}}}){{{fill}}}")
    };
    let kind = e.theta().kind(1e-3);
    if kind == ArchKind::Rectangle || e.h <= 1e-3 && e.v <= 1e-3 {
        let _ = writeln!(out, "{n} :: {jamb};");
        return;
    }
    let split = if e.h > 1e-3 {
        let _ = writeln!(out, "{n}_jambs :: {jamb};");
        format!("split(\"Y\", {{{n}_h, {n}_v}}){{{n}_jambs, {n}_arch}}")
    } else {
        format!("{{{n}_arch}}")
    };
    let _ = writeln!(out, "{n} :: {split};");
    let _ = writeln!(
        out,
        "{n}_arch :: I(\"box\", {{{n}_w, {n}_v, depth}}) T(0, 0, {z}) I(\"box\", {{{n}_w, {n}_v, {t}}}){{{n}_stone, {n}_light}};"
    );
    if nested {
        // n_light's frame is already the slab's (depth z): the holes are at 0 in it.
        let _ = writeln!(
            out,
            "{n}_light :: {};",
            slab(&format!("{n}_v"), &format!("{n}_y0 + {n}_h + {n}_v/2"), "0")
        );
    }
    if kind == ArchKind::Segmental {
        // One arc of radius r centred r − v below the springing line.
        let r = format!("(({n}_w*{n}_w/4 + {n}_v*{n}_v)/(2*{n}_v))");
        let cy = format!("{n}_v/2 - {r}");
        let _ = writeln!(
            out,
            "{n}_stone :: I(\"box\", {{{n}_w, {n}_v, depth}}) T(0, {cy}, 0) R(PI/2, 0, 0) I(\"cylinder\", {{{r}, depth + 1}}) difference(){{spandrel}};"
        );
        if !nested {
            let _ = writeln!(
                out,
                "{n}_light :: I(\"box\", {{{n}_w, {n}_v, {t}}}) T(0, {cy}, 0) R(PI/2, 0, 0) I(\"cylinder\", {{{r}, {t} + 1}}) intersection(){{{fill}}};"
            );
        }
        return;
    }
    // Round or pointed: gothic_window.vsg's rho = (w²/4 + v²)/w, arcs centred on the springing line.
    let rho = format!("(({n}_w*{n}_w/4 + {n}_v*{n}_v)/{n}_w)");
    let _ = writeln!(
        out,
        "{n}_stone :: split(\"X\", {{~1, ~1}}){{{n}_left, {n}_right}};"
    );
    let _ = writeln!(
        out,
        "{n}_left :: I(\"box\", {{{n}_w/2, {n}_v, depth}}) T({rho} - {n}_w/4, -{n}_v/2, 0) R(PI/2, 0, 0) I(\"cylinder\", {{{rho}, depth + 1}}) difference(){{spandrel}};"
    );
    let _ = writeln!(
        out,
        "{n}_right :: I(\"box\", {{{n}_w/2, {n}_v, depth}}) T({n}_w/4 - {rho}, -{n}_v/2, 0) R(PI/2, 0, 0) I(\"cylinder\", {{{rho}, depth + 1}}) difference(){{spandrel}};"
    );
    if !nested {
        let _ = writeln!(
            out,
            "{n}_light :: I(\"box\", {{{n}_w, {n}_v, {t}}}) T({rho} - {n}_w/2, -{n}_v/2, 0) R(PI/2, 0, 0) I(\"cylinder\", {{{rho}, {t} + 1}}) T({n}_w/2 - {rho}, -{n}_v/2, 0) R(PI/2, 0, 0) I(\"cylinder\", {{{rho}, {t} + 1}}) intersection(){{{fill}}};"
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn element(id: usize, x0: f64, w: f64, v: f64, parent: Option<usize>) -> Element {
        Element {
            id,
            x0,
            y0: 180.0,
            h: 60.0,
            w,
            v,
            group: None,
            parent,
            kind: ArchKind::Pointed,
            depth: 0,
            mean_distance: 0.0,
            support: 1.0,
        }
    }

    fn estimate() -> GothicEstimate {
        GothicEstimate {
            width: 300,
            height: 200,
            elements: vec![
                element(0, 40.0, 40.0, 28.0, Some(3)),
                element(1, 100.0, 40.0, 20.0, Some(3)),
                element(2, 200.0, 30.0, 0.0, None),
                Element {
                    y0: 190.0,
                    h: 70.0,
                    ..element(3, 30.0, 120.0, 8.0, None)
                },
            ],
            groups: vec![],
        }
    }

    #[test]
    fn the_program_runs_and_every_element_and_stone_is_built() {
        let masonry = Masonry {
            width: 300,
            height: 200,
            labels: vec![],
            stones: vec![super::super::masonry::Stone {
                id: 0,
                bbox: [250, 10, 279, 19],
                area: 300,
                colour: [1.0; 3],
            }],
            class_colours: [[200.0; 3], [120.0; 3]],
        };
        let src = to_vsg(&estimate(), Some(&masonry), &VsgOptions::default());
        let model = vsg::run(&src, &vsg::RunOptions::default())
            .unwrap_or_else(|e| panic!("{}\n{src}", e.render("gothic.vsg", &src)));
        let stats = vsg::stats::Stats::of(&model, &vsg::shape::Tessellation::default());
        let count = |s: &str| stats.by_symbol.get(s).copied().unwrap_or(0);
        // Pointed e0, round e1 and segmental e3: two, two and one spandrel pieces.
        assert_eq!(count("spandrel"), 5, "{:?}", stats.by_symbol);
        assert_eq!(count("glass"), 2 + 2 + 1, "{:?}", stats.by_symbol);
        assert_eq!(count("tympanum"), 2);
        assert_eq!(count("stone"), 1);
        assert_eq!(count("masonry"), 1);
        // The stone block is 0.3 x 0.1 x stoneDepth.
        let v = stats.volume.by_symbol["stone"];
        assert!((v - 0.3 * 0.1 * 0.05).abs() < 1e-9, "{v}");
    }

    /// Figure 4.4(c) on a two-light window: the arch, its tympanum kept solid between the arch
    /// and the lights, and each light cut through it (its box removed from the slab, its own
    /// spandrels and glass in the hole).
    #[test]
    fn a_nested_window_shows_its_arch_a_solid_tympanum_and_lights_cut_through_it() {
        let lancet = |id: usize, x0: f64| Element {
            id,
            x0,
            y0: 180.0,
            h: 50.0,
            w: 30.0,
            v: 25.0,
            parent: Some(2),
            depth: 1,
            ..element(id, x0, 30.0, 25.0, Some(2))
        };
        let arch = Element {
            id: 2,
            x0: 20.0,
            y0: 190.0,
            h: 100.0,
            w: 120.0,
            v: 70.0,
            ..element(2, 20.0, 120.0, 70.0, None)
        };
        let est = GothicEstimate {
            width: 200,
            height: 220,
            elements: vec![lancet(0, 35.0), lancet(1, 95.0), arch],
            groups: vec![],
        };
        let opt = VsgOptions::default();
        let src = to_vsg(&est, None, &opt);
        let model = vsg::run(&src, &vsg::RunOptions::default())
            .unwrap_or_else(|e| panic!("{}\n{src}", e.render("gothic.vsg", &src)));
        let stats = vsg::stats::Stats::of(&model, &vsg::shape::Tessellation::default());
        let count = |s: &str| stats.by_symbol.get(s).copied().unwrap_or(0);
        // The arch's two spandrels and each lancet's two; the tympanum's two slabs (below and
        // above the springing line); each lancet's glass below and above its springing line.
        assert_eq!(count("spandrel"), 2 + 2 * 2, "{:?}", stats.by_symbol);
        assert_eq!(count("tympanum"), 2, "{:?}", stats.by_symbol);
        assert_eq!(count("glass"), 2 * 2, "{:?}", stats.by_symbol);
        // Volumes in model units (100 px per unit): the slab is depth × 0.3 thick; below the
        // springing line it is the arch's jamb box (1.2 × 1.0) less the two lancets' boxes
        // (0.3 × 0.75 each), above it the arch zone's box (1.2 × 0.7).
        let t = opt.wall_depth * 0.3;
        let want = t * (1.2 * 1.0 - 2.0 * 0.3 * 0.75) + t * 1.2 * 0.7;
        let got = stats.volume.by_symbol["tympanum"];
        assert!((got - want).abs() < 1e-6, "tympanum volume {got} vs {want}");
        // Without the holes the slab would be t × 1.2 × 1.7: the lights are cut through.
        assert!(got < t * 1.2 * 1.7 - 0.1);
        // Each light is glass: the lancet's jamb box (0.3 × 0.5) and its pointed head, 0.1 ×
        // depth thick, all of it inside the hole.
        let glass = stats.volume.by_symbol["glass"];
        let g = opt.wall_depth * 0.1;
        assert!(
            glass > 2.0 * g * 0.3 * 0.5 && glass < 2.0 * g * 0.3 * 0.75,
            "{glass}"
        );
    }
}
