//! The reconstruction report (index.html): what was built (the structures by role, measured or
//! defaulted), the model, the overlays of every step, the integrated structures with the
//! provenance of their parameters, stage times and the model's figures.
//! A static page that opens from disk with no network.

use std::fmt::Write;

use base64::Engine;
use integrate::estimate::{Estimate, Footprint, MappedFacade};
use integrate::pipeline::Reconstruction;
use integrate::project::Project;

/// The viewer script (web/src/viewer.js with three.js, bundled by build.rs).
const VIEWER_JS: &str = include_str!(concat!(env!("OUT_DIR"), "/viewer.js"));

/// Models larger than this are linked, not embedded in the page.
pub const MAX_EMBEDDED_MODEL: usize = 64 << 20;

/// The model viewer: the glb embedded as base64 and the bundled script.
fn viewer(glb: &[u8], estimate: &Estimate) -> String {
    if glb.len() > MAX_EMBEDDED_MODEL {
        return format!(
            "<p>The model ({} MB) is too large to embed in this page: open <a href=\"model.glb\">model.glb</a> in Blender or another glTF viewer.</p>",
            glb.len() >> 20
        );
    }
    format!(
        "<div style=\"display:flex;gap:1em\"><div id=\"viewer\" style=\"flex:1;height:560px;border:1px solid #ccc\"></div><div id=\"outline\" style=\"width:260px;height:560px;overflow:auto;font-size:90%\"></div></div>\n<p>Drag to orbit, scroll to zoom, right-drag to pan; untick a structure or a symbol to peel it away; click a part to see its parameters, volume and provenance.</p>\n<script type=\"application/octet-stream\" id=\"castellan-model\">{}</script>\n<script type=\"application/json\" id=\"castellan-estimate\">{}</script>\n<script>{}</script>\n",
        base64::engine::general_purpose::STANDARD.encode(glb),
        serde_json::to_string(estimate)
            .unwrap_or_default()
            .replace("</", "<\\/"),
        VIEWER_JS.replace("</script", "<\\/script")
    )
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The page: what was read and assumed, the model, every step's overlay with its legend, the
/// structures with the provenance of their parameters, and the time per stage.
pub fn html(project: &Project, r: &Reconstruction) -> String {
    let e = &r.estimate;
    let mut h = String::new();
    let _ = write!(
        h,
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>castellan reconstruction</title>\n<style>body{{font-family:sans-serif;margin:2em;max-width:1200px}}img{{max-width:100%;border:1px solid #ccc}}table{{border-collapse:collapse}}td,th{{border:1px solid #ccc;padding:.3em .6em;text-align:left;vertical-align:top}}figure{{display:inline-block;margin:.5em;max-width:45%;vertical-align:top}}code{{background:#f4f4f4}}</style></head><body>\n<h1>castellan reconstruction</h1>\n"
    );
    let _ = writeln!(
        h,
        "<p>Plan <code>{}</code>, {} façade photo(s), {} Gothic façade(s); units: {} ({} per plan pixel). Outputs: <a href=\"model.glb\">model.glb</a> (Blender, three.js, any glTF viewer), <a href=\"model.obj\">model.obj</a> (MeshLab), <a href=\"model.city.json\">model.city.json</a> (CityJSON 2.0: QGIS, cjio, 3D city viewers), <a href=\"model.ifc\">model.ifc</a> (IFC4: Bonsai, IfcOpenShell, BIM tools), <a href=\"model.vsg\">model.vsg</a> (the generated program: <code>castellan vsg run model.vsg -o model.glb</code>), <a href=\"estimate.json\">estimate.json</a>, <a href=\"stats.json\">stats.json</a>, <a href=\"plan.svg\">plan.svg</a>.</p>",
        esc(&project.plan),
        project.facades.len(),
        project.gothics.len(),
        e.scale.units.symbol(),
        e.scale.units_per_pixel
    );
    for w in &r.warnings {
        let _ = writeln!(
            h,
            "<p class=\"warning\" style=\"background:#fff3cd;border-left:4px solid #e0a800;padding:.4em .8em\"><b>Warning:</b> {}.</p>",
            esc(&w.to_string())
        );
    }
    for a in &e.assumptions {
        let _ = writeln!(h, "<p><b>Assumed:</b> {}.</p>", esc(a));
    }
    what_was_built(&mut h, e);
    let _ = writeln!(h, "<h2>Model</h2>{}", viewer(&r.exports.glb, e));
    let _ = writeln!(
        h,
        "<details><summary>Software-rendered preview</summary><img src=\"preview.png\" alt=\"rendered model\"></details>"
    );
    let stats = &r.exports.stats;
    let _ = writeln!(
        h,
        "<p>{} terminals ({} visible, {} void), {} triangles, total volume {:.1}.</p>",
        stats["terminals"],
        stats["visible_terminals"],
        stats["void_terminals"],
        stats["triangles"],
        stats["volume"]["total"].as_f64().unwrap_or(0.0)
    );
    h.push_str("<h2>Steps</h2>");
    for o in &r.overlays {
        if let Some(caption) = &o.caption {
            let _ = writeln!(
                h,
                "<figure><img src=\"{}\"><figcaption>{}</figcaption></figure>",
                esc(&o.name),
                esc(caption)
            );
        }
    }
    data_images(&mut h, r);
    structures_table(&mut h, e);
    let _ = writeln!(h, "</table></details><h2>Time per stage</h2><table>");
    for (k, v) in &r.stages {
        let _ = writeln!(h, "<tr><td>{}</td><td>{v:.0} ms</td></tr>", k.name());
    }
    let _ = writeln!(h, "</table></body></html>");
    h
}

/// The index images the overlays leave out (a class number a pixel, black to the eye): each
/// linked with the view a person reads, the same classes in colour with a key (issue 22).
fn data_images(h: &mut String, r: &Reconstruction) {
    let names: Vec<&str> = r
        .overlays
        .iter()
        .filter(|o| o.caption.is_none() && !o.name.ends_with(".view.png"))
        .map(|o| o.name.as_str())
        .collect();
    if names.is_empty() {
        return;
    }
    let _ = write!(
        h,
        "<p>Label images for programs (a class index a pixel: 0 background, 1 wall, 2 window), each with its view in colour: "
    );
    let links: Vec<String> = names
        .iter()
        .map(|n| {
            let view = format!("{}.view.png", n.trim_end_matches(".png"));
            let viewable = r.overlays.iter().any(|o| o.name == view);
            if viewable {
                format!(
                    "<a href=\"{0}\">{0}</a> (view: <a href=\"{1}\">{1}</a>)",
                    esc(n),
                    esc(&view)
                )
            } else {
                format!("<a href=\"{0}\">{0}</a>", esc(n))
            }
        })
        .collect();
    let _ = writeln!(h, "{}.</p>", links.join(", "));
}

/// What the model holds, as an expert names it (issue 25): the structures by role, how high,
/// and which heights were set by the user, measured, lent by a measured structure alike, or
/// defaulted.
fn what_was_built(h: &mut String, e: &Estimate) {
    let unit = e.scale.units.symbol();
    let _ = writeln!(
        h,
        "<h2>What was built</h2><p>{}.</p><table><tr><th>structures</th><th>height</th><th>heights set by you · measured · lent · default</th><th>ids</th></tr>",
        esc(&integrate::summary::line(e))
    );
    for r in integrate::summary::by_role(e) {
        let height = if (r.heights[1] - r.heights[0]).abs() < 0.005 {
            format!("{:.2} {unit}", r.heights[0])
        } else {
            format!("{:.2}–{:.2} {unit}", r.heights[0], r.heights[1])
        };
        let length = if r.length > 0.0 {
            format!(", {:.0} {unit} long", r.length)
        } else {
            String::new()
        };
        let _ = writeln!(
            h,
            "<tr><td><b>{}</b>{length}</td><td>{height}</td><td>{} · {} · {} · {}</td><td>{}</td></tr>",
            r.counted(),
            r.user,
            r.measured,
            r.lent,
            r.defaulted,
            esc(&r.ids.join(", "))
        );
    }
    let _ = writeln!(h, "</table>");
}

/// The structures (§6.1.3): footprint, height, façades and the source of every parameter,
/// folded away below the overlays (the lead table says what matters).
fn structures_table(h: &mut String, e: &Estimate) {
    let _ = writeln!(
        h,
        "<details><summary><h2 style=\"display:inline\">Structures (§6.1.3), {} with every parameter's provenance</h2></summary><table><tr><th>id</th><th>role</th><th>label</th><th>footprint</th><th>height</th><th>façades</th><th>provenance</th></tr>",
        e.structures.len()
    );
    for s in &e.structures {
        let fp = match &s.footprint {
            Footprint::Rectangle {
                center,
                size,
                rotation,
            } => format!(
                "rectangle at ({:.1}, {:.1}), {:.1} × {:.1}, {:.1}°",
                center[0],
                center[1],
                size[0],
                size[1],
                rotation.to_degrees()
            ),
            Footprint::Circle { center, radius } => {
                format!(
                    "circle at ({:.1}, {:.1}), r {:.1}",
                    center[0], center[1], radius
                )
            }
            Footprint::Blocks { rotation, blocks } => {
                let area: f64 = blocks.iter().map(|b| b.size[0] * b.size[1]).sum();
                format!(
                    "{} blocks, {area:.1} in area, {:.1}°",
                    blocks.len(),
                    rotation.to_degrees()
                )
            }
            Footprint::Wall {
                thickness, closed, ..
            } => {
                let pieces = s.footprint.pieces();
                let length: f64 = pieces
                    .iter()
                    .map(|[a, b]| (b[0] - a[0]).hypot(b[1] - a[1]))
                    .sum();
                format!(
                    "{} wall, {} pieces, {length:.1} long, {thickness:.1} thick",
                    if *closed { "ring" } else { "open" },
                    pieces.len()
                )
            }
        };
        let facades: Vec<String> = s.facades.iter().map(facade_line).collect();
        let prov: Vec<String> = s
            .provenance
            .iter()
            .map(|(k, p)| {
                format!(
                    "<b>{}</b>: {} — {}{}",
                    esc(k),
                    esc(&p.image),
                    esc(&p.step),
                    p.fit_error
                        .map(|v| format!(" (error {v:.2} px)"))
                        .unwrap_or_default()
                )
            })
            .collect();
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.2}</td><td>{}</td><td>{}</td></tr>",
            esc(&s.id),
            s.role.name(),
            s.label.name(),
            fp,
            s.height,
            facades.join("<br>"),
            prov.join("<br>")
        );
    }
}

/// One mapped façade in the structures table: a Gothic one by its elements (and what the
/// learned check dropped, issue 23), a rectangular one by its floors and windows.
fn facade_line(f: &MappedFacade) -> String {
    match &f.gothic {
        Some(g) => format!(
            "{} → {}: Gothic, {} arches in {} groups, {} stones{}, s = {:.4}",
            esc(&f.image),
            f.side,
            g.elements,
            g.groups,
            g.stones,
            if g.dropped > 0 {
                format!(
                    " (the learned check dropped {} more that the fit found, as unlike openings)",
                    g.dropped
                )
            } else {
                String::new()
            },
            f.scale
        ),
        None => format!(
            "{} → {}: {} floors, {} windows/floor, s = {:.4}{}",
            esc(&f.image),
            f.side,
            f.floors.len(),
            f.windows.count,
            f.scale,
            if f.joint { ", joint" } else { "" }
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gothic_facade(dropped: usize) -> MappedFacade {
        serde_json::from_value(serde_json::json!({
            "image": "north.png", "side": "north", "scale": 0.05, "height_factor": 1.0,
            "width": 10.0, "height": 12.0, "floors": [], "joint": false,
            "windows": {"count": 0, "offset": 0.0, "width": 0.0, "gap": 0.0},
            "bbox": [0.0, 0.0, 200.0, 240.0],
            "gothic": {"program": "gothic_keep.vsg", "alias": "keep", "elements": 3,
                       "groups": 1, "stones": 40, "dropped": dropped}
        }))
        .unwrap()
    }

    #[test]
    fn a_gothic_facade_line_says_what_the_learned_check_dropped() {
        assert_eq!(
            facade_line(&gothic_facade(2)),
            "north.png → north: Gothic, 3 arches in 1 groups, 40 stones (the learned check \
             dropped 2 more that the fit found, as unlike openings), s = 0.0500"
        );
        assert_eq!(
            facade_line(&gothic_facade(0)),
            "north.png → north: Gothic, 3 arches in 1 groups, 40 stones, s = 0.0500"
        );
    }
}
