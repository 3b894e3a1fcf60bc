//! A ramp: a pitched slab whose top runs from the floor at its foot to `rise_m` at its head,
//! labelled `ramp` (walkable, neither an obstacle nor a staircase).

use cloud::EntityClass;
use glam::Vec3;
use scanner::{Building, BuildingGeometry};
use std::path::Path;

const HALL: &str = r#"
    [floor]
    min_m = [0.0, 0.0]
    max_m = [12.0, 6.0]
    [ceiling]
    height_m = 3.0
    [[ramps]]
    name = "ramp"
    start_m = [2.0, 3.0]
    direction_deg = 0.0
    length_m = 8.0
    width_m = 3.0
    rise_m = 1.0
"#;

#[test]
fn a_ray_down_onto_a_ramp_hits_its_slope_labelled_ramp() {
    let b = Building::from_toml_str(HALL, Path::new("hall.toml")).expect("valid");
    let g = BuildingGeometry::new(&b);
    let ramp = g
        .entities()
        .iter()
        .find(|e| e.name == "ramps[0]")
        .expect("ramp entity");
    assert_eq!(ramp.class, EntityClass::Ramp);
    for along in [0.5, 2.0, 4.0, 6.0, 7.5] {
        let origin = Vec3::new(2.0 + along, 3.0, 2.5);
        let (toi, label) = g
            .cast_ray(origin, Vec3::new(0.0, 0.0, -1.0), 10.0)
            .expect("hit");
        let z = 2.5 - toi;
        let want = along * 1.0 / 8.0;
        assert_eq!(label.entity, ramp.id, "at {along} m");
        assert!(
            (z - want).abs() < 1e-3,
            "at {along} m: top at {z}, slope at {want}"
        );
    }
    // Beside the ramp the ray reaches the floor.
    let (toi, label) = g
        .cast_ray(Vec3::new(6.0, 5.0, 2.5), Vec3::new(0.0, 0.0, -1.0), 10.0)
        .expect("hit");
    assert!(
        label.class == EntityClass::Floor && label.entity != ramp.id && (toi - 2.5).abs() < 1e-3
    );
    // Rotated to rise along +y, the slope follows.
    let turned = HALL
        .replace("direction_deg = 0.0", "direction_deg = 90.0")
        .replace("start_m = [2.0, 3.0]", "start_m = [6.0, 0.5]")
        .replace("length_m = 8.0", "length_m = 4.0")
        .replace("rise_m = 1.0", "rise_m = 0.5");
    let b = Building::from_toml_str(&turned, Path::new("hall.toml")).expect("valid");
    let g = BuildingGeometry::new(&b);
    let (toi, _) = g
        .cast_ray(Vec3::new(6.0, 3.5, 2.5), Vec3::new(0.0, 0.0, -1.0), 10.0)
        .expect("hit");
    assert!((2.5 - toi - 0.375).abs() < 1e-3, "top at {}", 2.5 - toi);
}
