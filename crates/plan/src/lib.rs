//! Parsing of castle plan drawings (Sui 2011, chapter 5): a scanned plan becomes a planar graph
//! of walls and open spaces with a semantic label on every wall, room and pixel.
//!
//! # Brief overview
//! - [`parse`] runs the pipeline on an image and returns a [`ParsedPlan`]:
//!   [`binarize::preprocess`] (§5.1.2) → [`thin::thin`] (§5.1.3) → [`graph::vectorise`] and
//!   [`graph::faces`] (§5.1.4) → [`fit`] (§5.1.5) → [`graph::Graph::simplify`] and
//!   [`label::heuristics`] (§5.1.6).
//! - [`ParsedPlan`] holds [`PlanEdge`]s (wall chains with a [`label::Label`] and a
//!   [`fit::Fit`]), [`PlanFace`]s (open spaces with a label and a circle/rectangle shape), the
//!   per-pixel labels, the tower count and warnings for what could not be found.
//! - [`output`] writes the PLAN.json value, LABELS.png, the label overlay and the vector SVG;
//!   [`extrude::to_vsg`] writes the §5.3 extrusion as a VSG program.
//! - [`clean`] (§5.1.1): the user's brush strokes painted on the drawing's binary image.
//!
//! ```
//! use image::{GrayImage, Luma};
//! // A square enclosure with 6-px walls and a round tower at its north-east corner.
//! let mut img = GrayImage::from_pixel(240, 240, Luma([255]));
//! for y in 0..240u32 {
//!     for x in 0..240u32 {
//!         let (fx, fy) = (x as f64, y as f64);
//!         let ring = |r0: f64, r1: f64| {
//!             let d = (fx - 170.0).hypot(fy - 70.0);
//!             d >= r0 && d <= r1
//!         };
//!         let in_square = (60..=170).contains(&x) && (70..=180).contains(&y);
//!         let inner = (66..=164).contains(&x) && (76..=174).contains(&y);
//!         let outside_tower = (fx - 170.0).hypot(fy - 70.0) > 24.0;
//!         if (in_square && !inner && outside_tower) || ring(18.0, 24.0) {
//!             img.put_pixel(x, y, Luma([0]));
//!         }
//!     }
//! }
//! let plan = plan::parse(&image::DynamicImage::ImageLuma8(img), &plan::Options::default()).unwrap();
//! assert_eq!(plan.towers, 1);
//! assert_eq!(plan.label_at(120, 120), plan::label::Label::Courtyard);
//! assert_eq!(plan.label_at(170, 70), plan::label::Label::TowerRoom);
//! assert_eq!(plan.label_at(5, 5), plan::label::Label::CastleSurroundings);
//! ```

pub mod binarize;
pub mod bulges;
mod castle_extent;
pub mod clean;
pub mod corrections;
pub mod dashes;
mod enlarged;
pub mod eval;
pub mod extrude;
pub mod fit;
pub mod gates;
pub mod graph;
pub mod hachure_bands;
pub mod hachure_blobs;
pub mod hatched_walls;
pub mod ink;
mod inner_towers;
pub mod label;
mod legend;
mod measure;
mod parsed;
pub use measure::{PlanFace, Spur};
pub use parsed::{ParsedPlan, PlanEdge};
pub mod output;
mod pixels;
mod ring_towers;
pub mod scale;
pub mod scalebar;
mod scene;
mod strokes;
pub mod synth;
pub mod synth_styles;
pub mod thick_towers;
pub mod thin;
pub mod tower_groups;
mod union_find;

use image::DynamicImage;

use crate::label::{Label, Scene};
use crate::thin::Mask;

