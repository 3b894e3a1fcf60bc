//! Exports a world (the default building, a building file or a semantic map) and optionally a
//! robot to MJCF, SDF or GLB.
//!
//! ```text
//! cargo run -p interop --example export_world -- FORMAT OUT [--building FILE|default]
//!     [--map semantic_map.json] [--robot NAME_OR_FILE] [--start X,Y,YAW_DEG]
//! ```
//! FORMAT is `mjcf`, `sdf`, `gltf` or `glb`. Used by `bench/mujoco_side_by_side.sh`.

use interop::{write_export, ExportFormat, ExportOptions};
use sim::{RobotModel, StartPose, WorldSpec};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

fn run(args: &[String]) -> Result<(), String> {
    let [format, out, rest @ ..] = args else {
        return Err("usage: export_world FORMAT OUT [--building FILE|default] \
                    [--map MAP.json] [--robot NAME_OR_FILE] [--start X,Y,YAW_DEG]"
            .into());
    };
    let format: ExportFormat = format.parse()?;
    let (mut building, mut map, mut robot, mut start) = (None, None, None, None);
    let mut it = rest.iter();
    while let Some(flag) = it.next() {
        let value = it
            .next()
            .ok_or_else(|| format!("{flag} needs a value"))?
            .clone();
        match flag.as_str() {
            "--building" => building = Some(value),
            "--map" => map = Some(PathBuf::from(value)),
            "--robot" => robot = Some(value),
            "--start" => start = Some(value),
            _ => return Err(format!("unknown option {flag}")),
        }
    }
    let mut relations = vec![];
    let spec = match (map, building.as_deref()) {
        (Some(path), _) => {
            let m = semantic::SemanticMap::load(&path).map_err(|e| e.to_string())?;
            relations = m.relations.clone();
            WorldSpec::from_semantic_map(&m)
                .map_err(|e| e.in_source(&path.display().to_string()).to_string())?
        }
        (None, None | Some("default")) => {
            let b = scanner::Building::default_building().map_err(|e| e.to_string())?;
            WorldSpec::from_building(&b).map_err(|e| e.to_string())?
        }
        (None, Some(file)) => {
            WorldSpec::from_building_file(Path::new(file)).map_err(|e| e.to_string())?
        }
    };
    let model = robot
        .map(|r| RobotModel::resolve(&r, Path::new(".")).map_err(|e| e.to_string()))
        .transpose()?;
    let start = match start {
        None => StartPose {
            x_m: 1.5,
            y_m: 0.0,
            yaw_deg: 0.0,
            z_m: 0.0,
        },
        Some(s) => {
            let v: Vec<f64> = s
                .split(',')
                .map(|p| p.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| format!("--start {s:?}: expected X,Y,YAW_DEG"))?;
            let [x_m, y_m, yaw_deg] = v[..] else {
                return Err(format!("--start {s:?}: expected X,Y,YAW_DEG"));
            };
            StartPose {
                x_m,
                y_m,
                yaw_deg,
                z_m: 0.0,
            }
        }
    };
    let options = ExportOptions {
        robot: model.as_ref().map(|m| (m, start)),
        relations: &relations,
    };
    write_export(Path::new(out), &spec, format, &options).map_err(|e| e.to_string())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("export_world: {e}");
            ExitCode::FAILURE
        }
    }
}
