//! Shared helpers for the world-export tests: the worlds (the default building's, and a
//! semantic map's with its relations), exporting to a file, and the oracles' reports.
#![allow(dead_code)]

use interop::{write_export, ExportFormat, ExportOptions};
use semantic::{Relation, SemanticMap};
use sim::{RobotModel, StartPose, WorldSpec};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The default building's world.
pub fn default_world() -> WorldSpec {
    WorldSpec::from_building(&scanner::Building::default_building().unwrap()).unwrap()
}

/// A semantic map (as built from scans) of a room with an east wall at x = 6 holding a door
/// 30 degrees open (hinge at y = -0.5, opening counter-clockwise), and its relations.
pub fn map_world() -> (WorldSpec, Vec<Relation>) {
    let relations = format!(
        r#"{},{{"type":"above","a":2,"b":1}},{{"type":"under","a":1,"b":2}}"#,
        fixtures::DOOR_RELATIONS
    );
    let json = fixtures::door_wall_map_json("left", 30.0, &relations);
    let map = SemanticMap::from_json_str(&json, Path::new("map.json")).unwrap();
    let spec = WorldSpec::from_semantic_map(&map).unwrap();
    (spec, map.relations.clone())
}

/// A built-in robot at a start pose.
pub fn robot(name: &str, x_m: f64, y_m: f64, yaw_deg: f64) -> (RobotModel, StartPose) {
    let model = RobotModel::builtin(name).unwrap();
    let start = StartPose {
        x_m,
        y_m,
        yaw_deg,
        z_m: 0.0,
    };
    (model, start)
}

/// Exports to `dir/<stem>.<extension>` and returns the path.
pub fn export(
    dir: &Path,
    stem: &str,
    spec: &WorldSpec,
    format: ExportFormat,
    options: &ExportOptions,
) -> PathBuf {
    let path = dir.join(format!("{stem}.{}", format.extension()));
    write_export(&path, spec, format, options).unwrap();
    path
}

/// Runs `tools/oracles/check_mjcf.py` on a file; `None` when the venv is missing.
pub fn check_mjcf(path: &Path, args: &[&str]) -> Option<serde_json::Value> {
    let python = fixtures::oracles::python()?;
    let out = fixtures::oracles::run_ok(
        Command::new(python)
            .arg(fixtures::oracles::script("check_mjcf.py"))
            .arg(path)
            .args(args),
    );
    Some(serde_json::from_str(&out).unwrap_or_else(|e| panic!("{e}: {out}")))
}

/// Asserts MuJoCo said nothing while loading and stepping (no runtime warnings, nothing
/// printed, no Python warnings).
pub fn assert_quiet(report: &serde_json::Value) {
    assert_eq!(report["warnings"], serde_json::json!({}), "{report:#}");
    assert_eq!(report["stderr"], serde_json::json!([]), "{report:#}");
    assert_eq!(
        report["python_warnings"],
        serde_json::json!([]),
        "{report:#}"
    );
}

/// The glTF frame of a semsim point: (x, y, z) -> (x, z, -y).
pub fn to_gltf(p: [f64; 3]) -> [f64; 3] {
    [p[0], p[2], -p[1]]
}

/// The axis-aligned bounds (glTF frame) of boxes given in semsim's frame.
pub fn gltf_bounds(boxes: &[&sim::BoxSpec], offset: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for b in boxes {
        let (s, c) = b.yaw_deg.to_radians().sin_cos();
        let h = b.half_extents_m;
        for (i, j, k) in (0..8).map(|n| (n & 1, (n >> 1) & 1, (n >> 2) & 1)) {
            let sx = if i == 0 { -h[0] } else { h[0] };
            let sy = if j == 0 { -h[1] } else { h[1] };
            let sz = if k == 0 { -h[2] } else { h[2] };
            let p = [
                b.center_m[0] + c * sx - s * sy - offset[0],
                b.center_m[1] + s * sx + c * sy - offset[1],
                b.center_m[2] + sz - offset[2],
            ];
            let g = to_gltf(p);
            for a in 0..3 {
                lo[a] = lo[a].min(g[a]);
                hi[a] = hi[a].max(g[a]);
            }
        }
    }
    (lo, hi)
}
