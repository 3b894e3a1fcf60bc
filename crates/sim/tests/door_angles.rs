//! The doors' angles are recorded with the trajectory (`Outcome::doors`, `doors.csv`), so that a
//! replay swings the doors as they moved: in the default scenario the robot pushes the stair
//! room's door, and the widest angle recorded for it is the widest the simulation saw (checked
//! every step), to within what a 10 Hz sample misses.

mod common;

use sim::{write_outputs, ReportConfig, RobotModel, Scenario, Simulation, DOORS_CSV};

#[test]
fn door_angles_are_recorded_with_the_trajectory_and_written_to_doors_csv() {
    let spec = common::default_world();
    let sc = Scenario::default_scenario().unwrap();
    let model = RobotModel::builtin(&sc.robot).unwrap();
    let mut sim = Simulation::new(&spec, &sc, &model).unwrap();
    sim.run();
    let o = sim.outcome();

    // One sample per trajectory point, at the same times, one angle per door of the world.
    let track = &o.doors;
    assert_eq!(track.doors.len(), spec.doors.len());
    assert!(!track.doors.is_empty());
    assert_eq!(track.samples.len(), o.trajectory.len());
    for (s, p) in track.samples.iter().zip(&o.trajectory) {
        assert_eq!(s.time_s, p.time_s);
        assert_eq!(s.angles_deg.len(), track.doors.len());
    }
    // Every door starts at its initial angle.
    for (d, a) in spec.doors.iter().zip(&track.samples[0].angles_deg) {
        assert_eq!(
            track.doors[spec
                .doors
                .iter()
                .position(|x| x.entity == d.entity)
                .unwrap()],
            d.entity
        );
        assert!(
            (a - d.initial_deg).abs() < 1.0,
            "{}: {a} vs {}",
            d.name,
            d.initial_deg
        );
    }

    // The door the robot pushed: its widest recorded angle is the simulation's widest, less
    // at most what the door swings in one 0.1 s sample (a leaf pushed at walking speed turns
    // well under 50 degrees a second).
    let pushed = spec
        .doors
        .iter()
        .find(|d| d.name == "walls[4].doors[2].leaf")
        .expect("the stair room's door");
    let door = pushed.entity;
    let column = track
        .doors
        .iter()
        .position(|d| *d == door)
        .expect("a column");
    let widest = sim.widest_door_angle_deg(door).expect("a widest angle");
    let recorded: Vec<f64> = track.samples.iter().map(|s| s.angles_deg[column]).collect();
    let widest_recorded = recorded.iter().copied().fold(f64::MIN, f64::max);
    assert!(
        widest_recorded <= widest + 1e-9 && widest_recorded > widest - 5.0,
        "recorded {widest_recorded}, simulated {widest}"
    );
    assert!(
        widest - recorded[0] > 5.0,
        "the door did not swing: {} -> {widest}",
        recorded[0]
    );

    // doors.csv: `time_s,door_ID,...` and one row per sample, beside the other outputs.
    let dir = tempfile::tempdir().unwrap();
    write_outputs(dir.path(), &o, &ReportConfig::default()).unwrap();
    let csv = std::fs::read_to_string(dir.path().join(DOORS_CSV)).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[0], "time_s");
    assert_eq!(header[1 + column], format!("door_{door}"));
    assert_eq!(lines.count(), o.trajectory.len());
}
