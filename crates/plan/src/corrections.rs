//! The user's corrections of a parsed plan (issue 22): a region's label (overruling §5.1.6's
//! heuristics), towers the parser missed or invented, two regions merged into one. Each is
//! given by a plan pixel, not by a face number, so that it survives a re-parse of a cleaned
//! drawing; they are applied after §5.1.6 and before the model is built, and the labels of
//! the walls round a changed region follow the region as §5.1.6 (4)–(9) make them follow.

use serde::{Deserialize, Serialize};

use crate::legend::Label;
use crate::{ParsedPlan, PlanFace, bulges::BulgeTower};

/// `[[label]]`: the region at `point` (a pixel inside it, or on its wall) has this label; a
/// wall's label names the wall at `point` instead (the wall whose ink holds it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LabelFix {
    pub point: [f64; 2],
    pub label: Label,
}

/// `[[tower]]`: a tower at `point` the parser missed (its outer radius in plan pixels
/// optional: measured on the ink when the point is on a tower drawn solid, the room's own
/// outline when it is inside a room), or, with `remove`, a tower it invented.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TowerFix {
    pub point: [f64; 2],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub remove: bool,
}

/// `[[merge]]`: the two regions at these points are one (the wall the drawing shows between
/// them is not built; a wall the parser invented, or a line that is no wall).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MergeFix {
    pub points: [[f64; 2]; 2],
}

/// The corrections of one plan, in the order they apply: merges, towers, then labels (regions,
/// then walls), so that the user's labels have the last word.
#[derive(Debug, Clone, Copy, Default)]
pub struct PlanFixes<'a> {
    pub merges: &'a [MergeFix],
    pub labels: &'a [LabelFix],
    pub towers: &'a [TowerFix],
}

/// The PROJECT.toml table an entry belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FixTable {
    Label,
    Tower,
    Merge,
}

impl FixTable {
    pub fn name(self) -> &'static str {
        match self {
            FixTable::Label => "[[label]]",
            FixTable::Tower => "[[tower]]",
            FixTable::Merge => "[[merge]]",
        }
    }
}

/// A correction that cannot apply, naming its entry (`[[label]] #2: …`, numbered from 1).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{} #{index}: {why}", table.name())]
pub struct FixError {
    pub table: FixTable,
    pub index: usize,
    pub why: String,
}

