//! Plan shapes → structures (§6.1.3, §5.3): rooms with a circle or rectangle fit become hollow
//! cylindrical or rectangular structures (outer footprint = the fitted wall centreline plus
//! half the wall), towers found as bulges of the curtain (`plan::bulges`, no room drawn)
//! become solid cylindrical towers, and the walls no room owns become runs of curtain and of
//! inner wall ([`walls`]). Each structure has a role ([`roles`]: keep, tower, range, room,
//! curtain, wall, and the masses of wall the rest leaves bare). Heights are the class defaults of §5.3 until a façade says otherwise.

mod bare;
mod blocks;
mod drawn;
mod roles;
mod spurs;
mod walls;

use std::collections::BTreeMap;

use plan::ParsedPlan;
use plan::extrude::Heights;
use plan::fit::Fit;
use plan::label::Label;
use plan::scale::{ModelScale, outer_wall_thickness};

use crate::correspond::{area, contains};
use crate::estimate::{Element, Footprint, Kind, Provenance, Role, Structure};
use roles::{Candidate, SQUAREISH};

/// The base of a structure's id: its role, or for a room its label's building.
fn id_base(role: Role, l: Label) -> &'static str {
    match (role, l) {
        (Role::Range | Role::Room, Label::GreatHall) => "hall",
        (Role::Range | Role::Room, Label::Chapel) => "chapel",
        _ => role.name(),
    }
}

/// The keep's default height: half as high again as the towers' class height of §5.3 (the
/// text's classes have no keep; a donjon rises above its towers).
pub(crate) const KEEP_OVER_TOWERS: f64 = 1.5;

/// The wall label that surrounds rooms of label `l` (for heights and names).
fn wall_of(l: Label) -> Label {
    match l {
        Label::TowerRoom => Label::TowerWall,
        Label::GreatHall => Label::GreatHallWall,
        Label::Chapel => Label::ChapelWall,
        _ => Label::UnknownWall,
    }
}

/// Children of a structure's root by kind (§6.1.3).
pub fn hierarchy(id: &str, kind: Kind) -> Vec<Element> {
    match kind {
        Kind::HollowRectangular => ["north", "south", "east", "west"]
            .iter()
            .map(|s| Element::leaf(format!("{id}Wall_{s}"), "wall"))
            .chain([Element::leaf(format!("{id}Interior"), "interior")])
            .collect(),
        Kind::HollowCylindrical => vec![
            Element::leaf(format!("{id}Wall"), "wall"),
            Element::leaf(format!("{id}Interior"), "interior"),
        ],
        Kind::SolidCylindrical => vec![
            Element::leaf(format!("{id}Wall"), "wall"),
            Element::leaf(format!("{id}Fill"), "fill"),
        ],
        Kind::Solid => vec![
            Element::leaf(format!("{id}Face_field"), "wall"),
            Element::leaf(format!("{id}Fill"), "fill"),
            Element::leaf(format!("{id}Face_ward"), "wall"),
        ],
    }
}

/// A room of the plan with a fitted shape, before its role is known.
struct Room {
    face: usize,
    footprint: Footprint,
    kind: Kind,
    fit: &'static str,
    error: f64,
    thickness_px: f64,
    on_curtain: bool,
}

/// A gate block's default height over the curtain's class height (the text's classes have no
/// gatehouse; it stands above the curtain it pierces).
const GATE_OVER_CURTAIN: f64 = 1.25;

