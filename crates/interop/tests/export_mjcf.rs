//! MJCF exports, loaded and stepped by MuJoCo (`tools/oracles/check_mjcf.py`): they load
//! without a warning, doors are bodies on hinges that a push swings in their opening sense
//! within their limits, static geometry never collides with itself, and a robot drives.

mod export_support;

use export_support::{assert_quiet, check_mjcf, default_world, export, map_world, robot};
use interop::{export_world, ExportFormat, ExportOptions};
use serde_json::Value;

/// The door report of `door_<id>`.
fn door(report: &Value, id: u32) -> &Value {
    let name = format!("door_{id}");
    report["doors"]
        .as_array()
        .unwrap()
        .iter()
        .find(|d| d["name"] == name.as_str())
        .unwrap_or_else(|| panic!("no {name} in {report:#}"))
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The difference of two angles in degrees, in (-180, 180].
fn turn(from: f64, to: f64) -> f64 {
    let d = (to - from).rem_euclid(360.0);
    if d > 180.0 {
        d - 360.0
    } else {
        d
    }
}

#[test]
fn the_default_world_steps_quietly_and_its_doors_swing_their_way() {
    let spec = default_world();
    let dir = tempfile::tempdir().unwrap();
    let path = export(
        dir.path(),
        "world",
        &spec,
        ExportFormat::Mjcf,
        &ExportOptions::default(),
    );
    let text = std::fs::read_to_string(&path).unwrap();
    // Entity ids and classes in the names.
    for d in &spec.doors {
        assert!(
            text.contains(&format!("name=\"door_{}_leaf\"", d.entity)),
            "{text}"
        );
        assert!(text.contains(&format!("name=\"door_{}_hinge\"", d.entity)));
    }
    assert!(text.contains("name=\"floor_1\""), "{text}");
    assert!(text.contains("<compiler angle=\"radian\""), "{text}");
    let Some(report) = check_mjcf(&path, &["--push-doors", "60", "--seconds", "2"]) else {
        return;
    };
    assert_quiet(&report);
    assert_eq!(report["timestep"], 1.0 / 60.0);
    // The world body, a body and a hinge per door; a geom per static box and door leaf; a
    // site per free space.
    assert_eq!(report["nbody"], 1 + spec.doors.len(), "{report:#}");
    assert_eq!(report["njnt"], spec.doors.len());
    assert_eq!(report["ngeom"], spec.static_box_count() + spec.doors.len());
    assert_eq!(report["nsite"], spec.free_spaces.len());
    // Walls meet the floor and each other, leaves stand in their frames: none may collide.
    assert_eq!(report["contacts"], serde_json::json!([]), "{report:#}");
    assert_eq!(spec.doors.len(), 4);
    for d in &spec.doors {
        let r = door(&report, d.entity);
        let (angle0, angle) = (f(&r["angle0_deg"]), f(&r["angle_deg"]));
        assert!((angle0 - d.initial_deg).abs() < 1e-9, "{r:#}");
        assert!((f(&r["range_deg"][0]) - d.min_deg).abs() < 1e-9, "{r:#}");
        assert!((f(&r["range_deg"][1]) - d.max_deg).abs() < 1e-9, "{r:#}");
        // The model starts with the door as open as sim's (its yaw = sense x opening).
        let yaw0 = f(&r["yaw0_deg"]);
        assert!(
            turn(d.opens.sign() * d.initial_deg, yaw0).abs() < 1e-6,
            "{r:#}"
        );
        // Pushed, it turned, within its limits (MuJoCo's limits are soft: 1 degree), ...
        let push = f(&r["push_sense"]);
        assert!((angle - angle0) * push > 3.0, "{r:#}");
        assert!(f(&r["min_angle_deg"]) > d.min_deg - 1.0, "{r:#}");
        assert!(f(&r["max_angle_deg"]) < d.max_deg + 1.0, "{r:#}");
        // ... and the leaf turned (seen from above) in the door's opening sense when the push
        // opened it, against it when the push closed it.
        let yaw_turn = turn(yaw0, f(&r["yaw_deg"]));
        assert!(yaw_turn * push * d.opens.sign() > 3.0, "{r:#}");
        assert!(
            (yaw_turn.abs() - (angle - angle0).abs()).abs() < 1e-6,
            "{r:#}"
        );
    }
}

#[test]
fn a_pioneer_drives_forward_in_mujoco() {
    let spec = default_world();
    let (model, start) = robot("pioneer3at", 1.5, 0.0, 0.0);
    let options = ExportOptions {
        robot: Some((&model, start)),
        ..Default::default()
    };
    let dir = tempfile::tempdir().unwrap();
    let path = export(dir.path(), "pioneer", &spec, ExportFormat::Mjcf, &options);
    let text = std::fs::read_to_string(&path).unwrap();
    let id = spec.entities().iter().map(|e| e.id).max().unwrap() + 1;
    assert!(
        text.contains(&format!("<freejoint name=\"robot_{id}_free\"/>")),
        "{text}"
    );
    assert_eq!(text.matches("<velocity ").count(), 4, "{text}");
    let wheel_speed = 0.5 / model.wheels[0].radius_m;
    let Some(report) = check_mjcf(
        &path,
        &["--wheel-speed", &wheel_speed.to_string(), "--seconds", "2"],
    ) else {
        return;
    };
    assert_quiet(&report);
    assert_eq!(report["nu"], 4);
    // Chassis + 4 wheels + the doors' bodies and the world body.
    assert_eq!(report["nbody"], 1 + spec.doors.len() + 5);
    let r = &report["robot"];
    let start_z = f(&r["start"][2]);
    let expected_z = model.chassis_height_m() + 0.002;
    assert!((start_z - expected_z).abs() < 1e-9, "{r:#}");
    assert!(f(&r["forward_m"]) > 0.3, "{r:#}");
    assert!(f(&r["end"][1]).abs() < 0.05, "it drove straight: {r:#}");
    assert!(f(&r["max_tilt_deg"]) < 10.0, "{r:#}");
    assert!(f(&r["tilt_deg"]) < 3.0, "{r:#}");
    // It touches the floor with its wheels only.
    for pair in report["contacts"].as_array().unwrap() {
        let names: Vec<&str> = pair
            .as_array()
            .unwrap()
            .iter()
            .map(|n| n.as_str().unwrap())
            .collect();
        assert!(names.contains(&"floor_1"), "{names:?}");
        assert!(
            names
                .iter()
                .any(|n| n.starts_with(&format!("robot_{id}_wheel_"))),
            "{names:?}"
        );
    }
}

#[test]
fn a_semantic_map_world_with_the_inspection_robot() {
    let (spec, relations) = map_world();
    let (model, start) = robot("inspection", 3.0, -1.0, 90.0);
    let options = ExportOptions {
        robot: Some((&model, start)),
        relations: &relations,
    };
    let bytes = export_world(&spec, ExportFormat::Mjcf, &options).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    // The door's break force, which MuJoCo cannot model, is kept as data; the arm servos'
    // start angles are the keyframe's.
    let d = &spec.doors[0];
    assert!(
        text.contains(&format!(
            "<numeric name=\"door_{}_hinge_break_force_n\" data=\"800\"/>",
            d.entity
        )),
        "{text}"
    );
    assert!(text.contains("<key name=\"start\""), "{text}");
    let dir = tempfile::tempdir().unwrap();
    let path = export(dir.path(), "map", &spec, ExportFormat::Mjcf, &options);
    let wheel_speed = 0.4 / model.wheels[0].radius_m;
    let Some(report) = check_mjcf(
        &path,
        &[
            "--wheel-speed",
            &wheel_speed.to_string(),
            "--seconds",
            "2",
            "--push-doors",
            "40",
        ],
    ) else {
        return;
    };
    assert_quiet(&report);
    // 6 wheel motors and 3 arm servos.
    assert_eq!(report["nu"], 9, "{report:#}");
    let r = &report["robot"];
    assert!((f(&r["heading_deg"]) - 90.0).abs() < 1e-6, "{r:#}");
    assert!(f(&r["forward_m"]) > 0.3, "{r:#}");
    assert!(f(&r["max_tilt_deg"]) < 15.0, "{r:#}");
    let dr = door(&report, d.entity);
    assert!(
        (f(&dr["angle0_deg"]) - d.initial_deg).abs() < 1e-9,
        "{dr:#}"
    );
    let push = f(&dr["push_sense"]);
    let yaw_turn = turn(f(&dr["yaw0_deg"]), f(&dr["yaw_deg"]));
    assert!(yaw_turn * push * d.opens.sign() > 3.0, "{dr:#}");
}
