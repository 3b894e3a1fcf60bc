//! Robots from URDF files: the shipped Pioneer 3-AT URDF is valid URDF (urdfdom's
//! `check_urdf`), maps to the built-in model's dimensions and drives a scenario to the same
//! verdict; an arm maps to a chain of links; URDFs semsim cannot model are refused, naming
//! the file.

mod common;

use cloud::BadInput;
use sim::{ArmAxis, EventKind, RobotModel, Scenario, SimError};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

fn pioneer_urdf() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data/pioneer3at.urdf")
}

#[test]
fn check_urdf_accepts_the_shipped_pioneer() {
    let Some(check) = fixtures::oracles::program("check_urdf") else {
        return;
    };
    let out = fixtures::oracles::run_ok(Command::new(check).arg(pioneer_urdf()));
    assert!(out.contains("Successfully Parsed XML"), "{out}");
    assert!(out.contains("root Link: chassis has 4 child(ren)"), "{out}");
}

#[test]
fn the_urdf_pioneer_has_the_built_in_dimensions() {
    let urdf = RobotModel::load(&pioneer_urdf()).unwrap();
    let builtin = RobotModel::builtin("pioneer3at").unwrap();
    assert_eq!(urdf.name, "pioneer3at");
    assert_eq!(urdf.chassis, builtin.chassis);
    assert_eq!(urdf.wheels.len(), 4);
    for (u, b) in urdf.wheels.iter().zip(&builtin.wheels) {
        for k in 0..3 {
            assert!((u.position_m[k] - b.position_m[k]).abs() < 1e-12, "{u:?}");
        }
        assert_eq!(
            (u.radius_m, u.width_m, u.mass_kg, u.driven, u.cleats),
            (b.radius_m, b.width_m, b.mass_kg, b.driven, b.cleats)
        );
    }
    assert_eq!(urdf.drive, builtin.drive);
    assert_eq!(urdf.arm, None);
    assert_eq!(urdf.chassis_height_m(), builtin.chassis_height_m());
}

#[test]
fn a_scenario_resolves_a_urdf_robot_relative_to_its_folder() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let by_path = RobotModel::resolve("pioneer3at.urdf", &dir).unwrap();
    assert_eq!(by_path, RobotModel::load(&pioneer_urdf()).unwrap());
    let sc = Scenario::from_toml_str(
        r#"
        robot = "pioneer3at.urdf"
        time_limit_s = 1.0
        start = { x_m = 1.0, y_m = 0.0 }
        "#,
        "t",
    )
    .unwrap();
    assert_eq!(sc.robot_model(&dir).unwrap().wheels.len(), 4);
}

/// Down the default building's corridor, through the stair room's half-open door.
const THROUGH_THE_DOOR: &str = r#"
name = "corridor and the stair room's door"
robot = "pioneer3at"
time_limit_s = 32.0
start = { x_m = 10.0, y_m = 0.0, yaw_deg = 0.0 }

[[waypoints]]
x_m = 14.55
y_m = 0.0
speed_mps = 0.6

[[waypoints]]
x_m = 14.55
y_m = 3.0
speed_mps = 0.4

[rules]
pass_through_door = "door@14.5,1.3"
open_door = "door@14.5,1.3"
open_door_by_deg = 5.0
max_wall_contact_s = 0.5
no_broken_joint = true
no_tipping = true
"#;

#[test]
fn the_urdf_pioneer_drives_through_a_door_like_the_built_in() {
    let spec = common::default_world();
    let sc = Scenario::from_toml_str(THROUGH_THE_DOOR, "through the door").unwrap();
    let run = |model: &RobotModel| {
        let o = sim::run_scenario(&spec, &sc, model).unwrap();
        let kinds: BTreeSet<String> = o.events.iter().map(|e| format!("{:?}", e.kind)).collect();
        (o, kinds)
    };
    let (builtin, builtin_kinds) = run(&RobotModel::builtin("pioneer3at").unwrap());
    let (urdf, urdf_kinds) = run(&RobotModel::load(&pioneer_urdf()).unwrap());
    let t = common::timeline(&urdf);
    assert_eq!(urdf.verdict.passed, builtin.verdict.passed, "{t}");
    let passed =
        |o: &sim::Outcome| -> Vec<bool> { o.verdict.rules.iter().map(|r| r.passed).collect() };
    assert_eq!(passed(&urdf), passed(&builtin), "{t}");
    assert_eq!(urdf_kinds, builtin_kinds, "{t}");
    // It is a real run: the robot went through the door's free space.
    assert!(
        urdf_kinds.contains(&format!("{:?}", EventKind::DoorFreeSpaceEntered)),
        "{t}"
    );
    assert!(urdf.verdict.passed, "{:#?}\n{t}", urdf.verdict);
}

