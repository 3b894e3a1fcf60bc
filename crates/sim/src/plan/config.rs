//! The planner's settings.

use crate::error::{check_range, Result};
use serde::{Deserialize, Serialize};

/// The planner's settings (`[plan]` of a run's configuration).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PlanConfig {
    /// The robot the planned scenario drives: a built-in model name or a model file.
    pub robot: String,
    /// Grid cell size (m). Grown automatically where the world would need more than
    /// `max_cells` cells.
    pub cell_m: f64,
    /// The most grid cells (memory: about 40 bytes each while planning).
    pub max_cells: usize,
    /// Clearance kept beyond the robot's half width (m): the grid is inflated by half the
    /// robot's width plus this.
    pub margin_m: f64,
    /// Cruise speed between goals (m/s; clamped to the robot's top speed).
    pub cruise_speed_mps: f64,
    /// Speed through door openings and on stairs (m/s; clamped to the robot's top speed).
    pub careful_speed_mps: f64,
    /// The time limit is the tour's driving time times this, plus `time_extra_s`.
    pub time_slack: f64,
    /// Added to the time limit (s): turning in place, pushing doors, settling.
    pub time_extra_s: f64,
    /// Waypoints stay within this of the searched path (m) when the path is simplified.
    pub simplify_tolerance_m: f64,
    /// The steepest ramp the tour drives up (degrees); steeper ones are listed as not
    /// reachable.
    pub max_ramp_pitch_deg: f64,
}

impl Default for PlanConfig {
    fn default() -> Self {
        PlanConfig {
            robot: "pioneer3at".into(),
            // 5 cm: a fifth of the narrowest robot half-width we model (Pioneer 3-AT, 0.25 m),
            // so inflation errs by at most a cell.
            cell_m: 0.05,
            max_cells: 4_000_000,
            margin_m: 0.05,
            cruise_speed_mps: 0.6,
            careful_speed_mps: 0.4,
            // Turning in place, slowing at the last waypoint and pushing doors take time that
            // the path length does not show: twice the driving time plus 15 s.
            time_slack: 2.0,
            time_extra_s: 15.0,
            simplify_tolerance_m: 0.1,
            // The Pioneer 3-AT's datasheet grade is 35 % (19 degrees), on a dry surface with
            // its tyres; 15 takes every car-park (at most 11) and wheelchair ramp (5) with a
            // margin for the simulated contact friction.
            max_ramp_pitch_deg: 15.0,
        }
    }
}

impl PlanConfig {
    /// Checks every parameter.
    pub fn validate(&self) -> Result<()> {
        let el = "plan";
        check_range(el, "cell_m", self.cell_m, 0.005, 1.0, "5 mm to 1 m")?;
        check_range(
            el,
            "max_cells",
            self.max_cells as f64,
            1.0e3,
            1.0e8,
            "1e3 to 1e8 cells",
        )?;
        check_range(el, "margin_m", self.margin_m, 0.0, 2.0, "0 to 2 m")?;
        check_range(
            el,
            "cruise_speed_mps",
            self.cruise_speed_mps,
            0.05,
            20.0,
            "0.05 to 20 m/s",
        )?;
        check_range(
            el,
            "careful_speed_mps",
            self.careful_speed_mps,
            0.05,
            20.0,
            "0.05 to 20 m/s",
        )?;
        check_range(el, "time_slack", self.time_slack, 1.0, 100.0, "1 to 100")?;
        check_range(
            el,
            "time_extra_s",
            self.time_extra_s,
            0.0,
            1.0e4,
            "0 to 1e4 s",
        )?;
        check_range(
            el,
            "simplify_tolerance_m",
            self.simplify_tolerance_m,
            0.0,
            10.0,
            "0 to 10 m",
        )?;
        check_range(
            el,
            "max_ramp_pitch_deg",
            self.max_ramp_pitch_deg,
            0.0,
            45.0,
            "0 to 45 degrees",
        )?;
        Ok(())
    }
}
