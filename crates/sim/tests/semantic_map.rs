//! A world from a semantic map (the map built from scans): the robot pushes its door open.

mod common;

use common::{has, timeline};
use sim::EventKind::*;
use sim::{EventKind, SimError, WorldSpec};

/// An east wall at x = 6 with a closed 0.9 m door (y -0.5 .. 0.4) opening away from x < 6.
fn map_json(relations: &str) -> String {
    fixtures::door_wall_map_json("right", 0.0, relations)
}

const RELATIONS: &str = fixtures::DOOR_RELATIONS;

#[test]
fn a_semantic_map_world_with_a_door_to_push() {
    let map = semantic::SemanticMap::from_json_str(
        &map_json(RELATIONS),
        std::path::Path::new("map.json"),
    )
    .unwrap();
    let spec = WorldSpec::from_semantic_map(&map).unwrap();
    assert_eq!(spec.doors.len(), 1);
    assert_eq!(spec.doors[0].wall, 3);
    assert_eq!(spec.free_spaces[0].door, Some(5));
    assert_eq!(
        spec.fixed.iter().filter(|f| f.entity == 3).count(),
        2,
        "wall from its solid boxes"
    );
    let o = common::run(
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
        pass_through_door = "door_5"
        open_door = "5"
        "#,
    );
    let t = timeline(&o);
    assert!(has(&o, DoorOpened, "door_5"), "{t}");
    assert!(
        has(&o, DoorFreeSpaceEntered, "free_space_for_door_6"),
        "{t}"
    );
    assert!(o.verdict.passed, "{:?}\n{t}", o.verdict);
}

#[test]
fn a_semantic_door_not_jointed_to_a_wall_is_an_error() {
    let relations =
        r#"{"type":"available_inside","a":6,"b":3},{"type":"available_inside","a":5,"b":6}"#;
    let map = semantic::SemanticMap::from_json_str(
        &map_json(relations),
        std::path::Path::new("map.json"),
    )
    .unwrap();
    let err = WorldSpec::from_semantic_map(&map).err().unwrap();
    assert!(
        matches!(&err, SimError::DoorWithoutWall { door, .. } if door == "door_5"),
        "{err}"
    );
}

#[test]
fn semantic_map_file_errors_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let relations =
        r#"{"type":"available_inside","a":6,"b":3},{"type":"available_inside","a":5,"b":6}"#;
    let path = dir.path().join("map.json");
    std::fs::write(&path, map_json(relations)).unwrap();
    let err = WorldSpec::from_semantic_map_file(&path).err().unwrap();
    assert!(
        matches!(&err, SimError::DoorWithoutWall { door, .. } if door == "door_5"),
        "{err}"
    );
    assert_eq!(
        err.to_string(),
        format!(
            "{}: door door_5: its wall (entity 0) is not a wall of this world",
            path.display()
        )
    );
    // A good map loads; a missing one is the semantic crate's error, naming it.
    std::fs::write(&path, map_json(RELATIONS)).unwrap();
    assert_eq!(
        WorldSpec::from_semantic_map_file(&path)
            .unwrap()
            .doors
            .len(),
        1
    );
    let missing = dir.path().join("nothing.json");
    let err = WorldSpec::from_semantic_map_file(&missing).err().unwrap();
    assert!(err.to_string().contains("nothing.json"), "{err}");
}

