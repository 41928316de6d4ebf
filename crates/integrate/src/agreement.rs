//! Plan–model agreement (issue 25): how well the model stands on the plan it was built from.
//! The model's visible terminals are seen from above — projected onto the ground plane and
//! rasterised at the plan's pixel grid (plan pixel (x, y) is model (x, z) / units per pixel) —
//! and compared with the plan's built area, every pixel not labelled castle_surroundings or
//! courtyard (walls, towers, rooms): intersection over union, precision (the share of the
//! model's footprint that the plan builds) and recall (the share of the plan's built area the
//! model covers). Each room of the plan and each tower (tower rooms and bulge towers) is
//! *present* when the footprint covers at least half of it, with the structure seen most over
//! it. Pure: plan, estimate and model in, figures out; stats.json carries the summary.

use plan::ParsedPlan;
use plan::bulges::BulgeTower;
use plan::label::Label;
use raster::legend::{Entry, Swatch};
use serde::Serialize;
use vsg::shape::Tessellation;
use vsg::tree::{Model, NodeState};

use crate::estimate::Estimate;

/// A room or tower counts as built when the footprint covers at least this share of its
/// pixels: half, so that a structure whose fitted outline is slightly smaller than the drawn
/// room still counts, and a room crossed by a neighbour's wall alone does not.
pub const PRESENT: f64 = 0.5;

/// The model seen from above at the plan's pixel grid: for each pixel, the structure whose
/// surface is highest over the pixel's centre.
#[derive(Debug, Clone, PartialEq)]
pub struct TopView {
    pub width: u32,
    pub height: u32,
    /// Row-major; [`TopView::EMPTY`] where no visible terminal lies over the pixel, else an
    /// index into the structure ids given to [`TopView::of`] or [`TopView::UNOWNED`].
    pub owner: Vec<u32>,
}

impl TopView {
    /// No visible terminal over the pixel.
    pub const EMPTY: u32 = u32::MAX;
    /// Covered by a terminal of no known structure.
    pub const UNOWNED: u32 = u32::MAX - 1;

    /// Renders the visible terminals of `model` (void terminals — rooms, slits, crenel gaps,
    /// the air of a wall walk — are not built) from above. `ids` are the structure ids of the
    /// estimate: a terminal belongs to the structure whose axiom successor it descends from,
    /// which the generated program names `{id}`, `{id}Site`, `{id}Roof` (program/mod.rs).
    /// Pixels are sampled at their centres; parts of the model off the grid are not counted.
    pub fn of(
        model: &Model,
        ids: &[String],
        units_per_pixel: f64,
        width: u32,
        height: u32,
        tessellation: &Tessellation,
    ) -> TopView {
        let n = width as usize * height as usize;
        let mut owner = vec![TopView::EMPTY; n];
        let mut top = vec![f64::NEG_INFINITY; n];
        if units_per_pixel <= 0.0 || !units_per_pixel.is_finite() {
            return TopView {
                width,
                height,
                owner,
            };
        }
        // Nodes come in creation order, parents first, so one pass settles each node's owner.
        let mut node_owner = vec![TopView::UNOWNED; model.nodes.len()];
        for (i, node) in model.nodes.iter().enumerate() {
            node_owner[i] = match node.parent {
                None => TopView::UNOWNED,
                Some(_) if node.depth == 1 => structure_of(model.symbol(node), ids),
                Some(p) => node_owner[p as usize],
            };
        }
        let inv = 1.0 / units_per_pixel;
        for (i, node) in model.nodes.iter().enumerate() {
            if node.state != NodeState::Terminal {
                continue;
            }
            let Some(solid) = model.solid(i as u32) else {
                continue;
            };
            let mesh = solid.mesh(tessellation);
            // (plan x, plan y, height) of each vertex.
            let pts: Vec<[f64; 3]> = mesh
                .positions
                .iter()
                .map(|p| {
                    let w = node.world * nalgebra::Point3::from(*p);
                    [w.x * inv, w.z * inv, w.y]
                })
                .collect();
            for t in &mesh.triangles {
                let tri = t.map(|k| pts[k as usize]);
                fill(&tri, width, height, |k, y| {
                    if y > top[k] {
                        top[k] = y;
                        owner[k] = node_owner[i];
                    }
                });
            }
        }
        TopView {
            width,
            height,
            owner,
        }
    }

