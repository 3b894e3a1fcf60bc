//! Reliability: worlds too big or too overlapping to simulate box by box, errors that name
//! their file and state the true problem, and long runs that report progress and can be stopped.

mod common;

use cloud::BadInput;
use common::{has, of, timeline};
use sim::EventKind::*;
use sim::{
    BoxSpec, EntityClass, FixedBox, RobotModel, Scenario, SimError, Simulation, World, WorldConfig,
    WorldSpec,
};
use std::ops::ControlFlow;

fn wall_box(entity: u32, name: &str, center_m: [f64; 3]) -> FixedBox {
    FixedBox {
        entity,
        class: EntityClass::Wall,
        name: name.to_string(),
        label: String::new(),
        geometry: BoxSpec {
            center_m,
            half_extents_m: [0.1, 2.0, 1.25],
            yaw_deg: 0.0,
        },
    }
}

/// A floor and `n` walls all at the same place (x = 5), as a bad map or building might have.
fn overlapping_walls(n: usize) -> WorldSpec {
    let mut spec = WorldSpec::default();
    spec.fixed.push(FixedBox {
        entity: 1,
        class: EntityClass::Floor,
        name: "floor".into(),
        label: String::new(),
        geometry: BoxSpec {
            center_m: [0.0, 0.0, -0.1],
            half_extents_m: [10.0, 10.0, 0.1],
            yaw_deg: 0.0,
        },
    });
    for i in 0..n {
        let id = 2 + i as u32;
        spec.fixed
            .push(wall_box(id, &format!("copy{i}"), [5.0, 0.0, 1.25]));
    }
    spec
}

const INTO_THE_WALL: &str = r#"
    robot = "pioneer3at"
    time_limit_s = 6.0
    start = { x_m = 3.5, y_m = 0.0, yaw_deg = 0.0 }
    [[velocity]]
    from_s = 0.3
    to_s = 6.0
    linear_mps = 0.5
"#;

#[test]
fn overlapping_static_boxes_are_merged_and_contacts_name_the_wall() {
    let spec = overlapping_walls(5_000);
    let world = World::new(&spec, WorldConfig::default()).unwrap();
    assert!(
        world.statics_merged(),
        "5000 boxes at one place: one compound"
    );
    let o = common::run(&spec, INTO_THE_WALL);
    let t = timeline(&o);
    let touched = of(&o, WallTouched);
    assert!(!touched.is_empty(), "{t}");
    for e in &touched {
        let wall = &e.entities[1];
        assert_eq!(wall.class, EntityClass::Wall, "{t}");
        assert!(wall.name.starts_with("copy"), "{t}");
    }
    // The wheels stand on the floor: no collision with it (a sub-shape of the compound).
    assert!(!has(&o, CollisionStarted, "floor"), "{t}");
    assert!(of(&o, RobotTipped).is_empty(), "{t}");
}

#[test]
fn ordinary_worlds_keep_one_collider_per_box() {
    // Their simulations stay bit-identical to those made before merging existed.
    let world = World::new(&common::default_world(), WorldConfig::default()).unwrap();
    assert!(!world.statics_merged());
    let world = World::new(&overlapping_walls(200), WorldConfig::default()).unwrap();
    assert!(!world.statics_merged());
}

#[test]
fn the_default_scenario_passes_in_a_merged_world() {
    // The default building plus 3000 boxes piled up far away: the stairs, the door and the
    // walls are sub-shapes of the compound now, and the events still name them.
    let mut spec = common::default_world();
    let first = spec.entities().last().unwrap().id + 1;
    // (Free spaces take ids after the geometry's; keep the new ids clear of every one.)
    let first = first.max(1_000);
    for i in 0..3_000u32 {
        spec.fixed.push(wall_box(
            first + i,
            &format!("pile{i}"),
            [-50.0, -50.0, 1.25],
        ));
    }
    let world = World::new(&spec, WorldConfig::default()).unwrap();
    assert!(world.statics_merged());
    let sc = Scenario::default_scenario().unwrap();
    let model = RobotModel::builtin(&sc.robot).unwrap();
    let o = sim::run_scenario(&spec, &sc, &model).unwrap();
    let t = timeline(&o);
    assert!(o.verdict.passed, "{:#?}\n{t}", o.verdict);
    assert!(has(&o, CollisionStarted, "walls[4].doors[2].leaf"), "{t}");
    let steps: Vec<f64> = of(&o, StairsStepReached)
        .iter()
        .map(|e| e.value("step").unwrap())
        .collect();
    assert_eq!(steps, vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0], "{t}");
    assert!(!has(&o, CollisionStarted, "floor"), "{t}");
    for e in of(&o, CollisionStarted) {
        assert!(!e.entities[1].name.starts_with("pile"), "{t}");
    }
}

