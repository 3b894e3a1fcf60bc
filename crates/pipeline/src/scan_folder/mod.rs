//! The scan folder: the one format semsim writes virtual scans in and reads sequences from.
//!
//! A folder holds `scanNNN.pcd` (organised, labelled scans in their scan frame), `poses.txt`
//! (ground-truth `world_from_scan` per scan, by name), `odometry.txt` (the same with drift
//! and noise), `entities.json` (the building's ground-truth entities: id, class, name) and
//! `config.toml`. Real sequences read the same way: scan files (`.pcd .ply .xyz .3d`) of a
//! folder in name order, odometry from `odometry.txt` or 3DTK `.pose` files beside the scans.

mod read;
mod write;

pub use read::{is_scan_file, read_sequence};
pub use write::{write_scan_folder, ScanFolderSummary};

use glam::DAffine3;
use std::path::{Path, PathBuf};

/// The ground-truth pose file of a scan folder.
pub const TRUTH_FILE: &str = "poses.txt";
/// The odometry pose file of a scan folder.
pub const ODOMETRY_FILE: &str = "odometry.txt";
/// The ground-truth entities of a scan folder.
pub const ENTITIES_FILE: &str = "entities.json";

/// The scans of a sequence, their odometry and (if known) their ground truth.
#[derive(Debug, Clone, Default)]
pub struct SequenceInput {
    /// Scan files in order.
    pub files: Vec<PathBuf>,
    /// Odometry `world_from_scan` per scan (empty if none).
    pub odometry: Vec<DAffine3>,
    /// Ground truth `world_from_scan` per scan (empty if none).
    pub truth: Vec<DAffine3>,
    /// Every file read: the scans and the pose files (outputs must not replace any of them).
    pub read: Vec<PathBuf>,
}

impl SequenceInput {
    /// Each scan's name: its file stem (pose files name scans by it).
    pub fn names(&self) -> Vec<String> {
        self.files.iter().map(|f| scan_name(f)).collect()
    }
}

/// A scan's name: its file stem.
pub fn scan_name(file: &Path) -> String {
    file.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// True if a pose's name names the scan file: its stem (`scan000`) or its whole file name
/// (`scan000.pcd`).
pub fn names_scan(pose_name: &str, file: &Path) -> bool {
    pose_name == scan_name(file)
        || file
            .file_name()
            .is_some_and(|n| n.to_string_lossy() == pose_name)
}