    pub fn covered(&self, x: u32, y: u32) -> bool {
        self.owner[(y * self.width + x) as usize] != TopView::EMPTY
    }
}

/// The structure a depth-1 node of the generated program belongs to: the longest id that the
/// symbol is, or begins with followed by a capital (`tower1Site`, `hall2Roof`; `tower10`
/// is not `tower1` followed by `0`).
pub(crate) fn structure_of(symbol: &str, ids: &[String]) -> u32 {
    let mut best: Option<(usize, usize)> = None;
    for (k, id) in ids.iter().enumerate() {
        let Some(rest) = symbol.strip_prefix(id.as_str()) else {
            continue;
        };
        let fits = rest.is_empty() || rest.starts_with(|c: char| c.is_ascii_uppercase());
        if fits && best.is_none_or(|(_, len)| id.len() > len) {
            best = Some((k, id.len()));
        }
    }
    best.map_or(TopView::UNOWNED, |(k, _)| k as u32)
}

/// Calls `hit(pixel index, height)` for every pixel whose centre lies inside the triangle's
/// projection (edges included, so neighbouring triangles leave no crack). Triangles seen
/// edge-on from above (walls' sides) cover nothing; the tops and bottoms cover the area.
fn fill(t: &[[f64; 3]; 3], width: u32, height: u32, mut hit: impl FnMut(usize, f64)) {
    let area =
        (t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[2][0] - t[0][0]) * (t[1][1] - t[0][1]);
    if area.abs() < 1e-12 {
        return;
    }
    let lo = |k: usize| t.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
    let hi = |k: usize| t.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
    let x0 = lo(0).ceil().max(0.0);
    let y0 = lo(1).ceil().max(0.0);
    let x1 = hi(0).floor().min(f64::from(width) - 1.0);
    let y1 = hi(1).floor().min(f64::from(height) - 1.0);
    if x0 > x1 || y0 > y1 {
        return;
    }
    // Tolerance of the inside test, relative to the doubled area, for centres on shared edges.
    let eps = -1e-9 * area.abs();
    let edge = |a: &[f64; 3], b: &[f64; 3], x: f64, y: f64| {
        ((b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0])) * area.signum()
    };
    for y in y0 as u32..=y1 as u32 {
        let fy = f64::from(y);
        for x in x0 as u32..=x1 as u32 {
            let fx = f64::from(x);
            let w0 = edge(&t[1], &t[2], fx, fy);
            let w1 = edge(&t[2], &t[0], fx, fy);
            let w2 = edge(&t[0], &t[1], fx, fy);
            if w0 < eps || w1 < eps || w2 < eps {
                continue;
            }
            let s = area.abs();
            let h = (w0 * t[0][2] + w1 * t[1][2] + w2 * t[2][2]) / s;
            hit((y * width + x) as usize, h);
        }
    }
}

/// How a region of the plan (a room, a tower) fared in the model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Presence {
    /// The region's plan label (a room's; tower_room for every tower).
    pub label: Label,
    pub pixels: usize,
    /// Mean of its pixels (plan pixels).
    pub centroid: [f64; 2],
    /// Share of its pixels under the model's footprint.
    pub covered: f64,
    /// The structure seen most often over it from above, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub structure: Option<String>,
}

impl Presence {
    pub fn present(&self) -> bool {
        self.covered >= PRESENT
    }
}

/// The agreement of a model with its plan, in plan pixels.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Agreement {
    pub iou: f64,
    pub precision: f64,
    pub recall: f64,
    /// Pixels of the plan's built area, of the model's footprint, and of both.
    pub plan_pixels: usize,
    pub model_pixels: usize,
    pub overlap_pixels: usize,
    /// The plan's built pixels the model leaves bare, by plan label (indexed as
    /// [`Label::ALL`]): where the recall is lost.
    pub missed_by_label: [usize; 11],
    /// The model's pixels on the plan's unbuilt area (surroundings, courtyards), by the
    /// structure that covers them (indexed as the view's `ids`): where the precision is lost.
    pub spilled_by_structure: Vec<usize>,
    /// The plan's rooms (tower_room, great_hall, chapel, unknown_room): 4-connected regions of
    /// one room label, which are the rooms' faces as the label image holds them (a
    /// [`plan::PlanFace`] keeps its area, not its pixels).
    pub rooms: Vec<Presence>,
    /// The plan's towers: its tower rooms, then its bulge towers (discs of their circles).
    pub towers: Vec<Presence>,
}

