//! Integration (§6.1.1–6.1.4): each façade mapped onto its plan structure by the user's
//! correspondences ([`crate::correspond`]), scaled by s = w_p / w_f (or the elevation's own
//! scale), façades sharing a structure re-estimated jointly (§6.1.2), Gothic façades replacing
//! their walls (§6.1.3), and the [`Estimate`] with the hierarchy of §6.1.3 and the provenance of
//! every parameter.

use facade::classify::Class;
use facade::model::{Facade, FacadeParams};
use facade::search::joint::{JointFacade, fit_floors_joint};
use facade::search::{Gradients, Integral, SearchParams};
use plan::ParsedPlan;

use crate::correspond::{Placement, facade_at, place, structure_at};
use crate::estimate::{
    Element, Estimate, FloorEstimate, GothicMapped, Kind, MappedFacade, PlanSource, Provenance,
    Side, Structure, WindowColumns,
};
use crate::gothic::GothicFacadeEstimate;
use crate::photo::FacadeEstimate;
use crate::project::Correspondence;
use crate::project::gothic_element_entry;
use crate::textures::Texture;
use plan::scale::{GivenScale, ModelScale, ScaleNote};

use crate::corrections::StructureFix;
use crate::error::IntegrateError;

/// Everything integration needs, already estimated.
pub struct Inputs<'a> {
    pub plan: &'a ParsedPlan,
    /// The plan's name in PROJECT.toml (for provenance).
    pub plan_image: &'a str,
    /// What the project says of the drawing's scale; [`ModelScale::decide`] turns it into the
    /// model's frame.
    pub scale: GivenScale,
    pub facades: &'a [FacadeEstimate],
    /// Gothic façade estimates (ch. 4).
    pub gothics: &'a [GothicFacadeEstimate],
    pub correspondences: &'a [Correspondence],
    /// The user's `[[structure]]` corrections (issue 22).
    pub structure_fixes: &'a [StructureFix],
}

/// One façade as mapped by a correspondence.
struct Mapping {
    photo: usize,
    facade: usize,
    placement: Placement,
}

/// What integration produced: the estimate and what goes with it.
pub struct Integrated {
    /// estimate.json, complete: texture names and Gothic program names are set.
    pub estimate: Estimate,
    /// How the drawing's scale was decided (an assumption is also in `estimate.assumptions`).
    pub scale_note: ScaleNote,
    /// The façade photos cropped to their mapped façades, named as `estimate` names them.
    pub textures: Vec<Texture>,
    /// Each mapped Gothic façade's block program (file name, text) that the generated program
    /// imports.
    pub gothic_programs: Vec<(String, String)>,
}