/// A two-wheel robot with a caster and a three-joint arm, as URDF.
fn arm_robot(extra_joint: &str) -> String {
    let wheel = |name: &str, y: f64, effort: f64| {
        format!(
            r#"<link name="{name}"><inertial><mass value="1.0"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
              <collision><origin rpy="1.5707963267948966 0 0"/><geometry><cylinder radius="0.1" length="0.05"/></geometry></collision></link>
            <joint name="{name}_axle" type="continuous"><parent link="base"/><child link="{name}"/>
              <origin xyz="0 {y} -0.05"/><axis xyz="0 1 0"/><limit effort="{effort}" velocity="10"/></joint>"#
        )
    };
    let link = |name: &str, length: f64, thick: f64| {
        format!(
            r#"<link name="{name}"><inertial><mass value="0.5"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
              <visual><origin xyz="{} 0 0"/><geometry><box size="{length} {thick} {thick}"/></geometry></visual></link>"#,
            length / 2.0
        )
    };
    format!(
        r#"<?xml version="1.0"?>
        <robot name="armed">
          <link name="base_footprint"/>
          <joint name="footprint" type="fixed"><parent link="base_footprint"/><child link="base"/><origin xyz="0 0 0.15"/></joint>
          <link name="base"><inertial><origin xyz="0.01 0 0"/><mass value="8.0"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
            <collision><geometry><box size="0.6 0.3 0.1"/></geometry></collision></link>
          <link name="lidar"><inertial><origin xyz="0 0 0"/><mass value="2.0"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
          <joint name="lidar_mount" type="fixed"><parent link="base"/><child link="lidar"/><origin xyz="0.1 0 0.1"/></joint>
          {}
          {}
          {}
          {}
          {}
          {}
          <joint name="turret_joint" type="revolute"><parent link="base"/><child link="turret"/><origin xyz="0.2 0 0.05"/>
            <axis xyz="0 0 1"/><limit lower="-3.0" upper="3.0" effort="20" velocity="1"/></joint>
          <joint name="shoulder_joint" type="revolute"><parent link="turret"/><child link="shoulder"/><origin xyz="0.1 0 0"/>
            <axis xyz="0 -1 0"/><limit lower="-0.5" upper="2.0" effort="25" velocity="1"/></joint>
          <joint name="elbow_joint" type="revolute"><parent link="shoulder"/><child link="elbow"/><origin xyz="0.35 0 0"/>
            <axis xyz="0 1 0"/><limit lower="-1.0" upper="2.5" effort="12" velocity="1"/></joint>
          {extra_joint}
        </robot>"#,
        wheel("left", 0.2, 6.0),
        wheel("right", -0.2, 6.0),
        wheel("caster", 0.0, 0.0).replace("0 0 -0.05", "0.25 0 -0.05"),
        link("turret", 0.1, 0.06),
        link("shoulder", 0.35, 0.05),
        link("elbow", 0.25, 0.04),
    )
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn an_arm_and_fixed_links_map_to_the_model() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "armed.urdf", &arm_robot(""));
    if let Some(check) = fixtures::oracles::program("check_urdf") {
        fixtures::oracles::run_ok(Command::new(check).arg(&path));
    }
    let m = RobotModel::load(&path).unwrap();
    // The root (base_footprint) has no box: the chassis is `base`, 15 cm up, and the lidar's
    // 2 kg (10 cm ahead, 10 cm up) joins its 8 kg.
    assert_eq!(m.chassis.size_m, [0.6, 0.3, 0.1]);
    assert_eq!(m.chassis.mass_kg, 10.0);
    let com = m.chassis.com_offset_m;
    assert!(
        (com[0] - (8.0 * 0.01 + 2.0 * 0.1) / 10.0).abs() < 1e-12,
        "{com:?}"
    );
    assert!((com[2] - 0.02).abs() < 1e-12, "{com:?}");
    assert_eq!(m.wheels.len(), 3);
    assert_eq!(m.wheels[0].position_m, [0.0, 0.2, -0.05]);
    assert_eq!((m.wheels[0].radius_m, m.wheels[0].width_m), (0.1, 0.05));
    assert!(m.wheels[0].driven && m.wheels[1].driven && !m.wheels[2].driven);
    assert_eq!(m.drive.max_wheel_torque_nm, 6.0);
    assert!((m.drive.max_speed_mps - 1.0).abs() < 1e-12);
    assert!((m.drive.max_yaw_rate_radps - 1.0 / 0.2).abs() < 1e-9);
    let arm = m.arm.unwrap();
    assert_eq!(arm.mount_m, [0.2, 0.0, 0.05]);
    let names: Vec<&str> = arm.links.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, ["turret", "shoulder", "elbow"]);
    assert_eq!(
        arm.links.iter().map(|l| l.axis).collect::<Vec<_>>(),
        [ArmAxis::Yaw, ArmAxis::Pitch, ArmAxis::Pitch]
    );
    let deg = |r: f64| r.to_degrees();
    let l = &arm.links;
    assert_eq!((l[0].min_deg, l[0].max_deg), (deg(-3.0), deg(3.0)));
    assert_eq!((l[1].min_deg, l[1].max_deg), (deg(-0.5), deg(2.0)));
    // The elbow turns about +y: semsim's pitch is about -y, so its limits are mirrored.
    assert_eq!((l[2].min_deg, l[2].max_deg), (deg(-2.5), deg(1.0)));
    assert_eq!(
        (l[1].length_m, l[1].thickness_m, l[1].mass_kg),
        (0.35, 0.05, 0.5)
    );
    assert_eq!(l[2].max_torque_nm, 12.0);
    assert_eq!(l[1].angle_deg, 0.0);
}