impl Agreement {
    pub fn rooms_present(&self) -> usize {
        self.rooms.iter().filter(|r| r.present()).count()
    }

    pub fn towers_present(&self) -> usize {
        self.towers.iter().filter(|t| t.present()).count()
    }

    /// stats.json's `agreement`: the three ratios (rounded to 4 decimals) and the counts.
    pub fn summary(&self) -> serde_json::Value {
        let r = |v: f64| (v * 1e4).round() / 1e4;
        serde_json::json!({
            "iou": r(self.iou),
            "precision": r(self.precision),
            "recall": r(self.recall),
            "rooms_present": self.rooms_present(),
            "rooms": self.rooms.len(),
            "towers_present": self.towers_present(),
            "towers": self.towers.len(),
        })
    }
}

/// The legend of [`overlay`].
pub const OVERLAY_LEGEND: &str = "grey: built on the plan and in the model; red: built on the plan (walls, towers, rooms) but not in the model; blue: in the model but not built on the plan; white: neither";

/// The agreement as a picture at the plan's size, for the user to see what the model misses
/// and what it adds ([`OVERLAY_LEGEND`]).
pub fn overlay(labels: &[u8], view: &TopView) -> image::RgbImage {
    const BOTH: [u8; 3] = [150, 150, 150];
    const PLAN_ONLY: [u8; 3] = [220, 40, 40];
    const MODEL_ONLY: [u8; 3] = [40, 90, 230];
    let colour = |x: u32, y: u32| {
        let i = (y * view.width + x) as usize;
        let built = labels.get(i).is_some_and(|&l| is_built(l));
        let covered = view.owner[i] != TopView::EMPTY;
        match (built, covered) {
            (true, true) => BOTH,
            (true, false) => PLAN_ONLY,
            (false, true) => MODEL_ONLY,
            (false, false) => [255, 255, 255],
        }
    };
    let mut img =
        image::RgbImage::from_fn(view.width, view.height, |x, y| image::Rgb(colour(x, y)));
    // Issue 22: the key in the corner with the least of either.
    let key = [
        Entry::new(Swatch::Fill(BOTH), "plan and model"),
        Entry::new(Swatch::Fill(PLAN_ONLY), "plan only"),
        Entry::new(Swatch::Fill(MODEL_ONLY), "model only"),
    ];
    raster::legend::draw(&mut img, &key, &|x, y| colour(x, y) != [255, 255, 255]);
    img
}

/// The model seen from above at `plan`'s grid, through the estimate's scale and structure ids.
pub fn top_view(
    plan: &ParsedPlan,
    estimate: &Estimate,
    model: &Model,
    tessellation: &Tessellation,
) -> TopView {
    let ids: Vec<String> = estimate.structures.iter().map(|s| s.id.clone()).collect();
    TopView::of(
        model,
        &ids,
        estimate.scale.units_per_pixel,
        plan.width,
        plan.height,
        tessellation,
    )
}

/// The agreement of `model` with `plan`, through the estimate's scale and structure ids.
pub fn measure(
    plan: &ParsedPlan,
    estimate: &Estimate,
    model: &Model,
    tessellation: &Tessellation,
) -> Agreement {
    let ids: Vec<String> = estimate.structures.iter().map(|s| s.id.clone()).collect();
    let view = top_view(plan, estimate, model, tessellation);
    compare(&plan.labels, &plan.bulge_towers, &view, &ids)
}

fn is_built(label: u8) -> bool {
    label != Label::CastleSurroundings as u8 && label != Label::Courtyard as u8
}

fn is_room(label: u8) -> bool {
    Label::ALL
        .get(usize::from(label))
        .is_some_and(|l| l.is_room())
}

/// A share that is 1 when there is nothing to share: an empty model builds nothing wrongly,
/// and an empty plan leaves nothing to cover.
fn ratio(part: usize, whole: usize) -> f64 {
    if whole == 0 {
        1.0
    } else {
        part as f64 / whole as f64
    }
}

