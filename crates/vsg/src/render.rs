//! Quick preview pictures of a produced model (for docs and for users without a 3D viewer): a
//! small software rasterizer with a z-buffer and Lambert shading, drawing the visible terminals
//! (§7.1.3; void terminals are skipped) in their appearance colours from a 3/4 orthographic
//! view fitted to the model's bounds. Returns RGB pixels; the caller encodes them.

use nalgebra::{Point3, Vector3};

use crate::shape::Tessellation;
use crate::tree::{Model, NodeState};

/// How to draw a preview.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    pub width: u32,
    pub height: u32,
    /// Horizontal angle of the viewer around the model, radians from +z towards +x.
    pub azimuth: f64,
    /// Angle of the viewer above the ground plane, radians.
    pub elevation: f64,
    /// Samples per pixel along each axis (anti-aliasing); 1 turns it off.
    pub supersample: u32,
    pub tessellation: Tessellation,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 800,
            height: 600,
            azimuth: -std::f64::consts::FRAC_PI_4 * 0.75,
            elevation: 0.45,
            supersample: 2,
            tessellation: Tessellation::default(),
        }
    }
}

/// An RGB picture, rows top to bottom, 3 bytes per pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Picture {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
}

const BACKGROUND: [f64; 3] = [0.93, 0.94, 0.96];

/// One world-space triangle with its colour.
struct Tri {
    p: [Point3<f64>; 3],
    color: [f64; 3],
}

/// Renders the visible terminals of `model`. An empty model gives a blank picture.
pub fn render(model: &Model, options: &RenderOptions) -> Picture {
    let ss = options.supersample.max(1);
    let (w, h) = (options.width.max(1) * ss, options.height.max(1) * ss);
    let tris = triangles(model, &options.tessellation);
    // Viewer basis: `e` points from the model towards the viewer.
    let (az, el) = (options.azimuth, options.elevation);
    let e = Vector3::new(el.cos() * az.sin(), el.sin(), el.cos() * az.cos());
    let right = Vector3::y().cross(&e).normalize();
    let up = e.cross(&right);
    let project = |p: &Point3<f64>| (p.coords.dot(&right), p.coords.dot(&up), p.coords.dot(&e));
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for t in &tris {
        for p in &t.p {
            let (x, y, _) = project(p);
            lo = [lo[0].min(x), lo[1].min(y)];
            hi = [hi[0].max(x), hi[1].max(y)];
        }
    }
    let mut color = vec![BACKGROUND; (w * h) as usize];
    let mut depth = vec![f64::NEG_INFINITY; (w * h) as usize];
    if !tris.is_empty() {
        let margin = 0.06;
        let (sx, sy) = ((hi[0] - lo[0]).max(1e-12), (hi[1] - lo[1]).max(1e-12));
        let scale =
            ((w as f64) * (1.0 - 2.0 * margin) / sx).min((h as f64) * (1.0 - 2.0 * margin) / sy);
        let (cx, cy) = ((lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0);
        let to_screen = |p: &Point3<f64>| {
            let (x, y, z) = project(p);
            [
                w as f64 / 2.0 + (x - cx) * scale,
                h as f64 / 2.0 - (y - cy) * scale,
                z,
            ]
        };
        // Light from above, over the viewer's left shoulder.
        let light = (e * 0.9 + up * 0.8 - right * 0.5).normalize();
        for t in &tris {
            let n = (t.p[1] - t.p[0]).cross(&(t.p[2] - t.p[0]));
            let Some(n) = n.try_normalize(1e-18) else {
                continue;
            };
            if n.dot(&e) <= 0.0 {
                continue; // back face of a closed mesh
            }
            let shade = 0.35 + 0.65 * n.dot(&light).max(0.0);
            let c = t.color.map(|v| (v * shade).clamp(0.0, 1.0));
            let s = t.p.map(|p| to_screen(&p));
            fill(&s, c, w, h, &mut color, &mut depth);
        }
    }
    downsample(&color, w, h, ss)
}

fn triangles(model: &Model, tessellation: &Tessellation) -> Vec<Tri> {
    let mut out = Vec::new();
    for (i, node) in model.nodes.iter().enumerate() {
        if node.state != NodeState::Terminal {
            continue;
        }
        let Some(solid) = model.solid(i as u32) else {
            continue;
        };
        let mesh = solid.mesh(tessellation);
        let color = model.appearance(node).color;
        let world: Vec<Point3<f64>> = mesh
            .positions
            .iter()
            .map(|p| node.world * Point3::from(*p))
            .collect();
        out.extend(mesh.triangles.iter().map(|t| Tri {
            p: t.map(|k| world[k as usize]),
            color,
        }));
    }
    out
}

/// Fills a screen-space triangle (`[x, y, depth]`, larger depth nearer) with edge functions,
/// sampling at pixel centres.
fn fill(s: &[[f64; 3]; 3], c: [f64; 3], w: u32, h: u32, color: &mut [[f64; 3]], depth: &mut [f64]) {
    let area =
        (s[1][0] - s[0][0]) * (s[2][1] - s[0][1]) - (s[2][0] - s[0][0]) * (s[1][1] - s[0][1]);
    if area.abs() < 1e-12 {
        return;
    }
    let x0 = s
        .iter()
        .map(|p| p[0])
        .fold(f64::INFINITY, f64::min)
        .floor()
        .max(0.0) as u32;
    let x1 = s
        .iter()
        .map(|p| p[0])
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil()
        .min(w as f64) as u32;
    let y0 = s
        .iter()
        .map(|p| p[1])
        .fold(f64::INFINITY, f64::min)
        .floor()
        .max(0.0) as u32;
    let y1 = s
        .iter()
        .map(|p| p[1])
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil()
        .min(h as f64) as u32;
    let edge = |a: &[f64; 3], b: &[f64; 3], x: f64, y: f64| {
        (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0])
    };
    for y in y0..y1 {
        for x in x0..x1 {
            let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
            let w0 = edge(&s[1], &s[2], px, py) / area;
            let w1 = edge(&s[2], &s[0], px, py) / area;
            let w2 = edge(&s[0], &s[1], px, py) / area;
            if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                continue;
            }
            let z = w0 * s[0][2] + w1 * s[1][2] + w2 * s[2][2];
            let k = (y * w + x) as usize;
            if z > depth[k] {
                depth[k] = z;
                color[k] = c;
            }
        }
    }
}

