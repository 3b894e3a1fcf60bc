//! Statistical outlier removal against ground truth: isolated points injected in mid-air into
//! full-resolution scans of the default building and of a long hall (far points), the realistic
//! laser's mixed pixels, and the 3DTK corridor's real scans.

use cloud::{Label, PointCloud, Rng};
use glam::Vec3;
use pipeline::{find_outliers, OutlierConfig};
use scanner::{Building, BuildingGeometry, LaserConfig, Realism, ScanPose, VirtualLaser};
use std::path::{Path, PathBuf};

/// A scan of `building` from `pose` with `laser` in the scan frame, missing returns and
/// no-echo readings dropped (as `read_scans` does before looking for outliers).
fn scan(building: &Building, laser: &LaserConfig, pose: &ScanPose) -> PointCloud {
    let geometry = BuildingGeometry::new(building);
    let laser = VirtualLaser::new(laser.clone()).expect("valid laser");
    pipeline::drop_no_echo(&laser.scan(&geometry, pose, 0).without_invalid()).0
}

/// Distance from a world point to the nearest surface of the building.
fn clearance_m(geometry: &BuildingGeometry, p: Vec3) -> f32 {
    (1..=geometry.entities().len() as u32)
        .map(|e| geometry.distance_to_entity(p, e))
        .fold(f32::INFINITY, f32::min)
}

/// The laser's coarsest angular step (beams along the line, or rotation steps), radians: its
/// samples on a surface facing it are this times the range apart.
fn angular_step_rad(laser: &LaserConfig) -> f32 {
    let beam = laser.line_fov_deg / (laser.beams - 1) as f64;
    let rotation = laser.rotation_fov_deg / laser.rotation_steps as f64;
    beam.max(rotation).to_radians() as f32
}

/// What "isolated" means here: farther than five of the laser's samples spacings at its range
/// (a point nearer a surface than a couple of spacings is, to any local statistic, that
/// surface's noise), and at least 20 cm (a body's width, well beyond the range noise).
fn isolation_m(laser: &LaserConfig, range_m: f32) -> f32 {
    (5.0 * angular_step_rad(laser) * range_m).max(0.2)
}

/// How far apart the injected points are: dust and stray echoes are a few returns in a scan,
/// not a fog (a cloud of them denser than the surfaces' samples is a surface to any local
/// statistic).
const APART_M: f32 = 1.0;

/// Random positions tried for the injected points of one scan.
const TRIES: usize = 100_000;

/// `count` isolated points in mid-air, as dust or a stray echo puts them: uniform in the
/// scan's bounding box, in the sensor's line of sight, and farther than
/// [`isolation_m`] from every surface and [`APART_M`] from each other. In the scan frame; only
/// those with a range within `ranges_m`; fewer than `count` where the view has no room for them.
fn mid_air_points(
    building: &Building,
    laser: &LaserConfig,
    pose: &ScanPose,
    scan: &PointCloud,
    count: usize,
    ranges_m: std::ops::Range<f32>,
) -> Vec<Vec3> {
    let geometry = BuildingGeometry::new(building);
    let world_from_scan = pose.world_from_scan(laser.mount_height_m);
    let origin = world_from_scan.translation.as_vec3();
    let bounds = scan.bounding_box().expect("a scan");
    let mut rng = Rng::new(7);
    let mut points: Vec<Vec3> = Vec::new();
    for _ in 0..TRIES {
        if points.len() == count {
            break;
        }
        let local = Vec3::new(
            rng.range(bounds.min.x as f64, bounds.max.x as f64) as f32,
            rng.range(bounds.min.y as f64, bounds.max.y as f64) as f32,
            rng.range(bounds.min.z as f64, bounds.max.z as f64) as f32,
        );
        let range = local.length();
        if !ranges_m.contains(&range) {
            continue;
        }
        let p = world_from_scan.transform_point3(local.as_dvec3()).as_vec3();
        let isolation = isolation_m(laser, range);
        let seen = geometry
            .cast_ray(origin, (p - origin) / range, range)
            .is_none();
        if seen
            && geometry.entity_containing(p).is_none()
            && points
                .iter()
                .all(|q| q.distance(local) > isolation.max(APART_M))
            && clearance_m(&geometry, p) > isolation
        {
            points.push(local);
        }
    }
    points
}

