//! The semantic map file: the semantic net (entities and relations, the paper's Fig. 2) as
//! versioned JSON. See `crates/semantic/schema/semantic_map.schema.json` for the schema.
//!
//! Frames: the map's frame is the input cloud's frame levelled so that the floor is horizontal
//! (`input_from_map` is the rotation between them; the identity for a level cloud). z is up,
//! lengths are metres, angles degrees. Every entity has an oriented box (`geometry`: centre,
//! full size along the box's own axes, yaw about z); the box's x axis points along `yaw_deg`.

mod door_swing;
mod file;

use cloud::EntityClass;
use glam::{DAffine3, DMat4};
use serde::{Deserialize, Serialize};

/// The `format` string of every semantic map file.
pub const MAP_FORMAT: &str = "semsim.semantic_map";
/// The map file version this build writes. Version 2 added the classes `obstacle`, `column` and
/// `beam` (with their `obstacle` section) and the relation `near`; version 3 the floor's
/// `floor` section (where the floor was seen); version 4 the class `ramp` (its box rises along
/// its own x axis); version 1, 2 and 3 files are still read (see [`READ_VERSIONS`]).
pub const MAP_VERSION: u32 = 4;
/// The map file versions this build reads: version 1 (walls, openings, doors, stairs, floor and
/// ceiling only), version 2 (no `floor` section: the floor is its box) and version 3 (no
/// ramps) are subsets of version 4 and are read as such.
pub const READ_VERSIONS: [u32; 4] = [1, 2, 3, 4];

/// An oriented box: centre, full size along its own axes (x along `yaw_deg`, y across, z up).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrientedBox {
    /// Centre in the map frame.
    pub center_m: [f64; 3],
    /// Full extent along the box's x (length), y (thickness or width) and z (height).
    pub size_m: [f64; 3],
    /// Rotation about z of the box's x axis, from the map's x axis.
    pub yaw_deg: f64,
}

impl OrientedBox {
    /// A box from its footprint axis: from `a` to `b` (XY) with the given width across and
    /// z range.
    pub fn along(a: [f64; 2], b: [f64; 2], width_m: f64, z_range_m: [f64; 2]) -> OrientedBox {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        OrientedBox {
            center_m: [
                (a[0] + b[0]) / 2.0,
                (a[1] + b[1]) / 2.0,
                (z_range_m[0] + z_range_m[1]) / 2.0,
            ],
            size_m: [
                dx.hypot(dy),
                width_m,
                (z_range_m[1] - z_range_m[0]).max(0.0),
            ],
            yaw_deg: dy.atan2(dx).to_degrees(),
        }
    }

    /// The four footprint corners (XY), counter-clockwise.
    pub fn corners_xy(&self) -> [[f64; 2]; 4] {
        let (s, c) = self.yaw_deg.to_radians().sin_cos();
        let (hx, hy) = (self.size_m[0] / 2.0, self.size_m[1] / 2.0);
        let at = |u: f64, v: f64| {
            [
                self.center_m[0] + c * u - s * v,
                self.center_m[1] + s * u + c * v,
            ]
        };
        [at(-hx, -hy), at(hx, -hy), at(hx, hy), at(-hx, hy)]
    }

    /// The z range `[bottom, top]`.
    pub fn z_range_m(&self) -> [f64; 2] {
        [
            self.center_m[2] - self.size_m[2] / 2.0,
            self.center_m[2] + self.size_m[2] / 2.0,
        ]
    }

    pub(crate) fn is_finite(&self) -> bool {
        self.center_m
            .iter()
            .chain(&self.size_m)
            .all(|v| v.is_finite())
            && self.yaw_deg.is_finite()
            && self.size_m.iter().all(|v| *v >= 0.0)
    }
}

/// The classes a semantic map's entities may have (the paper's L_sm and, from version 2, what
/// occupies space besides: obstacles, columns, beams; from version 4, ramps, kept last: a
/// version 2 or 3 file may hold every class but the last), in the order error messages list
/// them.
/// The other classes of [`EntityClass`] (`unknown`, `furniture`, `robot`) are point labels or
/// simulation bodies, never map entities.
pub const MAP_CLASSES: [EntityClass; 11] = [
    EntityClass::Wall,
    EntityClass::WallAboveDoor,
    EntityClass::Floor,
    EntityClass::Ceiling,
    EntityClass::Door,
    EntityClass::FreeSpaceForDoor,
    EntityClass::Stairs,
    EntityClass::Obstacle,
    EntityClass::Column,
    EntityClass::Beam,
    EntityClass::Ramp,
];

