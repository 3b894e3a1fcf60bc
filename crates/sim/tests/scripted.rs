//! Scripted runs on small hand-built buildings and on the default building: each produces its
//! semantic events and no spurious ones.

mod common;

use common::{closed_room, has, of, room, run, timeline};
use sim::EventKind::*;

/// An east wall at x = 6 with a 0.9 m door (y -0.5 .. 0.4), hinged at its south edge, and no
/// other wall; the floor reaches x = 9.2.
fn door_room(swing: &str) -> String {
    fixtures::RoomToml::new([0.0, -2.0], [6.0, 2.0], 2.5)
        .walls(&[])
        .floor_to_x(9.2)
        .toml(&fixtures::east_door_wall_with_leaf(swing))
}

#[test]
fn driving_into_a_wall() {
    let spec = common::world(&closed_room());
    let o = run(
        &spec,
        r#"
        robot = "pioneer3at"
        time_limit_s = 8.0
        start = { x_m = 4.0, y_m = 0.0, yaw_deg = 0.0 }
        [[velocity]]
        from_s = 0.5
        to_s = 5.5
        linear_mps = 0.5
        [[velocity]]
        from_s = 5.5
        to_s = 7.0
        linear_mps = -0.4
        [rules]
        max_wall_contact_s = 0.5
        "#,
    );
    let t = timeline(&o);
    assert_eq!(of(&o, WallTouched).len(), 1, "{t}");
    assert!(has(&o, WallTouched, "walls[3]"), "{t}");
    assert_eq!(of(&o, CollisionStarted).len(), 1, "{t}");
    assert!(of(&o, CollisionContinued).len() >= 2, "{t}");
    assert_eq!(of(&o, CollisionStopped).len(), 1, "{t}");
    let started = of(&o, CollisionStarted)[0].time_s;
    let stopped = of(&o, CollisionStopped)[0].time_s;
    assert!(started > 3.0 && started < 5.5 && stopped > 5.5, "{t}");
    for kind in [
        DoorOpened,
        DoorFreeSpaceEntered,
        StairsClimbingStarted,
        JointBroken,
        RobotTipped,
    ] {
        assert!(of(&o, kind).is_empty(), "spurious {kind:?}:\n{t}");
    }
    // The rule about wall contact fails, and says when.
    let rule = &o.verdict.rules[0];
    assert!(!rule.passed && rule.decided_s > started, "{rule:?}");
}

#[test]
fn pushing_a_door_open() {
    let spec = common::world(&door_room("right"));
    let o = run(
        &spec,
        r#"
        robot = "pioneer3at"
        time_limit_s = 9.0
        start = { x_m = 4.2, y_m = 0.05, yaw_deg = 0.0 }
        [[velocity]]
        from_s = 0.3
        to_s = 9.0
        linear_mps = 0.4
        [rules]
        open_door = "walls[0].doors[0]"
        pass_through_door = "walls[0].doors[0]"
        no_broken_joint = true
        "#,
    );
    let t = timeline(&o);
    let leaf = "walls[0].doors[0].leaf";
    assert!(has(&o, CollisionStarted, leaf), "{t}");
    assert!(has(&o, DoorOpened, leaf), "{t}");
    assert!(
        has(&o, DoorFreeSpaceEntered, "walls[0].doors[0].free_space"),
        "{t}"
    );
    assert!(of(&o, JointBroken).is_empty(), "{t}");
    assert!(of(&o, RobotTipped).is_empty(), "{t}");
    assert!(o.verdict.passed, "{:?}\n{t}", o.verdict);
}

#[test]
fn ramming_a_door_breaks_its_hinge() {
    // The leaf opens towards the robot, so the robot rams it against its stop.
    let spec = common::world(&door_room("left"));
    let o = run(
        &spec,
        r#"
        robot = "inspection"
        time_limit_s = 6.0
        start = { x_m = 4.0, y_m = 0.05, yaw_deg = 0.0 }
        [[velocity]]
        from_s = 0.2
        to_s = 6.0
        linear_mps = 0.8
        [rules]
        no_broken_joint = true
        "#,
    );
    let t = timeline(&o);
    let broken = of(&o, JointBroken);
    assert_eq!(broken.len(), 1, "{t}");
    let e = broken[0];
    assert_eq!(e.detail, "door hinge");
    assert!(
        e.entities
            .iter()
            .any(|x| x.name == "walls[0].doors[0].leaf"),
        "{t}"
    );
    assert!(e.entities.iter().any(|x| x.name == "robot"), "{t}");
    assert!(e.value("force_n").unwrap() > e.value("break_force_n").unwrap());
    assert!(!o.verdict.passed);
    assert!(
        o.verdict.rules[0].reason.contains("door hinge"),
        "{:?}",
        o.verdict
    );
}

#[test]
fn driving_through_an_open_doorway_without_contact() {
    let spec = common::world(
        r#"
        [floor]
        min_m = [-0.2, -2.2]
        max_m = [9.2, 2.2]
        [ceiling]
        height_m = 2.5
        [[walls]]
        start_m = [6.0, -2.0]
        end_m = [6.0, 2.0]
        thickness_m = 0.2
        [[walls.doors]]
        offset_m = 1.4
        width_m = 1.2
        height_m = 2.1
        "#,
    );
    let o = run(
        &spec,
        r#"
        robot = "pioneer3at"
        time_limit_s = 9.0
        start = { x_m = 4.0, y_m = 0.0, yaw_deg = 0.0 }
        [[velocity]]
        from_s = 0.3
        to_s = 9.0
        linear_mps = 0.5
        [rules]
        pass_through_door = "walls[0].doors[0]"
        max_wall_contact_s = 0.0
        "#,
    );
    let t = timeline(&o);
    let fs = "walls[0].doors[0].free_space";
    assert_eq!(of(&o, DoorFreeSpaceEntered).len(), 1, "{t}");
    let left = of(&o, DoorFreeSpaceLeft);
    assert_eq!(left.len(), 1, "{t}");
    assert!(
        has(&o, DoorFreeSpaceLeft, fs) && left[0].value("crossed") == Some(1.0),
        "{t}"
    );
    let significant: Vec<_> = o
        .events
        .iter()
        .filter(|e| e.kind.is_significant())
        .collect();
    assert_eq!(significant.len(), 2, "only free space entered/left:\n{t}");
    assert!(o.verdict.passed, "{:?}", o.verdict);
}