/// A gatehouse between every two towers close enough to flank a gate (`roles::gates`): a block
/// from one tower's centre to the other's, as deep as the smaller tower is wide, pierced by its
/// passage in the program.
fn gatehouses(
    built: &[Structure],
    heights: &Heights,
    image: &str,
    next_id: &mut impl FnMut(&'static str) -> String,
) -> Vec<Structure> {
    let towers: Vec<(&Structure, [f64; 2], f64)> = built
        .iter()
        .filter(|s| s.role == Role::Tower)
        .filter_map(|s| match &s.footprint {
            Footprint::Circle { center, radius } => Some((s, *center, *radius)),
            Footprint::Rectangle { center, size, .. } => {
                Some((s, *center, size[0].min(size[1]) / 2.0))
            }
            _ => None,
        })
        .collect();
    let circles: Vec<([f64; 2], f64)> = towers.iter().map(|t| (t.1, t.2)).collect();
    roles::gates(&circles)
        .into_iter()
        .map(|[i, j]| {
            let ((a, ca, ra), (b, cb, rb)) = (towers[i], towers[j]);
            let (dx, dy) = (cb[0] - ca[0], cb[1] - ca[1]);
            let length = dx.hypot(dy);
            let id = next_id(Role::Gatehouse.name());
            let mut provenance = BTreeMap::new();
            provenance.insert(
                "footprint".to_string(),
                Provenance::new(
                    image,
                    format!(
                        "issue 25: {} and {} flank a gate ({:.2} apart, within 0.75 of their summed radii): a block from centre to centre, as deep as the smaller is wide",
                        a.id,
                        b.id,
                        length - ra - rb,
                    ),
                    None,
                ),
            );
            provenance.insert(
                "height".to_string(),
                Provenance::new(
                    "default",
                    format!(
                        "the gatehouse: {GATE_OVER_CURTAIN} × the §5.3 class height of {}",
                        Label::CastleOuterWall.name()
                    ),
                    None,
                ),
            );
            Structure {
                children: vec![
                    Element::leaf(format!("{id}Body"), "wall"),
                    Element::leaf(format!("{id}Passage"), "passage"),
                ],
                id,
                label: Label::CastleOuterWall,
                role: Role::Gatehouse,
                kind: Kind::Solid,
                footprint: Footprint::Rectangle {
                    center: [(ca[0] + cb[0]) / 2.0, (ca[1] + cb[1]) / 2.0],
                    size: [length, 2.0 * ra.min(rb)],
                    rotation: dy.atan2(dx),
                },
                height: GATE_OVER_CURTAIN * heights.of(Label::CastleOuterWall),
                wall_thickness: a.wall_thickness.max(b.wall_thickness),
                facades: Vec::new(),
                roof: None,
                crenellated: None,
                provenance,
            }
        })
        .collect()
}

/// What every tower found on the outline is built in: the plan's scale (`s` model units per
/// pixel), the class heights, the drawing's name for provenance, and the curtain's thickness
/// (pixels) when the plan has outer walls.
struct OutlineFrame<'a> {
    s: f64,
    heights: &'a Heights,
    image: &'a str,
    curtain_px: Option<f64>,
}

/// A tower found on the outline rather than as a room (a bulge of the curtain, or a round tower
/// the other structures leave bare): a solid cylinder on its circle `b` (plan pixels), its
/// wall as thick as the curtain (at most half the radius); a keep is taller. `step` says how it
/// was found.
fn round_tower(
    b: &plan::bulges::BulgeTower,
    id: String,
    role: Role,
    step: String,
    frame: &OutlineFrame,
    plan: &ParsedPlan,
) -> Structure {
    let OutlineFrame {
        s,
        heights,
        image,
        curtain_px,
    } = *frame;
    let keep_here = role == Role::Keep;
    let wall_px = b.wall_width(curtain_px);
    // A thick tower wide enough has its room in the plan's labels (`plan::thick_towers::rooms`,
    // issue 26): it is built round its room, the ring as thick as the plan's.
    let room = plan.label_at_point(b.center) == Some(Label::TowerRoom);
    let kind = if room {
        Kind::HollowCylindrical
    } else {
        Kind::SolidCylindrical
    };
    let step = if room {
        format!("{step}; hollow: the plan gives it a room inside its wall ring")
    } else {
        format!("{step}, solid")
    };
    let mut provenance = BTreeMap::new();
    provenance.insert("footprint".to_string(), Provenance::new(image, step, None));
    provenance.insert(
        "wall_thickness".to_string(),
        Provenance::new(
            image,
            match curtain_px {
                Some(_) => "§5.1.4 median thickness of the outer walls (the curtain the tower studs), at most half the radius; inside it, fill or the room",
                None => "no outer wall: a third of the radius; inside it, fill or the room",
            },
            None,
        ),
    );
    let factor = if keep_here { KEEP_OVER_TOWERS } else { 1.0 };
    provenance.insert(
        "height".to_string(),
        Provenance::new(
            "default",
            if keep_here {
                format!(
                    "the keep: {KEEP_OVER_TOWERS} × the §5.3 class height of {}",
                    Label::TowerWall.name()
                )
            } else {
                format!("§5.3 class height of {}", Label::TowerWall.name())
            },
            None,
        ),
    );
    Structure {
        children: hierarchy(&id, kind),
        id,
        label: Label::TowerWall,
        role,
        kind,
        footprint: Footprint::Circle {
            center: [b.center[0] * s, b.center[1] * s],
            radius: b.radius * s,
        },
        height: factor * heights.of(Label::TowerWall),
        wall_thickness: wall_px * s,
        facades: Vec::new(),
        roof: None,
        crenellated: None,
        provenance,
    }
}

