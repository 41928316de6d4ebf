//! The eleven labels of §5.1.6 as the PLAN.json / LABELS.png contract has them: names, legend
//! order and the colours of the dissertation's figures. Re-exported as `plan::label::Label`.

use serde::{Deserialize, Serialize};

/// The label names of the PLAN.json / LABELS.png contract, in legend order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Label {
    CastleSurroundings = 0,
    CastleOuterWall = 1,
    Courtyard = 2,
    TowerWall = 3,
    TowerRoom = 4,
    GreatHall = 5,
    GreatHallWall = 6,
    Chapel = 7,
    ChapelWall = 8,
    UnknownRoom = 9,
    UnknownWall = 10,
}

impl Label {
    pub const ALL: [Label; 11] = [
        Label::CastleSurroundings,
        Label::CastleOuterWall,
        Label::Courtyard,
        Label::TowerWall,
        Label::TowerRoom,
        Label::GreatHall,
        Label::GreatHallWall,
        Label::Chapel,
        Label::ChapelWall,
        Label::UnknownRoom,
        Label::UnknownWall,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Label::CastleSurroundings => "castle_surroundings",
            Label::CastleOuterWall => "castle_outer_wall",
            Label::Courtyard => "courtyard",
            Label::TowerWall => "tower_wall",
            Label::TowerRoom => "tower_room",
            Label::GreatHall => "great_hall",
            Label::GreatHallWall => "great_hall_wall",
            Label::Chapel => "chapel",
            Label::ChapelWall => "chapel_wall",
            Label::UnknownRoom => "unknown_room",
            Label::UnknownWall => "unknown_wall",
        }
    }

    /// The colours of the dissertation's figures (§5.1.6 lists them by name).
    pub fn color(self) -> [u8; 3] {
        match self {
            Label::CastleSurroundings => [20, 30, 120],
            Label::CastleOuterWall => [240, 220, 30],
            Label::Courtyard => [50, 110, 230],
            Label::TowerWall => [250, 140, 20],
            Label::TowerRoom => [30, 170, 60],
            Label::GreatHall => [150, 200, 250],
            Label::GreatHallWall => [250, 140, 140],
            Label::Chapel => [40, 220, 220],
            Label::ChapelWall => [210, 30, 30],
            Label::UnknownRoom => [160, 230, 140],
            Label::UnknownWall => [255, 255, 255],
        }
    }

    /// The colour in words, for keys in text (`castellan plan --help`, docs/formats.md).
    pub fn color_name(self) -> &'static str {
        match self {
            Label::CastleSurroundings => "dark blue",
            Label::CastleOuterWall => "yellow",
            Label::Courtyard => "blue",
            Label::TowerWall => "orange",
            Label::TowerRoom => "green",
            Label::GreatHall => "light blue",
            Label::GreatHallWall => "pink",
            Label::Chapel => "cyan",
            Label::ChapelWall => "red",
            Label::UnknownRoom => "light green",
            Label::UnknownWall => "white",
        }
    }

    /// The name as a key writes it ("tower room").
    pub fn words(self) -> String {
        self.name().replace('_', " ")
    }

    /// An open space a building encloses: a tower room, great hall, chapel or unknown room.
    pub fn is_room(self) -> bool {
        matches!(
            self,
            Label::TowerRoom | Label::GreatHall | Label::Chapel | Label::UnknownRoom
        )
    }

    pub fn is_wall(self) -> bool {
        matches!(
            self,
            Label::CastleOuterWall
                | Label::TowerWall
                | Label::GreatHallWall
                | Label::ChapelWall
                | Label::UnknownWall
        )
    }
}
