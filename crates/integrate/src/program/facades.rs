//! The rules of structures with mapped façades (§6.1.3, figure 6.3; §7.2.3): a keep's walls
//! replaced by their rectified façades with floors and windows, and Gothic walls with their
//! arches, written for [`super::generate`].

use std::fmt::Write;

use super::common::{Options, list, n, storeys};
use crate::estimate::{Footprint, MappedFacade, Side, Structure};

/// Sides of a box: the axis its wall runs along, the axis through it, whether the outside is
/// the far end of that axis, and whether the façade's left-to-right (seen from outside) runs
/// against the run axis.
/// `None` for an arc, which is not a side of a box.
fn side_frame(side: Side) -> Option<(&'static str, &'static str, bool, bool)> {
    match side {
        Side::North => Some(("X", "Z", false, true)),
        Side::South => Some(("X", "Z", true, false)),
        Side::East => Some(("Z", "X", true, true)),
        Side::West => Some(("Z", "X", false, false)),
        Side::Arc => None,
    }
}

/// VSG rules 7.3's keep: walls split from the mass model, the walls with a photo replaced by
/// their façade (figure 6.3), storeys from the façade's floors inside.
pub(super) fn hollow_box_with_facades(
    s: &Structure,
    o: &Options,
    u: f64,
    imports: &mut String,
    params: &mut String,
    rules: &mut String,
) {
    let id = &s.id;
    let _ = writeln!(
        rules,
        "\n// {id}: walls and interior (§6.1.3).\n{id} :: split(\"Z\", {{{id}S[3], ~1, {id}S[3]}}){{{id}Wall_north, {id}Mid, {id}Wall_south}};\n{id}Mid :: split(\"X\", {{{id}S[3], ~1, {id}S[3]}}){{{id}Wall_west, {id}Interior, {id}Wall_east}};"
    );
    let Footprint::Rectangle { size, .. } = s.footprint else {
        return;
    };
    let t = s.wall_thickness.min(size[0].min(size[1]) * 0.3);
    // Interior storeys follow the first façade's floors.
    let floor_heights: Vec<f64> = match s.facades.iter().find(|f| !f.floors.is_empty()) {
        Some(f) => f.floors.iter().map(|fl| fl.height).collect(),
        None => vec![s.height / f64::from(storeys(s, o, u)); storeys(s, o, u) as usize],
    };
    let _ = writeln!(
        params,
        "float[] {id}FlH = {{{}}}; // storey heights, bottom-up",
        list(&floor_heights)
    );
    let storey_names: Vec<String> = (0..floor_heights.len())
        .map(|_| format!("{id}Storey"))
        .collect();
    let _ = writeln!(
        rules,
        "{id}Interior :: split(\"Y\", {{{}}}){{{}}};\n{id}Storey :: split(\"Y\", {{{}, ~1}}){{floorSlab, room}};",
        relative(&floor_heights),
        storey_names.join(", "),
        n((0.3 * u).min(floor_heights.iter().cloned().fold(f64::INFINITY, f64::min) * 0.2))
    );
    for side in Side::BOX {
        let facade = s.facades.iter().position(|f| f.side == side);
        match facade {
            None => {
                let _ = writeln!(rules, "{id}Wall_{side} :: {{masonry}};");
            }
            Some(k) => match &s.facades[k].gothic {
                Some(g) => gothic_wall(s, &s.facades[k], g, side, imports, rules),
                None => facade_rules(s, &s.facades[k], k + 1, side, t, params, rules),
            },
        }
    }
}