/// A room whose boundary §5.1.5 would not fit (a D-shaped tower, a chapel with its apse, a
/// room whose walls the drawing breaks): the circle or rectangle of its boundary within
/// `LOOSE_FIT` of its size, when the room's open area fills at least `LOOSE_FILL` of it —
/// so that every room of the plan is built (issue 25; §5.1.5 leaves such faces to their edges).
fn loose_fit(plan: &ParsedPlan, face: usize) -> Option<Fit> {
    let f = &plan.faces[face];
    let pts: Vec<[f64; 2]> = f
        .edges
        .iter()
        .flat_map(|&e| plan.edges[e].points.iter())
        .map(|&(x, y)| [f64::from(x), f64::from(y)])
        .collect();
    let fit = plan::fit::fit_face(&pts, LOOSE_FIT)?;
    let inside = match &fit {
        Fit::Circle { radius, .. } => std::f64::consts::PI * radius * radius,
        Fit::Rectangle { size, .. } => size[0] * size[1],
        _ => return None,
    };
    (f.area as f64 >= LOOSE_FILL * inside).then_some(fit)
}

/// How far from a circle or rectangle a room's boundary may be for [`loose_fit`] (mean distance
/// over half the size) …
const LOOSE_FIT: f64 = 0.3;
/// … and how much of it the room's open pixels must fill (the rest is its walls' inner half).
const LOOSE_FILL: f64 = 0.45;

