//! Reading a sequence: folders expanded into their scan files, odometry and ground truth found.

use super::{scan_name, SequenceInput, ODOMETRY_FILE, TRUTH_FILE};
use crate::error::{PipelineError, Result};
use cloud::NamedPose;
use glam::DAffine3;
use std::path::{Path, PathBuf};

/// Scan file extensions a sequence folder is read for.
const SCAN_EXTENSIONS: [&str; 4] = ["pcd", "ply", "3d", "xyz"];
/// Stems of files in a folder that are outputs, not scans (a registered map, a labelled map).
const NOT_SCANS: [&str; 2] = ["map", "labels"];

/// Expands folders into their scan files (in name order), and finds odometry (`odometry`, else
/// the folder's `odometry.txt`, else 3DTK `.pose` files beside every scan) and ground truth
/// (`truth`, else the folder's `poses.txt`). A sequence needs at least two scans.
pub fn read_sequence(
    inputs: &[PathBuf],
    odometry: Option<&Path>,
    truth: Option<&Path>,
) -> Result<SequenceInput> {
    let mut files = Vec::new();
    let mut folder = None;
    for i in inputs {
        if i.is_dir() {
            folder.get_or_insert(i.clone());
            let mut in_dir: Vec<PathBuf> = std::fs::read_dir(i)
                .map_err(|e| cloud::CloudError::io(i, e))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| is_scan_file(p))
                .collect();
            in_dir.sort();
            files.extend(in_dir);
        } else if i.is_file() {
            files.push(i.clone());
        } else {
            return Err(cloud::CloudError::io(
                i,
                std::io::Error::new(std::io::ErrorKind::NotFound, "no such file or folder"),
            )
            .into());
        }
    }
    if files.len() < 2 {
        return Err(PipelineError::bad_input(format!(
            "a sequence needs at least two scans, found {}",
            files.len()
        )));
    }
    let mut read = files.clone();
    let in_folder = |name: &str| {
        folder
            .as_ref()
            .map(|d| d.join(name))
            .filter(|p| p.is_file())
    };
    let odometry_file = odometry
        .map(Path::to_path_buf)
        .or_else(|| in_folder(ODOMETRY_FILE));
    let odometry = match odometry_file {
        Some(p) => {
            read.push(p.clone());
            poses_for(&files, &cloud::read_poses(&p)?, &p)?
        }
        None if files.iter().any(|f| f.with_extension("pose").is_file()) => {
            if let Some(missing) = files.iter().find(|f| !f.with_extension("pose").is_file()) {
                return Err(PipelineError::bad_input(format!(
                    "{}: no {} beside it, while other scans have their 3DTK .pose file: give \
                     every scan its .pose, or an odometry file (--odometry)",
                    missing.display(),
                    missing.with_extension("pose").display()
                )));
            }
            read.extend(files.iter().map(|f| f.with_extension("pose")));
            files
                .iter()
                .map(|f| cloud::io::threedtk::read_pose_3dtk(&f.with_extension("pose")))
                .collect::<Result<_, _>>()?
        }
        _ => Vec::new(),
    };
    let truth_file = truth
        .map(Path::to_path_buf)
        .or_else(|| in_folder(TRUTH_FILE));
    let truth = match truth_file {
        Some(p) => {
            read.push(p.clone());
            poses_for(&files, &cloud::read_poses(&p)?, &p)?
        }
        None => Vec::new(),
    };
    Ok(SequenceInput {
        files,
        odometry,
        truth,
        read,
    })
}

/// True for a file a sequence folder is read for: a cloud format's extension, and not one of
/// semsim's own map outputs (`map.*`, `labels.*`).
pub fn is_scan_file(p: &Path) -> bool {
    let ext = p
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let stem = scan_name(p);
    SCAN_EXTENSIONS.contains(&ext.as_str()) && !NOT_SCANS.contains(&stem.as_str())
}

/// Picks the pose of each scan by name from a pose file.
fn poses_for(files: &[PathBuf], poses: &[NamedPose], path: &Path) -> Result<Vec<DAffine3>> {
    files
        .iter()
        .map(|f| {
            let stem = scan_name(f);
            poses
                .iter()
                .find(|p| super::names_scan(&p.name, f))
                .map(|p| p.world_from_scan)
                .ok_or_else(|| {
                    PipelineError::bad_input(format!(
                        "{}: no pose for scan '{stem}'",
                        path.display()
                    ))
                })
        })
        .collect()
}