/// Integrates the plan and façade estimates (§6.1.1–6.1.4).
pub fn integrate(inputs: &Inputs) -> Result<Integrated, IntegrateError> {
    let plan = inputs.plan;
    let mut assumptions = Vec::new();
    let (frame, scale_note) = ModelScale::decide(plan, inputs.scale);
    if let Some(why) = scale_note.assumption() {
        assumptions.push(why.to_string());
    }
    let mut structures = crate::structures::from_plan(plan, inputs.plan_image, &frame);
    let fixed = crate::corrections::targets(&structures, inputs.structure_fixes, plan, &frame)
        .map_err(IntegrateError::Correction)?;
    crate::corrections::apply_roles(&mut structures, inputs.structure_fixes, &fixed);
    let mut mappings: Vec<Vec<Mapping>> = (0..structures.len()).map(|_| Vec::new()).collect();
    let mut gothic_mappings: Vec<Vec<(usize, Placement)>> =
        (0..structures.len()).map(|_| Vec::new()).collect();
    for (i, c) in inputs.correspondences.iter().enumerate() {
        let fail = |message: String| IntegrateError::Correspondence {
            index: i + 1,
            facade: c.facade.clone(),
            message,
        };
        let points: Vec<[f64; 2]> = c
            .plan_points
            .iter()
            .map(|p| [p[0] * frame.units_per_pixel, p[1] * frame.units_per_pixel])
            .collect();
        let target = structure_at(&structures, points[0]).ok_or_else(|| {
            let [x, y] = c.plan_points[0];
            let inside =
                x >= 0.0 && y >= 0.0 && x < f64::from(plan.width) && y < f64::from(plan.height);
            let label = if inside {
                plan.label_at(x as u32, y as u32).name()
            } else {
                "outside the drawing"
            };
            fail(format!(
                "plan point [{x}, {y}] is not inside any plan shape with a circle or rectangle fit or a wall (label there: {label})"
            ))
        })?;
        let placement = place(&structures[target].footprint, &points);
        if let Some(g) = inputs.gothics.iter().position(|g| g.name == c.facade) {
            let est = &inputs.gothics[g];
            let [x0, y0, x1, y1] = est.bbox;
            let inside = est
                .to_rectified(c.facade_point)
                .is_some_and(|q| (x0..=x1).contains(&q[0]) && (y0..=y1).contains(&q[1]));
            if !inside {
                return Err(fail(format!(
                    "facade_point {:?} is not inside the Gothic façade's box (rectified {:?})",
                    c.facade_point,
                    est.bbox.map(|v| v.round())
                )));
            }
            gothic_mappings[target].push((g, placement));
            continue;
        }
        let photo = inputs
            .facades
            .iter()
            .position(|f| f.name == c.facade)
            .ok_or_else(|| fail("no estimate for this façade image".into()))?;
        let est = &inputs.facades[photo];
        let q = est
            .to_rectified(c.facade_point)
            .ok_or_else(|| fail("facade_point maps to infinity under the rectification".into()))?;
        let facade = facade_at(&est.model, q).ok_or_else(|| {
            // Said in the photo's pixels, the ones the user clicked (issue 22): each façade's
            // extent there, as the serve page outlines it.
            let found: Vec<String> = est
                .outlines_in_photo()
                .iter()
                .flatten()
                .map(|quad| {
                    let xs = quad.map(|p| p[0]);
                    let ys = quad.map(|p| p[1]);
                    let lo = |v: [f64; 4]| v.into_iter().fold(f64::INFINITY, f64::min).round();
                    let hi = |v: [f64; 4]| v.into_iter().fold(f64::NEG_INFINITY, f64::max).round();
                    format!("x {}–{}, y {}–{}", lo(xs), hi(xs), lo(ys), hi(ys))
                })
                .collect();
            fail(format!(
                "facade_point {:?} is not inside any façade found in the photo (photo pixels; the façades found span {})",
                c.facade_point,
                if found.is_empty() { "nothing".into() } else { found.join("; ") }
            ))
        })?;
        mappings[target].push(Mapping {
            photo,
            facade,
            placement,
        });
    }
    for (structure, maps) in structures.iter_mut().zip(&mappings) {
        if maps.is_empty() {
            continue;
        }
        let params = facade_params(inputs.facades, maps);
        let widths: Vec<f64> = maps
            .iter()
            .map(|m| match m.placement {
                Placement::Side { length, .. } => length,
                Placement::Arc { diameter, .. } => diameter,
            })
            .collect();
        let measured = |m: &Mapping| {
            inputs.facades[m.photo]
                .metres_per_pixel
                .map(|mpp| mpp * frame.units_per_metre)
        };
        let scales: Vec<f64> = params
            .iter()
            .zip(&widths)
            .zip(maps)
            .map(|((p, w_p), m)| measured(m).unwrap_or(w_p / (p.x_fr - p.x_fl).max(1.0)))
            .collect();
        let how = |m: &Mapping| {
            if measured(m).is_some() {
                "the elevation's own scale (metres per pixel, from its scale bar)"
            } else {
                "w_p / w_f"
            }
        };
        let heights: Vec<f64> = params
            .iter()
            .zip(&scales)
            .map(|(p, s)| (p.y_fb - p.y_ft) * s)
            .collect();
        let mean_height = heights.iter().sum::<f64>() / heights.len() as f64;
        let several = maps.len() > 1;
        // The user's corrections are not re-estimated away (issue 22): a structure one of
        // whose façades the user corrected keeps each façade's own search.
        let corrected = |m: &Mapping| !inputs.facades[m.photo].fixes.is_empty();
        let joint = several && !maps.iter().any(corrected);
        let names: Vec<&str> = maps
            .iter()
            .map(|m| inputs.facades[m.photo].name.as_str())
            .collect();
        structure.height = mean_height;
        structure.provenance.insert(
            "height".into(),
            Provenance::new(
                &names.join(", "),
                if several {
                    format!(
                        "§6.1.2 mean of {} façade heights, each scaled by {}",
                        maps.len(),
                        how(&maps[0])
                    )
                } else {
                    format!(
                        "§6.1.2 façade boundary height (§3.1.5) scaled by {}",
                        how(&maps[0])
                    )
                },
                None,
            ),
        );
        for (k, m) in maps.iter().enumerate() {
            let p = &params[k];
            let s = scales[k];
            let sy = mean_height / heights[k].max(1e-12);
            let est = &inputs.facades[m.photo];
            let (side, arc) = match m.placement {
                Placement::Side { side, .. } => (side, None),
                Placement::Arc { start, end, .. } => (Side::Arc, Some([start, end])),
            };
            let mapped = MappedFacade {
                image: est.name.clone(),
                side,
                arc,
                scale: s,
                height_factor: sy,
                width: widths[k],
                height: mean_height,
                floors: if corrected(m) {
                    floors_of_tree(&est.model.facades[m.facade], s * sy, s)
                } else {
                    floors_of(p, s * sy)
                },
                windows: WindowColumns {
                    count: p.n_w,
                    offset: p.w_off * s,
                    width: p.w_w * s,
                    gap: p.w_gap * s,
                },
                joint,
                bbox: [p.x_fl, p.y_ft, p.x_fr, p.y_fb],
                texture: None,
                gothic: None,
            };
            replace_wall(
                structure.kind,
                &structure.id,
                &mut structure.children,
                &mapped,
                k,
            );
            structure.provenance.insert(
                format!("facade.{}.{side}", est.name),
                Provenance::new(
                    &est.name,
                    format!(
                        "§3.1.7 façade {} of the rectified photo{}, scaled by s = {s:.4} ({}, §6.1.2)",
                        m.facade,
                        if joint { ", floors re-estimated jointly (§6.1.2)" } else { "" },
                        how(m)
                    ),
                    None,
                ),
            );
            // Inputs.facades are in PROJECT.toml's order: photo k is the entry #k + 1.
            for c in est.fixes.corrections() {
                structure.provenance.insert(
                    format!("facade.{}.{side}.{}", est.name, c.parameter()),
                    Provenance::user(format!("[[facade]] #{} fix.{}", m.photo + 1, c.key())),
                );
            }
            structure.facades.push(mapped);
        }
    }
    for (k, (structure, maps)) in structures.iter_mut().zip(&gothic_mappings).enumerate() {
        for (j, (g, placement)) in maps.iter().enumerate() {
            let est = &inputs.gothics[*g];
            map_gothic(
                structure,
                est,
                *g,
                placement,
                &format!("g{}_{}", k + 1, j + 1),
            );
        }
    }
    crate::heights::propagate(&mut structures);
    crate::corrections::apply_values(&mut structures, inputs.structure_fixes, &fixed, &frame)
        .map_err(IntegrateError::Correction)?;
    let mut estimate = Estimate {
        scale: frame,
        plan: PlanSource {
            image: inputs.plan_image.to_string(),
            width: plan.width,
            height: plan.height,
            towers: plan.towers,
        },
        structures,
        assumptions,
    };
    let textures = crate::textures::facade_textures(&mut estimate, inputs.facades);
    let gothic_programs = gothic_programs(&estimate, inputs.gothics);
    Ok(Integrated {
        estimate,
        scale_note,
        textures,
        gothic_programs,
    })
}