/// The classes a version 1 map file may hold (the first seven of [`MAP_CLASSES`]).
pub const MAP_CLASSES_V1: [EntityClass; 7] = [
    EntityClass::Wall,
    EntityClass::WallAboveDoor,
    EntityClass::Floor,
    EntityClass::Ceiling,
    EntityClass::Door,
    EntityClass::FreeSpaceForDoor,
    EntityClass::Stairs,
];

/// The type of a relation between two entities (the paper's R_sm). A relation reads
/// "`a` TYPE `b`", e.g. `a` above `b`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RelationType {
    /// Walls whose directions agree (symmetric; listed once, `a < b`).
    Parallel,
    /// Walls at right angles (symmetric; listed once, `a < b`).
    Orthogonal,
    /// `a` lies above `b` (its bottom at or over `b`'s top, footprints overlapping).
    Above,
    /// `a` lies under `b` (the converse of `above`, listed too, as in the paper's net).
    Under,
    /// Walls with the same z range (symmetric; listed once, `a < b`).
    EqualHeight,
    /// `a` lies within `b`: a door's free space inside its wall, a door leaf inside its free
    /// space, a staircase on the floor.
    AvailableInside,
    /// `a` (a door) is hinged to `b` (its wall) by a revolute joint.
    ConnectedViaJoint,
    /// `a` (an obstacle, column or beam) stands within a distance of `b` (a door's free space,
    /// see `net.near_m`): it may narrow the way through (version 2).
    Near,
}

impl RelationType {
    /// All relation types.
    pub const ALL: [RelationType; 8] = [
        RelationType::Parallel,
        RelationType::Orthogonal,
        RelationType::Above,
        RelationType::Under,
        RelationType::EqualHeight,
        RelationType::AvailableInside,
        RelationType::ConnectedViaJoint,
        RelationType::Near,
    ];

    /// The name used in files.
    pub fn name(self) -> &'static str {
        match self {
            RelationType::Parallel => "parallel",
            RelationType::Orthogonal => "orthogonal",
            RelationType::Above => "above",
            RelationType::Under => "under",
            RelationType::EqualHeight => "equal_height",
            RelationType::AvailableInside => "available_inside",
            RelationType::ConnectedViaJoint => "connected_via_joint",
            RelationType::Near => "near",
        }
    }
}

/// A relation "`a` `kind` `b`" between two entity ids.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Relation {
    /// The relation's type.
    #[serde(rename = "type")]
    pub kind: RelationType,
    /// The subject's entity id.
    pub a: u32,
    /// The object's entity id.
    pub b: u32,
}

/// Which edge of a door opening carries the hinge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HingeEdge {
    /// The edge nearer the wall segment's start.
    Start,
    /// The edge nearer the wall segment's end.
    End,
}

/// To which side of its wall a door leaf swings, looking from the wall segment's start to its end.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SwingSide {
    /// The left-hand side.
    Left,
    /// The right-hand side.
    Right,
}

/// Wall geometry beyond the box.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallInfo {
    /// The wall's centre line, start and end (XY), over its observed extent.
    pub segment_m: [[f64; 2]; 2],
    /// Thickness across the centre line.
    pub thickness_m: f64,
    /// True if both faces were observed (the thickness is measured); false if only one was
    /// and the thickness is assumed (the centre is then placed that far behind the face).
    pub thickness_measured: bool,
    /// Bottom and top of the wall.
    pub z_range_m: [f64; 2],
    /// The wall's solid parts: the wall box minus its door openings, floor to top. A simulation
    /// builds the wall from these (lintels are their own `wall_above_door` entities).
    pub solid_boxes: Vec<OrientedBox>,
}

/// Door (leaf) geometry beyond the box. The entity's `geometry` is the leaf in its closed
/// position, filling the opening; the leaf turns about a vertical axis through `hinge_m`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DoorInfo {
    /// A point on the hinge axis at the bottom of the leaf (on the wall's centre line, at the
    /// hinge edge of the opening).
    pub hinge_m: [f64; 3],
    /// The hinge axis (unit vector; vertical).
    pub hinge_axis: [f64; 3],
    /// Which edge of the opening carries the hinge.
    pub hinge_edge: HingeEdge,
    /// The side the leaf opens to.
    pub swing: SwingSide,
    /// The opening angle seen in the scans (0 = closed).
    pub observed_open_deg: f64,
}

/// Staircase geometry beyond the box (the box encloses all steps and the landing).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StairsInfo {
    /// Number of steps (distinct tread heights above the floor, the top one included).
    pub step_count: u32,
    /// Height of each step.
    pub rise_m: f64,
    /// Depth of each tread.
    pub run_m: f64,
    /// Width across the direction of ascent.
    pub width_m: f64,
    /// Direction of ascent (0 = +x).
    pub direction_deg: f64,
    /// Centre of the first step's front edge, at the flight's foot: on the floor, or on the
    /// landing a flight starts from (the second flight of a staircase with a mid landing).
    pub start_m: [f64; 3],
    /// Depth of the top level beyond the last step's tread (0 if none).
    pub landing_m: f64,
    /// One solid box per step, from the floor to its tread, in order of ascent.
    pub steps: Vec<OrientedBox>,
    /// The landing, a solid box from the floor to the top tread, if there is one.
    pub landing: Option<OrientedBox>,
}

