//! The semantic map file: serde round trip, atomic save, structural validation against
//! `schema/semantic_map.schema.json`, and typed errors for bad files. Older file versions and
//! the obstacle section are in `map_file_versions.rs`.

mod common;

use common::default_map;
use semantic::{EntityClass, SemanticError, SemanticMap, MAP_CLASSES_V1};
use serde_json::Value;
use std::path::Path;

/// A small JSON Schema checker for the keywords the schema uses: type, const, enum, required,
/// properties, additionalProperties (false), items, minItems, maxItems, minimum, maximum,
/// anyOf and local $ref.
fn check(schema: &Value, root: &Value, v: &Value, at: &str, errors: &mut Vec<String>) {
    if let Some(r) = schema.get("$ref").and_then(Value::as_str) {
        let path = r.trim_start_matches("#/");
        let target = path.split('/').fold(root, |s, k| &s[k]);
        return check(target, root, v, at, errors);
    }
    if let Some(any) = schema.get("anyOf").and_then(Value::as_array) {
        let ok = any.iter().any(|s| {
            let mut e = Vec::new();
            check(s, root, v, at, &mut e);
            e.is_empty()
        });
        if !ok {
            errors.push(format!("{at}: matches none of anyOf"));
        }
        return;
    }
    if let Some(c) = schema.get("const") {
        if c != v {
            errors.push(format!("{at}: {v} is not {c}"));
        }
    }
    if let Some(e) = schema.get("enum").and_then(Value::as_array) {
        if !e.contains(v) {
            errors.push(format!("{at}: {v} not in enum"));
        }
    }
    if let Some(t) = schema.get("type").and_then(Value::as_str) {
        let ok = match t {
            "object" => v.is_object(),
            "array" => v.is_array(),
            "number" => v.is_number(),
            "integer" => v.is_i64() || v.is_u64(),
            "string" => v.is_string(),
            "boolean" => v.is_boolean(),
            "null" => v.is_null(),
            _ => false,
        };
        if !ok {
            errors.push(format!("{at}: expected {t}, found {v}"));
            return;
        }
    }
    if let (Some(min), Some(x)) = (schema.get("minimum").and_then(Value::as_f64), v.as_f64()) {
        if x < min {
            errors.push(format!("{at}: {x} < {min}"));
        }
    }
    if let (Some(max), Some(x)) = (schema.get("maximum").and_then(Value::as_f64), v.as_f64()) {
        if x > max {
            errors.push(format!("{at}: {x} > {max}"));
        }
    }
    if let Some(obj) = v.as_object() {
        for key in schema
            .get("required")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
        {
            let key = key.as_str().unwrap_or_default();
            if !obj.contains_key(key) {
                errors.push(format!("{at}: missing required {key:?}"));
            }
        }
        let props = schema.get("properties").and_then(Value::as_object);
        for (k, val) in obj {
            match props.and_then(|p| p.get(k)) {
                Some(s) => check(s, root, val, &format!("{at}.{k}"), errors),
                None if schema.get("additionalProperties") == Some(&Value::Bool(false)) => {
                    errors.push(format!("{at}: unexpected key {k:?}"))
                }
                None => {}
            }
        }
    }
    if let Some(arr) = v.as_array() {
        if let Some(n) = schema.get("minItems").and_then(Value::as_u64) {
            if (arr.len() as u64) < n {
                errors.push(format!("{at}: fewer than {n} items"));
            }
        }
        if let Some(n) = schema.get("maxItems").and_then(Value::as_u64) {
            if (arr.len() as u64) > n {
                errors.push(format!("{at}: more than {n} items"));
            }
        }
        if let Some(items) = schema.get("items") {
            for (i, x) in arr.iter().enumerate() {
                check(items, root, x, &format!("{at}[{i}]"), errors);
            }
        }
    }
}

fn schema() -> Value {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("schema/semantic_map.schema.json"),
    )
    .expect("schema file");
    serde_json::from_str(&text).expect("schema is JSON")
}

