//! Scans in and out: E57, LAS/LAZ and ROS 2 bags (MCAP) besides the `cloud` crate's own
//! formats (PCD, PLY, XYZ, 3DTK), chosen by the file extension.
//!
//! Every reader reads the whole file into memory first and parses the bytes, so the fuzz
//! targets in `fuzz/` run exactly what a path reader runs ([`fuzzing`]). Every number a file
//! gives that sizes an allocation is checked against the bytes that could hold it first.

mod e57_read;
mod e57_write;
mod las_check;
mod las_read;
mod las_stream;
mod las_write;
mod laz_check;
mod mcap;
mod merge;
mod source;
mod util;

use crate::error::{InteropError, Result};
use cloud::PointCloud;
use glam::{DAffine3, DVec3};
use std::path::Path;

/// What to read from a file that holds more than one stream of scans (a ROS 2 bag); ignored
/// for the other formats.
#[derive(Debug, Clone, Default)]
pub struct ReadOptions {
    /// The `sensor_msgs/msg/PointCloud2` topic of an MCAP bag to read (e.g. `/points`); `None`:
    /// the bag's only PointCloud2 topic (a bag with several is refused, naming them).
    pub topic: Option<String>,
    /// The `nav_msgs/msg/Odometry` topic of an MCAP bag to take scan poses from; `None`: the
    /// bag's only Odometry topic, if it has one (a bag with several is refused, naming them).
    pub odometry_topic: Option<String>,
}

/// One scan of a file: a cloud in the scan's own frame and where the file places it.
#[derive(Debug, Clone)]
pub struct ImportedScan {
    /// The scan's name: the E57 `name` (else `scanN`, N counting from 0), `<topic>#<index>` for
    /// a bag message (index counting from 0 in log-time order), the file stem otherwise.
    pub name: String,
    /// The points in the scan's frame (metres). Organised where the file keeps the scan's
    /// row/column structure (missing returns are all-NaN points there).
    pub cloud: PointCloud,
    /// The scan frame's pose in the set's frame (`world_from_scan`), where the file gives one:
    /// the E57 pose (identity where a scan has none, as the E57 standard says), or, for a bag
    /// message, the odometry pose where the cloud's `frame_id` is the odometry's child frame
    /// (identity where it is the odometry's own frame). `None`: the file says nothing; the
    /// cloud is used as it is (as single-cloud formats such as LAS and PCD are).
    pub world_from_scan: Option<DAffine3>,
    /// Acquisition time in nanoseconds since the Unix epoch (a bag message's header stamp).
    pub stamp_ns: Option<i64>,
    /// The frame the points are given in (a bag message's `header.frame_id`).
    pub frame_id: Option<String>,
}

/// Everything read from one file: its scans, in file order.
#[derive(Debug, Clone)]
pub struct ScanSet {
    /// The scans.
    pub scans: Vec<ImportedScan>,
    /// Where the set's frame lies in the file's coordinates, in metres (f64): the points and
    /// poses of the set are relative to it. Zero except for georeferenced LAS/LAZ files, whose
    /// coordinates (hundreds of kilometres) f32 could not hold to the millimetre.
    pub local_origin_m: DVec3,
    /// For a bag with an odometry topic: the odometry pose (`nav_msgs/msg/Odometry`
    /// `pose.pose`, the child frame in the odometry frame) at each scan's stamp, interpolated
    /// between the two nearest messages (the nearest outside their time span), one per scan.
    pub odometry: Option<Vec<DAffine3>>,
    /// What the readers converted, skipped or assumed, each starting with the file's path.
    pub notes: Vec<String>,
}

/// The formats of this module, by extension (lower case).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ScanFormat {
    E57,
    Las,
    Laz,
    Mcap,
}

fn scan_format(path: &Path) -> Option<ScanFormat> {
    let ext = path.extension()?.to_string_lossy().to_ascii_lowercase();
    match ext.as_str() {
        "e57" => Some(ScanFormat::E57),
        "las" => Some(ScanFormat::Las),
        "laz" => Some(ScanFormat::Laz),
        "mcap" => Some(ScanFormat::Mcap),
        _ => None,
    }
}

/// True for the formats that may hold several scans (`.e57`, `.mcap`): a caller that wants one
/// scan per file (a scan folder) reads these with [`read_scans`].
pub fn is_sequence_file(path: &Path) -> bool {
    matches!(scan_format(path), Some(ScanFormat::E57 | ScanFormat::Mcap))
}

