//! Worlds from elsewhere: [`building`] makes a [`WorldSpec`](crate::WorldSpec) from a
//! ground-truth building, `semantic_map` (feature `semantic`) from a semantic map built from
//! scans; [`ImportConfig`] says how both make doors and free spaces. `urdf` reads robot
//! models from URDF files ([`RobotModel::load_urdf`](crate::RobotModel::load_urdf)).

mod building;
pub(crate) mod ramp;
#[cfg(feature = "semantic")]
mod semantic_map;
mod urdf;

use crate::error::{check_range, Result};
use serde::{Deserialize, Serialize};

/// How doors and free spaces are made from a building.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ImportConfig {
    /// Door leaf mass (kg).
    pub door_mass_kg: f64,
    /// Door leaf angular damping (1/s).
    pub door_damping_per_s: f64,
    /// Hinge dry friction (N m).
    pub door_hinge_friction_nm: f64,
    /// Hinge force that breaks a door off (N); 0 = unbreakable.
    pub door_break_force_n: f64,
    /// Upper opening limit (degrees); a door initially open wider keeps its angle as the limit.
    pub door_max_deg: f64,
    /// How far the free space reaches out of the wall on each side (m).
    pub free_space_margin_m: f64,
    /// A semantic map's ramp stands on the floor and is entered at its foot: the world's floor
    /// runs under it and this far beyond its foot (m), seen or not (the floor is built from
    /// where the scans saw it, and a low laser rarely sees the floor at a ramp's foot).
    pub ramp_apron_m: f64,
}

impl Default for ImportConfig {
    fn default() -> Self {
        ImportConfig {
            door_mass_kg: 20.0,
            door_damping_per_s: 1.0,
            door_hinge_friction_nm: 2.0,
            door_break_force_n: 800.0,
            door_max_deg: 100.0,
            free_space_margin_m: 0.4,
            // A robot's length and a run-up: room to line up with the slope.
            ramp_apron_m: 1.0,
        }
    }
}

impl ImportConfig {
    /// Checks every field's range (the door's physics and the free space's margin).
    pub(crate) fn validate(&self) -> Result<()> {
        let el = "import config";
        check_range(
            el,
            "door_mass_kg",
            self.door_mass_kg,
            0.1,
            1.0e4,
            "0.1 kg to 10 t",
        )?;
        check_range(
            el,
            "door_max_deg",
            self.door_max_deg,
            1.0,
            180.0,
            "1 to 180 degrees",
        )?;
        check_range(
            el,
            "free_space_margin_m",
            self.free_space_margin_m,
            0.0,
            10.0,
            "0 to 10 m",
        )?;
        check_range(
            el,
            "ramp_apron_m",
            self.ramp_apron_m,
            0.0,
            10.0,
            "0 to 10 m",
        )?;
        check_range(
            el,
            "door_break_force_n",
            self.door_break_force_n,
            0.0,
            1.0e9,
            "0 (unbreakable) or a force in N",
        )?;
        Ok(())
    }
}