/// The agreement of a top view with the plan's per-pixel labels (`labels`, the view's size,
/// row-major label indices) and bulge towers; `ids` name the view's owners.
pub fn compare(labels: &[u8], bulges: &[BulgeTower], view: &TopView, ids: &[String]) -> Agreement {
    let (w, h) = (view.width as usize, view.height as usize);
    let (mut plan_px, mut model_px, mut both) = (0, 0, 0);
    let mut missed_by_label = [0usize; 11];
    let mut spilled_by_structure = vec![0usize; ids.len()];
    for (l, o) in labels.iter().zip(&view.owner) {
        let built = is_built(*l);
        let covered = *o != TopView::EMPTY;
        if covered
            && !built
            && let Some(s) = spilled_by_structure.get_mut(*o as usize)
        {
            *s += 1;
        }
        if built
            && !covered
            && let Some(m) = missed_by_label.get_mut(*l as usize)
        {
            *m += 1;
        }
        plan_px += usize::from(built);
        model_px += usize::from(covered);
        both += usize::from(built && covered);
    }
    let presence = |label: Label, pixels: &[usize]| {
        let mut counts = vec![0usize; ids.len()];
        let (mut covered, mut sx, mut sy) = (0, 0.0, 0.0);
        for &i in pixels {
            sx += (i % w) as f64;
            sy += (i / w) as f64;
            let o = view.owner[i];
            if o != TopView::EMPTY {
                covered += 1;
            }
            if let Some(c) = counts.get_mut(o as usize) {
                *c += 1;
            }
        }
        let n = pixels.len().max(1) as f64;
        let structure = counts
            .iter()
            .enumerate()
            .filter(|(_, c)| **c > 0)
            .max_by_key(|(k, c)| (**c, std::cmp::Reverse(*k)))
            .map(|(k, _)| ids[k].clone());
        Presence {
            label,
            pixels: pixels.len(),
            centroid: [sx / n, sy / n],
            covered: ratio(covered, pixels.len()),
            structure,
        }
    };
    let rooms: Vec<Presence> = regions(labels, w, h, is_room)
        .iter()
        .map(|px| presence(Label::ALL[labels[px[0]] as usize], px))
        .collect();
    let mut towers: Vec<Presence> = rooms
        .iter()
        .filter(|r| r.label == Label::TowerRoom)
        .cloned()
        .collect();
    for b in bulges {
        // A tower listed on the pixels whose centre is in a tower room is that room's tower
        // (a ring tower, `plan::ring_towers`): counted once, as the model builds it once.
        let [cx, cy] = b.center.map(|v| v.round() as i64);
        let at = (cx >= 0 && cy >= 0 && (cx as usize) < w && (cy as usize) < h)
            .then(|| labels[cy as usize * w + cx as usize]);
        if at == Some(Label::TowerRoom as u8) {
            continue;
        }
        let disc = disc(b, w, h);
        if !disc.is_empty() {
            towers.push(presence(Label::TowerRoom, &disc));
        }
    }
    Agreement {
        iou: ratio(both, plan_px + model_px - both),
        precision: ratio(both, model_px),
        recall: ratio(both, plan_px),
        plan_pixels: plan_px,
        model_pixels: model_px,
        overlap_pixels: both,
        missed_by_label,
        spilled_by_structure,
        rooms,
        towers,
    }
}

/// 4-connected regions of equal label among the pixels `keep` accepts, each as its pixel
/// indices (the first is the region's first pixel in row-major order).
fn regions(labels: &[u8], w: usize, h: usize, keep: impl Fn(u8) -> bool) -> Vec<Vec<usize>> {
    let mut seen = vec![false; labels.len()];
    let mut out = Vec::new();
    for start in 0..labels.len() {
        if seen[start] || !keep(labels[start]) {
            continue;
        }
        let l = labels[start];
        seen[start] = true;
        let mut region = vec![start];
        let mut k = 0;
        while k < region.len() {
            let i = region[k];
            k += 1;
            let (x, y) = (i % w, i / w);
            let mut visit = |j: usize| {
                if !seen[j] && labels[j] == l {
                    seen[j] = true;
                    region.push(j);
                }
            };
            if x > 0 {
                visit(i - 1);
            }
            if x + 1 < w {
                visit(i + 1);
            }
            if y > 0 {
                visit(i - w);
            }
            if y + 1 < h {
                visit(i + w);
            }
        }
        out.push(region);
    }
    out
}