#[test]
fn a_merged_world_resumes_from_a_checkpoint_identically() {
    let spec = overlapping_walls(600);
    let sc = Scenario::from_toml_str(INTO_THE_WALL, "t").unwrap();
    let model = RobotModel::builtin(&sc.robot).unwrap();
    let mut straight = Simulation::new(&spec, &sc, &model).unwrap();
    straight.run();
    let mut first = Simulation::new(&spec, &sc, &model).unwrap();
    first.run_until(3.0);
    let bytes = first.checkpoint_bytes().unwrap();
    let mut resumed = Simulation::from_checkpoint_bytes(&bytes).unwrap();
    assert!(resumed.world().statics_merged());
    resumed.run();
    assert!(straight.events().iter().any(|e| e.kind == WallTouched));
    assert_eq!(resumed.events(), straight.events());
    assert_eq!(resumed.verdict(), straight.verdict());
}

#[test]
fn a_world_over_the_static_box_limit_is_refused_up_front() {
    let spec = overlapping_walls(WorldSpec::MAX_STATIC_BOXES);
    let err = spec.validate().unwrap_err();
    let n = WorldSpec::MAX_STATIC_BOXES + 1;
    assert!(
        matches!(err, SimError::TooMany { count, limit, .. } if count == n && limit == WorldSpec::MAX_STATIC_BOXES),
        "{err}"
    );
    assert!(err.is_bad_input());
    let msg = err.to_string();
    assert!(
        msg.contains(&n.to_string()) && msg.contains(&WorldSpec::MAX_STATIC_BOXES.to_string()),
        "{msg}"
    );
    assert!(World::new(&spec, WorldConfig::default()).is_err());
    // Through JSON, the error names the file.
    let json = serde_json::to_string(&spec).unwrap();
    let err = WorldSpec::from_json_str(&json, "big.json").unwrap_err();
    assert!(err.to_string().starts_with("big.json: world: "), "{err}");
}

#[test]
fn too_many_doors_or_steps_are_refused_up_front() {
    let mut spec = common::default_world();
    let door = spec.doors[0].clone();
    let first = 100_000;
    spec.doors = (0..=WorldSpec::MAX_DOORS as u32)
        .map(|i| {
            let mut d = door.clone();
            d.entity = first + i;
            d.name = format!("d{i}");
            d
        })
        .collect();
    spec.free_spaces.clear();
    let err = spec.validate().unwrap_err();
    assert!(matches!(err, SimError::TooMany { .. }), "{err}");
    assert!(err.to_string().contains("doors"), "{err}");
    let mut spec = common::default_world();
    let step = spec.stairs[0].steps[0].clone();
    spec.stairs[0].steps = (0..=WorldSpec::MAX_STEPS as u32)
        .map(|i| sim::StepSpec {
            index: i,
            ..step.clone()
        })
        .collect();
    let err = spec.validate().unwrap_err();
    assert!(err.to_string().contains("steps"), "{err}");
}

fn write(dir: &std::path::Path, name: &str, text: &str) -> std::path::PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn scenario_errors_name_the_scenario_file() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "time_limit_s = 2e6\nstart = { x_m = 0.0, y_m = 0.0 }\n",
            "scenario: time_limit_s = 2000000 is out of range: more than 1000000",
        ),
        (
            "time_limit_s = 5.0\nstart = { x_m = 0.0, y_m = nan }\n",
            "start: y_m is not a finite number (NaN)",
        ),
        (
            "time_limit_s = 5.0\nstart = { x_m = 0.0, y_m = 0.0 }\n[[velocity]]\nfrom_s = 1.0\nto_s = 1e300\n",
            "velocity[0]: to_s = 1e300 is out of range: more than 1e7",
        ),
        (
            "time_limit_s = 5.0\nstart = { x_m = 0.0, y_m = 0.0 }\n[[velocity]]\nfrom_s = 2.0\nto_s = 1.0\n",
            "velocity[0]: to_s = 1 is out of range: less than 2",
        ),
    ];
    for (i, (text, expected)) in cases.iter().enumerate() {
        let path = write(dir.path(), &format!("s{i}.toml"), text);
        let err = Scenario::load(&path).unwrap_err();
        let msg = err.to_string();
        assert!(
            msg.starts_with(&format!("{}: ", path.display())) && msg.contains(expected),
            "{msg}\nexpected: {expected}"
        );
        assert!(err.is_bad_input());
    }
}

