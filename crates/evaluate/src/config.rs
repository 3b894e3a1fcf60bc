//! The thresholds of the evaluation.

use serde::{Deserialize, Serialize};

/// Thresholds of the evaluation (see the crate docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EvalConfig {
    /// Least labelled points of an expected wall piece, staircase, floor or ceiling.
    pub min_points: usize,
    /// Least observed length of an expected wall piece.
    pub min_length_m: f64,
    /// Gaps in a wall's labelled points wider than this split it into pieces.
    pub piece_gap_m: f64,
    /// Least labelled points in a 10 cm stretch of a wall for it to count as observed.
    pub min_bin_points: usize,
    /// Least labelled returns on a step's tread, riser or the top edge of its side for the step
    /// to count as seen.
    pub min_step_points: usize,
    /// Least labelled points (lintel and leaf) of an expected door opening.
    pub min_door_points: usize,
    /// Largest angle between matched walls.
    pub wall_max_angle_deg: f64,
    /// Largest offset of a matched wall beyond half the true thickness.
    pub wall_max_offset_m: f64,
    /// Least along-line intersection over union of matched walls.
    pub wall_min_iou: f64,
    /// Largest distance between matched door openings' centres.
    pub door_max_distance_m: f64,
    /// Largest distance between matched staircases' centres.
    pub stairs_max_distance_m: f64,
    /// Largest floor or ceiling height error of a match.
    pub max_height_error_m: f64,
    /// Obstacles at most this tall are not scored (a robot's wheels or a bumper deal with
    /// them; the "taller than 0.3 m").
    pub obstacle_min_height_m: f64,
    /// ... nor those at most this long across (a pole, a bollard: the 0.3 m).
    pub obstacle_min_across_m: f64,
    /// Least footprint intersection, as a fraction of the smaller footprint, of a match.
    pub obstacle_min_overlap: f64,
}

impl Default for EvalConfig {
    fn default() -> Self {
        EvalConfig {
            min_points: 50,
            min_length_m: 0.5,
            piece_gap_m: 1.5,
            min_bin_points: 5,
            min_door_points: 20,
            min_step_points: 5,
            wall_max_angle_deg: 5.0,
            wall_max_offset_m: 0.15,
            wall_min_iou: 0.5,
            door_max_distance_m: 0.3,
            stairs_max_distance_m: 1.0,
            max_height_error_m: 0.05,
            obstacle_min_height_m: 0.3,
            obstacle_min_across_m: 0.3,
            obstacle_min_overlap: 0.5,
        }
    }
}