/// Loads a URDF that must fail; checks the error names the file and says `what`.
fn refused(text: &str, what: &str) -> SimError {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "bad_robot.urdf", text);
    let err = RobotModel::resolve(path.to_str().unwrap(), Path::new(".")).unwrap_err();
    let msg = err.to_string();
    assert!(msg.contains("bad_robot.urdf"), "{msg}");
    assert!(msg.contains(what), "expected {what:?} in: {msg}");
    assert!(err.is_bad_input(), "{msg}");
    err
}

#[test]
fn urdfs_semsim_cannot_model_are_refused_naming_the_file() {
    let prismatic = r#"<joint name="lift" type="prismatic"><parent link="elbow"/><child link="tool"/>
        <axis xyz="1 0 0"/><limit lower="0" upper="0.1" effort="10" velocity="1"/></joint>
        <link name="tool"/>"#;
    let e = refused(&arm_robot(prismatic), "joint \"lift\": prismatic joints");
    assert!(matches!(e, SimError::Urdf { .. }));
    refused(
        &arm_robot("").replace("<robot", "<robot x=\"1\"><oops"),
        "not well-formed XML",
    );
    refused(
        r#"<robot name="r"><link name="box"><inertial><mass value="1"/></inertial>
            <collision><geometry><box size="1 1 1"/></geometry></collision></link></robot>"#,
        "no wheels",
    );
    // A wheel whose only geometry is a mesh.
    let mesh = arm_robot("").replacen(
        r#"<cylinder radius="0.1" length="0.05"/>"#,
        r#"<mesh filename="wheel.dae"/>"#,
        1,
    );
    refused(&mesh, "wheel link \"left\" has only mesh");
    // A wheel turning about the chassis' x.
    let sideways = arm_robot("").replacen(r#"<axis xyz="0 1 0"/>"#, r#"<axis xyz="1 0 0"/>"#, 1);
    refused(&sideways, "not the chassis' y axis");
    // Two links claiming the same child, and a robot that is not a tree.
    let two_parents = arm_robot(
        r#"<joint name="again" type="fixed"><parent link="base"/><child link="elbow"/></joint>"#,
    );
    refused(&two_parents, "has two parents");
    // A branching arm.
    let branch = arm_robot(
        r#"<link name="wrist"><collision><origin xyz="0.05 0 0"/><geometry><box size="0.1 0.03 0.03"/></geometry></collision></link>
           <joint name="wrist_joint" type="revolute"><parent link="shoulder"/><child link="wrist"/><origin xyz="0.35 0 0"/>
           <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" velocity="1"/></joint>"#,
    );
    refused(&branch, "the arm branches at link \"shoulder\"");
    // Numbers that are not numbers, and a revolute joint without limits.
    refused(
        &arm_robot("").replacen("0.35 0 0", "0.35 zero 0", 1),
        "not 3 finite number(s)",
    );
    refused(
        &arm_robot("").replacen(
            r#"<limit lower="-3.0" upper="3.0" effort="20" velocity="1"/>"#,
            "",
            1,
        ),
        "a revolute joint needs a <limit>",
    );
    // Only one driven side: the model's own check, naming the file.
    let one_side = pioneer_text().replace(
        r#"<origin xyz="0.13 -0.2 -0.06" rpy="0 0 0"/>"#,
        r#"<origin xyz="0.13 0.25 -0.06" rpy="0 0 0"/>"#,
    );
    let one_side = one_side.replace(
        r#"<origin xyz="-0.13 -0.2 -0.06" rpy="0 0 0"/>"#,
        r#"<origin xyz="-0.13 0.25 -0.06" rpy="0 0 0"/>"#,
    );
    refused(&one_side, "driven wheels on both sides");
}

fn pioneer_text() -> String {
    std::fs::read_to_string(pioneer_urdf()).unwrap()
}

#[test]
fn a_missing_urdf_file_is_an_error_naming_it() {
    let err = RobotModel::load(Path::new("/nonexistent/robot.urdf")).unwrap_err();
    assert!(err.to_string().contains("/nonexistent/robot.urdf"), "{err}");
}
