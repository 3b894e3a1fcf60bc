//! Files expanded into scans: a multi-scan file (E57, a ROS 2 bag) is read once, each of its
//! scans a [`ScanSource`] with the pose or odometry the file gives it; every other file is one
//! scan, read later.

use super::{scan_name, ScanSource};
use crate::error::Result;
use glam::DAffine3;
use std::path::PathBuf;

/// Scans found in files, with what the files say of their poses.
#[derive(Debug, Clone, Default)]
pub struct ExpandedScans {
    /// The scans in order.
    pub scans: Vec<ScanSource>,
    /// Each scan's `world_from_scan` as its file records it (E57 scan poses), else `None`.
    pub own_poses: Vec<Option<DAffine3>>,
    /// Each scan's odometry as its file records it (a bag's odometry topic), else `None`.
    pub odometry: Vec<Option<DAffine3>>,
}

impl ExpandedScans {
    /// The poses of every scan, if every scan has one.
    pub fn all(poses: &[Option<DAffine3>]) -> Option<Vec<DAffine3>> {
        poses.iter().copied().collect()
    }
}

/// Expands files into scans: `.e57` and `.mcap` files are read now (one source per scan), others
/// become one source each, read by [`crate::read_scans`]. The scans of a multi-scan file keep
/// the names the file gives them (white space replaced by `_`, as pose files separate fields
/// by it) where those are unique, else they are named `stem_NNN` after the file.
pub fn expand_files(files: &[PathBuf], options: &interop::ReadOptions) -> Result<ExpandedScans> {
    let mut out = ExpandedScans::default();
    for file in files {
        if !interop::is_sequence_file(file) {
            out.scans.push(ScanSource::file(file));
            out.own_poses.push(None);
            out.odometry.push(None);
            continue;
        }
        let set = interop::read_scans(file, options)?;
        cloud::io::print_notes(&set.notes);
        let names = scan_names(&scan_name(file), &set.scans);
        for (k, (scan, name)) in set.scans.into_iter().zip(names).enumerate() {
            out.scans.push(ScanSource {
                file: file.clone(),
                name,
                loaded: Some(scan.cloud),
            });
            out.own_poses.push(scan.world_from_scan);
            out.odometry
                .push(set.odometry.as_ref().and_then(|o| o.get(k).copied()));
        }
    }
    Ok(out)
}

/// The names of a multi-scan file's scans: their own (white space made `_`) if all are
/// non-empty and unique, else `stem_NNN`.
fn scan_names(stem: &str, scans: &[interop::ImportedScan]) -> Vec<String> {
    let own: Vec<String> = scans
        .iter()
        .map(|s| s.name.split_whitespace().collect::<Vec<_>>().join("_"))
        .collect();
    let unique = own.iter().collect::<std::collections::HashSet<_>>().len() == own.len();
    if unique && own.iter().all(|n| !n.is_empty()) {
        own
    } else {
        (0..scans.len()).map(|k| format!("{stem}_{k:03}")).collect()
    }
}
