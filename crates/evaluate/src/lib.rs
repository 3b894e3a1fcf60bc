//! Scores semsim's semantic maps against the ground truth of the building they were scanned
//! in: [`evaluate`] matches a [`SemanticMap`]'s walls, door openings, leaves, staircases,
//! floor and ceiling with a [`scanner::Building`]'s and gives precision, recall and F1 per
//! class with the errors of the matched pairs; [`evaluate_labels`] compares per-point labels;
//! [`check_ground_truth`] tells whether a cloud carries a building's ground-truth labels.
//!
//! # What is expected
//! Without `observed`, every element of the building is expected. With `observed` (the
//! registered cloud carrying the virtual laser's ground-truth labels), only what the scans saw:
//!
//! - a wall is expected piecewise: its labelled points, projected on its centre line, in 10 cm
//!   stretches; a stretch with fewer than `min_bin_points` (5) points was only glimpsed and
//!   does not count. The counted stretches split where they leave a gap over `piece_gap_m`
//!   (1.5 m, wider than any door, so a door does not split a wall but an unvisited room between
//!   two visited ones does); each piece with at least `min_points` (50) points and
//!   `min_length_m` (0.5 m) is one expected wall, whose extent is the observed one (min to max
//!   of its points along the centre line). A wall seen only in part is thus compared with the
//!   part that was seen. Two pieces of one wall are one expected wall where a map wall runs
//!   from one through the gap into the other (the map carried the wall on behind what hid it,
//!   which is right);
//! - a door opening is expected if its lintel and leaf together carry at least
//!   `min_door_points` (20) points (the opening itself has no surface);
//! - a staircase, the floor and the ceiling if they carry at least `min_points` points; for
//!   each expected staircase, the steps the scans saw are counted too (`stairs_seen`: at least
//!   `min_step_points` (5) returns on the step's tread, riser or the top edge of its side), so that a step count missed
//!   because a step was never seen is told from one the map got wrong;
//! - obstacles (boxes of class furniture, obstacle or column taller and longer than 0.3 m),
//!   columns and beams if they carry at least `min_bin_points` points (see `obstacles.rs` for
//!   their matching by footprint overlap, and the count of walls standing on beams or columns);
//! - ramps if they carry at least `min_bin_points` points (see `ramps.rs`).
//!
//! # Matching
//! Greedy one-to-one, best first. Walls: directions within `wall_max_angle_deg`, the detected
//! centre line's midpoint within half the true thickness plus `wall_max_offset_m` of the true
//! centre line, and along-line intersection over union at least `wall_min_iou`. Door openings:
//! centres within `door_max_distance_m`. Staircases: footprint centres within
//! `stairs_max_distance_m`. Floor and ceiling: the entity's height within `max_height_error_m`.
//! Endpoint errors: the distance of each detected centre-line end from the stretch of the true
//! centre line between the observed piece's end and the wall's true end (a map may carry a wall
//! on behind what hid it from the scans, which is right; stopping short of what was seen, or
//! running past the wall's end, is not). A wall piece whose scans saw one face only (both faces
//! with `min_bin_points` in fewer than half of its observed 10 cm stretches) is compared by the
//! face seen most: the map wall's face on that side against the true face, for the offset gate
//! and the endpoint errors. A wall
//! seen from one side cannot show its thickness; where its seen face stands is what a robot
//! meets, and what a map can get right.

//!
//! ```
//! use semantic::SemanticMap;
//!
//! // An empty map of the built-in building, expected whole (no observed cloud): nothing is
//! // found, everything is missed.
//! let building = scanner::Building::default_building().unwrap();
//! let ev = evaluate::evaluate(&SemanticMap::default(), &building, None);
//! assert_eq!(ev.walls.expected, building.walls.len());
//! assert_eq!((ev.walls.detected, ev.walls.recall), (0, 0.0));
//! assert!(ev.missed.iter().any(|m| m == "floor"));
//! ```
#![warn(missing_docs)]

mod config;
mod doors;
mod frame;
mod ground_truth;
mod labels;
mod object_groups;
mod obstacles;
mod ramps;
mod report;
mod score;
mod slabs;
mod stairs;
mod truth;
mod walls;

pub use config::EvalConfig;
pub use doors::DoorMatch;
pub use frame::registration_frame;
pub use ground_truth::{check_ground_truth, check_ground_truth_in_frame, EvalError};
pub use labels::{evaluate_labels, LabelEvaluation};
pub use obstacles::{ObstacleMatch, UnmatchedObstacle};
pub use ramps::RampMatch;
pub use score::ClassScore;
pub use stairs::{StairsMatch, StairsSeen};
pub use walls::{WallLength, WallMatch};

