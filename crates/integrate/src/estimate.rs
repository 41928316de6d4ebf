//! The integrated estimate (estimate.json, §6.1.3–6.1.4): structures from the plan, each with a
//! footprint in the plan's frame, a height, the façades mapped to it and its semantic
//! hierarchy, and for every parameter where it came from.

use std::collections::BTreeMap;

use plan::label::Label;
use plan::scale::ModelScale;
use serde::{Deserialize, Serialize};

/// estimate.json.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    /// The model's units (`units`), model units per plan pixel (`scale`) and per metre
    /// (`units_per_metre`), decided once by [`plan::scale::ModelScale::decide`].
    #[serde(flatten)]
    pub scale: ModelScale,
    pub plan: PlanSource,
    pub structures: Vec<Structure>,
    /// What was assumed rather than measured.
    pub assumptions: Vec<String>,
}

/// The plan drawing the structures come from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlanSource {
    pub image: String,
    pub width: u32,
    pub height: u32,
    pub towers: usize,
}

/// One building part: a plan shape with its label, lifted to 3D.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Structure {
    /// Symbol in the generated program, e.g. `tower2`.
    pub id: String,
    /// The plan label (§5.1.6) of the shape, the root of its hierarchy (§6.1.3).
    pub label: Label,
    /// What the structure is to a heritage expert, decided from the plan (issue 25).
    pub role: Role,
    pub kind: Kind,
    pub footprint: Footprint,
    pub height: f64,
    pub wall_thickness: f64,
    pub facades: Vec<MappedFacade>,
    /// The roof the user chose (`[[structure]] roof`, issue 22); absent, the library's roof
    /// for the structure's kind (a cone on round towers, a gable on keeps, flat blocks).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roof: Option<Roof>,
    /// Crenellation on or off as the user chose (`[[structure]] crenellated`); absent, the
    /// library's (curtains and square towers crenellated, the rest not).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crenellated: Option<bool>,
    /// The semantic hierarchy under the root (§6.1.3).
    pub children: Vec<Element>,
    /// Source of each parameter, by name (`footprint`, `height`, `wall_thickness`, …).
    pub provenance: BTreeMap<String, Provenance>,
}

/// The §6.1.3 classes of architecture.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// Four walls and an interior (rectangular towers, keeps, halls, rooms).
    HollowRectangular,
    /// A wall ring and an interior (round towers).
    HollowCylindrical,
    /// Wall faces and a fill (curtain walls).
    Solid,
    /// A wall ring round a fill: a round tower drawn solid, with no room (the plan's bulge
    /// towers, `plan::bulges`).
    SolidCylindrical,
}

/// What a structure is to a heritage expert (§6.1.3's classes named as §7.2.2's library names
/// them), decided from the plan's shapes and labels by `structures::roles`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// The donjon: the largest tower with the thickest walls, or a tower standing free in a
    /// ward.
    Keep,
    /// A tower of the curtain (a tower room, or a bulge of the outline drawn solid).
    Tower,
    /// A gate block between two towers that flank the way in, with its passage.
    Gatehouse,
    /// The curtain wall: a run of the castle's outer wall between towers, with its wall walk
    /// and a parapet crenellated on the field side.
    Curtain,
    /// A roofed range: a room built against the curtain (hall, chapel, lodgings).
    Range,
    /// A room standing in a ward, roofed.
    Room,
    /// A wall inside the castle that divides wards or rooms: no parapet.
    Wall,
    /// A mass of wall the plan draws that no fitted structure explains (a wall §5.1.5 fitted
    /// nothing to, a solid the skeleton pruned): blocks of stone cut from its pixels, §5.3's
    /// extrusion of the labelled wall (`structures::bare::masses`).
    Mass,
}

impl Role {
    /// The name estimate.json, the report and the program's symbols use.
    pub fn name(self) -> &'static str {
        match self {
            Role::Keep => "keep",
            Role::Tower => "tower",
            Role::Gatehouse => "gatehouse",
            Role::Curtain => "curtain",
            Role::Range => "range",
            Role::Room => "room",
            Role::Wall => "wall",
            Role::Mass => "mass",
        }
    }
}

