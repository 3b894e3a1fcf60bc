//! Where the robot stands for a stop-and-scan: a position on the floor and a heading.

use glam::{DAffine3, DQuat, DVec3};
use serde::{Deserialize, Serialize};

/// Where the robot stands for a scan: position on the floor and heading.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ScanPose {
    /// X on the floor.
    pub x_m: f64,
    /// Y on the floor.
    pub y_m: f64,
    /// Heading about z (0 = +x).
    pub yaw_deg: f64,
}

impl ScanPose {
    /// The scan frame in the world, for a laser mounted `mount_height_m` above the floor.
    pub fn world_from_scan(&self, mount_height_m: f64) -> DAffine3 {
        DAffine3::from_rotation_translation(
            DQuat::from_rotation_z(self.yaw_deg.to_radians()),
            DVec3::new(self.x_m, self.y_m, mount_height_m),
        )
    }
}