/// Settings of the pipeline; the defaults are the dissertation's.
#[derive(Debug, Clone)]
pub struct Options {
    /// Regions under this fraction of the image are noise (§5.1.2: 0.05 %).
    pub min_region: f64,
    /// A face loop takes a circle or rectangle when its mean error is under this fraction of
    /// its radius / half-side (§5.1.5 "accurate enough").
    pub face_tolerance: f64,
    /// Larger images are refused (pixels); the default is the `castellan` binary's pixel budget.
    pub max_pixels: u64,
    /// Drawings whose longer side is under this many pixels are parsed enlarged (by an integer
    /// factor, at most 2 so that 1-px grid lines stay thinner than the 3 × 3 element) so that
    /// the open/close of §5.1.2 keeps its meaning; 0 disables.
    pub upsample_below: u32,
    /// Close door and gate gaps narrower than the typical wall thickness
    /// ([`binarize::close_gaps`]), so that wards and rooms drawn with openings become faces.
    pub close_gaps: bool,
    /// Test walls inside the enceinte as towers of an inner ward (issue 11, several
    /// enclosures; departure from §5.1.6 (4), see `inner_towers`): a thick wall bulging into
    /// the courtyard around a small room, on a building attached to a ward's wall. On by
    /// default: on the development set it finds Chambord's and Bonaguil's inner towers with
    /// points and exact counts unchanged (docs/plan.md, "Inner-ward towers").
    pub inner_ward_towers: bool,
    /// Plug gates and doors wider than `close_gaps` bridges where that encloses a ward or a
    /// room ([`gates::close_gates`]; addition to §5.1.2, off: the text's open enclosures).
    /// Runs only after `close_gaps`, whose wall thickness it uses.
    pub close_gates: bool,
    /// After the parse, give the learned walls' blur beyond the drawn ink back to the rooms,
    /// courtyards and surroundings beside them ([`ink::trim::walls_to_drawing`]; learned ink
    /// only). Off by default: the labels and walls follow the drawing (R3D walls IoU 0.353 →
    /// 0.572; with the network and `one_building` 0.703 → 0.804), but the model, built from
    /// the unchanged fits, then agrees with the plan less (median 0.849 → 0.748;
    /// docs/plan.md, "Walls trimmed to the drawing").
    pub trim_ink: bool,
    /// The sheet shows one building, not a book page with several figures: every wall piece
    /// within [`castle_extent::ONE_BUILDING_REACH`] wall thicknesses of the castle is kept,
    /// where by default only those within 3 % of the sheet are. Off by default: on a book
    /// page it joins the next figure (stacked storeys of a tower); on a modern survey, whose
    /// walls windows and doors cut into pieces farther apart than that, it keeps the walls
    /// (R3D's walls with the network 0.459 → 0.703; docs/plan.md, "One building").
    pub one_building: bool,
    /// Drop ink regions without a room of their own that are not the castle (letters,
    /// numbers, north arrows; [`binarize::drop_marks`]), after the gaps are closed.
    pub drop_marks: bool,
    /// Faces on the outer wall at least this fraction of the courtyard's area are courtyards
    /// of further wards (issue 11; departure from §5.1.6 (3), see [`label::heuristics`]);
    /// 0 keeps the single courtyard of the text.
    pub ward_ratio: f64,
    /// Ink lines thinner than this fraction of the typical wall thickness are removed before
    /// §5.1.2's steps (vault ribs, hachures; [`binarize::drop_thin_lines`]); 0 keeps them.
    pub thin_lines: f64,
    /// Count bulges of the castle's outline with no room of their own as towers
    /// ([`bulges::find`]; issue 11, departure from §5.1.6 (4)).
    pub bulge_towers: bool,
    /// Count compact masses of ink much thicker than the curtain as towers
    /// ([`thick_towers::find`]; issue 26, departure from §5.1.6 (4)): development set exact
    /// counts 2 → 4 of 31 (mean error 7.2 → 4.9), other hands 3 → 6 of 20 (4.2 → 2.6;
    /// docs/plan.md, "Towers drawn as thick ink").
    pub thick_towers: bool,
    /// Take rooms that the surroundings wrap, round and small, as the rooms of towers drawn
    /// as rings on the curtain ([`label::heuristics`] (5''); issue 26, departure from §5.1.6
    /// (4)–(5)): development set points 131 → 138 of 169 (docs/plan.md, "Towers drawn as a
    /// ring").
    pub ring_towers: bool,
    /// Fill hatched walls ([`hatched_walls::fill_hatching`]) before §5.1.2's steps, for drawings
    /// whose walls are hatched. Off by default: on the development set (solid walls) it
    /// takes hachures for hatching and exact tower counts fall 6 → 4 (docs/plan.md).
    pub hatching: bool,
    /// Remove hachured slopes and moats ([`hachure_bands::drop_hachures`], then merged
    /// hachures by [`hachure_blobs::drop_hachure_blobs`]) before §5.1.2's steps. Off by
    /// default: points right 120 → 126 and exact towers stay 6, but closed outer walls fall
    /// 205 → 204 of 236 (docs/plan.md, "Hachures, second pass").
    pub hachures: bool,
    /// Join dotted and dashed lines ([`dashes::link_dashes`]) before the specks are removed
    /// (on: exact tower counts 5 → 6 on the development set, points unchanged).
    pub dashes: bool,
    /// Where the wall mask comes from: the learned wall ink (default) or §5.1.2's threshold
    /// with the clean-up steps above (`hatching`, `hachures`, `dashes`, `thin_lines` act on
    /// that chain only).
    pub ink: ink::InkMethod,
    /// The learned ink's model; `None`: the one that ships ([`ink::shipped`]).
    pub ink_model: Option<std::sync::Arc<ink::WallInk>>,
    /// The wall-ink network with `ink = Network`; `None`: the one that ships ([`ink::shipped_net`]).
    pub ink_net: Option<std::sync::Arc<ink::net::WallNet>>,
    /// The user's "wall" / "not wall" strokes, which refine the learned ink for this drawing
    /// ([`ink::refine`]); drawing pixels.
    pub ink_strokes: Vec<ink::refine::InkStroke>,
    /// Seed of the refinement's forest.
    pub seed: u64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            min_region: 0.0005,
            face_tolerance: 0.06,
            max_pixels: 40_000_000,
            upsample_below: 1000,
            close_gaps: true,
            close_gates: true,
            trim_ink: false,
            one_building: false,
            inner_ward_towers: true,
            drop_marks: true,
            ward_ratio: 0.3,
            thin_lines: 0.0,
            bulge_towers: true,
            thick_towers: true,
            ring_towers: true,
            hatching: false,
            hachures: false,
            dashes: true,
            ink: ink::InkMethod::Learned,
            ink_model: None,
            ink_net: None,
            ink_strokes: Vec::new(),
            seed: 0,
        }
    }
}

