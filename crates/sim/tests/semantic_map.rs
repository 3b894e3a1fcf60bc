//! A world from a semantic map (the map built from scans): the robot pushes its door open.

mod common;

use common::{has, timeline};
use sim::EventKind::*;
use sim::{SimError, WorldSpec};

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
