//! The products of a parse as plain values: the PLAN.json document, the LABELS.png raster
//! (label index per pixel), an overlay coloured by label, and the vector SVG of the walls with
//! their fitted lines and arcs. No files here: the binary encodes and writes them.

use image::{GrayImage, Luma, Rgb, RgbImage};
use serde_json::{Value, json};

use crate::ParsedPlan;
use crate::fit::Fit;
use crate::label::Label;

/// `{"0": "castle_surroundings", ...}`, the legend of LABELS.png.
pub fn legend() -> Value {
    Value::Object(
        Label::ALL
            .iter()
            .map(|l| ((*l as u8).to_string(), Value::from(l.name())))
            .collect(),
    )
}

/// The PLAN.json document (ARCHITECTURE.md contract), with the tower count, wall thickness,
/// pre-processing figures and warnings added. `scale` (units per pixel) is recorded, not
/// applied: coordinates stay in pixels.
pub fn plan_json(p: &ParsedPlan, scale: Option<f64>) -> Value {
    json!({
        "width": p.width,
        "height": p.height,
        "scale": scale,
        "legend": legend(),
        "towers": p.towers,
        "scale_bar": p.scale_bar,
        "warnings": p.warnings,
        "preprocessing": p.pre,
        "vertices": p.vertices.iter().enumerate().map(|(i, v)| json!({"id": i, "x": v.x, "y": v.y})).collect::<Vec<_>>(),
        "edges": p.edges.iter().enumerate().map(|(i, e)| json!({
            "id": i, "from": e.from, "to": e.to, "label": e.label.name(),
            "thickness": e.thickness,
            "points": e.points.iter().map(|&(x, y)| [x, y]).collect::<Vec<_>>(),
            "fit": e.fit,
        })).collect::<Vec<_>>(),
        "faces": p.faces.iter().enumerate().map(|(i, f)| json!({
            "id": i, "label": f.label.name(), "area": f.area, "centroid": f.centroid,
            "edges": f.edges, "shape": f.shape,
        })).collect::<Vec<_>>(),
    })
}

/// LABELS.png: each pixel's value is the index of its label in the legend.
pub fn labels_image(p: &ParsedPlan) -> GrayImage {
    GrayImage::from_fn(p.width, p.height, |x, y| {
        Luma([p.labels[(y * p.width + x) as usize]])
    })
}

/// The drawing in grey under the label colours: walls opaque, open spaces half-transparent.
pub fn overlay(p: &ParsedPlan, grey: &GrayImage) -> RgbImage {
    RgbImage::from_fn(p.width, p.height, |x, y| {
        let l = Label::ALL[p.labels[(y * p.width + x) as usize] as usize];
        let c = l.color();
        let g = f64::from(grey.get_pixel(x, y)[0]);
        let a = if l.is_wall() { 0.85 } else { 0.45 };
        Rgb(c.map(|v| (a * f64::from(v) + (1.0 - a) * g).round() as u8))
    })
}

fn hex(l: Label) -> String {
    let [r, g, b] = l.color();
    // White walls would vanish on the white page: unknown walls are drawn grey.
    if l == Label::UnknownWall {
        return "#777777".into();
    }
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// SVG of the vectorised walls: each chain in thin grey, its fitted line or arc over it in
/// its label's colour, and the circle / rectangle fitted to each room dashed.
pub fn svg(p: &ParsedPlan) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#,
        w = p.width,
        h = p.height
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    for (i, e) in p.edges.iter().enumerate() {
        let pts: Vec<String> = e.points.iter().map(|(x, y)| format!("{x},{y}")).collect();
        let _ = writeln!(
            s,
            r##"<polyline id="chain{i}" points="{}" fill="none" stroke="#bbbbbb" stroke-width="1"/>"##,
            pts.join(" ")
        );
        let colour = hex(e.label);
        let sw = (e.thickness / 2.0).clamp(1.0, 8.0);
        match &e.fit {
            Some(Fit::Line { p0, p1, .. }) => {
                let _ = writeln!(
                    s,
                    r#"<line id="edge{i}" class="{}" x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{colour}" stroke-width="{sw:.1}"/>"#,
                    e.label.name(),
                    p0[0],
                    p0[1],
                    p1[0],
                    p1[1]
                );
            }
            Some(Fit::Arc {
                center,
                radius,
                start,
                sweep,
                ..
            }) => {
                let end = start + sweep;
                let (x0, y0) = (
                    center[0] + radius * start.cos(),
                    center[1] + radius * start.sin(),
                );
                let (x1, y1) = (
                    center[0] + radius * end.cos(),
                    center[1] + radius * end.sin(),
                );
                let large = u8::from(sweep.abs() > std::f64::consts::PI);
                let dir = u8::from(*sweep > 0.0);
                let _ = writeln!(
                    s,
                    r#"<path id="edge{i}" class="{}" d="M {x0:.1} {y0:.1} A {radius:.1} {radius:.1} 0 {large} {dir} {x1:.1} {y1:.1}" fill="none" stroke="{colour}" stroke-width="{sw:.1}"/>"#,
                    e.label.name()
                );
            }
            _ => {}
        }
    }
    for (i, f) in p.faces.iter().enumerate() {
        let colour = hex(f.label);
        match &f.shape {
            Some(Fit::Circle { center, radius, .. }) => {
                let _ = writeln!(
                    s,
                    r#"<circle id="face{i}" class="{}" cx="{:.1}" cy="{:.1}" r="{radius:.1}" fill="none" stroke="{colour}" stroke-dasharray="4 3"/>"#,
                    f.label.name(),
                    center[0],
                    center[1]
                );
            }
            Some(Fit::Rectangle {
                center,
                size,
                angle,
                ..
            }) => {
                let _ = writeln!(
                    s,
                    r#"<rect id="face{i}" class="{}" x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" transform="rotate({:.2} {:.1} {:.1})" fill="none" stroke="{colour}" stroke-dasharray="4 3"/>"#,
                    f.label.name(),
                    center[0] - size[0] / 2.0,
                    center[1] - size[1] / 2.0,
                    size[0],
                    size[1],
                    angle.to_degrees(),
                    center[0],
                    center[1]
                );
            }
            _ => {}
        }
    }
    s.push_str("</svg>\n");
    s
}