/// Why a drawing could not be parsed at all.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    #[error("the image is empty ({0} x {1} pixels)")]
    Empty(u32, u32),
    #[error("the image is too large ({0} x {1} pixels; the limit is {2} pixels)")]
    TooLarge(u32, u32, u64),
    #[error(
        "no walls found: after thresholding at grey level {0} and removing specks and thin lines, nothing of the drawing is left (a blank page?)"
    )]
    NoWalls(u8),
    #[error(
        "no walls found: the learned wall ink sees no wall on the drawing (a blank page? `--ink rules` thresholds the ink instead)"
    )]
    NoLearnedWalls,
    #[error("{0}")]
    Strokes(ink::refine::StrokeError),
}

/// Runs §5.1.2 – §5.1.6 on a drawing.
///
/// Departure from §5.1.2, measured on real drawings (docs/plan.md): the text's 300-dpi scans
/// have walls many pixels thick, but plans from books and the web are ~500 px wide with walls
/// 2–4 px thick, which the 3 × 3 opening erases. Such drawings are enlarged by an integer
/// factor (bilinear) before parsing and every result is mapped back to the input's pixels.
pub fn parse(image: &DynamicImage, opts: &Options) -> Result<ParsedPlan, PlanError> {
    let (w, h) = (image.width(), image.height());
    if w == 0 || h == 0 {
        return Err(PlanError::Empty(w, h));
    }
    if u64::from(w) * u64::from(h) > opts.max_pixels {
        return Err(PlanError::TooLarge(w, h, opts.max_pixels));
    }
    let grey = image.to_luma8();
    let long = w.max(h);
    let k = if long < opts.upsample_below {
        opts.upsample_below.div_ceil(long).min(2)
    } else {
        1
    };
    let scale_bar = scalebar::find(&grey);
    // The learned ink reads the drawing at its own resolution; its map is enlarged with it.
    let (learned, even_odds) = match learned_mask(&grey, k, opts)? {
        Some(ink) => (Some(ink.mask), ink.even_odds),
        None => (None, None),
    };
    let parsed = if k == 1 {
        parse_grey(&grey, learned, opts, &mut Laps::default())?
    } else {
        let big =
            image::imageops::resize(&grey, w * k, h * k, image::imageops::FilterType::Triangle);
        enlarged::shrink(
            parse_grey(&big, learned, opts, &mut Laps::default())?,
            k,
            w,
            h,
        )
    };
    let mut parsed = parsed;
    // In the drawing's pixels, once the parse is mapped back to them.
    parsed
        .warnings
        .extend(tower_groups::warning(&parsed.edges, parsed.vertices.len()));
    // The map at even odds is made only for the trim, and only by a learned ink.
    if let Some(even_odds) = &even_odds {
        parsed.pre.trimmed_pixels =
            ink::trim::walls_to_drawing(&grey, even_odds, &mut parsed.labels, &mut parsed.walls);
    }
    Ok(ParsedPlan {
        scale_bar,
        ..parsed
    })
}