/// `scan` with `extra` points appended (labelled unknown).
fn with_points(scan: &PointCloud, extra: &[Vec3]) -> PointCloud {
    let mut out = scan.clone();
    out.points.extend_from_slice(extra);
    if let Some(l) = &mut out.labels {
        l.extend(extra.iter().map(|_| Label::default()));
    }
    out
}

/// Which of the first `n` points (the scan's own) and which of the rest (injected) are found.
fn split(outliers: &[usize], n: usize) -> (Vec<usize>, usize) {
    let own: Vec<usize> = outliers.iter().copied().filter(|&i| i < n).collect();
    let injected = outliers.len() - own.len();
    (own, injected)
}

/// A hall 60 m long, 30 m wide and 6 m high (a warehouse): from one end the laser sees
/// surfaces out to its 30 m range, many of the far ones at grazing incidence (floor, ceiling,
/// side walls).
fn long_hall() -> Building {
    let crate_box = r#"
        [[boxes]]
        name = "crate"
        center_m = [20.0, 2.0, 0.5]
        size_m = [1.0, 1.0, 1.0]
    "#;
    let text = fixtures::RoomToml::new([0.0, -15.0], [60.0, 15.0], 6.0)
        .name("long hall")
        .toml(crate_box);
    Building::from_toml_str(&text, Path::new("long_hall.toml")).expect("a valid building")
}

#[test]
fn isolated_points_in_mid_air_are_removed_and_the_surfaces_kept() {
    let building = Building::default_building().expect("default");
    let laser = LaserConfig::default();
    let geometry = BuildingGeometry::new(&building);
    let (mut injected, mut found) = (0, 0);
    // Every survey pose: the corridor's and the rooms'; up to 30 isolated points each.
    for pose in fixtures::survey_poses(&building, &geometry) {
        let s = scan(&building, &laser, &pose);
        let air = mid_air_points(&building, &laser, &pose, &s, 30, 0.5..30.0);
        let (surface, found_here) = split(
            &find_outliers(&with_points(&s, &air), &OutlierConfig::default()),
            s.len(),
        );
        eprintln!(
            "{pose:?}: {found_here} of {} isolated points removed, {} of {} surface points",
            air.len(),
            surface.len(),
            s.len()
        );
        assert!(
            surface.len() * 200 < s.len(),
            "{pose:?}: {} of {} surface points",
            surface.len(),
            s.len()
        );
        injected += air.len();
        found += found_here;
    }
    assert!(injected >= 200, "{injected} isolated points injected");
    assert!(found * 100 >= injected * 95, "{found} of {injected}");
}

#[test]
fn far_points_are_not_removed_for_being_far() {
    let building = long_hall();
    let laser = LaserConfig::default();
    let pose = ScanPose {
        x_m: 2.0,
        y_m: 0.0,
        yaw_deg: 0.0,
    };
    let s = scan(&building, &laser, &pose);
    let far = |p: &Vec3| p.length() > 15.0;
    let far_count = s.points.iter().filter(|p| far(p)).count();
    assert!(far_count > 5_000, "{far_count} points beyond 15 m");
    // Isolated points far away too: the range normalisation must not hide them either.
    let air = mid_air_points(&building, &laser, &pose, &s, 100, 5.0..29.0);
    assert!(air.len() >= 50, "{} isolated points", air.len());
    let (surface, found) = split(
        &find_outliers(&with_points(&s, &air), &OutlierConfig::default()),
        s.len(),
    );
    let far_removed = surface.iter().filter(|&&i| far(&s.points[i])).count();
    eprintln!(
        "long hall: {found} of {} isolated points removed; surface: {} of {}, beyond 15 m {far_removed} of {far_count}",
        air.len(),
        surface.len(),
        s.len()
    );
    assert!(
        far_removed * 200 < far_count,
        "{far_removed} of {far_count}"
    );
    assert!(
        surface.len() * 200 < s.len(),
        "{} of {}",
        surface.len(),
        s.len()
    );
    assert!(found * 100 >= air.len() * 95, "{found} of {}", air.len());
    // A global threshold (PCL's mean + 1 sigma of the mean neighbour distance, its default)
    // would have removed the far points wholesale: what the range normalisation is for.
    let global = global_threshold_outliers(&s, 8, 1.0);
    let global_far = global.iter().filter(|&&i| far(&s.points[i])).count();
    eprintln!(
        "a global threshold (mean + 1 sigma): {global_far} of {far_count} far points removed"
    );
    assert!(global_far * 2 > far_count, "{global_far} of {far_count}");
}