/// A Gothic façade on a structure's wall (§6.1.2–6.1.3): scaled by s = w_p / w_f, it replaces
/// the wall with its arches and stones; it sets the height when no rectangular façade did.
fn map_gothic(
    structure: &mut Structure,
    est: &GothicFacadeEstimate,
    entry: usize,
    placement: &Placement,
    alias: &str,
) {
    let (side, arc, w_p) = match *placement {
        Placement::Side { side, length } => (side, None, length),
        Placement::Arc {
            start,
            end,
            diameter,
        } => (Side::Arc, Some([start, end]), diameter),
    };
    let [x0, y0, x1, y1] = est.bbox;
    let s = w_p / (x1 - x0).max(1.0);
    let height = (y1 - y0) * s;
    if structure.facades.is_empty() {
        structure.height = height;
        structure.provenance.insert(
            "height".into(),
            Provenance::new(
                &est.name,
                "§6.1.2 Gothic façade height scaled by w_p / w_f",
                None,
            ),
        );
    }
    structure.provenance.insert(
        format!("facade.{}.{side}", est.name),
        Provenance::new(
            &est.name,
            format!(
                "§4.2 {} elements in {} groups, {} stones; scaled by s = {s:.4} (w_p / w_f, §6.1.2)",
                est.estimate.elements.len(),
                est.estimate.groups.len(),
                est.masonry.stones.len()
            ),
            None,
        ),
    );
    // Issue 22: the elements the user set, moved or deleted, each named by its entry
    // (`gothic.IMAGE.element.ID` for one in the estimate, `gothic.IMAGE.deleted.N` for the
    // N-th correction, a deletion).
    for a in &est.applied {
        let key = match a.element {
            Some(id) => format!("gothic.{}.element.{id}", est.name),
            None => format!("gothic.{}.deleted.{}", est.name, a.correction + 1),
        };
        structure.provenance.insert(
            key,
            Provenance::user(gothic_element_entry(entry, a.correction, &est.name)),
        );
    }
    let mapped = MappedFacade {
        image: est.name.clone(),
        side,
        arc,
        scale: s,
        height_factor: 1.0,
        width: w_p,
        height,
        floors: Vec::new(),
        windows: WindowColumns {
            count: 0,
            offset: 0.0,
            width: 0.0,
            gap: 0.0,
        },
        joint: false,
        bbox: est.bbox,
        texture: None,
        gothic: Some(GothicMapped {
            program: format!("gothic_{alias}.vsg"),
            alias: alias.to_string(),
            elements: est.estimate.elements.len(),
            groups: est.estimate.groups.len(),
            stones: est.masonry.stones.len(),
            dropped: est.dropped,
        }),
    };
    let k = structure.facades.len();
    let id = structure.id.clone();
    replace_wall(structure.kind, &id, &mut structure.children, &mapped, k);
    structure.facades.push(mapped);
}

