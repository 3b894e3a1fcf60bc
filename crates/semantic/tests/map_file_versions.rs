//! The semantic map file across versions: a version 1 file (and a version 2 one) still reads
//! as the current version, and the obstacle section version 2 added is required and
//! round-trips.

mod common;

use common::default_map;
use semantic::{EntityClass, SemanticError, SemanticMap, MAP_CLASSES, MAP_CLASSES_V1, MAP_VERSION};
use serde_json::Value;
use std::path::Path;

/// A version 1 file (written by the previous build, `tests/data/semantic_map_v1.json`: the
/// default building's map) is read, as version 2, with every entity and relation.
#[test]
fn version_1_files_are_still_read() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/semantic_map_v1.json");
    let text = std::fs::read_to_string(&path).expect("v1 file");
    let raw: Value = serde_json::from_str(&text).expect("JSON");
    assert_eq!(raw["version"], 1);
    // Version 2 knows every class version 1 knew, and obstacles, columns and beams.
    assert!(MAP_CLASSES_V1.iter().all(|c| MAP_CLASSES.contains(c)));
    for c in [
        EntityClass::Obstacle,
        EntityClass::Column,
        EntityClass::Beam,
    ] {
        assert!(MAP_CLASSES.contains(&c) && !MAP_CLASSES_V1.contains(&c));
    }
    let map = SemanticMap::load(&path).expect("a version 1 map reads");
    assert_eq!(map.version, MAP_VERSION);
    assert_eq!(
        map.entities.len(),
        raw["entities"].as_array().expect("entities").len()
    );
    assert_eq!(
        map.relations.len(),
        raw["relations"].as_array().expect("relations").len()
    );
    assert!(map.of_class(EntityClass::Wall).count() >= 8);
    assert_eq!(map.of_class(EntityClass::Stairs).count(), 1);
    // Saved again, it is a current-version file that reads back the same.
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("v3.json");
    map.save(&out).expect("save");
    let again: Value =
        serde_json::from_str(&std::fs::read_to_string(&out).expect("read")).expect("JSON");
    assert_eq!(again["version"], MAP_VERSION);
    assert_eq!(SemanticMap::load(&out).expect("v3"), map);
    // A version 2 file (no `floor` section: the floor is its box) reads as the current one.
    let mut v2 = again.clone();
    v2["version"] = Value::from(2);
    let v2 = SemanticMap::from_json_str(&v2.to_string(), Path::new("v2.json")).expect("v2");
    assert_eq!(v2.version, MAP_VERSION);
    assert!(v2.of_class(EntityClass::Floor).all(|f| f.floor.is_none()));
    // Version 1 knew no obstacles: one in a version 1 file is an unknown class.
    let mut bad = raw.clone();
    bad["entities"][0]["class"] = Value::from("obstacle");
    let err = SemanticMap::from_json_str(&bad.to_string(), Path::new("v1.json"))
        .expect_err("an obstacle in version 1");
    assert!(
        matches!(err, SemanticError::UnknownClass { ref class, .. } if class == "obstacle"),
        "{err}"
    );
}

/// An obstacle, column or beam needs its `obstacle` section; with it, it round-trips.
#[test]
fn obstacles_need_their_section_and_round_trip() {
    let map = default_map();
    let o = map
        .of_class(EntityClass::Obstacle)
        .next()
        .expect("the default building's furniture is obstacles");
    assert!(o.obstacle.as_ref().is_some_and(|i| i.hull_m.len() >= 3));
    let mut value: Value = serde_json::from_str(&map.to_json_string()).expect("JSON");
    let i = value["entities"]
        .as_array()
        .expect("array")
        .iter()
        .position(|e| e["class"] == "obstacle")
        .expect("an obstacle");
    value["entities"][i]
        .as_object_mut()
        .expect("object")
        .remove("obstacle");
    let err = SemanticMap::from_json_str(&value.to_string(), Path::new("m.json"))
        .expect_err("no obstacle section");
    assert!(matches!(err, SemanticError::InvalidEntity { .. }), "{err}");
}

/// Version 4 added ramps: a ramp reads from a version 4 file and is an unknown class in a
/// version 3 one (which knew none), naming the file.
#[test]
fn a_ramp_is_read_from_version_4_and_unknown_to_version_3() {
    let mut value: Value = serde_json::from_str(&default_map().to_json_string()).expect("JSON");
    assert_eq!(value["version"], 4);
    let mut ramp = value["entities"][0].clone();
    ramp["id"] = Value::from(10_000);
    ramp["class"] = Value::from("ramp");
    ramp["geometry"] = serde_json::json!({"center_m": [2.0, 1.0, 0.25], "size_m": [6.0, 2.0, 0.5], "yaw_deg": 90.0});
    for key in ["wall", "door", "opening", "stairs", "obstacle", "floor"] {
        ramp.as_object_mut().expect("object").remove(key);
    }
    value["entities"].as_array_mut().expect("array").push(ramp);
    let map = SemanticMap::from_json_str(&value.to_string(), Path::new("v4.json")).expect("v4");
    assert_eq!(map.of_class(EntityClass::Ramp).count(), 1);
    // A ramp steeper than 45 degrees (higher than long) is no ramp: a typed error naming it.
    let mut steep = value.clone();
    let last = steep["entities"].as_array().expect("array").len() - 1;
    steep["entities"][last]["geometry"]["size_m"] = serde_json::json!([0.2, 2.0, 0.5]);
    let err = SemanticMap::from_json_str(&steep.to_string(), Path::new("steep.json"))
        .expect_err("a ramp higher than long");
    assert!(
        matches!(err, SemanticError::InvalidEntity { id: 10_000, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("steep.json"), "{err}");
    value["version"] = Value::from(3);
    let err = SemanticMap::from_json_str(&value.to_string(), Path::new("v3.json"))
        .expect_err("a ramp in version 3");
    assert!(
        matches!(err, SemanticError::UnknownClass { ref class, .. } if class == "ramp"),
        "{err}"
    );
    assert!(err.to_string().contains("v3.json"), "{err}");
}