/// Applies the corrections; entries that no longer change anything (a tower to remove that is
/// not there any more) are not errors, and are returned as notes naming them.
pub fn apply(plan: &mut ParsedPlan, fixes: PlanFixes) -> Result<Vec<String>, FixError> {
    let mut notes = Vec::new();
    for (i, m) in fixes.merges.iter().enumerate() {
        let fail = |why: String| FixError {
            table: FixTable::Merge,
            index: i + 1,
            why,
        };
        for p in &m.points {
            check_point(plan, *p).map_err(fail)?;
        }
        let [a, b] = m
            .points
            .map(|p| region_at(plan, p).ok_or_else(|| no_region(p)));
        let (a, b) = (a.map_err(fail)?, b.map_err(fail)?);
        if a == b {
            return Err(fail(format!(
                "both points are in one region ({}); nothing to merge",
                plan.faces[a].label.name()
            )));
        }
        merge(plan, a, b).map_err(fail)?;
    }
    let mut changed = false;
    for (i, t) in fixes.towers.iter().enumerate() {
        let fail = |why: String| FixError {
            table: FixTable::Tower,
            index: i + 1,
            why,
        };
        check_point(plan, t.point).map_err(fail)?;
        if let Some(r) = t.radius {
            let most = f64::from(plan.width.max(plan.height)) / 2.0;
            if !(r.is_finite() && r >= 1.0 && r <= most) {
                return Err(fail(format!(
                    "radius {r} must be between 1 and {most} plan pixels"
                )));
            }
        }
        if t.remove {
            if !remove_tower(plan, t.point) {
                notes.push(format!(
                    "[[tower]] #{}: no tower at [{}, {}] to remove (already gone)",
                    i + 1,
                    t.point[0],
                    t.point[1]
                ));
            }
        } else {
            add_tower(plan, t.point, t.radius).map_err(fail)?;
        }
        changed = true;
    }
    // The user's labels have the last word: towers added or removed relabel rooms and their
    // walls, so the labels apply after them, regions first and then walls (a region's label
    // gives its walls §5.1.6's labels, which a wall's own label then overrules).
    let mut walls = Vec::new();
    // The regions labelled by a point inside them: a later label on the ink beside one of
    // them goes to the region across the wall (the simulated user's tower point on the ink of
    // a tower's wall had relabelled the courtyard labelled just before).
    let inside: Vec<usize> = fixes
        .labels
        .iter()
        .filter(|l| !l.label.is_wall())
        .filter_map(|l| {
            check_point(plan, l.point).ok()?;
            face_holding(plan, l.point)
        })
        .collect();
    for (i, l) in fixes.labels.iter().enumerate() {
        let fail = |why: String| FixError {
            table: FixTable::Label,
            index: i + 1,
            why,
        };
        check_point(plan, l.point).map_err(fail)?;
        if l.label.is_wall() {
            let e = wall_at(plan, l.point).ok_or_else(|| {
                fail(format!(
                    "{} is a wall's label and [{}, {}] is on no wall; a region is one of {}",
                    l.label.name(),
                    l.point[0],
                    l.point[1],
                    region_labels()
                ))
            })?;
            walls.push((e, l.label));
            continue;
        }
        let f = region_near(plan, l.point, &inside)
            .or_else(|| region_at(plan, l.point))
            .ok_or_else(|| no_region(l.point))
            .map_err(fail)?;
        relabel(plan, f, l.label);
        changed = true;
    }
    for (e, label) in walls {
        plan.edges[e].label = label;
        changed = true;
    }
    if changed || !fixes.merges.is_empty() {
        repaint_walls(plan);
        plan.towers =
            crate::tower_groups::count(&plan.edges, plan.vertices.len(), plan.bulge_towers.len());
        crate::tower_groups::rewarn(plan);
    }
    Ok(notes)
}

/// The labels a region can take.
fn region_labels() -> String {
    Label::ALL
        .iter()
        .filter(|l| !l.is_wall())
        .map(|l| l.name())
        .collect::<Vec<_>>()
        .join(", ")
}

fn check_point(plan: &ParsedPlan, [x, y]: [f64; 2]) -> Result<(), String> {
    if x.is_finite()
        && y.is_finite()
        && x >= 0.0
        && y >= 0.0
        && x < f64::from(plan.width)
        && y < f64::from(plan.height)
    {
        Ok(())
    } else {
        Err(format!(
            "point [{x}, {y}] is outside the plan ({} × {} px)",
            plan.width, plan.height
        ))
    }
}

fn no_region([x, y]: [f64; 2]) -> String {
    format!("point [{x}, {y}] is neither inside a region nor on a wall next to one")
}

/// The face whose open pixels hold `p`, if any.
fn face_holding(plan: &ParsedPlan, [x, y]: [f64; 2]) -> Option<usize> {
    let (x, y) = (x as u32, y as u32);
    plan.faces.iter().position(|f| {
        // Runs are sorted top to bottom.
        let first = f.runs.partition_point(|r| r[0] < y);
        f.runs[first..]
            .iter()
            .take_while(|r| r[0] == y)
            .any(|r| (r[1]..=r[2]).contains(&x))
    })
}

/// The region at `p`: the face holding it, else the surroundings when the pixel is labelled
/// so, else (a point on a wall) the face with an open pixel nearest to it within a few wall
/// thicknesses.
pub fn region_at(plan: &ParsedPlan, p: [f64; 2]) -> Option<usize> {
    region_near(plan, p, &[])
}

