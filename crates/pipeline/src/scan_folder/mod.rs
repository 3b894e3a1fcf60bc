//! The scan folder: the one format semsim writes virtual scans in and reads sequences from.
//!
//! A folder holds `scanNNN.pcd` (organised, labelled scans in their scan frame), `poses.txt`
//! (ground-truth `world_from_scan` per scan, by name), `odometry.txt` (the same with drift
//! and noise), `entities.json` (the building's ground-truth entities: id, class, name) and
//! `config.toml`. Real sequences read the same way: scan files (`.pcd .ply .xyz .3d .las .laz`)
//! of a folder in name order, odometry from `odometry.txt` or 3DTK `.pose` files beside the
//! scans; a multi-scan file (`.e57`, a ROS 2 bag `.mcap`) is a sequence by itself, its scans'
//! own poses (E57) or odometry topic (MCAP) its odometry.

mod read;
mod sources;
mod write;

pub use read::{is_scan_file, read_scan_set, read_sequence};
pub use sources::{expand_files, ExpandedScans};
pub use write::{write_scan_folder, ScanFolderSummary};

use glam::DAffine3;
use std::path::{Path, PathBuf};

/// The ground-truth pose file of a scan folder.
pub const TRUTH_FILE: &str = "poses.txt";
/// The odometry pose file of a scan folder.
pub const ODOMETRY_FILE: &str = "odometry.txt";
/// The ground-truth entities of a scan folder.
pub const ENTITIES_FILE: &str = "entities.json";

/// One scan of a sequence: a file, or one scan of a file that holds several (E57, MCAP).
#[derive(Debug, Clone)]
pub struct ScanSource {
    /// The file the scan comes from.
    pub file: PathBuf,
    /// The scan's name, which pose files name it by: the file stem, or `stem_NNN` for the
    /// NNN-th scan of a multi-scan file.
    pub name: String,
    /// The scan, where it was read with its file (a multi-scan file is read once).
    pub(crate) loaded: Option<cloud::PointCloud>,
}

impl ScanSource {
    /// The scan held by a whole file (read when the scans are read).
    pub fn file(path: &Path) -> ScanSource {
        ScanSource {
            file: path.to_path_buf(),
            name: scan_name(path),
            loaded: None,
        }
    }

    /// True if a pose's name names this scan: its name (`scan000`), or for a scan that is a
    /// whole file, the file's name (`scan000.pcd`).
    pub fn is_named(&self, pose_name: &str) -> bool {
        pose_name == self.name
            || (self.loaded.is_none()
                && self
                    .file
                    .file_name()
                    .is_some_and(|n| n.to_string_lossy() == pose_name))
    }
}

/// The scans of a sequence, their odometry and (if known) their ground truth.
#[derive(Debug, Clone, Default)]
pub struct SequenceInput {
    /// The scans in order.
    pub scans: Vec<ScanSource>,
    /// Odometry `world_from_scan` per scan (empty if none).
    pub odometry: Vec<DAffine3>,
    /// Ground truth `world_from_scan` per scan (empty if none).
    pub truth: Vec<DAffine3>,
    /// Every file read: the scans and the pose files (outputs must not replace any of them).
    pub read: Vec<PathBuf>,
}

impl SequenceInput {
    /// Each scan's name (pose files name scans by it).
    pub fn names(&self) -> Vec<String> {
        self.scans.iter().map(|s| s.name.clone()).collect()
    }
}

/// A scan's name: its file stem.
pub fn scan_name(file: &Path) -> String {
    file.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}