#[test]
fn robot_model_errors_name_the_model_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = include_str!("../data/pioneer3at.toml").replace("mass_kg = 10.0", "mass_kg = -1.0");
    let path = write(dir.path(), "robot.toml", &text);
    let err = RobotModel::load(&path).unwrap_err();
    let msg = err.to_string();
    assert!(msg.starts_with(&format!("{}: ", path.display())), "{msg}");
    assert!(msg.contains("less than"), "{msg}");
    // Through a scenario naming the file.
    let sc = Scenario::from_toml_str(
        "robot = \"robot.toml\"\ntime_limit_s = 5.0\nstart = { x_m = 0.0, y_m = 0.0 }\n",
        "s.toml",
    )
    .unwrap();
    let msg = sc.robot_model(dir.path()).unwrap_err().to_string();
    assert!(msg.contains("robot.toml: "), "{msg}");
}

#[test]
fn building_file_errors_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "room.toml", &common::room(""));
    let spec = WorldSpec::from_building_file(&path).unwrap();
    assert!(spec.fixed.len() >= 5);
    let missing = dir.path().join("missing.toml");
    let msg = WorldSpec::from_building_file(&missing)
        .unwrap_err()
        .to_string();
    assert!(msg.contains("missing.toml"), "{msg}");
}

#[test]
fn an_interrupted_run_keeps_its_events_and_says_so() {
    let spec = common::default_world();
    let sc = Scenario::default_scenario().unwrap();
    let model = RobotModel::builtin(&sc.robot).unwrap();
    let mut seen = vec![];
    let o = sim::run_scenario_with(&spec, &sc, &model, &mut |t| {
        seen.push(t);
        if t >= 20.0 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    })
    .unwrap();
    assert!(seen.windows(2).all(|w| w[0] < w[1]));
    let dt = 1.0 / 60.0;
    let step = sim::PROGRESS_EVERY_STEPS as f64 * dt;
    assert!((seen[0] - step).abs() < 1e-9, "{seen:?}");
    let at = o.verdict.interrupted_at_s.expect("interrupted");
    assert!((20.0..20.0 + step).contains(&at), "{at}");
    assert_eq!(o.verdict.end_time_s, at);
    assert!(!o.verdict.passed);
    assert!(!o.events.is_empty() && o.events.iter().all(|e| e.time_s <= at + 1e-9));
    assert!(o.trajectory.last().unwrap().time_s <= at + 1e-9);
    // The robot has not climbed yet at 20 s: that goal is not decided, and says so.
    let undecided: Vec<_> = o.verdict.rules.iter().filter(|r| r.undecided).collect();
    assert!(!undecided.is_empty(), "{:#?}", o.verdict);
    for r in &undecided {
        assert!(!r.passed && r.reason.contains("interrupted at"), "{r:?}");
    }
    let report = sim::report_markdown(&o, &sim::ReportConfig::default());
    assert!(
        report.contains(&format!("interrupted at {at:.2} s")),
        "{report}"
    );
    assert!(report.contains("| not decided |"), "{report}");
    assert!(!report.contains("PASSED"), "{report}");
}

#[test]
fn a_run_that_is_not_stopped_equals_run_scenario() {
    let spec = common::default_world();
    let mut sc = Scenario::default_scenario().unwrap();
    sc.time_limit_s = 12.0;
    let model = RobotModel::builtin(&sc.robot).unwrap();
    let mut calls = 0;
    let o = sim::run_scenario_with(&spec, &sc, &model, &mut |_| {
        calls += 1;
        ControlFlow::Continue(())
    })
    .unwrap();
    assert!(calls > 10);
    assert_eq!(o, sim::run_scenario(&spec, &sc, &model).unwrap());
    assert_eq!(o.verdict.interrupted_at_s, None);
    let json = serde_json::to_string(&o.verdict).unwrap();
    assert!(
        !json.contains("interrupted") && !json.contains("undecided"),
        "{json}"
    );
}