/// PCL's StatisticalOutlierRemoval: mean distance to `k` neighbours above the scan's mean +
/// `n_sigma` standard deviations (brute force over a voxel-free k-d tree).
fn global_threshold_outliers(scan: &PointCloud, k: usize, n_sigma: f64) -> Vec<usize> {
    let tree = registration::KdTree::new(&scan.points);
    let mut found = Vec::new();
    let d: Vec<f64> = scan
        .points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            tree.k_nearest(*p, k + 1, f32::INFINITY, &mut found);
            let s: f32 = found
                .iter()
                .filter(|&&j| j as usize != i)
                .map(|&j| scan.points[j as usize].distance(*p))
                .sum();
            s as f64 / k as f64
        })
        .collect();
    let mean = d.iter().sum::<f64>() / d.len() as f64;
    let var = d.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / d.len() as f64;
    let limit = mean + n_sigma * var.sqrt();
    (0..d.len()).filter(|&i| d[i] > limit).collect()
}

#[test]
fn a_scan_without_outliers_loses_almost_nothing() {
    let building = Building::default_building().expect("default");
    let laser = LaserConfig::default();
    let geometry = BuildingGeometry::new(&building);
    for pose in fixtures::survey_poses(&building, &geometry)
        .iter()
        .step_by(3)
    {
        let s = scan(&building, &laser, pose);
        let (kept, removed) = pipeline::remove_outliers(&s, &OutlierConfig::default());
        // The scan is organised (the building is closed: every beam returns), so it keeps its
        // shape, the outliers NaN.
        assert!(s.organized.is_some());
        assert_eq!(kept.organized, s.organized);
        assert_eq!(kept.valid_count() + removed, s.len());
        // One point in a thousand: the ideal laser's scan is every surface and nothing else.
        assert!(
            removed * 1000 < s.len(),
            "{pose:?}: {removed} of {}",
            s.len()
        );
    }
}

/// What the filter does to the realistic laser's unknown-labelled returns off the building's
/// surfaces (farther than five times the 1 cm noise from every one): how many there were,
/// how many of them were removed, how many of the isolated ones (farther than
/// [`isolation_m`]) there were and were removed; and to its surface points.
#[derive(Debug, Default)]
struct RealisticCount {
    off_surface: usize,
    off_surface_removed: usize,
    isolated: usize,
    isolated_removed: usize,
    surface: usize,
    surface_removed: usize,
}

/// The realistic laser (the mount level, so that the pose is the truth; people walking or
/// not) through every other survey pose of the default building.
fn realistic_counts(people: bool) -> RealisticCount {
    let building = Building::default_building().expect("default");
    let geometry = BuildingGeometry::new(&building);
    let mut realism = Realism::real();
    if !people {
        realism.people.count = 0;
    }
    realism.mount = scanner::Mount::off();
    let laser = LaserConfig {
        realism,
        ..LaserConfig::default()
    };
    let mut c = RealisticCount::default();
    for pose in fixtures::survey_poses(&building, &geometry)
        .iter()
        .step_by(2)
    {
        let s = scan(&building, &laser, pose);
        let world_from_scan = pose.world_from_scan(laser.mount_height_m);
        let labels = s.labels.as_ref().expect("labelled");
        let outliers: std::collections::HashSet<usize> =
            find_outliers(&s, &OutlierConfig::default())
                .into_iter()
                .collect();
        for (i, (p, l)) in s.points.iter().zip(labels).enumerate() {
            let removed = usize::from(outliers.contains(&i));
            if l.entity != 0 {
                c.surface += 1;
                c.surface_removed += removed;
                continue;
            }
            let w = world_from_scan.transform_point3(p.as_dvec3()).as_vec3();
            let clearance = clearance_m(&geometry, w);
            if clearance > 0.05 {
                c.off_surface += 1;
                c.off_surface_removed += removed;
            }
            if clearance > isolation_m(&laser, p.length()) {
                c.isolated += 1;
                c.isolated_removed += removed;
            }
        }
    }
    eprintln!("realistic laser, people {people}: {c:?}");
    c
}

