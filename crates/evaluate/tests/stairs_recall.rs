//! Staircases found by the realistic laser (issue #15, recall): a staircase standing free in a
//! big hall, seen only from scan positions metres away (sparse treads at grazing angles, mixed
//! pixels between its edges and the wall behind it, stray returns above its top), is found with
//! its exact step count; and furniture whose parts stand at step heights (a desk's top, a chair's
//! seat and back, a box) is still no staircase.

use evaluate::{evaluate, Evaluation};
use fixtures::RoomToml;
use glam::Vec3;
use scanner::{Building, BuildingGeometry, ScanPose};
use semantic::{build_semantic_map, SemanticConfig};

/// A 20 m x 12 m hall, 3.5 m high, holding `extra` (TOML).
fn hall(extra: &str) -> Building {
    let toml = RoomToml::new([0.0, 0.0], [20.0, 12.0], 3.5).toml(extra);
    Building::from_toml_str(&toml, std::path::Path::new("hall.toml")).expect("test building")
}

/// Poses on a 3 m grid at least `clear_m` from `(x, y)`, where the laser stands clear.
fn poses_away_from(g: &BuildingGeometry, x: f64, y: f64, clear_m: f64) -> Vec<ScanPose> {
    let mut out = Vec::new();
    for i in 0..7 {
        for j in 0..4 {
            let (px, py) = (1.0 + 3.0 * i as f64, 1.5 + 3.0 * j as f64);
            let free = [0.1f32, 0.5, 1.0].iter().all(|&z| {
                g.entity_containing(Vec3::new(px as f32, py as f32, z))
                    .is_none()
            });
            if free && (px - x).hypot(py - y) >= clear_m {
                out.push(ScanPose {
                    x_m: px,
                    y_m: py,
                    yaw_deg: 0.0,
                });
            }
        }
    }
    out
}

/// The building scanned with the realistic laser from `poses`, mapped and scored.
fn scan_map_score(b: &Building, poses: &[ScanPose]) -> Evaluation {
    let laser = fixtures::real_test_laser();
    let cloud = fixtures::scan_building(b, poses, &laser, 0.03);
    let out = build_semantic_map(&cloud, &SemanticConfig::default()).expect("map");
    evaluate(&out.map, b, Some(&cloud))
}

#[test]
fn a_free_standing_staircase_in_a_hall_seen_from_far_keeps_its_exact_step_count() {
    // Climbing west, 0.45 m in front of the south wall (a hall's staircase to a gallery).
    let b = hall(
        r#"
[[stairs]]
name = "stairs"
start_m = [15.0, 1.0]
direction_deg = 180.0
steps = 5
rise_m = 0.16
run_m = 0.30
width_m = 1.1
landing_m = 1.0
"#,
    );
    let g = BuildingGeometry::new(&b);
    let poses = poses_away_from(&g, 13.5, 1.0, 4.0);
    assert!(poses.len() >= 10, "{} poses", poses.len());
    let ev = scan_map_score(&b, &poses);
    assert_eq!(ev.stairs.expected, 1, "{ev:#?}");
    assert_eq!(ev.stairs.detected, 1, "no false staircase: {ev:#?}");
    let m = &ev.stairs_matches[0];
    assert_eq!(m.steps, 5, "{m:?}");
    assert!(m.direction_error_deg <= 5.0, "{m:?}");
}

#[test]
fn a_desk_and_a_chair_at_step_heights_are_no_staircase() {
    // A desk (top at 0.73 m on four legs) with a chair (seat 0.45 m, back to 0.87 m) in front
    // of it and a box (0.39 m) beside it: along the row they climb 0.39, 0.45, 0.73, 0.87 m.
    let b = hall(
        r#"
[[boxes]]
name = "desk top"
center_m = [10.16, 6.0, 0.71]
size_m = [0.72, 1.36, 0.04]
[[boxes]]
name = "desk leg 1"
center_m = [9.85, 5.37, 0.35]
size_m = [0.05, 0.05, 0.69]
[[boxes]]
name = "desk leg 2"
center_m = [10.47, 5.37, 0.35]
size_m = [0.05, 0.05, 0.69]
[[boxes]]
name = "desk leg 3"
center_m = [9.85, 6.63, 0.35]
size_m = [0.05, 0.05, 0.69]
[[boxes]]
name = "desk leg 4"
center_m = [10.47, 6.63, 0.35]
size_m = [0.05, 0.05, 0.69]
[[boxes]]
name = "chair seat"
center_m = [9.5, 6.0, 0.43]
size_m = [0.45, 0.45, 0.04]
[[boxes]]
name = "chair back"
center_m = [9.7, 6.0, 0.67]
size_m = [0.04, 0.45, 0.4]
[[boxes]]
name = "chair leg 1"
center_m = [9.31, 5.81, 0.21]
size_m = [0.04, 0.04, 0.41]
[[boxes]]
name = "chair leg 2"
center_m = [9.68, 5.81, 0.21]
size_m = [0.04, 0.04, 0.41]
[[boxes]]
name = "chair leg 3"
center_m = [9.31, 6.18, 0.21]
size_m = [0.04, 0.04, 0.41]
[[boxes]]
name = "chair leg 4"
center_m = [9.68, 6.18, 0.21]
size_m = [0.04, 0.04, 0.41]
[[boxes]]
name = "box"
center_m = [9.45, 4.45, 0.2]
size_m = [0.36, 0.55, 0.39]
"#,
    );
    let g = BuildingGeometry::new(&b);
    let poses = poses_away_from(&g, 10.0, 6.0, 1.5);
    assert!(poses.len() >= 10, "{} poses", poses.len());
    let ev = scan_map_score(&b, &poses);
    assert_eq!(ev.stairs.detected, 0, "no false staircase: {ev:#?}");
}