/// An edge's chain with its two vertices at the ends (so a one-pixel chain still fits a line).
fn chain_with_ends(g: &graph::Graph, e: &graph::Edge) -> Vec<[f64; 2]> {
    let v = |i: usize| [g.vertices[i].x, g.vertices[i].y];
    let mut pts = vec![v(e.from)];
    pts.extend(e.points.iter().map(|p| [p.0 as f64, p.1 as f64]));
    pts.push(v(e.to));
    pts
}

/// The learned wall ink of a drawing, as chapter 5 and the trim take it.
struct LearnedInk {
    /// P(wall) > [`ink::WALL_THRESHOLD`] (255 = wall), at the parse's size.
    mask: image::GrayImage,
    /// P(wall) > [`ink::trim::EVEN_ODDS`] (255 = wall), at the drawing's size; only with
    /// `trim_ink`, which alone reads it.
    even_odds: Option<image::GrayImage>,
}

/// The learned wall ink of `grey` at `k` times its size, refined by the user's strokes;
/// `None` when the walls are read by the rules.
fn learned_mask(
    grey: &image::GrayImage,
    k: u32,
    opts: &Options,
) -> Result<Option<LearnedInk>, PlanError> {
    if opts.ink == ink::InkMethod::Rules {
        return Ok(None);
    }
    let (w, h) = grey.dimensions();
    ink::refine::check(&opts.ink_strokes, w, h).map_err(PlanError::Strokes)?;
    let model = opts.ink_model.clone().unwrap_or_else(ink::shipped);
    let (wk, hk) = (w * k, h * k);
    let net = (opts.ink == ink::InkMethod::Network)
        .then(|| opts.ink_net.clone().unwrap_or_else(ink::shipped_net));
    let p = ink::refine::wall_probability(
        &model,
        net.as_deref(),
        grey,
        &opts.ink_strokes,
        opts.seed,
        wk,
        hk,
    );
    let above =
        |x: u32, y: u32, t: f32| image::Luma([if p[(y * wk + x) as usize] > t { 255 } else { 0 }]);
    // The map is enlarged with the drawing; each of the drawing's pixels reads its centre.
    let even_odds = opts.trim_ink.then(|| {
        image::GrayImage::from_fn(w, h, |x, y| {
            above(x * k + k / 2, y * k + k / 2, ink::trim::EVEN_ODDS)
        })
    });
    Ok(Some(LearnedInk {
        mask: image::GrayImage::from_fn(wk, hk, |x, y| above(x, y, ink::WALL_THRESHOLD)),
        even_odds,
    }))
}

