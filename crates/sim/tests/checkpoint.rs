//! Checkpoints: running 10 s straight equals running 5 s, saving, loading and running 5 s more.

mod common;

use sim::{events_to_jsonl, RobotModel, Scenario, Simulation};

#[test]
fn resume_from_checkpoint_gives_identical_results() {
    let spec = common::default_world();
    let mut sc = Scenario::default_scenario().unwrap();
    sc.start = sim::StartPose {
        x_m: 13.2,
        y_m: 0.0,
        yaw_deg: 0.0,
        z_m: 0.0,
    };
    sc.time_limit_s = 10.0;
    let model = RobotModel::builtin(&sc.robot).unwrap();

    let mut straight = Simulation::new(&spec, &sc, &model).unwrap();
    straight.run();

    let mut first = Simulation::new(&spec, &sc, &model).unwrap();
    first.run_until(5.0);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("state.ckpt");
    first.save_checkpoint(&path).unwrap();
    drop(first);
    let mut resumed = Simulation::load_checkpoint(&path).unwrap();
    assert!((resumed.time_s() - 5.0).abs() < 1e-9);
    resumed.run();

    // Something happens after the split: the robot reaches the stair room's door.
    assert!(straight
        .events()
        .iter()
        .any(|e| e.time_s > 5.0 && e.kind == sim::EventKind::CollisionStarted));
    assert_eq!(resumed.steps(), straight.steps());
    assert_eq!(
        events_to_jsonl(resumed.events()),
        events_to_jsonl(straight.events())
    );
    assert_eq!(resumed.robot_pose(), straight.robot_pose());
    assert_eq!(resumed.trajectory(), straight.trajectory());
    assert_eq!(resumed.verdict(), straight.verdict());
}

#[test]
fn a_file_that_is_no_checkpoint_is_a_typed_error() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("junk.ckpt");
    std::fs::write(&path, b"hello").unwrap();
    let err = Simulation::load_checkpoint(&path).err().unwrap();
    assert!(matches!(err, sim::SimError::Checkpoint { .. }), "{err}");
}
