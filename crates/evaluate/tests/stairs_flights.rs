//! Staircases against ground truth (issue #15): a straight staircase with a landing half-way,
//! described as two `[[stairs]]` flights (the second with `base_m`), is found as its two
//! flights with their exact step counts and the second's foot on the landing; and a straight
//! flight scanned with the realistic laser (mixed pixels floating in front of every step's
//! edge, range noise, dropouts) keeps its exact step count, with no false staircase.

use evaluate::{evaluate, Evaluation};
use fixtures::RoomToml;
use glam::Vec3;
use scanner::{Building, BuildingGeometry, LaserConfig, ScanPose};
use semantic::{build_semantic_map, EntityClass, SemanticConfig, SemanticMap};

/// Rise and run of the test flights (m).
const RISE: f64 = 0.17;
const RUN: f64 = 0.28;

/// A 9 m x 5 m room, 3 m high, with `stairs` (TOML) along its north wall.
fn room(stairs: &str) -> Building {
    let toml = RoomToml::new([0.0, -2.5], [9.0, 2.5], 3.0).toml(stairs);
    Building::from_toml_str(&toml, std::path::Path::new("stairs.toml")).expect("test building")
}

/// Poses every 1.5 m where the laser stands clear of everything.
fn poses(g: &BuildingGeometry) -> Vec<ScanPose> {
    let mut out = Vec::new();
    for i in 0..6 {
        for j in 0..3 {
            let (x, y) = (0.75 + 1.5 * i as f64, -1.75 + 1.5 * j as f64);
            let clear = [0.1f32, 0.5, 1.0].iter().all(|&z| {
                g.entity_containing(Vec3::new(x as f32, y as f32, z))
                    .is_none()
            });
            if clear {
                out.push(ScanPose {
                    x_m: x,
                    y_m: y,
                    yaw_deg: 0.0,
                });
            }
        }
    }
    out
}

/// The building scanned with `laser`, mapped and scored against what the scans saw.
fn map_and_score(b: &Building, laser: &LaserConfig) -> (SemanticMap, Evaluation) {
    let g = BuildingGeometry::new(b);
    let cloud = fixtures::scan_building(b, &poses(&g), laser, 0.03);
    let out = build_semantic_map(&cloud, &SemanticConfig::default()).expect("map");
    let ev = evaluate(&out.map, b, Some(&cloud));
    (out.map, ev)
}

/// Where the upper of the two test flights starts: four runs and a 1.1 m landing on (m).
const SECOND_X: f64 = 1.0 + 4.0 * RUN + 1.1;

/// A straight staircase with a landing half-way: two flights of 4 steps along +x (TOML).
fn two_flights_toml() -> String {
    let base = 4.0 * RISE;
    format!(
        r#"
[[stairs]]
name = "flight 1"
start_m = [1.0, 1.4]
direction_deg = 0.0
steps = 4
rise_m = {RISE}
run_m = {RUN}
width_m = 1.0
landing_m = 1.1

[[stairs]]
name = "flight 2"
start_m = [{SECOND_X}, 1.4]
direction_deg = 0.0
steps = 4
rise_m = {RISE}
run_m = {RUN}
width_m = 1.0
landing_m = 1.0
base_m = {base}
"#
    )
}

#[test]
fn a_staircase_with_a_mid_landing_is_found_as_its_two_flights() {
    let base = 4.0 * RISE;
    let b = room(&two_flights_toml());
    let (map, ev) = map_and_score(&b, &fixtures::test_laser());
    assert_eq!(ev.stairs.expected, 2, "{ev:#?}");
    assert_eq!(ev.stairs.detected, 2, "no false staircase: {ev:#?}");
    // Every step of both flights was seen (tread, riser or the top edge of its side).
    assert_eq!(ev.stairs_seen.len(), 2, "{ev:#?}");
    assert!(
        ev.stairs_seen.iter().all(|s| s.steps_seen == s.steps),
        "{:?}",
        ev.stairs_seen
    );
    for m in &ev.stairs_matches {
        assert_eq!(m.steps, m.steps_truth, "{m:?}");
        // (within a run: the first front edge of a flight seen from its side is the edge
        // between its first level and the floor or landing, sampled sparsely)
        assert!(m.start_error_m <= RUN, "{m:?}");
        assert!(m.base_error_m.abs() <= 0.04, "{m:?}");
    }
    // The upper flight's foot stands on the landing; its step boxes reach its treads.
    let upper = map
        .of_class(EntityClass::Stairs)
        .filter_map(|e| e.stairs.as_ref())
        .find(|s| s.start_m[2] > 0.3)
        .expect("the upper flight");
    assert!((upper.start_m[2] - base).abs() <= 0.04, "{upper:?}");
    let top = upper.steps.last().expect("steps").z_range_m()[1];
    assert!((top - 8.0 * RISE).abs() <= 0.05, "top {top}");
}

