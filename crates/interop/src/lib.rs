//! semsim's interoperability with the tools roboticists already use.
//!
//! * **Scans in** ([`read_scans`], [`read_cloud`]): E57 (every scan with its pose, organised
//!   shape and intensity), LAS 1.2-1.4 and LAZ (intensity and ASPRS classification kept,
//!   georeferenced coordinates moved to a recorded local origin in f64), ROS 2 bags in MCAP
//!   (`sensor_msgs/msg/PointCloud2` decoded from CDR by this crate, odometry from
//!   `nav_msgs/msg/Odometry`), and every format of the `cloud` crate (PCD, PLY, XYZ, 3DTK).
//!   [`write_cloud`] writes E57 and LAS/LAZ too.
//! * **Worlds out** ([`export_world`]): a simulation world ([`sim::WorldSpec`], from a semantic
//!   map or a building) and optionally a robot, as MuJoCo MJCF, Gazebo SDF 1.9 or glTF 2.0
//!   binary (GLB).
//!
//! ```
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("two.las");
//! let cloud = cloud::PointCloud::from_points(vec![glam::Vec3::ZERO, glam::Vec3::X]);
//! interop::write_cloud(&path, &cloud).unwrap();
//! let set = interop::read_scans(&path, &interop::ReadOptions::default()).unwrap();
//! assert_eq!(set.scans.len(), 1);
//! assert_eq!(set.scans[0].cloud.len(), 2);
//! ```
#![warn(missing_docs)]

mod error;
mod export;
mod scans;

pub use error::{InteropError, Result};
pub use export::{export_world, write_export, ExportFormat, ExportOptions};
pub use scans::{
    is_sequence_file, keeps_organized_shape, read_cloud, read_scans, write_cloud, ImportedScan,
    ReadOptions, ScanSet,
};

/// Byte-slice entry points of the readers, for the fuzz targets in `fuzz/` (not a stable API).
#[doc(hidden)]
pub mod fuzzing {
    pub use crate::scans::fuzzing::*;
}
