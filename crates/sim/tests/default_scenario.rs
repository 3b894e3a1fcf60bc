//! The demo's scenario: corridor, the stair room's door, the stairs. Every rule passes.

mod common;

use common::{has, of, timeline};
use sim::EventKind::*;
use sim::{write_outputs, ReportConfig, RobotModel, Scenario};

#[test]
fn the_default_scenario_passes() {
    let spec = common::default_world();
    let sc = Scenario::default_scenario().unwrap();
    assert_eq!(sc.robot, "inspection");
    let model = RobotModel::builtin(&sc.robot).unwrap();
    let o = sim::run_scenario(&spec, &sc, &model).unwrap();
    let t = timeline(&o);
    assert!(o.verdict.passed, "{:#?}\n{t}", o.verdict);
    assert_eq!(o.verdict.rules.len(), 6);
    // The robot pushed the stair room's door and went through its opening into the room.
    assert!(has(&o, CollisionStarted, "walls[4].doors[2].leaf"), "{t}");
    assert!(
        has(&o, DoorFreeSpaceEntered, "walls[4].doors[2].free_space"),
        "{t}"
    );
    let left: Vec<_> = of(&o, DoorFreeSpaceLeft)
        .into_iter()
        .filter(|e| e.value("crossed") == Some(1.0))
        .collect();
    assert_eq!(left.len(), 1, "{t}");
    // Then it climbed every step onto the landing.
    let steps: Vec<f64> = of(&o, StairsStepReached)
        .iter()
        .map(|e| e.value("step").unwrap())
        .collect();
    assert_eq!(steps, vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0], "{t}");
    assert_eq!(of(&o, StairsClimbingFinished).len(), 1, "{t}");
    assert!(left[0].time_s < of(&o, StairsClimbingStarted)[0].time_s);
    for kind in [JointBroken, RobotTipped, StairsClimbingAborted] {
        assert!(of(&o, kind).is_empty(), "{kind:?}:\n{t}");
    }
    // The outputs.
    let dir = tempfile::tempdir().unwrap();
    let [events, trajectory, report] =
        write_outputs(dir.path(), &o, &ReportConfig::default()).unwrap();
    let report = std::fs::read_to_string(report).unwrap();
    assert!(report.contains("## Verdict: PASSED"), "{report}");
    assert!(report.contains("stairs_climbing_finished"), "{report}");
    assert!(!report.contains("| movement |"), "{report}");
    let csv = std::fs::read_to_string(trajectory).unwrap();
    assert!(csv.starts_with("time_s,x_m,y_m,z_m,roll_deg,pitch_deg,yaw_deg,speed_mps\n"));
    assert_eq!(csv.lines().count(), 1 + 601, "10 Hz for 60 s plus t = 0");
    assert!(std::fs::metadata(events).unwrap().len() > 1000);
}

#[test]
fn the_default_scenario_is_shipped_as_a_file() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/default_scenario.toml");
    let from_file = Scenario::load(&path).unwrap();
    assert_eq!(from_file, Scenario::default_scenario().unwrap());
    assert_eq!(
        std::fs::read_to_string(path).unwrap(),
        Scenario::default_scenario_toml()
    );
}