/// Each mapped Gothic façade's block program (file name, text), in the model's units and with
/// its structure's wall thickness: the files the generated program imports.
fn gothic_programs(estimate: &Estimate, gothics: &[GothicFacadeEstimate]) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for s in &estimate.structures {
        for f in &s.facades {
            let (Some(g), Some(est)) = (&f.gothic, gothics.iter().find(|e| e.name == f.image))
            else {
                continue;
            };
            out.push((g.program.clone(), est.program(f.scale, s.wall_thickness)));
        }
    }
    out
}

/// The façades' parameters; several on one structure are re-estimated jointly (§6.1.2), unless
/// the user corrected one of them.
fn facade_params(photos: &[FacadeEstimate], maps: &[Mapping]) -> Vec<FacadeParams> {
    let single: Vec<FacadeParams> = maps
        .iter()
        .map(|m| photos[m.photo].model.facades[m.facade].params)
        .collect();
    if maps.len() < 2 || maps.iter().any(|m| !photos[m.photo].fixes.is_empty()) {
        return single;
    }
    let prepared: Option<Vec<(Integral, Gradients, [usize; 4])>> = maps
        .iter()
        .map(|m| {
            let est = &photos[m.photo];
            let ll = &est.log_likelihoods;
            let (win, wall) = (ll.get(Class::Window)?, ll.get(Class::Wall)?);
            let d: Vec<f64> = win
                .iter()
                .zip(wall)
                .map(|(a, b)| f64::from(a - b))
                .collect();
            let b = est.model.facades[m.facade].bbox;
            let rect = [
                b[0].max(0.0) as usize,
                b[1].max(0.0) as usize,
                (b[2].max(0.0) as usize).min(ll.width),
                (b[3].max(0.0) as usize).min(ll.height),
            ];
            (rect[2] > rect[0] && rect[3] > rect[1]).then(|| {
                (
                    Integral::new(&d, ll.width, ll.height),
                    Gradients::new(&est.rectified),
                    rect,
                )
            })
        })
        .collect();
    let Some(prepared) = prepared else {
        return single;
    };
    let joint: Vec<JointFacade> = prepared
        .iter()
        .map(|(d, g, rect)| JointFacade {
            rect: *rect,
            window_minus_wall: d,
            gradients: g,
        })
        .collect();
    fit_floors_joint(&joint, &SearchParams::default())
}