/// A roof the user can choose for a structure (issue 22).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Roof {
    /// A cone over a round footprint; over a rectangle, a pyramid (a cone has no corners).
    Cone,
    /// Four faces to a point over the footprint's rectangle (a circle's circumscribed square).
    Pyramid,
    /// Four faces to a ridge along the longer side.
    Hipped,
    /// Two faces to a ridge along the longer side, gable ends on the shorter.
    Gable,
    /// A flat slab.
    Flat,
    /// No roof: an open top.
    None,
}

impl Roof {
    pub fn name(self) -> &'static str {
        match self {
            Roof::Cone => "cone",
            Roof::Pyramid => "pyramid",
            Roof::Hipped => "hipped",
            Roof::Gable => "gable",
            Roof::Flat => "flat",
            Roof::None => "none",
        }
    }
}

/// A footprint in the plan's frame (x, z) = plan pixel (x, y) × scale.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum Footprint {
    /// `rotation`: angle of the `size[0]` side from the x axis, radians, measured in the plan
    /// image (y down).
    Rectangle {
        center: [f64; 2],
        size: [f64; 2],
        rotation: f64,
    },
    Circle {
        center: [f64; 2],
        radius: f64,
    },
    /// A room §5.1.5 could not fit as a circle or rectangle, covered by rectangles (`size`
    /// across and along, in the frame turned by `rotation` as a rectangle's) cut from its open
    /// pixels in strips across its long axis.
    Blocks {
        rotation: f64,
        blocks: Vec<Block>,
    },
    /// A wall `thickness` thick along a centreline (straight pieces, arcs as short chords);
    /// `closed` when it is a ring (the last point is then joined to the first). `widths`, when
    /// given, is each piece's own thickness as drawn ([`Footprint::pieces`] order; issue 25),
    /// and `thickness` the run's median.
    Wall {
        centerline: Vec<[f64; 2]>,
        thickness: f64,
        closed: bool,
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        widths: Vec<f64>,
    },
}

/// One rectangle of a [`Footprint::Blocks`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Block {
    pub center: [f64; 2],
    pub size: [f64; 2],
}

/// The wall a façade is mapped to: a side of a rectangle (the local −z, +z, +x, −x faces of
/// the box) or an arc of a circle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    North,
    South,
    East,
    West,
    Arc,
}

impl Side {
    /// The four sides of a box, in the order the program writes them.
    pub const BOX: [Side; 4] = [Side::North, Side::South, Side::East, Side::West];

    /// `north`, `south`, `east`, `west` or `arc`, as estimate.json and the program's symbols
    /// write it.
    pub fn name(self) -> &'static str {
        match self {
            Side::North => "north",
            Side::South => "south",
            Side::East => "east",
            Side::West => "west",
            Side::Arc => "arc",
        }
    }
}

impl std::fmt::Display for Side {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A façade estimate mapped onto a structure, scaled into model units (§6.1.2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MappedFacade {
    pub image: String,
    /// Which wall.
    pub side: Side,
    /// For an arc: start and end angle (radians, counter-clockwise on the drawing, 0 = +x).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub arc: Option<[f64; 2]>,
    /// s = w_p / w_f (or d_p / w_f for a circle): model units per rectified façade pixel,
    /// horizontally.
    pub scale: f64,
    /// s_yn = H̄ / (s H_n): the extra vertical factor that gives all façades of the structure
    /// the same height (1 with one façade).
    pub height_factor: f64,
    /// Façade width and height in model units.
    pub width: f64,
    pub height: f64,
    /// Bottom-up.
    pub floors: Vec<FloorEstimate>,
    pub windows: WindowColumns,
    /// True when re-estimated jointly with the structure's other façades (§6.1.2).
    pub joint: bool,
    /// The façade's bounding box [x0, y0, x1, y1] in the rectified photo, or in the part of it
    /// inside the [[facade]] entry's `bbox` when the user drew one (the search runs on that cut).
    pub bbox: [f64; 4],
    /// Texture file of the rectified, cropped photo, if written.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub texture: Option<String>,
    /// A Gothic façade (ch. 4) replaces the wall with its arches and stones.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gothic: Option<GothicMapped>,
}

/// A Gothic façade on a wall: the block program it becomes and what it holds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GothicMapped {
    /// The program file (facade::gothic::to_vsg at the model's scale) the model imports.
    pub program: String,
    /// The import's namespace in the generated program.
    pub alias: String,
    pub elements: usize,
    pub groups: usize,
    pub stones: usize,
    /// Elements the fit found that the learned check dropped as unlike openings (issue 23;
    /// `castellan gothic --no-verify` keeps them).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub dropped: usize,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// One floor of a mapped façade, model units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FloorEstimate {
    pub height: f64,
    pub windows: u32,
    /// Window height and its distance above the floor's bottom (0 when no windows).
    pub window_height: f64,
    pub window_sill: f64,
    /// The floor's own windows, [start, width] in model units from the façade's left edge,
    /// when they are not the façade's shared columns (`windows`): the floors of a façade the
    /// user corrected (issue 22), each window where its tree has it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub openings: Option<Vec<[f64; 2]>>,
}

/// The window columns shared by every floor, model units from the façade's left edge.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WindowColumns {
    pub count: u32,
    pub offset: f64,
    pub width: f64,
    pub gap: f64,
}

