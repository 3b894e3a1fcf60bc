//! Statistical outlier removal against ground truth: isolated points injected in mid-air into
//! full-resolution scans of the default building, the realistic laser's mixed pixels, and the
//! 3DTK corridor's real scans.

use cloud::{Label, PointCloud, Rng};
use glam::Vec3;
use pipeline::{find_outliers, remove_outliers, OutlierConfig};
use scanner::{Building, BuildingGeometry, LaserConfig, ScanPose, VirtualLaser};

/// A scan of `building` from `pose` with `laser`, missing returns dropped, in the scan frame.
fn scan(building: &Building, laser: &LaserConfig, pose: &ScanPose) -> PointCloud {
    let geometry = BuildingGeometry::new(building);
    let laser = VirtualLaser::new(laser.clone()).expect("valid laser");
    laser.scan(&geometry, pose, 0).without_invalid()
}

/// Distance from a world point to the nearest surface of the building.
fn clearance_m(geometry: &BuildingGeometry, p: Vec3) -> f32 {
    (1..=geometry.entities().len() as u32)
        .map(|e| geometry.distance_to_entity(p, e))
        .fold(f32::INFINITY, f32::min)
}

/// `count` isolated points in mid-air, as dust or a stray echo puts them: each on a random
/// beam from the sensor, before the surface the beam hits, farther than `min_clearance_m(r)`
/// from every surface (`r`: its range). In the scan frame; returns them with their ranges.
fn mid_air_points(
    building: &Building,
    laser: &LaserConfig,
    pose: &ScanPose,
    count: usize,
    min_clearance_m: impl Fn(f32) -> f32,
    seed: u64,
) -> Vec<Vec3> {
    let geometry = BuildingGeometry::new(building);
    let world_from_scan = pose.world_from_scan(laser.mount_height_m);
    let scan_from_world = world_from_scan.inverse();
    let origin = world_from_scan.translation.as_vec3();
    let mut rng = Rng::new(seed);
    let mut points = Vec::new();
    while points.len() < count {
        let dir = Vec3::new(
            rng.range(-1.0, 1.0) as f32,
            rng.range(-1.0, 1.0) as f32,
            rng.range(-0.6, 0.6) as f32,
        )
        .normalize();
        let Some((hit_m, _)) = geometry.cast_ray(origin, dir, laser.max_range_m as f32) else {
            continue;
        };
        let r = rng.range(0.5, hit_m as f64) as f32;
        let p = origin + dir * r;
        if geometry.entity_containing(p).is_none() && clearance_m(&geometry, p) >= min_clearance_m(r)
        {
            let local = scan_from_world.transform_point3(p.as_dvec3()).as_vec3();
            points.push(local);
        }
    }
    points
}

fn with_points(scan: &PointCloud, extra: &[Vec3]) -> PointCloud {
    let mut out = scan.clone();
    out.points.extend_from_slice(extra);
    if let Some(l) = &mut out.labels {
        l.extend(extra.iter().map(|_| Label::default()));
    }
    out
}

#[test]
fn explore() {
    let building = Building::default_building().expect("default");
    let laser = LaserConfig::default();
    let g = BuildingGeometry::new(&building);
    let poses = fixtures::survey_poses(&building, &g);
    for pose in poses.iter().take(3) {
        let s = scan(&building, &laser, pose);
        let step = (laser.rotation_fov_deg / laser.rotation_steps as f64).to_radians() as f32;
        let air = mid_air_points(&building, &laser, pose, 300, |r| (0.3f32).max(5.0 * step * r), 7);
        let all = with_points(&s, &air);
        let out = find_outliers(&all, &OutlierConfig::default());
        let n = s.len();
        let removed_surface: Vec<usize> = out.iter().copied().filter(|&i| i < n).collect();
        let removed_air = out.len() - removed_surface.len();
        let far = s.points.iter().filter(|p| p.length() > 15.0).count();
        let far_removed = removed_surface.iter().filter(|&&i| s.points[i].length() > 15.0).count();
        eprintln!(
            "pose {pose:?}: {n} points, {far} far; removed surface {} ({:.3} %), far {far_removed}, air {removed_air}/{}",
            removed_surface.len(),
            100.0 * removed_surface.len() as f64 / n as f64,
            air.len()
        );
    }
}
