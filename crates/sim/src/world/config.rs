//! The physics settings of a world: time step, solver iterations, gravity, friction, the
//! impulse that counts as a touch, and continuous collision detection.

use crate::error::{check_range, Result};
use serde::{Deserialize, Serialize};

/// Physics settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WorldConfig {
    /// Fixed time step (s).
    pub dt_secs: f64,
    /// Solver iterations (substeps) per step.
    pub solver_iterations: usize,
    /// Gravity (m/s^2, pointing down -z).
    pub gravity_mps2: f64,
    /// Friction coefficient of fixed geometry and doors.
    pub static_friction: f64,
    /// A contact pair touches when its solver impulse in the last step exceeds this (N s):
    /// rapier also keeps predictive contacts up to 2 cm apart, and with contact recycling
    /// their distances may be stale, so force exchanged is the reliable sign of a touch.
    pub touch_impulse_ns: f64,
    /// Continuous collision detection (rapier's CCD substeps; 0 = off). Robots and doors move
    /// slowly enough for speculative contacts; CCD costs much time with cleated wheels.
    pub ccd_substeps: usize,
}

impl Default for WorldConfig {
    fn default() -> Self {
        WorldConfig {
            dt_secs: 1.0 / 60.0,
            solver_iterations: 4,
            gravity_mps2: 9.81,
            static_friction: 0.7,
            touch_impulse_ns: 1.0e-4,
            ccd_substeps: 0,
        }
    }
}

impl WorldConfig {
    /// Checks the settings.
    pub fn validate(&self) -> Result<()> {
        let el = "world config";
        check_range(
            el,
            "dt_secs",
            self.dt_secs,
            1.0e-4,
            0.1,
            "a step of 0.1 ms to 100 ms",
        )?;
        check_range(
            el,
            "solver_iterations",
            self.solver_iterations as f64,
            1.0,
            64.0,
            "1 to 64",
        )?;
        check_range(
            el,
            "gravity_mps2",
            self.gravity_mps2,
            0.0,
            100.0,
            "0 to 100",
        )?;
        check_range(
            el,
            "static_friction",
            self.static_friction,
            0.0,
            10.0,
            "0 to 10",
        )?;
        check_range(
            el,
            "touch_impulse_ns",
            self.touch_impulse_ns,
            0.0,
            100.0,
            "0 to 100 N s",
        )?;
        check_range(
            el,
            "ccd_substeps",
            self.ccd_substeps as f64,
            0.0,
            16.0,
            "0 (off) to 16",
        )?;
        Ok(())
    }
}