/// A node of the semantic hierarchy.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Element {
    pub name: String,
    pub kind: String,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub children: Vec<Element>,
}

/// Where a value came from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    /// The input image (plan or façade photo), several joined by ", " when a value was
    /// estimated jointly from them (§6.1.2), "default" for class defaults, or "user" for a
    /// value the user set in PROJECT.toml (the step then names the entry, issue 22).
    pub image: String,
    /// The pipeline step, e.g. "§5.1.5 circle fit of plan face 4".
    pub step: String,
    /// The step's fit error where it has one (pixels of its image).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fit_error: Option<f64>,
    /// The structure whose measurement this value is, when it was lent by one alike
    /// (`heights::propagate`, issue 25).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lent_by: Option<String>,
}

/// The `image` of a value the user set (issue 22).
pub const USER: &str = "user";

/// How a value was had: set by the user, measured on this structure, lent by a measured one
/// alike, or a default.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Source {
    User,
    Measured,
    Lent,
    Default,
}

impl Footprint {
    /// The straight pieces of a wall's centreline, the closing piece of a ring included (none
    /// for rectangles and circles).
    pub fn pieces(&self) -> Vec<[[f64; 2]; 2]> {
        let Footprint::Wall {
            centerline, closed, ..
        } = self
        else {
            return Vec::new();
        };
        let mut out: Vec<[[f64; 2]; 2]> = centerline.windows(2).map(|w| [w[0], w[1]]).collect();
        if *closed && centerline.len() > 2 {
            out.push([centerline[centerline.len() - 1], centerline[0]]);
        }
        out
    }

    /// Each straight piece of a wall with its thickness: its drawn width where `widths` gives
    /// one, else the wall's thickness (none for rectangles and circles).
    pub fn pieces_with_widths(&self) -> Vec<([[f64; 2]; 2], f64)> {
        let Footprint::Wall {
            thickness, widths, ..
        } = self
        else {
            return Vec::new();
        };
        self.pieces()
            .into_iter()
            .enumerate()
            .map(|(k, p)| (p, widths.get(k).copied().unwrap_or(*thickness)))
            .collect()
    }
}

impl Structure {
    /// A tower: a tower room's structure (round or square) or a tower drawn solid as a bulge
    /// of the curtain.
    pub fn is_tower(&self) -> bool {
        matches!(self.role, Role::Tower | Role::Keep)
    }
}

impl Provenance {
    pub fn new(image: &str, step: impl Into<String>, fit_error: Option<f64>) -> Provenance {
        Provenance {
            image: image.to_string(),
            step: step.into(),
            fit_error,
            lent_by: None,
        }
    }

    /// A value the user set: `entry` names the PROJECT.toml entry, e.g. `[[structure]] #2`.
    pub fn user(entry: impl Into<String>) -> Provenance {
        Provenance::new(USER, entry, None)
    }

    /// User, measured, lent or default (a default's `image` is "default", a user's "user").
    pub fn source(&self) -> Source {
        if self.image == USER {
            Source::User
        } else if self.image == "default" {
            Source::Default
        } else if self.lent_by.is_some() {
            Source::Lent
        } else {
            Source::Measured
        }
    }
}

impl Element {
    pub fn leaf(name: impl Into<String>, kind: &str) -> Element {
        Element {
            name: name.into(),
            kind: kind.into(),
            children: Vec::new(),
        }
    }
}
