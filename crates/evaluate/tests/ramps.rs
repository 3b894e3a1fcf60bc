//! Ramps in the semantic map (issue #15: "ramps (not stairs)"): a room with a car-park ramp
//! and a wheelchair ramp, scanned with the virtual laser (ideal and realistic) from the floor,
//! mapped and scored against the building.

use cloud::EntityClass;
use scanner::Building;
use semantic::{build_semantic_map, SemanticConfig};
use std::path::Path;

/// A 16 x 10 m room, 3 m high: a 9-degree ramp 7 m long and 3 m wide rising east along its
/// south wall, a 4.8-degree (1:12) ramp 4 m long and 1.2 m wide rising north, and a parked
/// car (body and cabin) beside them.
fn building() -> Building {
    let text = fixtures::RoomToml::new([0.0, 0.0], [16.0, 10.0], 3.0).toml(
        r#"
        [[ramps]]
        name = "car ramp"
        start_m = [6.0, 1.7]
        direction_deg = 0.0
        length_m = 7.0
        width_m = 3.0
        rise_m = 1.109

        [[ramps]]
        name = "wheelchair ramp"
        start_m = [3.0, 5.0]
        direction_deg = 90.0
        length_m = 4.0
        width_m = 1.2
        rise_m = 0.333

        [[boxes]]
        name = "car"
        class = "obstacle"
        center_m = [10.0, 6.5, 0.55]
        size_m = [4.4, 1.8, 0.7]

        [[boxes]]
        name = "car"
        class = "obstacle"
        center_m = [10.2, 6.5, 1.2]
        size_m = [2.4, 1.6, 0.6]
        "#,
    );
    Building::from_toml_str(&text, Path::new("ramps.toml")).expect("valid building")
}

fn check(laser: &scanner::LaserConfig) {
    let b = building();
    let poses = fixtures::poses_at(&[(2.0, 2.0), (14.5, 8.5), (5.0, 8.5), (14.5, 4.5), (1.5, 8.0)]);
    let cloud = fixtures::scan_building(&b, &poses, laser, 0.03);
    let out = build_semantic_map(&cloud, &SemanticConfig::default()).expect("map");
    let ev = evaluate::evaluate(&out.map, &b, Some(&cloud));
    eprintln!("{ev}");
    for r in out.map.of_class(EntityClass::Ramp) {
        eprintln!("ramp {}: {:?} {:?}", r.id, r.geometry, r.rules);
    }
    // Both ramps found, rising the right way at the right pitch to the right height.
    assert_eq!(
        (ev.ramps.expected, ev.ramps.detected, ev.ramps.matched),
        (2, 2, 2),
        "{:#?}",
        out.map.of_class(EntityClass::Ramp).collect::<Vec<_>>()
    );
    for m in &ev.ramp_matches {
        assert!(m.footprint_iou >= 0.6, "{m:?}");
        assert!(m.pitch_error_deg.abs() <= 0.6, "{m:?}");
        assert!(m.rise_error_m.abs() <= 0.06, "{m:?}");
    }
    // Neither ramp is a staircase or an obstacle; the car is an obstacle.
    assert_eq!(out.map.of_class(EntityClass::Stairs).count(), 0);
    assert_eq!(ev.obstacles.recall, 1.0, "{:#?}", ev.obstacle_matches);
    let on_ramp = out.map.of_class(EntityClass::Obstacle).filter(|e| {
        let [x, y, _] = e.geometry.center_m;
        (6.0..13.0).contains(&x) && (0.2..3.2).contains(&y) && e.geometry.size_m[0] > 1.0
    });
    assert_eq!(on_ramp.count(), 0, "an obstacle on the car ramp");
    // The ramps' returns are labelled `ramp`: most of what the truth calls ramp, above the
    // floor's own band (a ramp's foot is floor to the map).
    let truth = cloud.labels.as_deref().expect("ground truth");
    let (mut on, mut labelled) = (0usize, 0usize);
    for ((t, l), p) in truth.iter().zip(&out.labels).zip(&cloud.points) {
        if t.class == EntityClass::Ramp && p.z >= 0.1 {
            on += 1;
            labelled += usize::from(l.class == EntityClass::Ramp);
        }
    }
    assert!(
        labelled * 10 >= on * 7,
        "{labelled} of {on} ramp returns labelled ramp"
    );
}

#[test]
fn ramps_seen_by_the_ideal_laser_are_ramps_rising_the_right_way() {
    check(&fixtures::test_laser());
}

#[test]
fn ramps_seen_by_the_realistic_laser_are_ramps_rising_the_right_way() {
    check(&fixtures::real_test_laser());
}