#[test]
fn output_validates_against_the_schema_and_holds_every_class() {
    let map = default_map();
    // The default building has no columns or beams; its furniture is obstacles.
    for class in MAP_CLASSES_V1.into_iter().chain([EntityClass::Obstacle]) {
        assert!(
            map.of_class(class).count() > 0,
            "no {} in the default building's map",
            class.name()
        );
    }
    let schema = schema();
    let value: Value = serde_json::from_str(&map.to_json_string()).expect("JSON");
    let mut errors = Vec::new();
    check(&schema, &schema, &value, "$", &mut errors);
    assert!(errors.is_empty(), "schema violations: {errors:#?}");
    // The checker does catch violations.
    let mut bad = value.clone();
    bad["entities"][0]["class"] = Value::from("window");
    bad["entities"][0]["confidence"] = Value::from(1.5);
    bad["relations"][0]["extra"] = Value::from(1);
    let mut errors = Vec::new();
    check(&schema, &schema, &bad, "$", &mut errors);
    assert_eq!(errors.len(), 3, "{errors:#?}");
}

#[test]
fn save_and_load_round_trip_atomically() {
    let map = default_map();
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("map.json");
    map.save(&path).expect("saves");
    let back = SemanticMap::load(&path).expect("loads");
    assert_eq!(&back, map);
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .expect("dir")
        .map(|e| e.expect("entry").file_name())
        .collect();
    assert_eq!(names.len(), 1, "left behind: {names:?}");
    // Saving into a missing folder fails cleanly.
    assert!(matches!(
        map.save(&dir.path().join("no/such/map.json")),
        Err(SemanticError::Cloud(_))
    ));
}

#[test]
fn pngs_are_written_atomically() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("a.png");
    semantic::save_png(&path, image::GrayImage::new(4, 3)).expect("writes");
    let back = image::open(&path).expect("reads").to_luma8();
    assert_eq!(back.dimensions(), (4, 3));
    assert!(semantic::save_png(
        &dir.path().join("no/such/b.png"),
        image::RgbImage::new(2, 2)
    )
    .is_err());
}

#[test]
fn bad_files_give_typed_errors() {
    let map = default_map();
    let text = map.to_json_string();
    let path = Path::new("bad.json");
    let edit = |f: &dyn Fn(&mut Value)| {
        let mut v: Value = serde_json::from_str(&text).expect("JSON");
        f(&mut v);
        SemanticMap::from_json_str(&v.to_string(), path)
    };
    let err =
        edit(&|v| v["entities"][2]["class"] = Value::from("window")).expect_err("unknown class");
    assert!(
        matches!(&err, SemanticError::UnknownClass { index: 2, class, .. } if class == "window"),
        "{err}"
    );
    assert!(
        err.to_string().contains("bad.json") && err.to_string().contains("wall_above_door"),
        "{err}"
    );
    // A class of the workspace's vocabulary that no map entity has (a point label's).
    let err = edit(&|v| v["entities"][2]["class"] = Value::from("furniture"))
        .expect_err("furniture is no map class");
    assert!(
        matches!(&err, SemanticError::UnknownClass { index: 2, class, .. } if class == "furniture")
            && err.to_string().contains("bad.json"),
        "{err}"
    );
    let err = edit(&|v| v["relations"][0]["type"] = Value::from("adjacent"))
        .expect_err("unknown relation");
    assert!(
        matches!(&err, SemanticError::UnknownRelation { index: 0, kind, .. } if kind == "adjacent"),
        "{err}"
    );
    let err = edit(&|v| v["relations"][1]["b"] = Value::from(9999)).expect_err("dangling id");
    assert!(
        matches!(
            err,
            SemanticError::DanglingId {
                index: 1,
                id: 9999,
                ..
            }
        ),
        "{err}"
    );
    let err = edit(&|v| v["format"] = Value::from("something else")).expect_err("format");
    assert!(matches!(err, SemanticError::WrongFormat { .. }), "{err}");
    let err = edit(&|v| v["version"] = Value::from(5)).expect_err("version");
    assert!(
        matches!(err, SemanticError::UnsupportedVersion { found: 5, .. }),
        "{err}"
    );
    let err = edit(&|v| v["entities"][1]["id"] = v["entities"][0]["id"].clone())
        .expect_err("duplicate id");
    assert!(
        matches!(err, SemanticError::BadId { index: 1, .. }),
        "{err}"
    );
    let err = edit(&|v| {
        let i = v["entities"]
            .as_array()
            .expect("array")
            .iter()
            .position(|e| e["class"] == "wall")
            .expect("a wall");
        v["entities"][i]
            .as_object_mut()
            .expect("object")
            .remove("wall");
    })
    .expect_err("wall without its section");
    assert!(
        matches!(err, SemanticError::InvalidEntity { class: "wall", .. }),
        "{err}"
    );
    let err = SemanticMap::from_json_str("{ not json", path).expect_err("syntax");
    assert!(matches!(err, SemanticError::Syntax { .. }), "{err}");
    let err = SemanticMap::load(Path::new("/nonexistent/map.json")).expect_err("missing file");
    assert!(matches!(err, SemanticError::Cloud(_)), "{err}");
}

