//! Reading a sequence: folders expanded into their scan files, odometry and ground truth found.

use super::{
    expand_files, scan_name, ExpandedScans, ScanSource, SequenceInput, ODOMETRY_FILE, TRUTH_FILE,
};
use crate::error::{PipelineError, Result};
use cloud::NamedPose;
use glam::DAffine3;
use std::path::{Path, PathBuf};

/// Scan file extensions a sequence folder is read for.
const SCAN_EXTENSIONS: [&str; 8] = ["pcd", "ply", "3d", "xyz", "las", "laz", "e57", "mcap"];
/// Stems of files in a folder that are outputs, not scans (a registered map, a labelled map).
const NOT_SCANS: [&str; 2] = ["map", "labels"];

/// Expands folders into their scan files (in name order), and finds odometry (`odometry`, else
/// the folder's `odometry.txt`, else 3DTK `.pose` files beside every scan) and ground truth
/// (`truth`, else the folder's `poses.txt`). A multi-scan file (E57, a ROS 2 bag) is read now,
/// its scans' recorded poses (E57) or odometry topic (bag) its odometry where no odometry file
/// is given. A sequence needs at least two scans.
pub fn read_sequence(
    inputs: &[PathBuf],
    odometry: Option<&Path>,
    truth: Option<&Path>,
    options: &interop::ReadOptions,
) -> Result<SequenceInput> {
    read_scans_in(inputs, odometry, truth, options, 2)
}

/// As [`read_sequence`], one scan too: a single station, or a cloud registered already (a
/// surveyor's E57 or LAS of a whole floor), which `semsim run` maps as it stands (the scan
/// defines the world; there is nothing to register it against).
pub fn read_scan_set(
    inputs: &[PathBuf],
    odometry: Option<&Path>,
    truth: Option<&Path>,
    options: &interop::ReadOptions,
) -> Result<SequenceInput> {
    read_scans_in(inputs, odometry, truth, options, 1)
}

/// [`read_sequence`] with at least `min_scans` scans.
fn read_scans_in(
    inputs: &[PathBuf],
    odometry: Option<&Path>,
    truth: Option<&Path>,
    options: &interop::ReadOptions,
    min_scans: usize,
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
    let mut read = files.clone();
    let expanded = expand_files(&files, options)?;
    if expanded.scans.len() < min_scans {
        let found = expanded.scans.len();
        let what = if found == 0 {
            format!(
                "no scan files found (a scan is a .{} file)",
                SCAN_EXTENSIONS.join(", .")
            )
        } else {
            format!("a sequence needs at least two scans, found {found}")
        };
        return Err(PipelineError::bad_input(format!(
            "{}: {what}",
            shown_inputs(inputs)
        )));
    }
    let scans = &expanded.scans;
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
            poses_for(scans, &cloud::read_poses(&p)?, &p)?
        }
        None if recorded_odometry(&expanded).is_some() => {
            recorded_odometry(&expanded).unwrap_or_default()
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
            poses_for(scans, &cloud::read_poses(&p)?, &p)?
        }
        None => Vec::new(),
    };
    Ok(SequenceInput {
        scans: expanded.scans,
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

/// The odometry the scans' own files record: a bag's odometry topic, else E57 scan poses
/// (where every scan has one).
fn recorded_odometry(expanded: &ExpandedScans) -> Option<Vec<DAffine3>> {
    ExpandedScans::all(&expanded.odometry).or_else(|| ExpandedScans::all(&expanded.own_poses))
}

/// The inputs as a message names them.
fn shown_inputs(inputs: &[PathBuf]) -> String {
    inputs
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Picks the pose of each scan by name from a pose file.
fn poses_for(scans: &[ScanSource], poses: &[NamedPose], path: &Path) -> Result<Vec<DAffine3>> {
    scans
        .iter()
        .map(|scan| {
            poses
                .iter()
                .find(|p| scan.is_named(&p.name))
                .map(|p| p.world_from_scan)
                .ok_or_else(|| {
                    PipelineError::bad_input(format!(
                        "{}: no pose for scan '{}'",
                        path.display(),
                        scan.name
                    ))
                })
        })
        .collect()
}
