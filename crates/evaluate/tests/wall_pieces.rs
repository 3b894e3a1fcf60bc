//! A true wall seen in two pieces, a stretch nobody saw between them, and one map wall carried
//! on through that stretch (the map's join of collinear pieces): one expected wall, found; not
//! one found and one missed.

use cloud::{EntityClass, Label, PointCloud};
use glam::Vec3;
use scanner::{Building, BuildingGeometry};
use semantic::{Entity, OrientedBox, SemanticMap, WallInfo};
use std::path::Path;

const BUILDING: &str = r#"
name = "one wall"

[floor]
min_m = [-1.0, -1.0]
max_m = [25.0, 5.0]
thickness_m = 0.2

[ceiling]
height_m = 3.0
thickness_m = 0.2

[[walls]]
name = "south outer"
start_m = [0.0, 0.0]
end_m = [24.0, 0.0]
thickness_m = 0.15
"#;

/// The wall's north face seen from x = `x0` to `x1`, every 2 cm at ten heights.
fn face(x0: f32, x1: f32, id: u32) -> (Vec<Vec3>, Vec<Label>) {
    let n = ((x1 - x0) / 0.02) as usize;
    let points: Vec<Vec3> = (0..n)
        .flat_map(|i| {
            (0..10).map(move |k| Vec3::new(x0 + 0.02 * i as f32, 0.075, 0.25 * k as f32 + 0.1))
        })
        .collect();
    let labels = vec![
        Label {
            entity: id,
            class: EntityClass::Wall
        };
        points.len()
    ];
    (points, labels)
}

/// A map holding one wall along y = 0 from `x0` to `x1`, seen from one side.
fn map_with_wall(x0: f64, x1: f64) -> SemanticMap {
    let mut map = SemanticMap::default();
    let geometry = OrientedBox {
        center_m: [(x0 + x1) / 2.0, 0.0, 1.5],
        size_m: [x1 - x0, 0.15, 3.0],
        yaw_deg: 0.0,
    };
    map.entities.push(Entity {
        id: 1,
        class: EntityClass::Wall,
        geometry,
        support_points: 1000,
        confidence: 1.0,
        rules: Vec::new(),
        wall: Some(WallInfo {
            segment_m: [[x0, 0.0], [x1, 0.0]],
            thickness_m: 0.15,
            thickness_measured: false,
            z_range_m: [0.0, 3.0],
            solid_boxes: vec![geometry],
        }),
        door: None,
        opening: None,
        stairs: None,
        obstacle: None,
        floor: None,
    });
    map
}

/// The one-wall building and its wall's ground-truth label id.
fn building_and_wall_id() -> (Building, u32) {
    let b = Building::from_toml_str(BUILDING, Path::new("one wall")).expect("building");
    let id = BuildingGeometry::new(&b)
        .entities()
        .iter()
        .find(|e| e.name == "walls[0]")
        .map(|e| e.id)
        .expect("the wall's id");
    (b, id)
}

#[test]
fn a_map_wall_through_the_unseen_stretch_between_two_pieces_finds_both() {
    let (b, id) = building_and_wall_id();
    // Seen from 0 to 16.5 m and from 18.4 to 24 m: 1.9 m unseen (more than `piece_gap_m`).
    let (mut points, mut labels) = face(0.0, 16.5, id);
    let (p2, l2) = face(18.4, 24.0, id);
    points.extend(p2);
    labels.extend(l2);
    let mut cloud = PointCloud::from_points(points);
    cloud.labels = Some(labels);
    // One map wall through the stretch: one expected wall, matched, its ends right.
    let ev = evaluate::evaluate(&map_with_wall(0.0, 24.0), &b, Some(&cloud));
    assert_eq!(
        (ev.walls.expected, ev.walls.matched),
        (1, 1),
        "{:?}",
        ev.missed
    );
    assert!(ev.wall_endpoint_error_max_m < 0.01);
    // A map wall that stops before the stretch leaves the second piece missed.
    let ev = evaluate::evaluate(&map_with_wall(0.0, 16.5), &b, Some(&cloud));
    assert_eq!((ev.walls.expected, ev.walls.matched), (2, 1));
    assert_eq!(ev.missed, vec!["walls[0] [18.40, 23.98] m".to_string()]);
}

/// A map wall over two thirds of a seen piece is a match (its ends are off), and the wall
/// length says how much of the piece no map wall runs along; a map wall over all of it
/// covers it whole.
#[test]
fn the_wall_length_counts_a_seen_stretch_no_map_wall_runs_along() {
    let (b, id) = building_and_wall_id();
    let (points, labels) = face(0.0, 24.0, id);
    let mut cloud = PointCloud::from_points(points);
    cloud.labels = Some(labels);
    let ev = evaluate::evaluate(&map_with_wall(0.0, 16.0), &b, Some(&cloud));
    assert_eq!((ev.walls.expected, ev.walls.matched), (1, 1));
    assert!((ev.wall_length.expected_m - 23.98).abs() < 0.01, "{ev}");
    assert!((ev.wall_length.covered_m - 16.0).abs() < 0.01, "{ev}");
    assert!((ev.wall_length.recall - 16.0 / 23.98).abs() < 0.001, "{ev}");
    let whole = evaluate::evaluate(&map_with_wall(-0.5, 24.5), &b, Some(&cloud));
    assert!((whole.wall_length.recall - 1.0).abs() < 1e-9, "{whole}");
}