use cloud::PointCloud;
use doors::evaluate_doors;
use obstacles::evaluate_obstacles;
use ramps::evaluate_ramps;
use scanner::Building;
use semantic::SemanticMap;
use serde::{Deserialize, Serialize};
use slabs::evaluate_slabs;
use stairs::evaluate_stairs;
use truth::Truth;
use walls::evaluate_walls;

/// The evaluation of a map (serialisable for `--json`).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Evaluation {
    /// Walls.
    pub walls: ClassScore,
    /// Door openings (free space for door).
    pub door_openings: ClassScore,
    /// Door leaves (expected: true leaves in expected openings).
    pub doors: ClassScore,
    /// Floor.
    pub floor: ClassScore,
    /// Ceiling.
    pub ceiling: ClassScore,
    /// Staircases.
    pub stairs: ClassScore,
    /// Obstacles (truth: furniture, obstacles and columns over 0.3 m tall and across; map:
    /// obstacles and columns).
    #[serde(default)]
    pub obstacles: ClassScore,
    /// Columns.
    #[serde(default)]
    pub columns: ClassScore,
    /// Beams.
    #[serde(default)]
    pub beams: ClassScore,
    /// Ramps (truth: the building's ramps the scans saw; map: its `ramp` entities).
    #[serde(default)]
    pub ramps: ClassScore,
    /// Map walls standing where only beams or columns stand (their centre line mostly on them).
    #[serde(default)]
    pub walls_on_beams_or_columns: usize,
    /// The observed length of the true walls and how much of it map walls cover.
    #[serde(default)]
    pub wall_length: WallLength,
    /// Mean distance of matched walls' ends from the observed ends.
    pub wall_endpoint_error_mean_m: f64,
    /// Largest such distance.
    pub wall_endpoint_error_max_m: f64,
    /// Floor height error, if found.
    pub floor_height_error_m: Option<f64>,
    /// Ceiling height error, if found.
    pub ceiling_height_error_m: Option<f64>,
    /// Matched walls.
    pub wall_matches: Vec<WallMatch>,
    /// Matched door openings.
    pub door_matches: Vec<DoorMatch>,
    /// Matched staircases.
    pub stairs_matches: Vec<StairsMatch>,
    /// How many steps of each expected staircase the scans saw (with an observed cloud only).
    #[serde(default)]
    pub stairs_seen: Vec<StairsSeen>,
    /// Matched obstacles, columns and beams.
    #[serde(default)]
    pub obstacle_matches: Vec<ObstacleMatch>,
    /// Map obstacles and columns over the size limits matching no expected object, with what
    /// the scans saw inside each (see [`UnmatchedObstacle`]).
    #[serde(default)]
    pub obstacles_unmatched: Vec<UnmatchedObstacle>,
    /// Matched ramps.
    #[serde(default)]
    pub ramp_matches: Vec<RampMatch>,
    /// Expected elements not found (names, walls with their piece).
    pub missed: Vec<String>,
    /// Map entities matching nothing expected (ids).
    pub spurious: Vec<u32>,
}

/// Evaluates `map` against `building` with the default thresholds (see the crate docs).
pub fn evaluate(
    map: &SemanticMap,
    building: &Building,
    observed: Option<&PointCloud>,
) -> Evaluation {
    evaluate_with(map, building, observed, &EvalConfig::default())
}

/// Evaluates `map` against `building` with the given thresholds.
pub fn evaluate_with(
    map: &SemanticMap,
    building: &Building,
    observed: Option<&PointCloud>,
    c: &EvalConfig,
) -> Evaluation {
    evaluate_in_frame(map, building, observed, glam::DAffine3::IDENTITY, c)
}

/// Evaluates `map`, made from a cloud in a frame `input_from_building` away from the
/// building's (a registration's frame: see [`registration_frame`]), against `building`;
/// `observed` is in that input frame too.
pub fn evaluate_in_frame(
    map: &SemanticMap,
    building: &Building,
    observed: Option<&PointCloud>,
    input_from_building: glam::DAffine3,
    c: &EvalConfig,
) -> Evaluation {
    let t = Truth::new(map, building, observed, input_from_building);
    let mut ev = Evaluation::default();
    evaluate_walls(&mut ev, map, building, &t, c);
    evaluate_doors(&mut ev, map, building, &t, c);
    evaluate_stairs(&mut ev, map, building, &t, c);
    evaluate_slabs(&mut ev, map, building, &t, c);
    evaluate_obstacles(&mut ev, map, building, &t, c);
    evaluate_ramps(&mut ev, map, building, &t, c);
    ev
}
