//! Helpers shared by the realistic-laser tests (`laser_realism.rs`, `laser_realism_scene.rs`):
//! a closed test room with extra TOML, entity look-up, lasers with a given realism, poses,
//! world-frame points, labels and a bit-for-bit fingerprint of a scan.

use cloud::PointCloud;
use glam::Vec3;
use scanner::{
    Building, BuildingGeometry, LaserConfig, MixedPixels, People, Realism, ScanPose, VirtualLaser,
};
use std::path::Path;

/// A closed room `x` 0..24 m, `y` -4..4 m (inner faces at 0.1 from the wall lines), 2.8 m
/// high, plus `extra` TOML (boxes, walls).
pub fn room(extra: &str) -> (Building, BuildingGeometry) {
    let text = format!(
        r#"
[floor]
min_m = [-0.2, -4.2]
max_m = [24.2, 4.2]
thickness_m = 0.2
[ceiling]
height_m = 2.8
thickness_m = 0.2
[[walls]]
name = "west"
start_m = [0.0, -4.1]
end_m = [0.0, 4.1]
thickness_m = 0.2
[[walls]]
name = "east"
start_m = [24.0, -4.1]
end_m = [24.0, 4.1]
thickness_m = 0.2
[[walls]]
name = "south"
start_m = [-0.1, -4.0]
end_m = [24.1, -4.0]
thickness_m = 0.2
[[walls]]
name = "north"
start_m = [-0.1, 4.0]
end_m = [24.1, 4.0]
thickness_m = 0.2
{extra}
"#
    );
    let building = Building::from_toml_str(&text, Path::new("<test room>")).expect("valid room");
    let geometry = BuildingGeometry::new(&building);
    (building, geometry)
}

pub fn entity(geometry: &BuildingGeometry, name: &str) -> u32 {
    geometry
        .entities()
        .iter()
        .find(|e| e.name == name)
        .unwrap_or_else(|| panic!("no entity {name}"))
        .id
}

pub fn laser(realism: Realism) -> VirtualLaser {
    VirtualLaser::new(LaserConfig {
        realism,
        ..Default::default()
    })
    .expect("valid laser")
}

/// The real preset without the effects a test does not look at.
pub fn real_without_people_and_mixing() -> Realism {
    Realism {
        people: People::off(),
        mixed: MixedPixels::off(),
        ..Realism::real()
    }
}

pub fn at(x_m: f64, y_m: f64) -> ScanPose {
    ScanPose {
        x_m,
        y_m,
        yaw_deg: 0.0,
    }
}

/// The scan's points in the world frame (by the sensor's true pose), and the sensor's origin.
pub fn in_world(laser: &VirtualLaser, scan: &PointCloud, pose: &ScanPose) -> (Vec<Vec3>, Vec3) {
    let mut s = scan.clone();
    let world_from_sensor = laser.world_from_sensor(pose);
    s.transform(&world_from_sensor);
    (s.points, world_from_sensor.translation.as_vec3())
}

pub fn labels(scan: &PointCloud) -> &[cloud::Label] {
    scan.labels.as_deref().expect("labelled")
}

/// FNV-1a over the bits of every point and label.
pub fn fingerprint(scan: &PointCloud) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |x: u32| {
        for b in x.to_le_bytes() {
            h ^= b as u64;
            h = h.wrapping_mul(0x100_0000_01b3);
        }
    };
    for (p, l) in scan.points.iter().zip(labels(scan)) {
        eat(p.x.to_bits());
        eat(p.y.to_bits());
        eat(p.z.to_bits());
        eat(l.entity);
        eat(l.class.code() as u32);
    }
    h
}