/// [`region_at`], except that a point on a wall does not reach the faces `set` (the regions
/// the user has labelled by a point inside them: a click on the ink beside such a region means
/// the region on the wall's other side).
fn region_near(plan: &ParsedPlan, p: [f64; 2], set: &[usize]) -> Option<usize> {
    if let Some(f) = face_holding(plan, p) {
        return Some(f);
    }
    let (x, y) = (p[0] as u32, p[1] as u32);
    if plan.label_at(x, y) == Label::CastleSurroundings {
        return plan
            .faces
            .iter()
            .position(|f| f.label == Label::CastleSurroundings);
    }
    let reach = (3.0 * typical_thickness(plan)).clamp(3.0, 60.0);
    let mut best: Option<(f64, usize)> = None;
    for (fi, f) in plan.faces.iter().enumerate() {
        if set.contains(&fi) {
            continue;
        }
        for r in &f.runs {
            let dy = f64::from(r[0]) - p[1];
            if dy.abs() > reach {
                continue;
            }
            let dx = if p[0] < f64::from(r[1]) {
                f64::from(r[1]) - p[0]
            } else if p[0] > f64::from(r[2]) {
                p[0] - f64::from(r[2])
            } else {
                0.0
            };
            let d = dx.hypot(dy);
            if d <= reach && best.is_none_or(|(b, _)| d < b) {
                best = Some((d, fi));
            }
        }
    }
    best.map(|(_, f)| f)
}

/// The wall (edge) whose ink holds `p`, or the nearest within a wall's thickness.
fn wall_at(plan: &ParsedPlan, p: [f64; 2]) -> Option<usize> {
    let owner = wall_owners(plan);
    let (w, h) = (i64::from(plan.width), i64::from(plan.height));
    let reach = typical_thickness(plan).ceil().clamp(1.0, 30.0) as i64;
    let (cx, cy) = (p[0] as i64, p[1] as i64);
    let mut best: Option<(i64, usize)> = None;
    for dy in -reach..=reach {
        for dx in -reach..=reach {
            let (x, y) = (cx + dx, cy + dy);
            if x < 0 || y < 0 || x >= w || y >= h {
                continue;
            }
            let o = owner[(y * w + x) as usize];
            let d = dx * dx + dy * dy;
            if o != u32::MAX && d <= reach * reach && best.is_none_or(|(b, _)| d < b) {
                best = Some((d, o as usize));
            }
        }
    }
    best.map(|(_, e)| e)
}

