//! `semsim export`: a semantic map's world (or a building's), optionally with a robot, for
//! MuJoCo (MJCF), Gazebo (SDF 1.9) or a glTF viewer (GLB).

use crate::exit::bad_input;
use clap::{ArgGroup, Args};
use pipeline::{export_world_file, ExportFormat, WorldSource};
use sim::RobotModel;
use std::path::{Path, PathBuf};

/// Arguments of `semsim export`.
#[derive(Args)]
#[command(group(ArgGroup::new("world").required(true).args(["map", "building"])))]
pub struct ExportArgs {
    /// The semantic map (semantic_map.json, from `semsim map` or `semsim run`).
    #[arg(long, value_name = "FILE")]
    map: Option<PathBuf>,
    /// A building description (TOML/JSON), or "default" for the built-in building.
    #[arg(long, value_name = "FILE")]
    building: Option<PathBuf>,
    /// mjcf (MuJoCo), sdf (Gazebo, SDFormat 1.9) or gltf (glTF 2.0 binary, .glb).
    #[arg(long, value_name = "mjcf|sdf|gltf")]
    format: ExportFormat,
    /// A robot to place in the world: a built-in name (pioneer3at, inspection), a robot TOML
    /// or a URDF file.
    #[arg(long, value_name = "NAME|FILE")]
    robot: Option<String>,
    /// The robot's start: x,y,yaw (metres, degrees); default: the default scenario's start.
    #[arg(long, value_name = "X,Y,YAW_DEG", requires = "robot")]
    start: Option<String>,
    /// The file to write.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
}

/// Runs `semsim export`.
pub fn run(a: ExportArgs) -> anyhow::Result<()> {
    let source = match (&a.map, &a.building) {
        (Some(m), _) => WorldSource::Map(m.clone()),
        (None, Some(b)) => WorldSource::Building(b.clone()),
        (None, None) => return Err(bad_input("give --map FILE or --building FILE")),
    };
    let inputs: Vec<PathBuf> = a.map.iter().chain(&a.building).cloned().collect();
    pipeline::refuse_overwriting_inputs(std::slice::from_ref(&a.out), &inputs)?;
    let robot = match &a.robot {
        Some(name) => Some((
            RobotModel::resolve(name, Path::new("."))?,
            pipeline::parse_start(a.start.as_deref())?,
        )),
        None => None,
    };
    let summary = export_world_file(
        &source,
        a.format,
        robot.as_ref().map(|(m, s)| (m, *s)),
        &a.out,
    )?;
    println!(
        "wrote {} ({} bytes): {} fixed boxes, {} doors, {} staircases, {} door free spaces{}",
        a.out.display(),
        summary.bytes,
        summary.fixed_boxes,
        summary.doors,
        summary.stairs,
        summary.free_spaces,
        summary
            .robot
            .map(|r| format!(", robot {r}"))
            .unwrap_or_default()
    );
    Ok(())
}
