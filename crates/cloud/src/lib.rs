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
#![warn(missing_docs)]

mod atomic;
mod class;
mod cloud;
mod error;
pub mod io;
mod param;
mod poses;
mod rng;
mod voxel;

/// Byte-slice entry points of every reader, for the fuzz targets in `fuzz/` (not a stable API).
/// Each takes the path its messages name and the file's bytes, and does what the path reader
/// does after reading the file (notes are returned, not printed).
#[doc(hidden)]
pub mod fuzzing {
    use crate::{NamedPose, PointCloud, Result};
    use glam::DAffine3;
    use std::path::Path;

    /// A `.pcd` file (any `DATA` encoding).
    pub fn read_pcd_bytes(path: &Path, bytes: &[u8]) -> Result<(PointCloud, Vec<String>)> {
        crate::io::pcd::parse_pcd(path, bytes)
    }

    /// A `.ply` file (any encoding).
    pub fn read_ply_bytes(path: &Path, bytes: &[u8]) -> Result<(PointCloud, Vec<String>)> {
        crate::io::ply::parse_ply(path, bytes)
    }

    /// A `.xyz` / `.txt` file.
    pub fn read_xyz_bytes(path: &Path, bytes: &[u8]) -> Result<PointCloud> {
        crate::io::xyz::parse_xyz(path, bytes)
    }

    /// A 3DTK `.3d` scan.
    pub fn read_3d_bytes(path: &Path, bytes: &[u8]) -> Result<PointCloud> {
        crate::io::threedtk::parse_3d(path, bytes)
    }

    /// A 3DTK `.pose` file.
    pub fn read_pose_3dtk_bytes(path: &Path, bytes: &[u8]) -> Result<DAffine3> {
        crate::io::threedtk::parse_pose_3dtk(path, bytes)
    }

    /// A 3DTK `.frames` file.
    pub fn read_frames_3dtk_bytes(path: &Path, bytes: &[u8]) -> Result<Vec<DAffine3>> {
        crate::io::threedtk::parse_frames_3dtk(path, bytes)
    }

    /// A pose file (`name` and 16 numbers a line).
    pub fn read_poses_bytes(path: &Path, bytes: &[u8]) -> Result<Vec<NamedPose>> {
        crate::poses::parse_poses(path, bytes)
    }

    /// Any cloud file, the format chosen by `path`'s extension.
    pub fn read_cloud_bytes(path: &Path, bytes: &[u8]) -> Result<(PointCloud, Vec<String>)> {
        let format = crate::CloudFormat::from_path(path)?;
        crate::io::read_cloud_bytes(path, format, bytes)
    }
}

pub use atomic::{write_atomically, write_bytes_atomically};
pub use class::EntityClass;
pub use cloud::{Aabb, Label, Organized, PointCloud};
pub use error::{CloudError, Result};
pub use io::{
    read_cloud, read_cloud_with_notes, write_cloud, write_cloud_as, CloudFormat, PcdEncoding,
    PlyEncoding,
};
pub use param::{check_range, BadInput, InvalidParameter};
pub use poses::{affine_from_mat4, pose_error, read_poses, write_poses, NamedPose};
pub use rng::Rng;
pub use voxel::voxel_downsample;