/// The pixels whose centres lie within a bulge tower's circle.
fn disc(b: &BulgeTower, w: usize, h: usize) -> Vec<usize> {
    let [cx, cy] = b.center;
    let r = b.radius;
    let x0 = (cx - r).ceil().max(0.0) as usize;
    let y0 = (cy - r).ceil().max(0.0) as usize;
    let x1 = (cx + r).floor().min(w as f64 - 1.0);
    let y1 = (cy + r).floor().min(h as f64 - 1.0);
    if x1 < 0.0 || y1 < 0.0 {
        return Vec::new();
    }
    let mut out = Vec::new();
    for y in y0..=y1 as usize {
        for x in x0..=x1 as usize {
            if (x as f64 - cx).hypot(y as f64 - cy) <= r {
                out.push(y * w + x);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const W: u32 = 20;
    const H: u32 = 20;

    /// A 20 × 20 plan whose built area is the square of pixels 5..=14 (100 px): a tower wall
    /// ring round a tower room of pixels 7..=12 (36 px); the rest surroundings.
    fn square_plan() -> Vec<u8> {
        let mut labels = vec![Label::CastleSurroundings as u8; (W * H) as usize];
        for y in 5..15 {
            for x in 5..15 {
                let room = (7..13).contains(&x) && (7..13).contains(&y);
                labels[(y * W + x) as usize] = if room {
                    Label::TowerRoom as u8
                } else {
                    Label::TowerWall as u8
                };
            }
        }
        labels
    }

    /// A model of boxes, each `(symbol, [x0, x1] and [y0, y1] in plan pixels, height, void)`,
    /// at `upp` model units per plan pixel.
    fn boxes(upp: f64, parts: &[(&str, [f64; 4], f64, bool)]) -> Model {
        let mut axiom = String::from("Axiom ::");
        let mut rules = String::new();
        let mut names = Vec::new();
        for (symbol, [x0, x1, y0, y1], height, void) in parts {
            let (cx, cz) = ((x0 + x1) / 2.0 * upp, (y0 + y1) / 2.0 * upp);
            let (sx, sz) = ((x1 - x0) * upp, (y1 - y0) * upp);
            axiom += &format!(
                " T({cx}, {}, {cz}) I(\"box\", {{{sx}, {height}, {sz}}})",
                height / 2.0
            );
            names.push(symbol.to_string());
            let body = if *void { "void()" } else { "" };
            rules += &format!("{symbol} :: {body}{{j3d.terminal}};\n");
        }
        let src = format!("{axiom} {{{}}};\n{rules}", names.join(", "));
        vsg::run(&src, &vsg::RunOptions::default()).unwrap()
    }

    fn ids(names: &[&str]) -> Vec<String> {
        names.iter().map(|s| s.to_string()).collect()
    }

    fn view(model: &Model, names: &[&str], upp: f64) -> TopView {
        TopView::of(model, &ids(names), upp, W, H, &Tessellation::default())
    }

    #[test]
    fn a_box_half_over_the_square_gives_iou_one_third() {
        // Pixels 10..=19 × 5..=14: half the plan's square (50 px) and 50 px outside it.
        let upp = 2.0;
        let model = boxes(upp, &[("tower1Site", [9.5, 19.5, 4.5, 14.5], 10.0, false)]);
        let v = view(&model, &["tower1"], upp);
        let a = compare(&square_plan(), &[], &v, &ids(&["tower1"]));
        assert_eq!(
            (a.plan_pixels, a.model_pixels, a.overlap_pixels),
            (100, 100, 50)
        );
        assert_eq!(a.iou, 1.0 / 3.0);
        assert_eq!((a.precision, a.recall), (0.5, 0.5));
        // The 50 pixels outside the square are the tower's spill.
        assert_eq!(a.spilled_by_structure, vec![50]);
        // The room (7..=12) has columns 10..=12 covered: 18 of 36 pixels, exactly the bar.
        assert_eq!(a.rooms.len(), 1);
        assert_eq!(a.rooms[0].pixels, 36);
        assert_eq!(a.rooms[0].covered, 0.5);
        assert!(a.rooms[0].present());
        assert_eq!(a.rooms[0].structure.as_deref(), Some("tower1"));
        assert_eq!(a.towers, a.rooms);
        assert_eq!(a.summary()["iou"], 0.3333);
        assert_eq!(a.summary()["rooms_present"], 1);
    }

    #[test]
    fn the_square_built_exactly_agrees_wholly_and_void_terminals_build_nothing() {
        let upp = 0.25;
        let model = boxes(
            upp,
            &[
                ("keep", [4.5, 14.5, 4.5, 14.5], 5.0, false),
                ("air", [15.5, 19.5, 0.0, 19.5], 5.0, true),
            ],
        );
        let v = view(&model, &[], upp);
        let a = compare(&square_plan(), &[], &v, &[]);
        assert_eq!((a.iou, a.precision, a.recall), (1.0, 1.0, 1.0));
        // Owned by no structure of the (empty) estimate.
        assert_eq!(a.rooms[0].structure, None);
        assert!(
            v.owner
                .iter()
                .all(|&o| o == TopView::EMPTY || o == TopView::UNOWNED)
        );
    }

    #[test]
    fn the_highest_structure_owns_a_pixel_and_uncovered_rooms_and_bulges_are_absent() {
        let upp = 1.0;
        // tower10's roof over the room's left part, higher than tower1 over all of it; tower2
        // over the east wall beside the room (x 13..14, y 10..12).
        let model = boxes(
            upp,
            &[
                ("tower1", [6.5, 12.5, 6.5, 12.5], 5.0, false),
                ("tower10Roof", [6.5, 9.5, 6.5, 12.5], 8.0, false),
                ("tower2", [12.5, 14.5, 9.5, 12.5], 5.0, false),
            ],
        );
        let names = ["tower1", "tower10", "tower2"];
        let v = view(&model, &names, upp);
        assert_eq!(v.owner[(8 * W + 7) as usize], 1);
        assert_eq!(v.owner[(8 * W + 11) as usize], 0);
        let bulges = [
            // On the east wall: covered by tower1 (x 12) and tower2.
            BulgeTower {
                center: [13.0, 11.0],
                radius: 1.0,
            },
            // Off the model.
            BulgeTower {
                center: [2.0, 2.0],
                radius: 1.5,
            },
            // Centred in the tower room: that room's tower (a ring tower), not counted again.
            BulgeTower {
                center: [10.0, 10.0],
                radius: 3.0,
            },
        ];
        let a = compare(&square_plan(), &bulges, &v, &ids(&names));
        assert_eq!(a.rooms[0].covered, 1.0);
        // 18 pixels each; ties go to the first structure.
        assert_eq!(a.rooms[0].structure.as_deref(), Some("tower1"));
        assert_eq!(a.towers.len(), 3);
        assert_eq!(a.towers[1].pixels, 5);
        assert!(a.towers[1].present());
        assert_eq!(a.towers[2].pixels, 9);
        assert!(!a.towers[2].present());
        assert_eq!((a.towers_present(), a.rooms_present()), (2, 1));
        // 42 px over 100 of the plan, all of them built: precision 1, recall 0.42.
        assert_eq!((a.precision, a.recall, a.iou), (1.0, 0.42, 0.42));
    }

    #[test]
    fn an_empty_model_covers_nothing_and_builds_nothing_wrongly() {
        let v = TopView {
            width: W,
            height: H,
            owner: vec![TopView::EMPTY; (W * H) as usize],
        };
        let a = compare(&square_plan(), &[], &v, &[]);
        assert_eq!((a.iou, a.precision, a.recall), (0.0, 1.0, 0.0));
        assert_eq!(a.rooms_present(), 0);
    }

    #[test]
    fn structure_symbols_match_the_longest_id_followed_by_a_capital() {
        let ids = ids(&["tower1", "tower10", "wall3"]);
        assert_eq!(structure_of("tower1", &ids), 0);
        assert_eq!(structure_of("tower10Site", &ids), 1);
        assert_eq!(structure_of("tower1Roof", &ids), 0);
        assert_eq!(structure_of("tower12", &ids), TopView::UNOWNED);
        assert_eq!(structure_of("wall3s", &ids), TopView::UNOWNED);
    }
}
