//! Obstacles seen from some sides only (issue #15, "obstacles found"): cabinets against a wall,
//! seen from the room as their front faces, and boxes standing turned in the room, seen as two
//! faces meeting at a corner, scanned with the realistic laser from the room's open half and
//! scored against the building's ground truth.

use cloud::EntityClass;
use scanner::Building;
use semantic::{build_semantic_map, MapOutput, SemanticConfig};
use std::path::Path;
use std::sync::OnceLock;

/// A 7 x 5 m room, 2.6 m tall: two cabinets (0.45 m deep) against the north wall, boxes turned
/// 35 and 50 degrees in its middle; scanned from three poses in its southern half.
fn room() -> &'static (Building, cloud::PointCloud, MapOutput) {
    static OUT: OnceLock<(Building, cloud::PointCloud, MapOutput)> = OnceLock::new();
    OUT.get_or_init(|| {
        let boxes = r#"
[[boxes]]
name = "cabinet west"
class = "obstacle"
center_m = [1.6, 4.675, 0.95]
size_m = [1.6, 0.45, 1.9]

[[boxes]]
name = "cabinet east"
class = "obstacle"
center_m = [5.0, 4.725, 0.9]
size_m = [1.2, 0.35, 1.8]

[[boxes]]
name = "box turned 35"
center_m = [2.5, 2.8, 0.35]
size_m = [0.6, 0.45, 0.7]
yaw_deg = 35.0

[[boxes]]
name = "box turned 50"
center_m = [4.6, 2.9, 0.3]
size_m = [0.55, 0.4, 0.6]
yaw_deg = 50.0
"#;
        let text = fixtures::RoomToml::new([0.0, 0.0], [7.0, 5.0], 2.6)
            .walls(&[
                fixtures::Side::South,
                fixtures::Side::North,
                fixtures::Side::West,
                fixtures::Side::East,
            ])
            .toml(boxes);
        let b = Building::from_toml_str(&text, Path::new("room.toml")).expect("test building");
        let poses = fixtures::poses_at(&[(1.5, 1.0), (3.5, 1.2), (5.5, 1.0)]);
        let laser = fixtures::real_test_laser();
        let cloud = fixtures::scan_building(&b, &poses, &laser, 0.03);
        let out = build_semantic_map(&cloud, &SemanticConfig::default()).expect("map");
        (b, cloud, out)
    })
}

/// Regression: a cabinet against a wall, seen only from the room, got a box around its front
/// face alone (a few centimetres deep, straddling that face), which covered too little of the
/// cabinet to be found. Its box now reaches back to the wall: it covers most of the cabinet.
#[test]
fn a_cabinet_against_a_wall_gets_a_box_back_to_the_wall() {
    let (b, cloud, out) = room();
    let ev = evaluate::evaluate(&out.map, b, Some(cloud));
    for name in ["cabinet west", "cabinet east"] {
        let m = ev
            .obstacle_matches
            .iter()
            .find(|m| m.truth == name)
            .unwrap_or_else(|| panic!("{name} not found: {ev}"));
        assert!(m.footprint_iou >= 0.6, "{m:?}");
        let e = out
            .map
            .entities
            .iter()
            .find(|e| e.id == m.entity)
            .expect("the matched entity");
        // Its back at the wall's face (y = 4.9), not at the cabinet's front.
        let g = &e.geometry;
        let back = g.corners_xy().iter().map(|c| c[1]).fold(f64::MIN, f64::max);
        assert!((back - 4.9).abs() <= 0.1, "{name}: back at y {back}, {g:?}");
        assert_eq!(e.class, EntityClass::Obstacle, "{e:?}");
    }
    // The cabinets are obstacles, not walls: the walls are the room's four.
    assert_eq!(ev.walls.detected, 4, "{ev}");
}

/// Boxes standing turned in the room, seen from one side of the room only (two faces meeting
/// at a corner, or three): each found, its box along its faces.
#[test]
fn a_turned_box_seen_at_a_corner_gets_a_box_along_its_faces() {
    let (b, cloud, out) = room();
    let ev = evaluate::evaluate(&out.map, b, Some(cloud));
    for (name, yaw) in [("box turned 35", 35.0f64), ("box turned 50", 50.0)] {
        let m = ev
            .obstacle_matches
            .iter()
            .find(|m| m.truth == name)
            .unwrap_or_else(|| panic!("{name} not found: {ev}"));
        let e = out
            .map
            .entities
            .iter()
            .find(|e| e.id == m.entity)
            .expect("the matched entity");
        // The box's axes within 10 degrees of the truth's (a rectangle's yaw is modulo 90).
        let off = (e.geometry.yaw_deg - yaw).rem_euclid(90.0);
        assert!(off.min(90.0 - off) <= 10.0, "{name}: {:?}", e.geometry);
        assert!(m.footprint_iou >= 0.5, "{m:?}");
    }
}
