//! A semantic map file scored against a building (`semsim eval map`): the map, the building
//! (a file, or `default` for the built-in one) and, optionally, the scans that made the map with
//! their ground-truth labels (then only what they saw is expected).

use crate::error::{PipelineError, Result};
use crate::scans::merge_scan_files;
use evaluate::Evaluation;
use glam::DAffine3;
use scanner::Building;
use semantic::SemanticMap;
use std::path::{Path, PathBuf};

/// Loads the map and the building (`"default"` for the built-in one), places and merges the
/// labelled scans if any (checking they carry the building's ground truth) and scores the map.
/// With `true_poses` (the scans' true poses, as `semsim scan` writes them) beside registered
/// `poses`, the registration's frame is first related to the building's
/// ([`evaluate::registration_frame`]): a registration anchored on tilt-free odometry works in a
/// frame turned by the laser mount's tilt.
pub fn score_map_file(
    map: &Path,
    building: &Path,
    scans: &[PathBuf],
    poses: Option<&Path>,
    true_poses: Option<&Path>,
) -> Result<Evaluation> {
    let map = SemanticMap::load(map)?;
    let building = if building.as_os_str() == "default" {
        Building::default_building()?
    } else {
        Building::load(building)?
    };
    // 1. The registration's frame relative to the building's (identity without both files).
    let input_from_building = match (poses, true_poses) {
        (Some(registered), Some(truth)) => evaluate::registration_frame(
            &cloud::read_poses(registered)?,
            &cloud::read_poses(truth)?,
        )
        .ok_or_else(|| {
            PipelineError::bad_input(format!(
                "{}: no scan of {} has a pose there",
                truth.display(),
                registered.display()
            ))
        })?,
        _ => DAffine3::IDENTITY,
    };
    // 2. The labelled scans placed in that frame, checked against the building.
    let observed = if scans.is_empty() {
        None
    } else {
        // Every return, moving or not, as the scans saw them: the truth is what was seen.
        // (A single return on a step's tread seen at grazing incidence, between the risers,
        // may read as a mixed pixel: it is kept here.)
        let every_return = crate::TransientConfig {
            enabled: false,
            ..Default::default()
        };
        let no_mixed_pixels_dropped = crate::MixedPixelConfig {
            enabled: false,
            ..Default::default()
        };
        let merged = merge_scan_files(
            scans,
            poses,
            None,
            &Default::default(),
            &Default::default(),
            &no_mixed_pixels_dropped,
            &every_return,
        )?;
        evaluate::check_ground_truth_in_frame(&merged, &building, input_from_building.inverse())?;
        Some(merged)
    };
    // 3. The score.
    Ok(evaluate::evaluate_in_frame(
        &map,
        &building,
        observed.as_ref(),
        input_from_building,
        &Default::default(),
    ))
}
