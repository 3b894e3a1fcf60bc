//! Point clouds for semsim: positions in metres (right-handed, z up) with optional intensity,
//! ground-truth labels and organised shape; their files (PCD, PLY, XYZ, 3DTK); voxel
//! downsampling; pose files; atomic output. Also what every crate of the workspace shares: the
//! one vocabulary of entity classes ([`EntityClass`]), the range check of parameters
//! ([`check_range`]), whether an error is the user's ([`BadInput`]) and a deterministic [`Rng`].
//!
//! ```
//! use cloud::{PointCloud, voxel_downsample};
//! use glam::Vec3;
//!
//! let cloud = PointCloud::from_points(vec![Vec3::new(0.01, 0.0, 0.0), Vec3::new(0.02, 0.0, 0.0)]);
//! let down = voxel_downsample(&cloud, 0.05).unwrap();
//! assert_eq!(down.len(), 1);
//! assert_eq!(cloud.bounding_box().unwrap().max.x, 0.02);
//! ```

mod atomic;
mod class;
mod cloud;
mod error;
pub mod io;
mod param;
mod poses;
mod rng;
mod voxel;

pub use atomic::{write_atomically, write_bytes_atomically};
pub use class::EntityClass;
pub use cloud::{Aabb, Label, Organized, PointCloud};
pub use error::{CloudError, Result};
pub use io::{read_cloud, write_cloud, write_cloud_as, CloudFormat, PcdEncoding, PlyEncoding};
pub use param::{check_range, BadInput, InvalidParameter};
pub use poses::{affine_from_mat4, pose_error, read_poses, write_poses, NamedPose};
pub use rng::Rng;
pub use voxel::voxel_downsample;
