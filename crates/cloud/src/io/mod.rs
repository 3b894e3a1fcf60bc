//! Point cloud files, picked by extension: PCD (`.pcd`), PLY (`.ply`), XYZ (`.xyz`, `.txt`)
//! and 3DTK (`.3d`). All writers are atomic (temporary file + rename).

mod asprs;
mod labels;
pub(crate) mod lzf;
pub mod pcd;
pub mod ply;
mod scalar;
pub(crate) mod text;
pub mod threedtk;
pub mod xyz;

use crate::cloud::PointCloud;
use crate::error::{CloudError, Result};
use std::path::Path;
pub use text::print_notes;
use text::read_file;

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

/// Reads a point cloud, choosing the format by the file extension. What the reader converted
/// or skipped rather than refusing the file (see [`read_cloud_with_notes`]) is printed to
/// standard error, one `note: ...` line each.
pub fn read_cloud(path: &Path) -> Result<PointCloud> {
    let (cloud, notes) = read_cloud_with_notes(path)?;
    print_notes(&notes);
    Ok(cloud)
}

/// Reads a point cloud like [`read_cloud`], returning the notes instead of printing them: one
/// per thing converted or skipped rather than refusing the file (a field of another type than
/// semsim's, a label that is no entity id, a field semsim does not use...), each starting with
/// the file's path.
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("foreign.pcd");
/// let head = "FIELDS x y z label\nSIZE 4 4 4 4\nTYPE F F F I\nWIDTH 2\nHEIGHT 1\nDATA ascii\n";
/// std::fs::write(&path, format!("{head}0 0 0 7\n1 1 1 -1\n")).unwrap();
/// let (cloud, notes) = cloud::read_cloud_with_notes(&path).unwrap();
/// let entities: Vec<u32> = cloud.labels.unwrap().iter().map(|l| l.entity).collect();
/// assert_eq!(entities, [7, 0]);
/// assert_eq!(notes.len(), 2, "{notes:?}"); // label TYPE I read as entity ids; -1 read as none
/// assert!(notes.iter().all(|n| n.starts_with(&path.display().to_string())));
/// ```
pub fn read_cloud_with_notes(path: &Path) -> Result<(PointCloud, Vec<String>)> {
    let format = CloudFormat::from_path(path)?;
    read_cloud_bytes(path, format, &read_file(path)?)
}

/// Reads a point cloud of the given format from bytes; `path` is for messages.
pub(crate) fn read_cloud_bytes(
    path: &Path,
    format: CloudFormat,
    bytes: &[u8],
) -> Result<(PointCloud, Vec<String>)> {
    match format {
        CloudFormat::Pcd(_) => pcd::parse_pcd(path, bytes),
        CloudFormat::Ply(_) => ply::parse_ply(path, bytes),
        CloudFormat::Xyz => Ok((xyz::parse_xyz(path, bytes)?, Vec::new())),
        CloudFormat::ThreeDtk => Ok((threedtk::parse_3d(path, bytes)?, Vec::new())),
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