fn downsample(color: &[[f64; 3]], w: u32, h: u32, ss: u32) -> Picture {
    let (ow, oh) = (w / ss, h / ss);
    let mut rgb = Vec::with_capacity((ow * oh * 3) as usize);
    let n = (ss * ss) as f64;
    for y in 0..oh {
        for x in 0..ow {
            let mut sum = [0.0; 3];
            for dy in 0..ss {
                for dx in 0..ss {
                    let c = color[((y * ss + dy) * w + x * ss + dx) as usize];
                    (0..3).for_each(|k| sum[k] += c[k]);
                }
            }
            rgb.extend(sum.map(|v| (v / n * 255.0).round().clamp(0.0, 255.0) as u8));
        }
    }
    Picture {
        width: ow,
        height: oh,
        rgb,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pixel(p: &Picture, x: u32, y: u32) -> [u8; 3] {
        let k = ((y * p.width + x) * 3) as usize;
        [p.rgb[k], p.rgb[k + 1], p.rgb[k + 2]]
    }

    fn model(src: &str) -> Model {
        crate::run(src, &Default::default()).unwrap()
    }

    #[test]
    fn a_red_box_fills_the_middle_and_leaves_the_corners_blank() {
        let m =
            model("Axiom :: I(\"box\",{2,2,2}) appearance(\"color\", {1, 0, 0}){j3d.terminal};");
        let options = RenderOptions {
            width: 64,
            height: 48,
            supersample: 1,
            ..Default::default()
        };
        let p = render(&m, &options);
        assert_eq!((p.width, p.height, p.rgb.len()), (64, 48, 64 * 48 * 3));
        let bg = BACKGROUND.map(|v| (v * 255.0).round() as u8);
        assert_eq!(pixel(&p, 0, 0), bg);
        let c = pixel(&p, 32, 24);
        assert!(c[0] > 60 && c[1] == 0 && c[2] == 0, "{c:?}");
        // Three faces are seen, with three different shades of red.
        let mut shades: Vec<u8> = (0..p.width * p.height)
            .map(|i| pixel(&p, i % p.width, i / p.width))
            .filter(|c| c[1] == 0 && c[2] == 0)
            .map(|c| c[0])
            .collect();
        shades.sort();
        shades.dedup();
        assert_eq!(shades.len(), 3, "{shades:?}");
    }

    #[test]
    fn void_terminals_are_not_drawn() {
        let m = model("Axiom :: I(\"box\",{2,2,2}) void(){j3d.terminal};");
        let p = render(
            &m,
            &RenderOptions {
                width: 16,
                height: 16,
                ..Default::default()
            },
        );
        let bg = BACKGROUND.map(|v| (v * 255.0).round() as u8);
        assert!(p.rgb.chunks(3).all(|c| c == bg));
    }

    #[test]
    fn nearer_faces_hide_farther_ones() {
        // A small green box in front of (towards the viewer) a large blue one, and the same
        // behind it: green shows only in the first picture.
        let (az, el) = (0.0, 0.0); // looking along -z from +z
        let scene = |z: f64| {
            model(&format!(
                "Axiom :: I(\"box\",{{4,4,1}}) T(0,0,{z}) I(\"box\",{{1,1,1}}){{back, front}};\n\
                 back :: appearance(\"color\", {{0,0,1}}){{j3d.terminal}};\n\
                 front :: appearance(\"color\", {{0,1,0}}){{j3d.terminal}};"
            ))
        };
        let options = RenderOptions {
            width: 40,
            height: 40,
            azimuth: az,
            elevation: el,
            supersample: 1,
            ..Default::default()
        };
        let green = |p: &Picture| p.rgb.chunks(3).any(|c| c[1] > 0 && c[0] == 0 && c[2] == 0);
        assert!(green(&render(&scene(2.0), &options)));
        assert!(!green(&render(&scene(-2.0), &options)));
    }
}
