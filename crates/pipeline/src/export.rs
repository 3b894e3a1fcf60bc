//! The export stage: a semantic map's world (or a building's) and optionally a robot, written
//! for another simulator or viewer (MuJoCo MJCF, Gazebo SDF, glTF binary) by the `interop`
//! crate.

use crate::error::{PipelineError, Result};
use interop::{ExportFormat, ExportOptions};
use scanner::Building;
use semantic::SemanticMap;
use sim::{RobotModel, Scenario, StartPose, WorldSpec};
use std::path::{Path, PathBuf};

/// Where the exported world comes from.
#[derive(Debug, Clone)]
pub enum WorldSource {
    /// A semantic map file (`semantic_map.json`); its relations go into the export.
    Map(PathBuf),
    /// A building description (TOML/JSON), or `default` for the built-in building.
    Building(PathBuf),
}

/// What was exported.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportSummary {
    /// Fixed boxes (floor, ceiling, walls, lintels, furniture).
    pub fixed_boxes: usize,
    /// Hinged doors.
    pub doors: usize,
    /// Staircases.
    pub stairs: usize,
    /// Free-space volumes of doors.
    pub free_spaces: usize,
    /// The robot's name, if one was exported.
    pub robot: Option<String>,
    /// Bytes written.
    pub bytes: usize,
}

/// Exports the world of `source` (and `robot` at `start`, if given) as `format` into `out`
/// (written atomically).
pub fn export_world_file(
    source: &WorldSource,
    format: ExportFormat,
    robot: Option<(&RobotModel, StartPose)>,
    out: &Path,
) -> Result<ExportSummary> {
    // 1. The world, and the semantic net's relations where the source is a map.
    let (spec, relations) = match source {
        WorldSource::Map(path) => {
            let map = SemanticMap::load(path)?;
            let spec = WorldSpec::from_semantic_map(&map)
                .map_err(|e| e.in_source(&path.display().to_string()))?;
            (spec, map.relations)
        }
        WorldSource::Building(path) => {
            let building = if path.as_os_str() == "default" {
                Building::default_building()?
            } else {
                Building::load(path)?
            };
            (WorldSpec::from_building(&building)?, Vec::new())
        }
    };
    // 2. The export, written atomically.
    let options = ExportOptions {
        robot,
        relations: &relations,
    };
    let bytes = interop::export_world(&spec, format, &options)?;
    cloud::write_bytes_atomically(out, &bytes)?;
    Ok(ExportSummary {
        fixed_boxes: spec.fixed.len(),
        doors: spec.doors.len(),
        stairs: spec.stairs.len(),
        free_spaces: spec.free_spaces.len(),
        robot: robot.map(|(m, _)| m.name.clone()),
        bytes: bytes.len(),
    })
}

/// The robot's start for an export (`--start x,y,yaw_deg`, metres and degrees), or the default
/// scenario's start for `None`.
pub fn parse_start(text: Option<&str>) -> Result<StartPose> {
    let Some(text) = text else {
        return Ok(Scenario::default_scenario()?.start);
    };
    let bad = || {
        PipelineError::bad_input(format!(
            "--start {text}: expected x,y,yaw_deg (three finite numbers)"
        ))
    };
    let numbers: Vec<f64> = text
        .split(',')
        .map(|s| s.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| bad())?;
    let [x_m, y_m, yaw_deg] = numbers[..] else {
        return Err(bad());
    };
    let pose = StartPose {
        x_m,
        y_m,
        yaw_deg,
        z_m: 0.0,
    };
    pose.validate().map_err(|_| bad())?;
    Ok(pose)
}
