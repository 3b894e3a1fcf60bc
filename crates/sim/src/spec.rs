//! The world specification: the simulation's input, independent of where it came from (a
//! ground-truth building or a semantic map). Fixed boxes, hinged doors, door free-space
//! sensors and staircases, each tagged with its semantic entity (id, class, name).

use cloud::EntityClass;
use serde::{Deserialize, Serialize};

/// A semantic entity: id, class, machine name and an optional human label.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EntityInfo {
    /// Entity id (unique in the world, never 0).
    pub id: u32,
    /// Its class.
    pub class: EntityClass,
    /// Machine name, e.g. `walls[4].doors[2].leaf`; usable in scenarios.
    pub name: String,
    /// Human label, e.g. `corridor north` (may be empty); usable in scenarios when unique.
    pub label: String,
}

/// An oriented box: centre, half extents along its own axes, rotation about z.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    /// Centre in world coordinates (metres).
    pub center_m: [f64; 3],
    /// Half extents along the box's own x, y, z axes (metres).
    pub half_extents_m: [f64; 3],
    /// Rotation about z (degrees).
    #[serde(default)]
    pub yaw_deg: f64,
}

/// A fixed (static) box of an entity: floor, ceiling, wall piece, lintel or furniture.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixedBox {
    /// The entity this box belongs to (an entity may have several boxes).
    pub entity: u32,
    /// The entity's class.
    pub class: EntityClass,
    /// The entity's machine name.
    pub name: String,
    /// The entity's human label (may be empty).
    #[serde(default)]
    pub label: String,
    /// The box.
    pub geometry: BoxSpec,
}

/// Which end of the closed leaf carries the hinge (informational; the hinge point decides).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HingeEnd {
    /// The leaf's end at its local -x.
    Start,
    /// The leaf's end at its local +x.
    End,
}

/// The sense of rotation about +z (seen from above) in which a door opens.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OpeningSense {
    /// Counter-clockwise.
    Ccw,
    /// Clockwise.
    Cw,
}

impl OpeningSense {
    /// +1 for counter-clockwise, -1 for clockwise.
    pub fn sign(self) -> f64 {
        match self {
            OpeningSense::Ccw => 1.0,
            OpeningSense::Cw => -1.0,
        }
    }
}

/// A door leaf on a revolute joint (axis z through the hinge point).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DoorSpec {
    /// The door's entity id.
    pub entity: u32,
    /// Machine name.
    pub name: String,
    /// Human label (may be empty).
    #[serde(default)]
    pub label: String,
    /// The wall entity the door hangs in.
    pub wall: u32,
    /// The leaf box in its CLOSED position.
    pub leaf: BoxSpec,
    /// The hinge axis position (x, y), metres.
    pub hinge_m: [f64; 2],
    /// Which end of the closed leaf carries the hinge.
    pub hinge_end: HingeEnd,
    /// The sense in which the door opens.
    pub opens: OpeningSense,
    /// Lower opening limit (degrees, 0 = closed).
    pub min_deg: f64,
    /// Upper opening limit (degrees).
    pub max_deg: f64,
    /// Initial opening angle (degrees).
    pub initial_deg: f64,
    /// Leaf mass (kg).
    pub mass_kg: f64,
    /// Angular damping of the leaf (1/s).
    pub damping_per_s: f64,
    /// Dry friction torque of the hinge (N m).
    pub hinge_friction_nm: f64,
    /// Hinge force that breaks the joint (N); absent = unbreakable.
    #[serde(default)]
    pub break_force_n: Option<f64>,
}

/// A door's free space: the opening volume, a sensor the robot enters and leaves.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FreeSpaceSpec {
    /// The free space's entity id.
    pub entity: u32,
    /// Machine name.
    pub name: String,
    /// The door leaf in this opening, if it has one.
    #[serde(default)]
    pub door: Option<u32>,
    /// The wall the opening is in, if known.
    #[serde(default)]
    pub wall: Option<u32>,
    /// The volume; its local y axis is the wall's normal.
    pub geometry: BoxSpec,
}

/// One stair step (a solid block from the floor to its tread).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepSpec {
    /// 0 for the lowest step.
    pub index: u32,
    /// The block.
    pub geometry: BoxSpec,
}

/// A staircase: its steps and optional top landing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StairsSpec {
    /// The staircase's entity id.
    pub entity: u32,
    /// Machine name.
    pub name: String,
    /// Human label (may be empty).
    #[serde(default)]
    pub label: String,
    /// The steps, lowest first.
    pub steps: Vec<StepSpec>,
    /// The landing at the top (its index in events is the number of steps).
    #[serde(default)]
    pub landing: Option<BoxSpec>,
}

/// The world to simulate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct WorldSpec {
    /// A name for people.
    #[serde(default)]
    pub name: String,
    /// Fixed boxes: floor, ceiling, walls, lintels, furniture.
    #[serde(default)]
    pub fixed: Vec<FixedBox>,
    /// Hinged doors.
    #[serde(default)]
    pub doors: Vec<DoorSpec>,
    /// Door free-space sensors.
    #[serde(default)]
    pub free_spaces: Vec<FreeSpaceSpec>,
    /// Staircases.
    #[serde(default)]
    pub stairs: Vec<StairsSpec>,
}