/// A map's ramp (version 4) is a slope the robot drives up: from the floor at its foot
/// (x = 2) to 0.5 m at its head (x = 8), 2 m wide.
#[test]
fn the_robot_drives_up_a_mapped_ramp() {
    let identity = "[1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0]";
    let entity = |id: u32, class: &str, c: [f64; 3], s: [f64; 3]| {
        format!(
            r#"{{"id":{id},"class":"{class}","geometry":{{"center_m":{c:?},"size_m":{s:?},"yaw_deg":0.0}},"support_points":1000,"confidence":0.9,"rules":["test"]}}"#
        )
    };
    let text = format!(
        r#"{{"format":"semsim.semantic_map","version":4,"input_from_map":{identity},"entities":[{},{}],"relations":[]}}"#,
        entity(1, "floor", [5.0, 0.0, -0.1], [12.0, 6.0, 0.2]),
        entity(2, "ramp", [5.0, 0.0, 0.25], [6.0, 2.0, 0.5]),
    );
    let map =
        semantic::SemanticMap::from_json_str(&text, std::path::Path::new("map.json")).unwrap();
    let spec = WorldSpec::from_semantic_map(&map).unwrap();
    let blocks: Vec<_> = spec.fixed.iter().filter(|f| f.entity == 2).collect();
    assert_eq!(blocks.len(), 50, "one block per centimetre of rise");
    let o = common::run(
        &spec,
        r#"
        robot = "pioneer3at"
        time_limit_s = 20.0
        start = { x_m = 0.5, y_m = 0.0, yaw_deg = 0.0 }
        [[waypoints]]
        x_m = 7.4
        y_m = 0.0
        speed_mps = 0.5
        tolerance_m = 0.15
        [rules]
        no_tipping = true
        reach_top_of_ramps = ["2"]
        "#,
    );
    let t = timeline(&o);
    // The climb is an event, and the wheels on the ramp are no collision with it.
    let on_ramp = |kind: EventKind| o.events.iter().any(|e| e.kind == kind && e.involves(2));
    assert!(on_ramp(EventKind::RampClimbingStarted), "{t}");
    assert!(on_ramp(EventKind::RampClimbingFinished), "{t}");
    assert!(!on_ramp(EventKind::CollisionStarted), "{t}");
    let (first, last) = (o.trajectory[0].pose, o.trajectory.last().unwrap().pose);
    assert!(last.x_m > 7.0, "drove up: {last:?}\n{t}");
    // At x = 7.4 the ramp's top is 0.45 m up: the robot stands that much higher.
    let climbed = last.z_m - first.z_m;
    assert!((climbed - 0.45).abs() < 0.05, "climbed {climbed} m\n{t}");
    assert!(o.verdict.passed, "{:?}\n{t}", o.verdict);
}

/// A map's floor is where the scans saw it, and a low laser rarely sees the floor at a ramp's
/// foot: here the seen floor ends 1 m before the ramp (x 2..8). The world's floor runs under
/// the ramp and `ramp_apron_m` (1 m) before its foot, so the planned tour reaches the foot and
/// drives up; without the apron the ramp is listed with the reason.
#[test]
fn the_floor_runs_under_a_mapped_ramp_and_before_its_foot() {
    let identity = "[1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0]";
    let b =
        |c: [f64; 3], s: [f64; 3]| format!(r#"{{"center_m":{c:?},"size_m":{s:?},"yaw_deg":0.0}}"#);
    let floor = format!(
        r#"{{"id":1,"class":"floor","geometry":{},"support_points":1000,"confidence":0.9,"rules":["test"],"floor":{{"parts":[{}],"coverage":1.0}}}}"#,
        b([-1.0, 0.0, -0.1], [4.0, 4.0, 0.2]),
        b([-1.0, 0.0, -0.1], [4.0, 4.0, 0.2]),
    );
    let ramp = format!(
        r#"{{"id":2,"class":"ramp","geometry":{},"support_points":1000,"confidence":0.9,"rules":["test"]}}"#,
        b([5.0, 0.0, 0.25], [6.0, 2.0, 0.5])
    );
    let text = format!(
        r#"{{"format":"semsim.semantic_map","version":4,"input_from_map":{identity},"entities":[{floor},{ramp}],"relations":[]}}"#
    );
    let map =
        semantic::SemanticMap::from_json_str(&text, std::path::Path::new("map.json")).unwrap();
    let model = sim::RobotModel::builtin("pioneer3at").unwrap();
    let plan = sim::PlanConfig::default();
    let spec = WorldSpec::from_semantic_map(&map).unwrap();
    let p = sim::plan_scenario(&spec, &model, None, &plan).unwrap();
    assert_eq!(p.tour, vec![sim::Goal::Ramp("ramp_2".into())], "{p:?}");
    let o = sim::run_scenario(&spec, &p.scenario, &model).unwrap();
    assert!(o.verdict.passed, "{:#?}\n{}", o.verdict.rules, timeline(&o));
    // Without the apron the seen floor (x -3..1) stops 1 m short of the foot.
    let cfg = sim::ImportConfig {
        ramp_apron_m: 0.0,
        ..sim::ImportConfig::default()
    };
    let bare = WorldSpec::from_semantic_map_with(&map, &cfg).unwrap();
    let p = sim::plan_scenario(&bare, &model, None, &plan).unwrap();
    assert!(p.tour.is_empty(), "{p:?}");
    assert!(
        p.unreachable[0]
            .reason
            .starts_with("no floor in the world before the foot"),
        "{:?}",
        p.unreachable
    );
}