/// Door opening geometry beyond the box (for `free_space_for_door` entities).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OpeningInfo {
    /// Distance along the wall segment from its start to the opening's near edge.
    pub offset_m: f64,
    /// Width of the opening.
    pub width_m: f64,
    /// Height of the opening (the lintel's underside) above the floor.
    pub height_m: f64,
}

/// Obstacle, column and beam geometry beyond the box (version 2). The entity's `geometry` is
/// the oriented box fitted to the points (the smallest-area rectangle around their footprint,
/// z from their heights); a simulation makes it a fixed body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObstacleInfo {
    /// Bottom and top of the points (for a beam, its underside and top).
    pub z_range_m: [f64; 2],
    /// Height of the bottom above the floor (a robot lower than this passes under a beam).
    pub clearance_m: f64,
    /// The convex hull of the footprint (XY, counter-clockwise).
    pub hull_m: Vec<[f64; 2]>,
    /// Fraction of the box's footprint covered by occupied cells (1 for a solid block, low for
    /// a table with legs or an L-shaped heap).
    pub fill: f64,
}

/// Floor geometry beyond the box (version 3): where the floor was seen. The entity's
/// `geometry` is the extent of these parts; a simulation builds the floor from the parts (a
/// map without them, version 1 or 2, from the box).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FloorInfo {
    /// Non-overlapping boxes covering the seen floor, largest first, each with the entity's
    /// top and thickness.
    pub parts: Vec<OrientedBox>,
    /// Fraction of the seen floor's area (its points' cells, gaps closed) that the parts cover.
    pub coverage: f64,
}

/// A semantic entity: a node of the semantic net.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Entity {
    /// Unique id within the map (never 0; per-point labels carry it).
    pub id: u32,
    /// The class.
    pub class: EntityClass,
    /// The oriented box of the entity (for a door, the leaf in its closed position).
    pub geometry: OrientedBox,
    /// Number of input points that support it (labelled with its id).
    pub support_points: u64,
    /// Confidence in 0..1 (see the crate docs for how each class computes it).
    pub confidence: f64,
    /// The rules that led to the label, for people.
    pub rules: Vec<String>,
    /// For walls.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall: Option<WallInfo>,
    /// For doors.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub door: Option<DoorInfo>,
    /// For free space for door.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub opening: Option<OpeningInfo>,
    /// For stairs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stairs: Option<StairsInfo>,
    /// For obstacles, columns and beams (version 2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub obstacle: Option<ObstacleInfo>,
    /// For the floor: where it was seen (version 3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub floor: Option<FloorInfo>,
}

/// The semantic map: entities, relations and the map frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SemanticMap {
    /// Always [`MAP_FORMAT`].
    pub format: String,
    /// Always [`MAP_VERSION`] when written by this build (a version 1 file is read as version 2).
    pub version: u32,
    /// The rotation from the map frame (floor levelled) to the input cloud's frame, row-major 4x4.
    pub input_from_map: [f64; 16],
    /// The entities, by ascending id.
    pub entities: Vec<Entity>,
    /// The relations between entity ids.
    pub relations: Vec<Relation>,
}

impl Default for SemanticMap {
    fn default() -> Self {
        SemanticMap {
            format: MAP_FORMAT.into(),
            version: MAP_VERSION,
            input_from_map: DMat4::IDENTITY.transpose().to_cols_array(),
            entities: Vec::new(),
            relations: Vec::new(),
        }
    }
}

impl SemanticMap {
    /// The entity with `id`.
    pub fn entity(&self, id: u32) -> Option<&Entity> {
        self.entities.iter().find(|e| e.id == id)
    }

    /// The entities of one class.
    pub fn of_class(&self, class: EntityClass) -> impl Iterator<Item = &Entity> {
        self.entities.iter().filter(move |e| e.class == class)
    }

    /// The relations of one type.
    pub fn relations_of(&self, kind: RelationType) -> impl Iterator<Item = &Relation> {
        self.relations.iter().filter(move |r| r.kind == kind)
    }

    /// `input_from_map` as an affine transform.
    pub fn input_from_map(&self) -> DAffine3 {
        DAffine3::from_mat4(DMat4::from_cols_array(&self.input_from_map).transpose())
    }
}

#[cfg(test)]
mod tests;
