//! Bad input gives clear typed errors, never a panic.

mod common;

use sim::{RobotModel, Scenario, SimError, Simulation, WorldSpec};

fn scenario(rules: &str) -> Scenario {
    Scenario::from_toml_str(
        &format!("time_limit_s = 5.0\nstart = {{ x_m = 1.5, y_m = 0.0 }}\n[rules]\n{rules}\n"),
        "test",
    )
    .unwrap()
}

#[test]
fn unknown_entity_in_a_scenario_is_named() {
    let spec = common::default_world();
    let model = RobotModel::builtin("pioneer3at").unwrap();
    let sc = scenario(r#"pass_through_door = "walls[99].doors[0]""#);
    let err = Simulation::new(&spec, &sc, &model).err().unwrap();
    match &err {
        SimError::UnknownEntity {
            element, reference, ..
        } => {
            assert_eq!(element, "test: rules.pass_through_door");
            assert_eq!(reference, "walls[99].doors[0]");
        }
        e => panic!("wrong error {e:?}"),
    }
    // The message names the scenario (its file, here the source name "test") and the reference.
    assert!(err.to_string().starts_with("test: "), "{err}");
    assert!(err.to_string().contains("walls[99].doors[0]"), "{err}");
    // A known entity of the wrong class.
    let sc = scenario(r#"reach_top_of_stairs = "corridor north""#);
    let err = Simulation::new(&spec, &sc, &model).err().unwrap();
    assert!(matches!(err, SimError::WrongEntityClass { .. }), "{err}");
    assert!(
        err.to_string().contains("is a wall, expected stairs"),
        "{err}"
    );
}

#[test]
fn entities_resolve_by_id_name_opening_and_label() {
    let spec = common::default_world();
    let by_name = spec.resolve("walls[4].doors[2].leaf", "t").unwrap();
    assert_eq!(spec.resolve("walls[4].doors[2]", "t").unwrap(), by_name);
    assert_eq!(spec.resolve(&by_name.id.to_string(), "t").unwrap(), by_name);
    assert_eq!(
        spec.resolve("corridor north, door 2", "t").unwrap(),
        by_name
    );
    assert_eq!(
        spec.resolve("stairs to the landing", "t").unwrap().name,
        "stairs[0]"
    );
    // By location: the nearest opening (its leaf) or staircase, in either world.
    assert_eq!(spec.resolve("door@14.5,1.3", "t").unwrap(), by_name);
    assert_eq!(
        spec.resolve("stairs@17.0,4.0", "t").unwrap().name,
        "stairs[0]"
    );
    for bad in ["door@14.6", "door@x,1", "window@1,1", "door@100,100"] {
        let e = spec.resolve(bad, "rules.open_door").unwrap_err();
        assert!(matches!(e, SimError::UnknownEntity { .. }), "{bad}: {e}");
    }
    // An opening without a leaf resolves to its free space.
    assert_eq!(
        spec.resolve("walls[5].doors[1]", "t").unwrap().name,
        "walls[5].doors[1].free_space"
    );
}

#[test]
fn door_with_no_wall() {
    let mut spec = common::default_world();
    let furniture = spec
        .fixed
        .iter()
        .find(|f| f.class == sim::EntityClass::Furniture)
        .unwrap()
        .entity;
    spec.doors[0].wall = furniture;
    let err = spec.validate().err().unwrap();
    assert!(
        matches!(err, SimError::DoorWithoutWall { wall, .. } if wall == furniture),
        "{err}"
    );
    spec.doors[0].wall = 9999;
    let json = serde_json::to_string(&spec).unwrap();
    let err = WorldSpec::from_json_str(&json, "spec.json").err().unwrap();
    assert!(
        err.to_string().contains("is not a wall of this world"),
        "{err}"
    );
}

#[test]
fn bad_numbers_in_a_world_spec() {
    let mut spec = common::default_world();
    spec.fixed[3].geometry.center_m[0] = f64::NAN;
    assert!(matches!(spec.validate(), Err(SimError::NonFinite { .. })));
    let mut spec = common::default_world();
    spec.fixed[3].geometry.half_extents_m[2] = 1.0e6;
    assert!(matches!(spec.validate(), Err(SimError::OutOfRange { .. })));
    let mut spec = common::default_world();
    spec.free_spaces[0].door = Some(4242);
    assert!(matches!(
        spec.validate(),
        Err(SimError::UnknownEntity { .. })
    ));
    let mut spec = common::default_world();
    spec.doors[0].hinge_m[0] += 0.5;
    assert!(matches!(spec.validate(), Err(SimError::Invalid { .. })));
}

#[test]
fn negative_or_nan_time_limit() {
    for limit in ["-5.0", "nan", "0.0"] {
        let err = Scenario::from_toml_str(
            &format!("time_limit_s = {limit}\nstart = {{ x_m = 0.0, y_m = 0.0 }}\n"),
            "t",
        )
        .err()
        .unwrap();
        assert!(
            matches!(&err, SimError::OutOfRange { field, .. } | SimError::NonFinite { field, .. } if field == "time_limit_s"),
            "{limit}: {err}"
        );
    }
}

#[test]
fn unknown_fields_are_syntax_errors_naming_the_field() {
    let text = include_str!("../data/pioneer3at.toml").replace("[drive]", "[drive]\nturbo = true");
    let err = RobotModel::from_toml_str(&text, "my_robot.toml")
        .err()
        .unwrap();
    assert!(matches!(err, SimError::Syntax { .. }), "{err}");
    let msg = err.to_string();
    assert!(
        msg.contains("my_robot.toml") && msg.contains("turbo"),
        "{msg}"
    );
    let err = Scenario::from_toml_str(
        "time_limit_s = 5.0\nstart = { x_m = 0.0, y_m = 0.0 }\nspeed = 3\n",
        "s.toml",
    )
    .err()
    .unwrap();
    assert!(err.to_string().contains("speed"), "{err}");
}

#[test]
fn bad_robot_models() {
    let err = RobotModel::resolve("roomba", std::path::Path::new("."))
        .err()
        .unwrap();
    assert!(matches!(err, SimError::UnknownRobotModel { .. }));
    assert!(err.to_string().contains("pioneer3at, inspection"), "{err}");
    let one_side = include_str!("../data/pioneer3at.toml").replace("-0.2, -0.06]", "0.2, -0.06]");
    let err = RobotModel::from_toml_str(&one_side, "t").err().unwrap();
    assert!(err.to_string().contains("both sides"), "{err}");
    let heavy = include_str!("../data/pioneer3at.toml").replace("mass_kg = 10.0", "mass_kg = -1.0");
    assert!(matches!(
        RobotModel::from_toml_str(&heavy, "t"),
        Err(SimError::OutOfRange { .. })
    ));
}