/// Mixed pixels (people left out: every unknown-labelled return off the surfaces is one).
/// Most lie within a few sample spacings of the foreground or the background, where they are
/// that surface's noise to any local statistic, and they come in streaks along the depth edge
/// (one per scan line crossing it), each the next one's neighbour: so only a share of them go.
#[test]
fn mixed_pixels_of_the_realistic_laser_are_partly_removed_and_its_surfaces_kept() {
    let c = realistic_counts(false);
    assert!(c.off_surface > 100, "{c:?}");
    let share = c.off_surface_removed as f64 / c.off_surface as f64;
    assert!(share >= MIXED_PIXELS_REMOVED, "{share}: {c:?}");
    let isolated_share = c.isolated_removed as f64 / c.isolated.max(1) as f64;
    assert!(
        isolated_share >= ISOLATED_MIXED_PIXELS_REMOVED,
        "{isolated_share}: {c:?}"
    );
    assert!(c.surface_removed * 200 < c.surface, "{c:?}");
}

/// People walking past are streaks of returns, dense along each scan line: they are kept
/// (they are no isolated points; what a person is belongs to the map's stages), and the
/// surfaces are kept as well.
#[test]
fn walking_people_are_kept_with_the_surfaces() {
    let with_people = realistic_counts(true);
    let without = realistic_counts(false);
    let people = with_people.off_surface - without.off_surface.min(with_people.off_surface);
    assert!(people > 1000, "{with_people:?} {without:?}");
    let removed = with_people.off_surface_removed - without.off_surface_removed;
    assert!(
        removed * 20 < people,
        "{removed} of {people} returns of people removed"
    );
    assert!(
        with_people.surface_removed * 200 < with_people.surface,
        "{with_people:?}"
    );
}

/// The least share of mixed pixels removed that the test pins: 54 of 244 (22 %) were when it
/// was written; the bound is a floor under that, not a target.
const MIXED_PIXELS_REMOVED: f64 = 0.15;
/// The least share of the isolated mixed pixels (farther than [`isolation_m`] from every
/// surface) removed: 13 of 87 (15 %) were; most of them are in streaks.
const ISOLATED_MIXED_PIXELS_REMOVED: f64 = 0.10;

/// The 3DTK corridor's folder, or `None` (skip) where it is absent.
fn corridor() -> Option<PathBuf> {
    fixtures::real_data_dir("3dtk-corridor")
}

#[test]
fn the_3dtk_corridor_scans_lose_less_than_1_percent_to_outlier_removal() {
    let Some(dir) = corridor() else { return };
    for k in 0..3 {
        let path = dir.join(format!("scan{k:03}.3d"));
        let raw = cloud::io::threedtk::read_3d(&path)
            .expect("scan")
            .without_invalid();
        let (kept, _) = pipeline::drop_no_echo(&raw);
        let (_, removed) = pipeline::remove_outliers(&kept, &OutlierConfig::default());
        eprintln!(
            "{}: {removed} of {} points removed",
            path.display(),
            kept.len()
        );
        assert!(removed > 0, "a real scan has isolated returns");
        assert!(removed * 100 < kept.len(), "{removed} of {}", kept.len());
        // read_scans removes the same.
        let read = pipeline::read_scans(&[pipeline::ScanSource::file(&path)], None).expect("read");
        assert_eq!(read[0].len(), kept.len() - removed);
    }
}
