//! The products of a parse as plain values: the PLAN.json document, the LABELS.png raster
//! (label index per pixel), an overlay coloured by label, and the vector SVG of the walls with
//! their fitted lines and arcs. No files here: the binary encodes and writes them.

use image::{GrayImage, Luma, Rgb, RgbImage};
use raster::legend::{self, Entry, Swatch};
use serde_json::{Value, json};

use crate::ParsedPlan;
use crate::fit::Fit;
use crate::label::Label;
use crate::scalebar::ScaleBar;

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
/// pre-processing figures and warnings added. `scale` (metres per pixel, given or read from
/// the bar) is recorded, not applied: coordinates stay in pixels.
pub fn plan_json(p: &ParsedPlan, metres_per_pixel: Option<f64>) -> Value {
    json!({
        "width": p.width,
        "height": p.height,
        "scale": metres_per_pixel,
        "legend": legend(),
        "towers": p.towers,
        "bulge_towers": p.bulge_towers,
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

/// The key of the label pictures: each label the plan has, in legend order, and the scale
/// bar's frame when one was found.
pub fn label_key(p: &ParsedPlan) -> Vec<Entry> {
    let mut present = [false; 11];
    for &l in &p.labels {
        present[usize::from(l).min(10)] = true;
    }
    let mut key: Vec<Entry> = Label::ALL
        .iter()
        .filter(|l| present[**l as usize])
        .map(|l| Entry::new(Swatch::Fill(l.color()), l.words()))
        .collect();
    if p.scale_bar.is_some() {
        key.push(Entry::new(Swatch::Ring(SCALE_BAR_COLOUR), "scale bar"));
    }
    key
}

/// The labels of [`label_key`] with their colours in words, for captions: "courtyard blue,
/// tower room green, …".
pub fn label_key_words(p: &ParsedPlan) -> String {
    let mut present = [false; 11];
    for &l in &p.labels {
        present[usize::from(l).min(10)] = true;
    }
    let mut words: Vec<String> = Label::ALL
        .iter()
        .filter(|l| present[**l as usize])
        .map(|l| format!("{} {}", l.words(), l.color_name()))
        .collect();
    if p.scale_bar.is_some() {
        words.push("scale bar framed in magenta".into());
    }
    words.join(", ")
}

/// Draws `key` into a picture of `p` where it covers the least of the castle and none of the
/// scale bar (issue 22: every overlay carries its key).
fn draw_key(img: &mut RgbImage, p: &ParsedPlan, key: &[Entry]) -> Option<legend::Placed> {
    let outside = Label::CastleSurroundings as u8;
    let frame = p
        .scale_bar
        .as_ref()
        .map(|b| scale_bar_frame(b, p.width, p.height));
    legend::draw(img, key, &|x, y| {
        p.labels[(y * p.width + x) as usize] != outside
            || frame
                .is_some_and(|[x0, y0, x1, y1]| (x0..=x1).contains(&x) && (y0..=y1).contains(&y))
    })
}

/// LABELS.view.png: the label colours alone, with the key — LABELS.png (an index image, dark
/// to a person) as a person views it.
pub fn labels_view(p: &ParsedPlan) -> RgbImage {
    let mut img = RgbImage::from_fn(p.width, p.height, |x, y| {
        Rgb(Label::ALL[usize::from(p.labels[(y * p.width + x) as usize]).min(10)].color())
    });
    draw_key(&mut img, p, &label_key(p));
    img
}

/// The label colours in words, one label a line ("tower_room: green"), for `--help` and
/// the docs.
pub fn label_colours_text() -> String {
    Label::ALL
        .iter()
        .map(|l| {
            let [r, g, b] = l.color();
            format!("  {:<20} {} ({r}, {g}, {b})", l.name(), l.color_name())
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The drawing in grey under the label colours: walls opaque, open spaces half-transparent.
/// A scale bar found on the sheet is framed in [`SCALE_BAR_COLOUR`], so the user can check
/// what the metres hang on. The key ([`label_key`]) sits in the emptiest corner.
pub fn overlay(p: &ParsedPlan, grey: &GrayImage) -> RgbImage {
    let mut img = RgbImage::from_fn(p.width, p.height, |x, y| {
        let l = Label::ALL[p.labels[(y * p.width + x) as usize] as usize];
        let c = l.color();
        let g = f64::from(grey.get_pixel(x, y)[0]);
        let a = if l.is_wall() { 0.85 } else { 0.45 };
        Rgb(c.map(|v| (a * f64::from(v) + (1.0 - a) * g).round() as u8))
    });
    if let Some(bar) = &p.scale_bar {
        let [x0, y0, x1, y1] = scale_bar_frame(bar, p.width, p.height);
        for x in x0..=x1 {
            for y in [y0, y1] {
                img.put_pixel(x, y, Rgb(SCALE_BAR_COLOUR));
            }
        }
        for y in y0..=y1 {
            for x in [x0, x1] {
                img.put_pixel(x, y, Rgb(SCALE_BAR_COLOUR));
            }
        }
    }
    draw_key(&mut img, p, &label_key(p));
    img
}

/// Colour of the walls in [`walls_overlay`].
pub const WALL_INK_COLOUR: [u8; 3] = [220, 30, 30];

/// The walls chapter 5 read (the wall mask after §5.1.2, from the learned wall ink or the
/// rules) in [`WALL_INK_COLOUR`] over the drawing in grey: what the user judges and strokes
/// against (legend: [`WALLS_LEGEND`]).
pub fn walls_overlay(p: &ParsedPlan, grey: &GrayImage) -> RgbImage {
    let mut img = RgbImage::from_fn(p.width, p.height, |x, y| {
        let g = f64::from(grey.get_pixel(x, y)[0]);
        if p.walls.data[(y * p.width + x) as usize] != 0 {
            Rgb(WALL_INK_COLOUR.map(|v| (0.75 * f64::from(v) + 0.25 * g).round() as u8))
        } else {
            let v = (0.55 * g + 0.45 * 255.0).round() as u8;
            Rgb([v, v, v])
        }
    });
    let key = [
        Entry::new(Swatch::Fill(WALL_INK_COLOUR), "wall as read"),
        Entry::new(Swatch::Fill([200, 200, 200]), "drawing, not wall"),
    ];
    draw_key(&mut img, p, &key);
    img
}

/// The legend of [`walls_overlay`].
pub const WALLS_LEGEND: &str = "red: wall as read (learned wall ink or rules, then §5.1.2's open/close and specks); grey: the drawing, not wall";

/// Colour of the frame drawn round a found scale bar (no label uses it).
pub const SCALE_BAR_COLOUR: [u8; 3] = [230, 0, 200];

/// The frame round a scale bar: its ticks reach up to 14 px either side of the line, so the
/// frame stands a little beyond, clipped to the image.
fn scale_bar_frame(bar: &ScaleBar, width: u32, height: u32) -> [u32; 4] {
    const MARGIN: u32 = 4;
    const HALF_HEIGHT: u32 = 8;
    [
        bar.x0.saturating_sub(MARGIN),
        bar.y0.min(bar.y1).saturating_sub(HALF_HEIGHT),
        (bar.x1 + MARGIN).min(width - 1),
        (bar.y0.max(bar.y1) + HALF_HEIGHT).min(height - 1),
    ]
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
    if let Some(bar) = &p.scale_bar {
        let [x0, y0, x1, y1] = scale_bar_frame(bar, p.width, p.height);
        let [r, g, b] = SCALE_BAR_COLOUR;
        let _ = writeln!(
            s,
            r##"<rect id="scale_bar" x="{x0}" y="{y0}" width="{}" height="{}" fill="none" stroke="#{r:02x}{g:02x}{b:02x}"><title>scale bar, {} px</title></rect>"##,
            x1 - x0,
            y1 - y0,
            bar.length_px
        );
    }
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::Canvas;

    fn plan_with_bar(bar: Option<ScaleBar>) -> ParsedPlan {
        let mut c = Canvas::new(200, 160);
        c.poly(
            &[(40.0, 30.0), (160.0, 30.0), (160.0, 110.0), (40.0, 110.0)],
            6.0,
        );
        let img = image::DynamicImage::ImageLuma8(c.0);
        let mut p = crate::parse(&img, &crate::Options::default()).unwrap();
        p.scale_bar = bar;
        p
    }

    const BAR: ScaleBar = ScaleBar {
        x0: 50,
        y0: 140,
        x1: 150,
        y1: 140,
        length_px: 101,
    };

    #[test]
    fn overlay_frames_the_scale_bar_and_nothing_else() {
        let grey = GrayImage::from_pixel(200, 160, Luma([255]));
        let framed = |p: &ParsedPlan| {
            overlay(p, &grey)
                .pixels()
                .filter(|px| px.0 == SCALE_BAR_COLOUR)
                .count()
        };
        let with = plan_with_bar(Some(BAR));
        // Frame 46..=154 × 132..=148: two rows of 109 and two columns of 17, corners once;
        // and the key's swatch of it, a 5 × 5 ring (16 pixels).
        assert_eq!(framed(&with), 2 * 109 + 2 * 17 - 4 + 16);
        assert_eq!(overlay(&with, &grey).get_pixel(46, 140).0, SCALE_BAR_COLOUR);
        assert_eq!(framed(&plan_with_bar(None)), 0);
    }

    #[test]
    fn the_overlays_carry_their_key_off_the_castle_and_the_view_is_the_label_colours() {
        let p = plan_with_bar(Some(BAR));
        let key = label_key(&p);
        let words: Vec<&str> = key.iter().map(|e| e.text.as_str()).collect();
        // The parsed square: surroundings, its wall, the courtyard; and the bar.
        assert_eq!(
            words,
            [
                "castle surroundings",
                "castle outer wall",
                "courtyard",
                "scale bar"
            ]
        );
        let grey = GrayImage::from_pixel(200, 160, Luma([255]));
        // The key goes to a top corner (the bottom has the bar), the one that covers the least
        // of the castle, the same in every picture of the plan.
        let placed = draw_key(&mut RgbImage::new(200, 160), &p, &key);
        assert_eq!(placed, Some([0, 0, 86, 30]));
        let framed_top_left = |img: &RgbImage| {
            img.get_pixel(0, 0).0 == [60, 60, 60] && img.get_pixel(0, 159).0 != [60, 60, 60]
        };
        assert!(framed_top_left(&overlay(&p, &grey)));
        let v = labels_view(&p);
        assert!(framed_top_left(&v));
        assert_eq!(v.get_pixel(100, 70).0, Label::Courtyard.color());
        // The walls' key, smaller, goes where it covers least: its frame is drawn somewhere.
        let frame = |img: RgbImage| img.pixels().filter(|q| q.0 == [60, 60, 60]).count();
        assert!(frame(walls_overlay(&p, &grey)) > 100);
        assert_eq!(
            label_key_words(&p),
            "castle surroundings dark blue, castle outer wall yellow, courtyard blue, scale bar framed in magenta"
        );
        let text = label_colours_text();
        assert_eq!(text.lines().count(), 11);
        assert!(
            text.contains("tower_room           green (30, 170, 60)"),
            "{text}"
        );
    }

    #[test]
    fn frame_is_clipped_to_the_image() {
        let bar = ScaleBar {
            x0: 1,
            y0: 158,
            x1: 198,
            y1: 158,
            length_px: 198,
        };
        assert_eq!(scale_bar_frame(&bar, 200, 160), [0, 150, 199, 159]);
        let p = plan_with_bar(Some(bar));
        let grey = GrayImage::from_pixel(200, 160, Luma([255]));
        assert_eq!(overlay(&p, &grey).get_pixel(0, 159).0, SCALE_BAR_COLOUR);
    }

    #[test]
    fn svg_names_the_scale_bar_with_its_length() {
        let s = svg(&plan_with_bar(Some(BAR)));
        assert!(
            s.contains(r#"<rect id="scale_bar" x="46" y="132" width="108" height="16""#),
            "{s}"
        );
        assert!(s.contains("scale bar, 101 px"));
        assert!(!svg(&plan_with_bar(None)).contains("scale_bar"));
    }
}