/// The median thickness of the plan's walls, pixels.
fn typical_thickness(plan: &ParsedPlan) -> f64 {
    let mut t: Vec<f64> = plan.edges.iter().map(|e| e.thickness).collect();
    if t.is_empty() {
        return 2.0;
    }
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// Sets a face's label, paints its pixels and gives its walls the label §5.1.6 gives the
/// walls of such a region.
fn relabel(plan: &mut ParsedPlan, f: usize, label: Label) {
    plan.faces[f].label = label;
    paint_face(plan, f);
    let edges = plan.faces[f].edges.clone();
    let faces_of = plan.faces_of_edges();
    for e in edges {
        plan.edges[e].label = wall_label(plan, &faces_of[e]);
    }
}

fn paint_face(plan: &mut ParsedPlan, f: usize) {
    let v = plan.faces[f].label as u8;
    let w = plan.width as usize;
    for r in &plan.faces[f].runs {
        let row = r[0] as usize * w;
        for x in r[1]..=r[2] {
            plan.labels[row + x as usize] = v;
        }
    }
}

/// The label §5.1.6 gives a wall between these regions: a tower room's walls are tower walls
/// ((4)–(5)); else a wall on the surroundings is the outer wall ((2)); else the great hall's
/// and the chapel's walls are theirs ((7), (9)); the rest are unknown walls ((10)).
fn wall_label(plan: &ParsedPlan, faces: &[usize]) -> Label {
    let has = |l: Label| faces.iter().any(|&f| plan.faces[f].label == l);
    if has(Label::TowerRoom) {
        Label::TowerWall
    } else if has(Label::CastleSurroundings) {
        Label::CastleOuterWall
    } else if has(Label::GreatHall) {
        Label::GreatHallWall
    } else if has(Label::Chapel) {
        Label::ChapelWall
    } else {
        Label::UnknownWall
    }
}

/// Faces `a` and `b` become `a`: the walls between them are dropped from the graph.
fn merge(plan: &mut ParsedPlan, a: usize, b: usize) -> Result<(), String> {
    let shared: Vec<usize> = plan.faces[a]
        .edges
        .iter()
        .copied()
        .filter(|e| plan.faces[b].edges.contains(e))
        .collect();
    if shared.is_empty() {
        return Err(format!(
            "the {} and the {} share no wall; only neighbours merge",
            plan.faces[a].label.name(),
            plan.faces[b].label.name()
        ));
    }
    if plan.faces[a].label == Label::CastleSurroundings
        || plan.faces[b].label == Label::CastleSurroundings
    {
        return Err(
            "the castle's surroundings merge with nothing; relabel the region instead".into(),
        );
    }
    // The dropped walls' pixels become the merged region's.
    let owner = wall_owners(plan);
    let v = plan.faces[a].label as u8;
    for (i, o) in owner.iter().enumerate() {
        if *o != u32::MAX && shared.contains(&(*o as usize)) {
            plan.labels[i] = v;
        }
    }
    let other = plan.faces.remove(b);
    let a = if b < a { a - 1 } else { a };
    let face = &mut plan.faces[a];
    let total = (face.area + other.area).max(1) as f64;
    face.centroid = [
        (face.centroid[0] * face.area as f64 + other.centroid[0] * other.area as f64) / total,
        (face.centroid[1] * face.area as f64 + other.centroid[1] * other.area as f64) / total,
    ];
    face.area += other.area;
    face.runs.extend(other.runs);
    face.runs.sort_unstable();
    face.edges.extend(other.edges);
    face.edges.retain(|e| !shared.contains(e));
    face.edges.sort_unstable();
    face.edges.dedup();
    // The room's outline changed: its §5.1.5 fit no longer holds (the model fits it again).
    face.shape = None;
    paint_face(plan, a);
    remove_edges(plan, &shared);
    Ok(())
}

/// Drops edges, renumbering the faces' references.
fn remove_edges(plan: &mut ParsedPlan, gone: &[usize]) {
    let mut new_index = vec![usize::MAX; plan.edges.len()];
    let mut next = 0;
    for (i, slot) in new_index.iter_mut().enumerate() {
        if !gone.contains(&i) {
            *slot = next;
            next += 1;
        }
    }
    let mut i = 0;
    plan.edges.retain(|_| {
        i += 1;
        !gone.contains(&(i - 1))
    });
    for f in &mut plan.faces {
        f.edges = f
            .edges
            .iter()
            .filter_map(|&e| (new_index[e] != usize::MAX).then_some(new_index[e]))
            .collect();
    }
}

/// The edge each wall pixel belongs to: a breadth-first flood over the wall ink from every
/// edge's skeleton pixels (as §5.1.6's pixel labels are spread); `u32::MAX` off the walls.
fn wall_owners(plan: &ParsedPlan) -> Vec<u32> {
    let (w, h) = (plan.width as usize, plan.height as usize);
    let mut owner = vec![u32::MAX; w * h];
    let mut queue = std::collections::VecDeque::new();
    for (e, edge) in plan.edges.iter().enumerate() {
        for &(x, y) in &edge.points {
            let i = y as usize * w + x as usize;
            if i < owner.len() && owner[i] == u32::MAX {
                owner[i] = e as u32;
                queue.push_back(i);
            }
        }
    }
    while let Some(i) = queue.pop_front() {
        let (x, y) = ((i % w) as i64, (i / w) as i64);
        for (dx, dy) in crate::thin::NEIGHBOURS {
            let (nx, ny) = (x + i64::from(dx), y + i64::from(dy));
            if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                continue;
            }
            let j = ny as usize * w + nx as usize;
            if owner[j] == u32::MAX && plan.walls.data[j] == 1 {
                owner[j] = owner[i];
                queue.push_back(j);
            }
        }
    }
    owner
}

