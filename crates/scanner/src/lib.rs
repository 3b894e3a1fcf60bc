//! Buildings and a virtual 3D laser for semsim.
//!
//! A [`Building`] is a human-editable description (TOML) of floor, ceiling, walls with door
//! openings and leaves, staircases and furniture. [`generate_building`] makes varied ones from a
//! seed. [`BuildingGeometry`] turns a building into labelled boxes, and [`VirtualLaser`] scans it
//! like the robot's rotating 2D line scanner, giving organised clouds with ground-truth labels.
//!
//! ```
//! use scanner::{Building, BuildingGeometry, LaserConfig, VirtualLaser};
//!
//! let building = Building::default_building().unwrap();
//! let geometry = BuildingGeometry::new(&building);
//! let laser = VirtualLaser::new(LaserConfig { beams: 61, rotation_steps: 31, ..Default::default() }).unwrap();
//! let scan = laser.scan(&geometry, &scanner::ScanPose { x_m: 2.0, y_m: 0.0, yaw_deg: 0.0 }, 7);
//! assert_eq!(scan.len(), 61 * 31);
//! assert!(scan.valid_count() > 1000);
//! ```
#![warn(missing_docs)]

mod building;
mod error;
mod generate;
mod geometry;
mod laser;
mod odometry;
mod pose;
mod summary;
mod survey;
mod validate;

pub use building::{
    Building, Ceiling, Door, Floor, Furniture, Hinge, Leaf, Material, Ramp, Staircase, Swing, Wall,
};
pub use error::{Result, ScannerError};
pub use generate::{generate_building, resolve_style, GeneratorConfig, Style};
pub use geometry::{BoxPart, BuildingGeometry, TruthEntity};
pub use laser::{
    LaserConfig, MixedPixels, Mount, People, RangeNoise, Realism, Returns, VirtualLaser, PRESETS,
};
pub use odometry::{odometry_from_truth, OdometryConfig};
pub use pose::ScanPose;
pub use survey::{room_of, survey_poses, SurveyConfig, BLOCKING_TOP_M};