/// Reads every scan of a file, the format chosen by the extension: `.e57`, `.las`, `.laz`,
/// `.mcap` here, the `cloud` crate's formats otherwise (one scan named after the file stem,
/// `world_from_scan` `None`, the reader's notes kept). An unknown extension is the `cloud`
/// crate's [`cloud::CloudError::UnknownFormat`].
pub fn read_scans(path: &Path, options: &ReadOptions) -> Result<ScanSet> {
    let Some(format) = scan_format(path) else {
        let (cloud, notes) = cloud::read_cloud_with_notes(path)?;
        return Ok(single_scan(path, cloud, DVec3::ZERO, notes));
    };
    match format {
        ScanFormat::E57 => e57_read::read_e57(path, &source::FileSource::open(path)?),
        ScanFormat::Las | ScanFormat::Laz => {
            las_read::read_las(path, &source::FileSource::open(path)?)
        }
        ScanFormat::Mcap => mcap::parse_mcap(path, &util::read_file(path)?, options),
    }
}

/// Reads a file as one cloud: a file of several scans has them placed by their poses
/// (`world_from_scan`) and merged (see [`ScanSet`] for the frame; missing returns of organised
/// scans are dropped when scans are merged); a single scan keeps its organised shape. The notes
/// say what was converted, dropped or assumed, and the local origin of a georeferenced LAS file.
pub fn read_cloud(path: &Path, options: &ReadOptions) -> Result<(PointCloud, Vec<String>)> {
    let set = read_scans(path, options)?;
    merge::merge_scans(path, set)
}

/// Writes a cloud, the format chosen by the extension: `.e57` (one scan, identity pose,
/// cartesian f64 coordinates, intensity and row/column indices of an organised cloud),
/// `.las` / `.laz` (LAS 1.4 point format 6, 0.1 mm resolution; see the LAS writer's notes
/// below), any other through [`cloud::write_cloud`]. The file is replaced atomically.
///
/// What LAS/LAZ keeps: the finite points (missing returns of an organised cloud and the
/// organised shape are dropped), intensity rounded to `u16` (0 where the cloud has none),
/// the ASPRS classification (0 where the cloud has none). Neither E57 nor LAS keeps labels or
/// the sensor pose.
pub fn write_cloud(path: &Path, cloud: &PointCloud) -> Result<()> {
    let Some(format) = scan_format(path) else {
        return cloud::write_cloud(path, cloud).map_err(InteropError::from);
    };
    cloud
        .validate()
        .map_err(|e| InteropError::format(path, format!("cannot write this cloud: {e}")))?;
    cloud.check_finite(path)?;
    match format {
        ScanFormat::E57 => e57_write::write_e57(path, cloud),
        ScanFormat::Las => las_write::write_las(path, cloud, false),
        ScanFormat::Laz => las_write::write_las(path, cloud, true),
        ScanFormat::Mcap => Err(InteropError::unsupported(
            path,
            "semsim reads ROS 2 bags but does not write them; write .e57, .las, .laz, .pcd, .ply, .xyz or .3d",
        )),
    }
}

/// A set of one scan named after the file stem, without pose.
/// Whether writing `path` (by its extension) keeps an organised cloud's row/column grid:
/// PCD (width x height) and E57 (row and column indices) do; PLY, XYZ, 3DTK, LAS and LAZ store
/// a list of points, so an organised cloud's missing returns are dropped before writing.
pub fn keeps_organized_shape(path: &Path) -> bool {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    matches!(ext.as_str(), "pcd" | "e57")
}

pub(super) fn single_scan(
    path: &Path,
    cloud: PointCloud,
    origin: DVec3,
    notes: Vec<String>,
) -> ScanSet {
    ScanSet {
        scans: vec![ImportedScan {
            name: util::file_stem(path),
            cloud,
            world_from_scan: None,
            stamp_ns: None,
            frame_id: None,
        }],
        local_origin_m: origin,
        odometry: None,
        notes,
    }
}

/// Byte-slice entry points of the readers, for the fuzz targets (not a stable API): each does
/// what [`read_scans`] does after reading the file; `path` is only named in messages.
pub mod fuzzing {
    use super::{e57_read, las_read, mcap, ReadOptions, ScanSet};
    use crate::error::Result;
    use std::path::Path;

    /// An E57 file.
    pub fn read_e57_bytes(path: &Path, bytes: &[u8]) -> Result<ScanSet> {
        e57_read::read_e57(path, &super::source::MemorySource(bytes))
    }

    /// A LAS or LAZ file (the header says which).
    pub fn read_las_bytes(path: &Path, bytes: &[u8]) -> Result<ScanSet> {
        las_read::read_las(path, &super::source::MemorySource(bytes))
    }

    /// A ROS 2 bag in MCAP, with the default [`ReadOptions`].
    pub fn read_mcap_bytes(path: &Path, bytes: &[u8]) -> Result<ScanSet> {
        mcap::parse_mcap(path, bytes, &ReadOptions::default())
    }
}
