//! A semantic map file scored against a building (`semsim eval map`): the map, the building
//! (a file, or `default` for the built-in one) and, optionally, the scans that made the map with
//! their ground-truth labels (then only what they saw is expected).

use crate::error::Result;
use crate::scans::merge_scan_files;
use evaluate::Evaluation;
use scanner::Building;
use semantic::SemanticMap;
use std::path::{Path, PathBuf};

/// Loads the map and the building (`"default"` for the built-in one), places and merges the
/// labelled scans if any (checking they carry the building's ground truth) and scores the map.
pub fn score_map_file(
    map: &Path,
    building: &Path,
    scans: &[PathBuf],
    poses: Option<&Path>,
) -> Result<Evaluation> {
    let map = SemanticMap::load(map)?;
    let building = if building.as_os_str() == "default" {
        Building::default_building()?
    } else {
        Building::load(building)?
    };
    let observed = if scans.is_empty() {
        None
    } else {
        let merged =
            merge_scan_files(scans, poses, None, &Default::default(), &Default::default())?;
        evaluate::check_ground_truth(&merged, &building)?;
        Some(merged)
    };
    Ok(evaluate::evaluate(&map, &building, observed.as_ref()))
}
