//! A slightly tilted mount: the rotating unit is never perfectly level on the robot. The scan is
//! written in the frame of the sensor as mounted (tilted), exactly as a real sensor reports
//! it, so registration and levelling downstream must cope with the tilt;
//! [`super::VirtualLaser::world_from_sensor`] gives the true pose of that frame, which is what a
//! scan folder records as ground truth.

use cloud::check_range;
use glam::DQuat;
use serde::{Deserialize, Serialize};

/// The tilt of the sensor on its mount.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Mount {
    /// Rotation about the sensor's forward (x) axis, degrees.
    pub roll_deg: f64,
    /// Rotation about the sensor's left (y) axis, degrees.
    pub pitch_deg: f64,
}

impl Default for Mount {
    fn default() -> Self {
        Mount::off()
    }
}

impl Mount {
    /// A level mount.
    pub fn off() -> Mount {
        Mount {
            roll_deg: 0.0,
            pitch_deg: 0.0,
        }
    }

    /// The preset: a few tenths of a degree, what a rotating unit bolted to a robot's deck
    /// plausibly carries (a 1 mm shim under one side of a 20 cm base is 0.3 degrees).
    pub fn real() -> Mount {
        Mount {
            roll_deg: 0.3,
            pitch_deg: -0.2,
        }
    }

    /// Checks the tilt: at most 5 degrees each way (more is a mis-mounted sensor, not a tilt).
    pub fn validate(&self) -> Result<(), cloud::InvalidParameter> {
        check_range(
            "realism.mount.roll_deg",
            self.roll_deg,
            -5.0,
            5.0,
            "within -5..5 degrees",
        )?;
        check_range(
            "realism.mount.pitch_deg",
            self.pitch_deg,
            -5.0,
            5.0,
            "within -5..5 degrees",
        )?;
        Ok(())
    }

    /// The rotation from the tilted sensor's frame to the level scan frame (roll, then pitch).
    pub fn scan_from_sensor(&self) -> DQuat {
        DQuat::from_rotation_y(self.pitch_deg.to_radians())
            * DQuat::from_rotation_x(self.roll_deg.to_radians())
    }
}