/// The wall-clock time of each step of a parse, in order (`examples/stage_times.rs`).
#[derive(Debug, Default)]
pub struct Laps {
    last: Option<std::time::Instant>,
    pub steps: Vec<(&'static str, std::time::Duration)>,
}

impl Laps {
    /// Ends the step `name`, begun at the previous lap (or at the first call's start).
    fn lap(&mut self, name: &'static str) {
        let now = std::time::Instant::now();
        if let Some(t) = self.last {
            self.steps.push((name, now - t));
        }
        self.last = Some(now);
    }
}

/// The learned wall mask of a drawing parsed at its own size (`None` with `--ink rules`), for
/// `examples/stage_times.rs`.
#[doc(hidden)]
pub fn learned_mask_of(
    grey: &image::GrayImage,
    opts: &Options,
) -> Result<Option<image::GrayImage>, PlanError> {
    Ok(learned_mask(grey, 1, opts)?.map(|ink| ink.mask))
}

/// [`parse`]'s steps after the wall ink on `learned` ([`learned_mask_of`]; `None`: the rules'
/// threshold), each timed, for `examples/stage_times.rs`.
#[doc(hidden)]
pub fn parse_mask_timed(
    grey: &image::GrayImage,
    learned: Option<image::GrayImage>,
    opts: &Options,
) -> (Result<ParsedPlan, PlanError>, Laps) {
    let mut laps = Laps::default();
    let p = parse_grey(grey, learned, opts, &mut laps);
    (p, laps)
}

/// Parses `grey` (already enlarged if it was small); `learned` is the learned wall mask at
/// its size, `None` for §5.1.2's threshold and the clean-up chain.
fn parse_grey(
    grey: &image::GrayImage,
    learned: Option<image::GrayImage>,
    opts: &Options,
    laps: &mut Laps,
) -> Result<ParsedPlan, PlanError> {
    laps.lap("");
    let (w, h) = grey.dimensions();
    let cleanup = binarize::Cleanup {
        thin_lines: opts.thin_lines,
        hatching: opts.hatching,
        hachures: opts.hachures,
        dashes: opts.dashes,
    };
    let is_learned = learned.is_some();
    let (mut bin, mut pre) = match learned {
        Some(mask) => binarize::preprocess_learned(
            mask,
            opts.min_region,
            opts.one_building,
            opts.ink == ink::InkMethod::Learned,
        ),
        None => binarize::preprocess_clean(grey, opts.min_region, &cleanup, opts.one_building),
    };
    laps.lap("preprocess");
    if pre.wall_pixels == 0 {
        return Err(if is_learned {
            PlanError::NoLearnedWalls
        } else {
            PlanError::NoWalls(pre.threshold)
        });
    }
    if opts.close_gaps {
        // Radius T / 3 for the typical wall thickness T, so gaps up to about two thirds of a
        // thickness close; bounded by 1/150 of the long side so that a drawing of huge black
        // masses cannot weld the whole castle into one blob. Both were chosen on the
        // development set: T / 2, T / 3, T / 4 and caps 1/100 … 1/500 (docs/plan.md).
        let t = binarize::wall_thickness(&bin);
        let cap = (w.max(h) / 150).clamp(1, 12) as f64;
        binarize::close_gaps(&mut bin, (t / 3.0).ceil().min(cap) as u8);
        if opts.close_gates {
            // Gates up to about twice the wall's thickness (probe radius T; 0.75 T and 1.5 T
            // were measured, docs/plan.md "Gates"), when plugging them encloses more than a
            // speck of step (2).
            let radius = t.ceil().min(f64::from(gates::MAX_RADIUS)) as u8;
            let min = binarize::speck_pixels(&bin, opts.min_region);
            pre.gate_pixels = gates::close_gates(&mut bin, radius, min);
        }
    }
    laps.lap("wall_thickness + close_gaps");
    if opts.drop_marks {
        pre.dropped_marks = binarize::drop_marks(&mut bin, is_learned);
        pre.wall_pixels = bin.pixels().filter(|p| p[0] == 255).count();
    }
    laps.lap("drop_marks");
    let walls = Mask::from_gray(&bin);
    let mut skel = walls.clone();
    thin::thin(&mut skel);
    laps.lap("mask + thin");
    let full = graph::vectorise(&skel);
    laps.lap("vectorise");
    let (face_of, nf) = graph::faces(&skel);
    laps.lap("faces");
    let (g, parts) = full.simplify();
    laps.lap("simplify");

    // Distances: inside walls to the open space, and inside open space to the walls (`bin`
    // is 0 or 255 only).
    // `in_wall` is read along the skeleton only, so it is not computed for every pixel.
    let (in_wall, in_open) = rayon::join(
        || {
            let open: Vec<bool> = bin.as_raw().iter().map(|&p| p != 255).collect();
            pixels::EuclideanAt::new(&open, w as usize, h as usize)
        },
        || {
            let wall: Vec<bool> = bin.as_raw().iter().map(|&p| p > 0).collect();
            pixels::euclidean(&wall, w as usize, h as usize)
        },
    );
    laps.lap("distance transforms");
    let infos = measure::face_infos(&face_of, nf, &walls, &in_open);
    laps.lap("face infos");
    let spurs = measure::spurs(&full, &parts, &in_wall);
    let edge_faces = measure::edge_faces(&g, &face_of, w, h);
    let thickness: Vec<f64> = g
        .edges
        .iter()
        .map(|e| measure::chain_thickness(&in_wall, &e.points))
        .collect();
    laps.lap("spurs, edge faces, thickness");
    let scene = Scene {
        walls: &walls,
        skel: &skel,
        graph: &g,
        face_of: &face_of,
        faces: &infos,
        edge_faces: &edge_faces,
        thickness: &thickness,
        inner_ward_towers: opts.inner_ward_towers,
        ring_towers: opts.ring_towers,
        ward_ratio: opts.ward_ratio,
    };
    let labelling = label::heuristics(&scene);
    laps.lap("heuristics");
    let mut labels = label::pixel_labels(&scene, &labelling);
    laps.lap("pixel labels");

    // §5.1.5: fits for edges, and circles / rectangles for the loops of the faces.
    let edges: Vec<PlanEdge> = g
        .edges
        .iter()
        .enumerate()
        .map(|(k, e)| PlanEdge {
            from: e.from,
            to: e.to,
            label: labelling.edges[k],
            fit: fit::fit_edge(&chain_with_ends(&g, e)),
            points: e.points.clone(),
            thickness: thickness[k],
        })
        .collect();
    laps.lap("edge fits");
    let runs = measure::face_runs(&face_of, nf, &walls, &labelling.faces);
    laps.lap("face runs");
    let edge_points: Vec<&[(u32, u32)]> = edges.iter().map(|e| e.points.as_slice()).collect();
    let faces = measure::plan_faces(
        &infos,
        runs,
        &edge_points,
        &edge_faces,
        &labelling,
        opts.face_tolerance,
    );
    laps.lap("face fits");
    let mut warnings = labelling.warnings;
    warnings.extend(measure::sheet_warnings(&walls, &pre));
    laps.lap("wall bbox, warnings");
    // The outer walls' thicknesses, sorted, and the curtain's from them (`None`: no outer wall,
    // so no tower of the outline or of thick ink).
    let mut outer: Vec<(f64, usize)> = edges
        .iter()
        .filter(|e| e.label == Label::CastleOuterWall)
        .map(|e| (e.thickness, e.points.len()))
        .collect();
    let curtain = bulges::curtain_thickness(&mut outer);
    // The outer walls' median thickness, the curtain as the model reads it.
    let outer_median = scale::outer_wall_thickness_of(&edges);
    // The ring towers' walls first, so that the outline's bulges on them are left out.
    let rings: Vec<bulges::BulgeTower> = labelling
        .ring_towers
        .iter()
        .map(|rooms| ring_towers::disc(&infos, rooms, curtain.unwrap_or(0.0)))
        .collect();
    mark_tower_walls(&mut labels, &walls, &rings, Label::is_wall);
    let mut bulge_towers = match curtain {
        Some(c) if opts.bulge_towers => {
            find_bulge_towers(&mut labels, grey, &walls, c, outer_median)
        }
        _ => Vec::new(),
    };
    bulge_towers.extend(rings);
    laps.lap("bulge towers");
    if let Some(c) = curtain.filter(|_| opts.thick_towers) {
        let thick = thick_towers::find(&walls, &labels, c);
        mark_tower_walls(&mut labels, &walls, &thick, Label::is_wall);
        if let Some(wall) = outer_median {
            thick_towers::rooms(&mut labels, walls.width, walls.height, &thick, wall);
        }
        bulge_towers.extend(thick);
    }
    bulges::drop_nested(&mut bulge_towers);
    laps.lap("thick towers");
    let towers = tower_groups::count(&edges, g.vertices.len(), bulge_towers.len());
    if towers == 0 && faces.iter().any(|f| f.label == Label::Courtyard) {
        warnings.push(tower_groups::NO_TOWERS.into());
    }
    laps.lap("count towers");
    Ok(ParsedPlan {
        width: w,
        height: h,
        vertices: g.vertices,
        edges,
        faces,
        labels,
        walls,
        towers,
        bulge_towers,
        spurs,
        pre,
        warnings,
        scale_bar: None,
    })
}

/// Bulge towers of the outline, measured against the curtain's thickness `curtain` and the
/// outer walls' median thickness `median` (`None` without outer-wall edges; the bulges'
/// rooms then take their ring from the curtain); their outer-wall pixels become tower walls,
/// and those of a wide bulge's heart that the drawing `grey` leaves open tower room
/// ([`thick_towers::bulge_rooms`]).
fn find_bulge_towers(
    labels: &mut [u8],
    grey: &image::GrayImage,
    walls: &Mask,
    curtain: f64,
    median: Option<f64>,
) -> Vec<bulges::BulgeTower> {
    let mut towers = bulges::find(labels, walls.width, walls.height, curtain);
    // A letter or a dot drawn against the curtain bulges too, but a tower is wider than the
    // wall it studs. Bulges of radius under 0.4 × the outer walls' median thickness (over
    // edges, as integration takes the curtain) were, on the development set, exactly the
    // letter O on Sully's plan and a dot on the Tower of London's (2.8 and 3.6 px against
    // 10–12 px); 0.5 also dropped a real half-round tower of the Louvre (5.5 px against 11).
    towers.retain(|t| t.radius >= 0.4 * median.unwrap_or(0.0));
    mark_tower_walls(labels, walls, &towers, |l| l == Label::CastleOuterWall);
    thick_towers::bulge_rooms(labels, grey, &towers, curtain, median.unwrap_or(curtain));
    towers
}

/// The wall pixels of each tower's disc (grown by a pixel) whose label `from` accepts become
/// tower walls.
fn mark_tower_walls(
    labels: &mut [u8],
    walls: &Mask,
    towers: &[bulges::BulgeTower],
    from: impl Fn(Label) -> bool,
) {
    for t in towers {
        for i in t.pixels(walls.width, walls.height) {
            if walls.data[i] == 1 && from(Label::ALL[labels[i] as usize]) {
                labels[i] = Label::TowerWall as u8;
            }
        }
    }
}