/// Regression: a cupboard standing right beyond the upper flight's top landing rose above the
/// staircase's top in its profile: the top taken there counted 7 steps where 4 were seen, and
/// the staircase was lost. The upper flight now ends at the far edge of its top landing.
#[test]
fn a_cupboard_beyond_the_top_landing_leaves_the_flights_their_step_counts() {
    let cupboard_x = SECOND_X + 4.0 * RUN + 1.0 + 0.25;
    let b = room(&format!(
        r#"{}
[[boxes]]
name = "cupboard"
class = "obstacle"
center_m = [{cupboard_x}, 1.4, 0.9]
size_m = [0.5, 1.0, 1.8]
yaw_deg = 0.0
"#,
        two_flights_toml()
    ));
    let (_, ev) = map_and_score(&b, &fixtures::test_laser());
    assert_eq!(ev.stairs.expected, 2, "{ev:#?}");
    assert_eq!(ev.stairs.matched, 2, "{ev:#?}");
    assert_eq!(ev.stairs.detected, 2, "no false staircase: {ev:#?}");
    for m in &ev.stairs_matches {
        assert_eq!(m.steps, m.steps_truth, "{m:?}");
    }
}

/// Regression: a cupboard beyond a single flight's top landing, standing less than a flight's
/// worth of rises above it, was no landing's climb, so the flight's profile reached the
/// cupboard's top and counted steps it does not have; the flight was lost.
#[test]
fn a_cupboard_beyond_a_single_flights_top_landing_leaves_its_step_count() {
    let steps = 7;
    let cupboard_x = 1.5 + steps as f64 * RUN + 1.0 + 0.25;
    let top = steps as f64 * RISE;
    let b = room(&format!(
        r#"
[[stairs]]
name = "stairs"
start_m = [1.5, 1.4]
direction_deg = 0.0
steps = {steps}
rise_m = {RISE}
run_m = {RUN}
width_m = 1.0
landing_m = 1.0

[[boxes]]
name = "cupboard"
class = "obstacle"
center_m = [{cupboard_x}, 1.4, {h}]
size_m = [0.5, 1.0, {size}]
yaw_deg = 0.0
"#,
        h = (top + 0.25) / 2.0,
        size = top + 0.25,
    ));
    let (_, ev) = map_and_score(&b, &fixtures::test_laser());
    assert_eq!(ev.stairs.expected, 1, "{ev:#?}");
    assert_eq!(ev.stairs.matched, 1, "{ev:#?}");
    assert_eq!(ev.stairs.detected, 1, "no false staircase: {ev:#?}");
    assert_eq!(ev.stairs_matches[0].steps, steps, "{:?}", ev.stairs_matches);
}

#[test]
fn a_flight_scanned_with_the_realistic_laser_keeps_its_exact_step_count() {
    let b = room(&format!(
        r#"
[[stairs]]
name = "stairs"
start_m = [1.5, 1.35]
direction_deg = 0.0
steps = 7
rise_m = {RISE}
run_m = {RUN}
width_m = 1.1
landing_m = 1.0
"#
    ));
    let laser = fixtures::real_test_laser();
    let (_, ev) = map_and_score(&b, &laser);
    assert_eq!(ev.stairs.expected, 1, "{ev:#?}");
    assert_eq!(ev.stairs.detected, 1, "no false staircase: {ev:#?}");
    let m = &ev.stairs_matches[0];
    assert_eq!(m.steps, 7, "{m:?}");
    assert!(m.direction_error_deg <= 2.0, "{m:?}");
}
