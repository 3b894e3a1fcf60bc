//! The configuration of the ramp stage (see the `ramps` module).

use crate::error::Result;
use cloud::check_range;
use serde::{Deserialize, Serialize};

/// Configuration of the ramp stage.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RampConfig {
    /// Edge of the grid's cells and of the profile's bins (m): 10 cm, as the obstacles' grid.
    pub cell_m: f64,
    /// Points this far above the floor at least (m): twice the floor's labelling tolerance, as
    /// for the obstacles (a ramp's foot below it is floor to the robot).
    pub min_above_floor_m: f64,
    /// ... and below this height above the floor (m): the obstacles' head height. A beam over
    /// a ramp is not part of it; a ramp's part above head height is left to the obstacles.
    pub head_height_m: f64,
    /// Fewest returns in an occupied cell.
    pub min_cell_points: usize,
    /// Occupied cells up to this many cells apart are of one cluster: a laser's lines on a
    /// shallow slope seen from near its foot fall 0.2-0.4 m apart (at 5-10 m, 0.5-0.7 degrees
    /// between lines, 10-15 degrees of incidence).
    pub reach_cells: usize,
    /// ... if their tops differ by at most this (m) plus the steepest ramp's rise over the
    /// distance between them: a ramp's top changes by a few centimetres from cell to cell, a
    /// car's or a shelf's top beside it by decimetres.
    pub max_top_step_m: f64,
    /// A profile bin is on the line within this (m): the laser's range noise and a bin's own
    /// rise (1-2 cm each); a step of 0.15-0.18 m leaves most bins of a flight off any line.
    pub inlier_m: f64,
    /// ... and the bins on it fit it within this RMS (m) ...
    pub max_rms_m: f64,
    /// ... and are at least this fraction of the bins holding returns between the first and
    /// last on it (what stands on a ramp, a car or a person, lifts some bins off it).
    pub min_inliers: f64,
    /// A ramp is at least this steep (degrees): below it, a floor's own slope or a thing's
    /// tilted top (1:20, ~3 degrees, is where accessibility codes start calling it a ramp).
    pub min_pitch_deg: f64,
    /// ... and at most this steep (degrees): car-park ramps are up to ~15 degrees, wheelchair
    /// ramps 1:12 (4.8 degrees); steeper is a windscreen or a flight of stairs' string.
    pub max_pitch_deg: f64,
    /// The line starts at most this high above the floor (m): a ramp rises from the floor,
    /// though a laser low over a shallow ramp sees its foot's side face and top too obliquely
    /// to return below 0.2-0.35 m (a seat, a car's bonnet or a table's edge starts higher:
    /// 0.45 m and more).
    pub max_foot_height_m: f64,
    /// ... unless the stretch on the line is at least this long (m): beside a ramp, a laser
    /// mounted low (a robot's) sees its top and side face only where they stand up to about
    /// its own height, so a long ramp may be seen from well above its foot, while a seat's, a
    /// bonnet's or a table's sloping edge is short.
    pub min_length_high_foot_m: f64,
    /// A ramp is at least this long, foot to head (m) ...
    pub min_length_m: f64,
    /// ... at least this wide (m): the narrowest wheelchair ramps are 0.9 m between rails ...
    pub min_width_m: f64,
    /// ... and rises at least this much (m): lower, it is a threshold to a robot.
    pub min_rise_m: f64,
    /// Returns under the ramp's plane or at most this above it are the ramp's (m).
    pub surface_tolerance_m: f64,
    /// Cells within this of a wall's slab, a door leaf's swing or a staircase's box are left
    /// out (m), as the obstacles' `wall_margin_m`: a wall face's noise beside a ramp along
    /// the wall stands over the ramp's line and would cut its head short.
    pub wall_margin_m: f64,
}

impl Default for RampConfig {
    fn default() -> Self {
        RampConfig {
            cell_m: 0.1,
            min_above_floor_m: 0.08,
            head_height_m: 1.95,
            min_cell_points: 2,
            reach_cells: 4,
            max_top_step_m: 0.1,
            inlier_m: 0.04,
            max_rms_m: 0.025,
            min_inliers: 0.7,
            min_pitch_deg: 3.0,
            max_pitch_deg: 20.0,
            max_foot_height_m: 0.4,
            min_length_high_foot_m: 3.0,
            min_length_m: 1.5,
            min_width_m: 0.7,
            min_rise_m: 0.15,
            surface_tolerance_m: 0.08,
            wall_margin_m: 0.1,
        }
    }
}

impl RampConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range("ramps.cell_m", self.cell_m, 0.01, 1.0, "within 0.01..1 m")?;
        for (name, v) in [
            ("ramps.min_above_floor_m", self.min_above_floor_m),
            ("ramps.head_height_m", self.head_height_m),
            ("ramps.max_top_step_m", self.max_top_step_m),
            ("ramps.inlier_m", self.inlier_m),
            ("ramps.max_rms_m", self.max_rms_m),
            ("ramps.max_foot_height_m", self.max_foot_height_m),
            ("ramps.min_length_high_foot_m", self.min_length_high_foot_m),
            ("ramps.min_length_m", self.min_length_m),
            ("ramps.min_width_m", self.min_width_m),
            ("ramps.min_rise_m", self.min_rise_m),
            ("ramps.surface_tolerance_m", self.surface_tolerance_m),
            ("ramps.wall_margin_m", self.wall_margin_m),
        ] {
            check_range(name, v, 0.0, 100.0, "within 0..100 m")?;
        }
        check_range(
            "ramps.min_pitch_deg",
            self.min_pitch_deg,
            0.0,
            89.0,
            "within 0..89 degrees",
        )?;
        check_range(
            "ramps.max_pitch_deg",
            self.max_pitch_deg,
            self.min_pitch_deg,
            89.0,
            "within ramps.min_pitch_deg..89 degrees",
        )?;
        check_range(
            "ramps.min_cell_points",
            self.min_cell_points as f64,
            1.0,
            1e6,
            "within 1..1e6",
        )?;
        check_range(
            "ramps.reach_cells",
            self.reach_cells as f64,
            1.0,
            20.0,
            "within 1..20 cells",
        )?;
        check_range(
            "ramps.min_inliers",
            self.min_inliers,
            0.0,
            1.0,
            "a fraction within 0..1",
        )?;
        Ok(())
    }
}