/// Every structure of the plan, without façades: rooms (the keep, towers, ranges, rooms), then
/// the bulge towers (named after the tower rooms' `tower1 … tower{k}`), then the curtain and
/// the inner walls.
pub fn from_plan(plan: &ParsedPlan, image: &str, frame: &ModelScale) -> Vec<Structure> {
    let heights = Heights::scaled(frame.units_per_metre);
    let s = frame.units_per_pixel;
    let faces_of = plan.faces_of_edges();
    let borders_field = |fi: usize| {
        plan.faces[fi].edges.iter().any(|&e| {
            faces_of[e]
                .iter()
                .any(|&f| plan.faces[f].label == Label::CastleSurroundings)
        })
    };
    let rooms: Vec<Room> = plan
        .faces
        .iter()
        .enumerate()
        .filter(|(_, f)| f.label.is_room())
        .filter_map(|(fi, face)| {
            let t_px = if face.edges.is_empty() {
                2.0
            } else {
                face.edges
                    .iter()
                    .map(|&e| plan.edges[e].thickness)
                    .sum::<f64>()
                    / face.edges.len() as f64
            };
            let loose = face.shape.is_none();
            let shape = face.shape.clone().or_else(|| loose_fit(plan, fi));
            let (footprint, kind, fit, error) = match &shape {
                Some(Fit::Circle {
                    center,
                    radius,
                    error,
                }) if *radius > 0.5 => (
                    Footprint::Circle {
                        center: [center[0] * s, center[1] * s],
                        radius: (radius + t_px / 2.0) * s,
                    },
                    Kind::HollowCylindrical,
                    if loose { "loose circle" } else { "circle" },
                    *error,
                ),
                Some(Fit::Rectangle {
                    center,
                    size,
                    angle,
                    error,
                }) if size[0] > 0.5 && size[1] > 0.5 => (
                    Footprint::Rectangle {
                        center: [center[0] * s, center[1] * s],
                        size: [(size[0] + t_px) * s, (size[1] + t_px) * s],
                        rotation: *angle,
                    },
                    Kind::HollowRectangular,
                    if loose {
                        "loose rectangle"
                    } else {
                        "rectangle"
                    },
                    *error,
                ),
                _ => {
                    // Issue 25: every room is built; one no circle or rectangle fits is
                    // covered by blocks cut from its open pixels, inside its walls.
                    (
                        blocks::footprint(&face.runs, t_px, s)?,
                        Kind::HollowRectangular,
                        "blocks",
                        0.0,
                    )
                }
            };
            Some(Room {
                face: fi,
                footprint,
                kind,
                fit,
                error,
                thickness_px: t_px,
                on_curtain: borders_field(fi),
            })
        })
        .collect();
    let curtain_px = outer_wall_thickness(plan);
    // Bulge towers on a tower whose room the plan found are that tower: built once.
    let bulges: Vec<(usize, &plan::bulges::BulgeTower)> = plan
        .bulge_towers
        .iter()
        .enumerate()
        .filter(|(_, b)| b.radius > 0.5)
        .filter(|(_, b)| {
            let c = [b.center[0] * s, b.center[1] * s];
            !rooms
                .iter()
                .any(|r| plan.faces[r.face].label == Label::TowerRoom && contains(&r.footprint, c))
        })
        .collect();
    let candidates: Vec<Candidate> = rooms
        .iter()
        .map(|r| Candidate {
            area: area(&r.footprint),
            thickness: r.thickness_px * s,
            tower: plan.faces[r.face].label == Label::TowerRoom,
            compact: match r.footprint {
                Footprint::Rectangle { size, .. } => {
                    size[0].max(size[1]) <= SQUAREISH * size[0].min(size[1])
                }
                Footprint::Circle { .. } => true,
                // A shape no circle or rectangle fits is no keep.
                Footprint::Blocks { .. } | Footprint::Wall { .. } => false,
            },
            on_curtain: r.on_curtain,
        })
        .chain(bulges.iter().map(|(_, b)| Candidate {
            area: std::f64::consts::PI * (b.radius * s).powi(2),
            thickness: curtain_px.unwrap_or(b.radius / 3.0).min(b.radius / 2.0) * s,
            tower: true,
            compact: true,
            on_curtain: true,
        }))
        .collect();
    let keep = roles::keep(&candidates, curtain_px.map(|t| t * s));
    let tower_wall = roles::median(
        candidates
            .iter()
            .filter(|c| c.tower)
            .map(|c| c.thickness)
            .collect(),
    );
    let role_of_room = |i: usize| {
        if keep == Some(i) {
            Role::Keep
        } else if plan.faces[rooms[i].face].label == Label::TowerRoom
            && !roles::thin_for_a_tower(candidates[i].thickness, tower_wall)
        {
            Role::Tower
        } else {
            roles::room(rooms[i].on_curtain)
        }
    };

    let mut counters: BTreeMap<&str, usize> = BTreeMap::new();
    let mut next_id = |base: &'static str| {
        let n = counters.entry(base).or_insert(0);
        *n += 1;
        format!("{base}{n}")
    };
    let mut owned = vec![false; plan.edges.len()];
    let mut tower_owned = vec![false; plan.edges.len()];
    let mut out = Vec::new();
    for (i, room) in rooms.iter().enumerate() {
        let face = &plan.faces[room.face];
        let role = role_of_room(i);
        // A fitted footprint takes in half its walls; blocks cover the inside, and the walls
        // are built as walls.
        let covers_walls = !matches!(room.footprint, Footprint::Blocks { .. });
        for &e in face.edges.iter().filter(|_| covers_walls) {
            owned[e] = true;
            if matches!(role, Role::Tower | Role::Keep) {
                tower_owned[e] = true;
            }
        }
        let id = next_id(id_base(role, face.label));
        // A tower room built as a room (walls too thin for a tower) takes a room's height.
        let wall_label = match (role, face.label) {
            (Role::Range | Role::Room, Label::TowerRoom) => Label::UnknownWall,
            (_, l) => wall_of(l),
        };
        let mut provenance = BTreeMap::new();
        provenance.insert(
            "footprint".to_string(),
            Provenance::new(
                image,
                if covers_walls {
                    format!(
                        "§5.1.5 {} fit of plan face {} ({}), plus half the wall",
                        room.fit,
                        room.face,
                        face.label.name()
                    )
                } else {
                    format!(
                        "issue 25: the open pixels of plan face {} ({}), which no circle or rectangle fits, cut into blocks along its long axis",
                        room.face,
                        face.label.name()
                    )
                },
                (covers_walls).then_some(room.error),
            ),
        );
        provenance.insert(
            "wall_thickness".to_string(),
            Provenance::new(
                image,
                format!(
                    "§5.1.4 mean thickness of the {} walls around plan face {}",
                    face.edges.len(),
                    room.face
                ),
                None,
            ),
        );
        let height = if role == Role::Keep {
            provenance.insert(
                "role".to_string(),
                Provenance::new(
                    image,
                    "issue 25: the largest compact shape of the plan, clearly larger than the towers with walls as thick, or standing free in a ward with walls as thick as the curtain's",
                    None,
                ),
            );
            provenance.insert(
                "height".to_string(),
                Provenance::new(
                    "default",
                    format!(
                        "the keep: {KEEP_OVER_TOWERS} × the §5.3 class height of {}",
                        Label::TowerWall.name()
                    ),
                    None,
                ),
            );
            KEEP_OVER_TOWERS * heights.of(Label::TowerWall)
        } else {
            provenance.insert(
                "height".to_string(),
                Provenance::new(
                    "default",
                    format!("§5.3 class height of {}", wall_label.name()),
                    None,
                ),
            );
            heights.of(wall_label)
        };
        let children = if covers_walls {
            hierarchy(&id, room.kind)
        } else {
            vec![
                Element::leaf(format!("{id}Mass"), "mass"),
                Element::leaf(format!("{id}Roof"), "roof"),
            ]
        };
        out.push(Structure {
            children,
            id,
            label: face.label,
            role,
            kind: room.kind,
            footprint: room.footprint.clone(),
            height,
            wall_thickness: room.thickness_px * s,
            facades: Vec::new(),
            roof: None,
            crenellated: None,
            provenance,
        });
    }
    let outline = OutlineFrame {
        s,
        heights: &heights,
        image,
        curtain_px,
    };
    for (k, (bi, b)) in bulges.iter().enumerate() {
        let keep_here = keep == Some(rooms.len() + k);
        let role = if keep_here { Role::Keep } else { Role::Tower };
        let step = format!(
            "§5.1.6 bulge tower {bi} of the castle's outline (plan::bulges, no room drawn): circle fitted to the bulge"
        );
        let id = next_id(role.name());
        out.push(round_tower(b, id, role, step, &outline, plan));
    }
    for gate in gatehouses(&out, &heights, image, &mut next_id) {
        out.push(gate);
    }
    let runs = walls::runs(plan, &owned, &tower_owned);
    for run in runs.into_iter().chain(spurs::runs(plan)) {
        if run.points.len() < 2 {
            continue;
        }
        let label = match run.role {
            Role::Curtain => Label::CastleOuterWall,
            _ => Label::UnknownWall,
        };
        let height = heights.of(label);
        let id = next_id(run.role.name());
        let mut provenance = BTreeMap::new();
        provenance.insert(
            "footprint".to_string(),
            Provenance::new(
                image,
                if run.spur {
                    format!(
                        "wall chains §5.1.6 prunes (leaves of the skeleton's graph: a wall running out, a solid mass) joined end to end, kept for their thickness and length (issue 25), the straight pieces fitted and each laid on the wall as drawn{}",
                        if run.role == Role::Curtain {
                            "; the plan labels it outer or tower wall"
                        } else {
                            ""
                        }
                    )
                } else {
                    format!(
                        "§5.1.5 fits of plan edges {:?} joined into one run (issue 25: a line between vertices, arcs as chords, collinear pieces merged), each straight piece laid on the middle of the wall as drawn{}",
                        run.edges,
                        if run.role == Role::Curtain {
                            "; it borders the castle's surroundings, which lie on its left"
                        } else {
                            ""
                        }
                    )
                },
                None,
            ),
        );
        provenance.insert(
            "wall_thickness".to_string(),
            Provenance::new(
                image,
                "§5.1.4 length-weighted median thickness of its edges; each straight piece takes its own width as drawn (`widths`, issue 25)",
                None,
            ),
        );
        provenance.insert(
            "height".to_string(),
            Provenance::new(
                "default",
                format!("§5.3 class height of {}", label.name()),
                None,
            ),
        );
        let thickness = run.thickness * s;
        let (centerline, widths) =
            drawn::onto_ink(&plan.walls, &run.points, run.closed, run.thickness);
        out.push(Structure {
            children: hierarchy(&id, Kind::Solid),
            id,
            label,
            role: run.role,
            kind: Kind::Solid,
            footprint: Footprint::Wall {
                centerline: centerline.iter().map(|p| [p[0] * s, p[1] * s]).collect(),
                thickness,
                closed: run.closed,
                widths: widths.iter().map(|w| w * s).collect(),
            },
            height,
            wall_thickness: thickness,
            facades: Vec::new(),
            roof: None,
            crenellated: None,
            provenance,
        });
    }
    // Issue 25: round towers of the outer wall that nothing above covers (`bare`).
    if let Some(t) = curtain_px {
        for (k, b) in bare::towers(plan, &out, s, t).iter().enumerate() {
            let step = format!(
                "round tower {k} of the outer wall that no other structure covers (issue 25): circle fitted to the edge of the bare wall towards the surroundings"
            );
            let id = next_id(Role::Tower.name());
            out.push(round_tower(b, id, Role::Tower, step, &outline, plan));
        }
        // Issue 25: masses of wall nothing above covers (`bare::masses`), blocks of stone.
        for mass in bare::masses(plan, &out, s, t) {
            if let Some(st) = mass.structure(|| next_id(Role::Mass.name()), &outline) {
                out.push(st);
            }
        }
    }
    out
}