/// Floors bottom-up in model units (`k` model units per façade pixel vertically).
fn floors_of(p: &FacadeParams, k: f64) -> Vec<FloorEstimate> {
    p.floor_bands()
        .into_iter()
        .map(|(top, bottom, wh, wg)| {
            let has = wh > 0.0 && p.n_w > 0;
            FloorEstimate {
                height: (bottom - top) * k,
                windows: if has { p.n_w } else { 0 },
                window_height: if has { wh * k } else { 0.0 },
                window_sill: if has { wg * k } else { 0.0 },
                openings: None,
            }
        })
        .collect()
}

/// Floors bottom-up in model units (`k` model units per façade pixel vertically, `s`
/// horizontally) read from the façade tree, for a façade the user corrected (issue 22): the 18
/// parameters hold equal middle floors with one window grid, not the user's floor lines, blind
/// floors and single windows. Each floor's window height and sill are its windows' means; its
/// windows keep their own places (`openings`).
fn floors_of_tree(f: &Facade, k: f64, s: f64) -> Vec<FloorEstimate> {
    f.floors
        .iter()
        .rev()
        .map(|fl| {
            let n = fl.windows.len();
            let mean = |of: &dyn Fn(&[f64; 4]) -> f64| {
                if n == 0 {
                    0.0
                } else {
                    fl.windows.iter().map(of).sum::<f64>() / n as f64
                }
            };
            FloorEstimate {
                height: (fl.y1 - fl.y0) * k,
                windows: n as u32,
                window_height: mean(&|w| w[3] - w[1]) * k,
                window_sill: mean(&|w| (fl.y1 - w[3]).max(0.0)) * k,
                openings: Some(openings(fl, f.bbox[0], s)),
            }
        })
        .collect()
}

/// A floor's windows as [start, width] from the façade's left edge `x0`, scaled by `s`, left to
/// right.
fn openings(fl: &facade::model::Floor, x0: f64, s: f64) -> Vec<[f64; 2]> {
    let mut out: Vec<[f64; 2]> = fl
        .windows
        .iter()
        .map(|w| [(w[0] - x0) * s, (w[2] - w[0]) * s])
        .collect();
    out.sort_by(|a, b| a[0].total_cmp(&b[0]));
    out
}

/// §6.1.3 / figure 6.3: the wall a façade is mapped to is replaced by the façade's hierarchy.
fn replace_wall(kind: Kind, id: &str, children: &mut Vec<Element>, f: &MappedFacade, k: usize) {
    let wall_name = match kind {
        Kind::HollowRectangular => format!("{id}Wall_{}", f.side),
        Kind::HollowCylindrical | Kind::SolidCylindrical => format!("{id}Wall"),
        Kind::Solid => format!("{id}Face_field"),
    };
    let facade = Element {
        name: format!("{id}Facade{}", k + 1),
        kind: "facade".into(),
        children: f
            .floors
            .iter()
            .enumerate()
            .map(|(i, fl)| Element {
                name: format!("{id}Facade{}Floor{}", k + 1, i + 1),
                kind: "floor".into(),
                children: (0..fl.windows)
                    .map(|j| {
                        Element::leaf(
                            format!("{id}Facade{}Floor{}Window{}", k + 1, i + 1, j + 1),
                            "window",
                        )
                    })
                    .collect(),
            })
            .collect(),
    };
    match children.iter_mut().find(|c| c.name == wall_name) {
        Some(slot) => *slot = facade,
        // A further façade on a round tower's single wall: the façades stand side by side.
        None => children.push(facade),
    }
}