/// §6.1.3 for a Gothic façade: the wall is replaced by the façade's block program (its wall
/// minus the arches, the arches' glass and tympana, the stones), imported and placed with its
/// origin at the wall's foot at its left end seen from outside, x along the wall, z outwards.
fn gothic_wall(
    s: &Structure,
    f: &MappedFacade,
    g: &crate::estimate::GothicMapped,
    side: Side,
    imports: &mut String,
    rules: &mut String,
) {
    let Footprint::Rectangle { size, .. } = s.footprint else {
        return;
    };
    let (a, b, h) = (size[0] / 2.0, size[1] / 2.0, s.height / 2.0);
    let (x, z, turn) = match side {
        Side::North => (a, 0.0, std::f64::consts::PI),
        Side::South => (-a, 0.0, 0.0),
        Side::East => (0.0, b, std::f64::consts::FRAC_PI_2),
        Side::West => (0.0, -b, -std::f64::consts::FRAC_PI_2),
        Side::Arc => return,
    };
    let id = &s.id;
    let alias = &g.alias;
    let _ = writeln!(
        imports,
        "import {:?} as {alias}; // Gothic façade {} ({} arches, {} stones), scaled by s = {}",
        g.program,
        f.image,
        g.elements,
        g.stones,
        n(f.scale)
    );
    let _ = writeln!(
        rules,
        "\n// {id}Wall_{side} is replaced by the Gothic façade {} (figure 6.3, ch. 4).\n{id}Wall_{side} :: T({}, {}, {}) R(0, {}, 0) I(\"box\", {{0.001, 0.001, 0.001}}){{{alias}.Axiom}};",
        f.image,
        n(x),
        n(-h),
        n(z),
        n(turn)
    );
}