/// Paints every wall pixel an edge owns with the edge's label.
fn repaint_walls(plan: &mut ParsedPlan) {
    let owner = wall_owners(plan);
    for (i, o) in owner.iter().enumerate() {
        if *o != u32::MAX && Label::ALL[plan.labels[i] as usize].is_wall() {
            plan.labels[i] = plan.edges[*o as usize].label as u8;
        }
    }
}

/// A tower the parser missed: inside a room, the room is a tower room (a circle of the given
/// radius when one is given); elsewhere (on a tower drawn solid, or a radius given in the open)
/// a solid tower of the measured or given radius.
fn add_tower(plan: &mut ParsedPlan, p: [f64; 2], radius: Option<f64>) -> Result<(), String> {
    if let Some(f) = face_holding(plan, p)
        && plan.faces[f].label.is_room()
    {
        relabel(plan, f, Label::TowerRoom);
        if let Some(r) = radius {
            let t = room_wall_thickness(plan, &plan.faces[f]);
            plan.faces[f].shape = Some(crate::fit::Fit::Circle {
                center: p,
                radius: (r - t / 2.0).max(0.5),
                error: 0.0,
            });
        }
        return Ok(());
    }
    let radius = match radius {
        Some(r) => r,
        None => ink_radius(plan, p).ok_or_else(|| {
            format!(
                "point [{}, {}] is neither in a room nor on a tower drawn solid: give the tower's radius",
                p[0], p[1]
            )
        })?,
    };
    plan.bulge_towers.push(BulgeTower { center: p, radius });
    Ok(())
}

fn room_wall_thickness(plan: &ParsedPlan, face: &PlanFace) -> f64 {
    if face.edges.is_empty() {
        return 2.0;
    }
    face.edges
        .iter()
        .map(|&e| plan.edges[e].thickness)
        .sum::<f64>()
        / face.edges.len() as f64
}

/// The radius of the solid ink disc round `p`: the distance to the nearest paper pixel, when
/// `p` is on the walls (a tower drawn solid is a disc of ink).
fn ink_radius(plan: &ParsedPlan, p: [f64; 2]) -> Option<f64> {
    let (w, h) = (plan.width as i64, plan.height as i64);
    let (cx, cy) = (p[0] as i64, p[1] as i64);
    if plan.walls.data[(cy * w + cx) as usize] != 1 {
        return None;
    }
    let most = w.max(h) / 2;
    for r in 1..=most {
        let mut nearest = f64::INFINITY;
        for dy in -r..=r {
            for dx in -r..=r {
                if dx.abs() != r && dy.abs() != r {
                    continue;
                }
                let (x, y) = (cx + dx, cy + dy);
                let paper = x < 0
                    || y < 0
                    || x >= w
                    || y >= h
                    || plan.walls.data[(y * w + x) as usize] != 1;
                if paper {
                    nearest = nearest.min((dx as f64).hypot(dy as f64));
                }
            }
        }
        if nearest.is_finite() {
            return Some(nearest.max(1.0));
        }
    }
    None
}

/// Removes the tower at `p`: a solid tower whose disc holds it, else the tower room there
/// (which becomes an unknown room, its walls following). False when there is none.
fn remove_tower(plan: &mut ParsedPlan, p: [f64; 2]) -> bool {
    let before = plan.bulge_towers.len();
    plan.bulge_towers
        .retain(|t| (t.center[0] - p[0]).hypot(t.center[1] - p[1]) > t.radius);
    if plan.bulge_towers.len() < before {
        return true;
    }
    match region_at(plan, p) {
        Some(f) if plan.faces[f].label == Label::TowerRoom => {
            relabel(plan, f, Label::UnknownRoom);
            true
        }
        _ => false,
    }
}