#[test]
fn the_net_relates_doors_to_their_walls() {
    use semantic::RelationType as R;
    let map = default_map();
    for door in map.of_class(EntityClass::Door) {
        let joint: Vec<_> = map
            .relations_of(R::ConnectedViaJoint)
            .filter(|r| r.a == door.id)
            .collect();
        assert_eq!(joint.len(), 1, "door {} has no hinge relation", door.id);
        let wall = map.entity(joint[0].b).expect("exists");
        assert_eq!(wall.class, EntityClass::Wall);
        let info = door.door.as_ref().expect("door section");
        // The hinge lies on the wall's centre line, at an edge of the closed leaf.
        let seg = wall.wall.as_ref().expect("wall section").segment_m;
        let (a, b) = (
            glam::DVec2::from_array(seg[0]),
            glam::DVec2::from_array(seg[1]),
        );
        let h = glam::DVec2::new(info.hinge_m[0], info.hinge_m[1]);
        let off = (h - a).perp_dot((b - a).normalize()).abs();
        assert!(off < 0.01, "hinge {off} m off its wall's centre line");
        let corners = door.geometry.corners_xy();
        let edge = |i: usize, j: usize| {
            glam::DVec2::from_array(corners[i]).lerp(glam::DVec2::from_array(corners[j]), 0.5)
        };
        assert!(
            edge(0, 3).distance(h).min(edge(1, 2).distance(h)) < 0.01,
            "hinge not at a leaf edge"
        );
        // The leaf is available inside a free space, under a lintel.
        assert!(map.relations_of(R::AvailableInside).any(|r| r.a == door.id
            && map
                .entity(r.b)
                .is_some_and(|e| e.class == EntityClass::FreeSpaceForDoor)));
    }
    let walls: Vec<_> = map.of_class(EntityClass::Wall).collect();
    let pairs = walls.len() * (walls.len() - 1) / 2;
    let related = map.relations_of(R::Parallel).count() + map.relations_of(R::Orthogonal).count();
    assert_eq!(
        related, pairs,
        "the default building is rectilinear: every wall pair is parallel or orthogonal"
    );
    for s in map.of_class(EntityClass::Stairs) {
        let info = s.stairs.as_ref().expect("stairs section");
        assert_eq!(info.steps.len() as u32, info.step_count);
        for (k, step) in info.steps.iter().enumerate() {
            let top = step.z_range_m()[1];
            assert!(
                (top - info.start_m[2] - info.rise_m * (k + 1) as f64).abs() < 1e-6,
                "step {k} top"
            );
        }
    }
}