/// Lengths as `~` relative sizes (they fill their shape whatever the rounding).
fn relative(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("~{}", n(*x)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Figure 6.3: a wall replaced by its façade — floors, each a band of sill, window row and
/// lintel; each row split into piers and windows along the wall.
fn facade_rules(
    s: &Structure,
    f: &MappedFacade,
    k: usize,
    side: Side,
    t: f64,
    params: &mut String,
    rules: &mut String,
) {
    let id = &s.id;
    let fid = format!("{id}Facade{k}");
    let Some((run, through, outside_far, reversed)) = side_frame(side) else {
        return;
    };
    // Under a photo the pieces keep its texture untinted.
    // Under a photo the pieces keep its texture untinted, but only on a skin on the wall's
    // outer face (a twentieth of the wall); behind it the wall is masonry, so the photo does
    // not show again on the inner face.
    let wall = format!("{fid}Wall");
    let (photo, masonry, glass) = match &f.texture {
        Some(t) => (
            format!("appearance(\"photo\", {t:?}, \"color\", {{1, 1, 1}}) "),
            wall.as_str(),
            "facadeGlass",
        ),
        None => (String::new(), "masonry", "glass"),
    };
    let heights: Vec<f64> = f.floors.iter().map(|fl| fl.height).collect();
    let _ = writeln!(
        params,
        "// {fid}: {} on the {side} wall; floors and windows by §3.1.7, scaled by s = {} (w_p / w_f){}.\nfloat[] {fid}FlH = {{{}}}; // floor heights, bottom-up\nfloat[] {fid}WinV = {{{}}}; // per floor: sill, window height\nfloat[] {fid}WinH = {{{}, {}, {}, {}}}; // offset, width, gap, count (from the left seen from outside)",
        f.image,
        n(f.scale),
        if f.joint {
            " and re-estimated jointly with the other façades (§6.1.2)"
        } else {
            ""
        },
        list(&heights),
        list(
            &f.floors
                .iter()
                .flat_map(|fl| [fl.window_sill, fl.window_height])
                .collect::<Vec<_>>()
        ),
        n(f.windows.offset),
        n(f.windows.width),
        n(f.windows.gap),
        f.windows.count
    );
    let floor_names: Vec<String> = (1..=f.floors.len())
        .map(|i| format!("{fid}Floor{i}"))
        .collect();
    let _ = writeln!(
        rules,
        "\n// {fid} replaces {id}Wall_{side} (figure 6.3){}.\n{id}Wall_{side} :: {{{fid}}};\n{fid} :: {photo}split(\"Y\", {{{}}}){{{}}};",
        if f.texture.is_some() {
            ", the rectified photo stretched over it"
        } else {
            ""
        },
        relative(&heights),
        floor_names.join(", ")
    );
    if f.texture.is_some() {
        let (sizes, names) = if outside_far {
            ("~19, ~1", "facadeBack, facadeWall")
        } else {
            ("~1, ~19", "facadeWall, facadeBack")
        };
        let _ = writeln!(
            rules,
            "{wall} :: split(\"{through}\", {{{sizes}}}){{{names}}};"
        );
    }
    // The east and west walls sit between the north and south ones: their run starts t later.
    let inset = if run == "Z" { t } else { 0.0 };
    let wall_len = if run == "Z" {
        f.width - 2.0 * t
    } else {
        f.width
    };
    // A row of windows [start, width] along the wall (seen from outside): masonry between
    // them, as split sizes and symbols.
    let window = format!("{fid}Window");
    let row = |windows: &[(f64, f64)]| -> (Vec<String>, Vec<String>) {
        let mut pieces: Vec<(f64, &str)> = Vec::new();
        let mut x = -inset;
        for &(start, width) in windows {
            let start = start - inset;
            let (a, b) = (start.max(0.0), (start + width).min(wall_len));
            if b - a < 1e-6 || a < x - 1e-9 {
                continue;
            }
            if a - x.max(0.0) > 1e-6 {
                pieces.push((a - x.max(0.0), "masonry"));
            }
            pieces.push((b - a, "window"));
            x = b;
        }
        let rest = wall_len - x.max(0.0);
        if rest > 1e-6 {
            pieces.push((rest, "masonry"));
        }
        if reversed {
            pieces.reverse();
        }
        let sizes = pieces.iter().map(|(l, _)| format!("~{}", n(*l))).collect();
        let names = pieces
            .iter()
            .map(|(_, s)| {
                if *s == "window" {
                    window.clone()
                } else {
                    masonry.to_string()
                }
            })
            .collect();
        (sizes, names)
    };
    let w = &f.windows;
    let shared: Vec<(f64, f64)> = (0..w.count)
        .map(|j| (w.offset + f64::from(j) * (w.width + w.gap), w.width))
        .collect();
    let (sizes, names) = row(&shared);
    let mut own_rows = String::new();
    for (i, fl) in f.floors.iter().enumerate() {
        let name = &floor_names[i];
        // Issue 22: a floor of a corrected façade has its windows where the user left them.
        let (row_name, has_window) = match &fl.openings {
            Some(openings) => {
                let mine: Vec<(f64, f64)> = openings.iter().map(|o| (o[0], o[1])).collect();
                let (sizes, names) = row(&mine);
                let row_name = format!("{fid}Row{}", i + 1);
                let has = names.contains(&window);
                if has {
                    let _ = writeln!(
                        own_rows,
                        "{row_name} :: split(\"{run}\", {{{}}}){{{}}};",
                        sizes.join(", "),
                        names.join(", ")
                    );
                }
                (row_name, has)
            }
            None => (format!("{fid}Row"), names.contains(&window)),
        };
        if fl.windows == 0 || fl.window_height <= 0.0 || !has_window {
            let _ = writeln!(rules, "{name} :: {{{masonry}}};");
            continue;
        }
        let above = (fl.height - fl.window_sill - fl.window_height).max(0.0);
        let _ = writeln!(
            rules,
            "{name} :: split(\"Y\", {{~{}, ~{}, ~{}}}){{{masonry}, {row_name}, {masonry}}};",
            n(fl.window_sill.max(1e-4)),
            n(fl.window_height),
            n(above.max(1e-4))
        );
    }
    rules.push_str(&own_rows);
    let _ = writeln!(
        rules,
        "{fid}Row :: split(\"{run}\", {{{}}}){{{}}};",
        sizes.join(", "),
        names.join(", ")
    );
    // Glass set back in the inner third; the outer two thirds are the opening.
    let (a, b) = if outside_far {
        (glass, "opening")
    } else {
        ("opening", glass)
    };
    let (la, lb) = if outside_far {
        ("~1", "~2")
    } else {
        ("~2", "~1")
    };
    let _ = writeln!(
        rules,
        "{window} :: split(\"{through}\", {{{la}, {lb}}}){{{a}, {b}}};"
    );
}
