//! Point cloud files, picked by extension: PCD (`.pcd`), PLY (`.ply`), XYZ (`.xyz`, `.txt`)
//! and 3DTK (`.3d`). All writers are atomic (temporary file + rename).

pub(crate) mod lzf;
pub mod pcd;
pub mod ply;
mod scalar;
pub mod threedtk;
pub mod xyz;

use crate::cloud::PointCloud;
use crate::error::{CloudError, Result};
use std::path::Path;

pub use pcd::PcdEncoding;
pub use ply::PlyEncoding;

/// A file format with its encoding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CloudFormat {
    /// PCD v0.7.
    Pcd(PcdEncoding),
    /// PLY 1.0.
    Ply(PlyEncoding),
    /// Whitespace-separated columns `x y z [intensity]`.
    Xyz,
    /// 3DTK `scanNNN.3d` (centimetres, left-handed, y up).
    ThreeDtk,
}

impl CloudFormat {
    /// The format for a path's extension, with the default encoding
    /// (PCD `binary`, PLY `binary_little_endian`).
    pub fn from_path(path: &Path) -> Result<Self> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        match ext.as_str() {
            "pcd" => Ok(CloudFormat::Pcd(PcdEncoding::Binary)),
            "ply" => Ok(CloudFormat::Ply(PlyEncoding::BinaryLittleEndian)),
            "xyz" | "txt" => Ok(CloudFormat::Xyz),
            "3d" => Ok(CloudFormat::ThreeDtk),
            _ => Err(CloudError::UnknownFormat {
                path: path.to_path_buf(),
            }),
        }
    }
}

/// Reads a point cloud, choosing the format by the file extension.
pub fn read_cloud(path: &Path) -> Result<PointCloud> {
    match CloudFormat::from_path(path)? {
        CloudFormat::Pcd(_) => pcd::read_pcd(path),
        CloudFormat::Ply(_) => ply::read_ply(path),
        CloudFormat::Xyz => xyz::read_xyz(path),
        CloudFormat::ThreeDtk => threedtk::read_3d(path),
    }
}

/// Writes a point cloud in the format its extension names, with the default encoding.
pub fn write_cloud(path: &Path, cloud: &PointCloud) -> Result<()> {
    write_cloud_as(path, cloud, CloudFormat::from_path(path)?)
}

/// Writes a point cloud in the given format.
pub fn write_cloud_as(path: &Path, cloud: &PointCloud, format: CloudFormat) -> Result<()> {
    cloud.validate()?;
    match format {
        CloudFormat::Pcd(enc) => pcd::write_pcd(path, cloud, enc),
        CloudFormat::Ply(enc) => ply::write_ply(path, cloud, enc),
        CloudFormat::Xyz => xyz::write_xyz(path, cloud),
        CloudFormat::ThreeDtk => threedtk::write_3d(path, cloud),
    }
}
