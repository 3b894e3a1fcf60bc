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

fn entity(id: u32, class: &str, c: [f64; 3], s: [f64; 3], yaw: f64, extra: &str) -> String {
    format!(
        r#"{{"id":{id},"class":"{class}","geometry":{{"center_m":{c:?},"size_m":{s:?},"yaw_deg":{yaw:?}}},"support_points":500,"confidence":0.8,"rules":["export test"]{extra}}}"#
    )
}

/// A semantic map (as built from scans) of a room with an east wall at x = 6 holding a door
/// 30 degrees open (hinge at y = -0.5, opening counter-clockwise), and its relations.
pub fn map_world() -> (WorldSpec, Vec<Relation>) {
    let wall = r#","wall":{"segment_m":[[6.0,-2.0],[6.0,2.0]],"thickness_m":0.2,"thickness_measured":true,"z_range_m":[0.0,2.5],"solid_boxes":[{"center_m":[6.0,-1.25,1.25],"size_m":[1.5,0.2,2.5],"yaw_deg":90.0},{"center_m":[6.0,1.2,1.25],"size_m":[1.6,0.2,2.5],"yaw_deg":90.0}]}"#;
    let door = r#","door":{"hinge_m":[6.0,-0.5,0.0],"hinge_axis":[0.0,0.0,1.0],"hinge_edge":"start","swing":"left","observed_open_deg":30.0}"#;
    let opening = r#","opening":{"offset_m":1.5,"width_m":0.9,"height_m":2.0}"#;
    let entities = [
        entity(1, "floor", [4.5, 0.0, -0.1], [9.4, 4.4, 0.2], 0.0, ""),
        entity(2, "ceiling", [4.5, 0.0, 2.6], [9.4, 4.4, 0.2], 0.0, ""),
        entity(3, "wall", [6.0, 0.0, 1.25], [4.0, 0.2, 2.5], 90.0, wall),
        entity(
            4,
            "wall_above_door",
            [6.0, -0.05, 2.25],
            [0.9, 0.2, 0.5],
            90.0,
            "",
        ),
        entity(5, "door", [6.0, -0.05, 1.0], [0.9, 0.04, 2.0], 90.0, door),
        entity(
            6,
            "free_space_for_door",
            [6.0, -0.05, 1.0],
            [0.9, 1.0, 2.0],
            90.0,
            opening,
        ),
    ];
    let relations = r#"{"type":"connected_via_joint","a":5,"b":3},{"type":"available_inside","a":6,"b":3},{"type":"available_inside","a":5,"b":6},{"type":"above","a":2,"b":1},{"type":"under","a":1,"b":2}"#;
    let identity = "[1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0]";
    let json = format!(
        r#"{{"format":"semsim.semantic_map","version":1,"input_from_map":{identity},"entities":[{}],"relations":[{relations}]}}"#,
        entities.join(",")
    );
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
