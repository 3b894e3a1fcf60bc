//! The one vocabulary of entity classes in semsim: point labels (the PCD `class` field),
//! the semantic map's entities and the simulation world's bodies all use [`EntityClass`],
//! with one code table.

use serde::{Deserialize, Serialize};

/// What an entity of a building is. The numeric code is what point files store (the PCD
/// `class` field); the lower-case name is what JSON and TOML files store.
///
/// | code | name | |
/// |---|---|---|
/// | 0 | `unknown` | no label, or a missing return |
/// | 1 | `floor` | the floor slab |
/// | 2 | `ceiling` | the ceiling slab |
/// | 3 | `wall` | a wall (beside its openings) |
/// | 4 | `wall_above_door` | the lintel above a door opening |
/// | 5 | `door` | a door leaf |
/// | 6 | `stairs` | a staircase: its steps and landing |
/// | 7 | `furniture` | furniture and clutter |
/// | 8 | `free_space_for_door` | the free volume of a door opening |
/// | 9 | `robot` | a robot (simulation only) |
/// | 10 | `obstacle` | anything else standing on the floor and occupying space (cars, shelves, clutter) |
/// | 11 | `column` | a pillar: a free-standing vertical post from the floor to the ceiling |
/// | 12 | `beam` | a downstand beam, duct or pipe under the ceiling, above head height |
/// | 13 | `ramp` | a sloped floor rising from the floor, driven up (car-park and wheelchair ramps) |
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord, Serialize, Deserialize,
)]
#[serde(rename_all = "snake_case")]
#[repr(u8)]
pub enum EntityClass {
    /// No label, or a missing return.
    #[default]
    Unknown = 0,
    /// The floor slab.
    Floor = 1,
    /// The ceiling slab.
    Ceiling = 2,
    /// A wall (beside openings): a vertical slab from the floor to (usually) the ceiling.
    Wall = 3,
    /// The part of a wall above a door opening (the lintel).
    WallAboveDoor = 4,
    /// A door leaf, hinged to its wall.
    Door = 5,
    /// A staircase: its steps and landing.
    Stairs = 6,
    /// Furniture and clutter.
    Furniture = 7,
    /// The free volume of a door opening.
    FreeSpaceForDoor = 8,
    /// A robot (a body of the simulation; never a point label of a building).
    Robot = 9,
    /// Anything else that stands on the floor and occupies space: parked cars, shelves,
    /// cabinets, clutter. The semantic map's class for what it cannot name more precisely.
    Obstacle = 10,
    /// A pillar: a free-standing vertical post from the floor to the ceiling.
    Column = 11,
    /// A downstand beam, duct or pipe under the ceiling, above head height: a robot passes
    /// under it.
    Beam = 12,
    /// A ramp: a sloped floor rising from the floor, which robots and people drive and walk
    /// up. In a semantic map its box rises along its own x axis, from the floor at its -x end
    /// to its top at its +x end.
    Ramp = 13,
}

impl EntityClass {
    /// All classes, in code order.
    pub const ALL: [EntityClass; 14] = [
        EntityClass::Unknown,
        EntityClass::Floor,
        EntityClass::Ceiling,
        EntityClass::Wall,
        EntityClass::WallAboveDoor,
        EntityClass::Door,
        EntityClass::Stairs,
        EntityClass::Furniture,
        EntityClass::FreeSpaceForDoor,
        EntityClass::Robot,
        EntityClass::Obstacle,
        EntityClass::Column,
        EntityClass::Beam,
        EntityClass::Ramp,
    ];

    /// The class for a stored code; `None` for codes no class has.
    pub fn from_code(code: u8) -> Option<Self> {
        Self::ALL.get(code as usize).copied()
    }

    /// The stored code.
    pub fn code(self) -> u8 {
        self as u8
    }

    /// The lower-case name used in files (`wall_above_door`, `free_space_for_door`, ...).
    pub fn name(self) -> &'static str {
        match self {
            EntityClass::Unknown => "unknown",
            EntityClass::Floor => "floor",
            EntityClass::Ceiling => "ceiling",
            EntityClass::Wall => "wall",
            EntityClass::WallAboveDoor => "wall_above_door",
            EntityClass::Door => "door",
            EntityClass::Stairs => "stairs",
            EntityClass::Furniture => "furniture",
            EntityClass::FreeSpaceForDoor => "free_space_for_door",
            EntityClass::Robot => "robot",
            EntityClass::Obstacle => "obstacle",
            EntityClass::Column => "column",
            EntityClass::Beam => "beam",
            EntityClass::Ramp => "ramp",
        }
    }

    /// The class of a name as [`EntityClass::name`] writes it.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|c| c.name() == name)
    }
}

impl std::fmt::Display for EntityClass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_and_names_round_trip() {
        for c in EntityClass::ALL {
            assert_eq!(EntityClass::from_code(c.code()), Some(c));
            assert_eq!(EntityClass::from_name(c.name()), Some(c));
            assert_eq!(c.to_string(), c.name());
        }
        assert_eq!(EntityClass::from_code(200), None);
        assert_eq!(EntityClass::from_name("pillar"), None);
    }

    #[test]
    fn the_pcd_codes_of_the_first_eight_classes_never_change() {
        // Files written before the vocabulary was unified store these codes.
        let codes: Vec<u8> = [
            EntityClass::Unknown,
            EntityClass::Floor,
            EntityClass::Ceiling,
            EntityClass::Wall,
            EntityClass::WallAboveDoor,
            EntityClass::Door,
            EntityClass::Stairs,
            EntityClass::Furniture,
        ]
        .iter()
        .map(|c| c.code())
        .collect();
        assert_eq!(codes, (0..8).collect::<Vec<u8>>());
    }
}