#[test]
fn climbing_the_default_stairs() {
    let spec = common::default_world();
    let o = run(
        &spec,
        r#"
        robot = "inspection"
        time_limit_s = 20.0
        start = { x_m = 15.1, y_m = 4.2, yaw_deg = 0.0 }
        [[waypoints]]
        x_m = 18.4
        y_m = 4.2
        speed_mps = 0.4
        tolerance_m = 0.1
        [controller]
        slowdown_m = 0.3
        [rules]
        reach_top_of_stairs = "stairs to the landing"
        no_tipping = true
        "#,
    );
    let t = timeline(&o);
    assert_eq!(of(&o, StairsClimbingStarted).len(), 1, "{t}");
    let steps: Vec<f64> = of(&o, StairsStepReached)
        .iter()
        .map(|e| e.value("step").unwrap())
        .collect();
    assert_eq!(steps, vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0], "{t}");
    assert_eq!(of(&o, StairsStepReached).last().unwrap().detail, "landing");
    assert_eq!(of(&o, StairsClimbingFinished).len(), 1, "{t}");
    let finished = of(&o, StairsClimbingFinished)[0].time_s;
    assert!(finished > of(&o, StairsStepReached).last().unwrap().time_s - 1e-9);
    for kind in [
        StairsClimbingAborted,
        WallTouched,
        RobotTipped,
        JointBroken,
        DoorFreeSpaceEntered,
    ] {
        assert!(of(&o, kind).is_empty(), "spurious {kind:?}:\n{t}");
    }
    assert!(o.verdict.passed, "{:?}", o.verdict);
    let end = o.trajectory.last().unwrap().pose;
    assert!(
        (end.z_m - (0.9 + 0.21)).abs() < 0.05,
        "on the landing: {end:?}"
    );
}

#[test]
fn driving_off_a_ledge_tips_the_robot() {
    let spec = common::world(&room(
        r#"
        [[boxes]]
        name = "platform"
        center_m = [1.5, 0.0, 0.5]
        size_m = [2.0, 2.0, 1.0]
        "#,
    ));
    let o = run(
        &spec,
        r#"
        robot = "pioneer3at"
        time_limit_s = 6.0
        start = { x_m = 1.5, y_m = 0.0, yaw_deg = 0.0, z_m = 1.0 }
        [[velocity]]
        from_s = 0.2
        to_s = 6.0
        linear_mps = 0.4
        [rules]
        no_tipping = true
        "#,
    );
    let t = timeline(&o);
    let tipped = of(&o, RobotTipped);
    assert_eq!(tipped.len(), 1, "{t}");
    assert!(tipped[0].time_s > 2.0, "{t}");
    assert!(!o.verdict.passed);
    assert!(
        o.verdict.rules[0].reason.starts_with("tipped over"),
        "{:?}",
        o.verdict
    );
}

#[test]
fn ramming_a_wall_with_the_arm_out_breaks_an_arm_joint() {
    let spec = common::world(&closed_room());
    let sc = sim::Scenario::from_toml_str(
        r#"
        robot = "inspection"
        time_limit_s = 5.0
        start = { x_m = 2.5, y_m = 0.0, yaw_deg = 0.0 }
        [[velocity]]
        from_s = 0.2
        to_s = 5.0
        linear_mps = 0.8
        [rules]
        no_broken_joint = true
        "#,
        "arm test",
    )
    .unwrap();
    // Unfold the arm straight ahead at about 0.4 m height.
    let mut model = sim::RobotModel::builtin("inspection").unwrap();
    let arm = model.arm.as_mut().unwrap();
    arm.links[0].angle_deg = 0.0;
    arm.links[1].angle_deg = 0.0;
    arm.links[2].angle_deg = 0.0;
    let o = sim::run_scenario(&spec, &sc, &model).unwrap();
    let t = timeline(&o);
    let broken = of(&o, JointBroken);
    assert!(!broken.is_empty(), "{t}");
    assert!(broken[0].detail.starts_with("arm joint"), "{t}");
    assert_eq!(broken[0].entities[0].name, "robot");
    // The arm touched the wall before the chassis could.
    assert!(has(&o, WallTouched, "walls[3]"), "{t}");
    assert!(!o.verdict.passed);
}

#[test]
fn pushing_against_a_wall_for_long_is_being_stuck() {
    let spec = common::world(&closed_room());
    let o = run(
        &spec,
        r#"
        robot = "pioneer3at"
        time_limit_s = 10.0
        start = { x_m = 5.0, y_m = 0.0, yaw_deg = 0.0 }
        [[velocity]]
        from_s = 0.2
        to_s = 10.0
        linear_mps = 0.5
        [rules]
        no_stuck = true
        "#,
    );
    let t = timeline(&o);
    let stuck = of(&o, RobotStuck);
    assert_eq!(stuck.len(), 1, "{t}");
    assert!(stuck[0].time_s > 3.0 && stuck[0].time_s < 5.0, "{t}");
    assert!(!o.verdict.passed && o.verdict.rules[0].reason.starts_with("stuck at"));
}
