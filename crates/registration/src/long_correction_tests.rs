//! The check of a long correction on virtual scans of the default building (a corridor
//! 20 m long with rooms on both sides).

use super::*;
use cloud::pose_error;
use glam::DVec3;
use scanner::{Building, BuildingGeometry, LaserConfig, ScanPose, VirtualLaser};

/// The map: one scan in the corridor at x = 2 m; the source: one scan 6.5 m further along it,
/// in front of a room's open door; and the true `world_from_scan` of the source.
fn corridor_pair() -> (PointCloud, PointCloud, DAffine3) {
    let building = Building::default_building().expect("default building");
    let geometry = BuildingGeometry::new(&building);
    let config = LaserConfig {
        beams: 271,
        rotation_steps: 151,
        ..LaserConfig::default()
    };
    let mount = config.mount_height_m;
    let laser = VirtualLaser::new(config).expect("laser");
    let at = |x_m, y_m| ScanPose {
        x_m,
        y_m,
        yaw_deg: 0.0,
    };
    let (map_pose, source_pose) = (at(2.0, 0.0), at(8.45, 0.5));
    let map = laser.scan(&geometry, &map_pose, 0);
    let source = laser.scan(&geometry, &source_pose, 1);
    let truth = map_pose.world_from_scan(mount).inverse() * source_pose.world_from_scan(mount);
    (map, source, truth)
}

/// Runs the check of `end` (an ICP's end from `guess`) with the sequence's defaults.
fn check_end(guess: DAffine3, end: DAffine3) -> (IcpResult, Option<CorrectionCheck>, DAffine3) {
    let (map, source, truth) = corridor_pair();
    let icp = IcpConfig {
        range_knee_m: 1.0,
        ..IcpConfig::default()
    };
    let views = vec![map.sensor_origin; map.len()];
    let target = Target::with_viewpoints(&map, &views, &icp).expect("target");
    let mut registrar = Registrar::new(&icp).expect("registrar");
    let result = IcpResult {
        target_from_source: end,
        iterations: Vec::new(),
        converged: true,
        rmse_m: 0.05,
        fitness: 0.5,
        total_ms: 0.0,
    };
    let view = MapView {
        points: &map.points,
        views: &views,
        target: &target,
        cell: (0.25, 1.0),
    };
    // The search about the map's scan, as the sequence runs it.
    let settings = initial::Settings {
        cell_m: 0.25,
        range_knee_m: 1.0,
    };
    let previous = (&DAffine3::IDENTITY, map.sensor_origin);
    let search =
        || initial::align(&map.points, &views, &source, previous, &guess, settings).map(|(s, _)| s);
    let (kept, check) =
        check(&mut registrar, view, &source, &guess, result, &icp, search).expect("checks");
    (kept, check, truth)
}

#[test]
fn a_scan_carried_a_metre_along_a_corridor_is_brought_back_to_its_odometry() {
    // The odometry's guess is 0.1 m off; the ICP's end 1.1 m along the corridor (as an
    // office's scan 22 after a 9.7 m move).
    let (_, _, truth) = corridor_pair();
    let shift = |dx: f64, dy: f64| DAffine3::from_translation(DVec3::new(dx, dy, 0.0)) * truth;
    let (kept, check, truth) = check_end(shift(0.08, -0.06), shift(-1.1, 0.0));
    let check = check.expect("a 1.1 m correction is checked");
    let (et, er) = pose_error(&kept.target_from_source, &truth);
    eprintln!("{check:?}: {et:.4} m {er:.3} deg from the truth");
    assert_ne!(check.kept, CheckedEnd::Icp, "{check:?}");
    let score_of = |end| check.scores.iter().find(|s| s.end == end).map(|s| s.score);
    let icp = score_of(CheckedEnd::Icp).expect("the ICP's end compared");
    let kept_score = score_of(check.kept).expect("the kept end compared");
    assert!(kept_score > icp, "{:?}", check.scores);
    assert!(et < 0.02 && er < 0.2, "{et} m {er} deg");
}

#[test]
fn a_scan_whose_odometry_drifted_a_metre_is_found_by_the_search() {
    // The odometry's guess is 1.8 m along the corridor (odometry that drifted over a long
    // move), the ICP's end 1.0 m: the narrow schedule from the guess cannot reach the truth,
    // the search about the previous scan can.
    let (_, _, truth) = corridor_pair();
    let shift = |dx: f64, dy: f64| DAffine3::from_translation(DVec3::new(dx, dy, 0.0)) * truth;
    let (kept, check, truth) = check_end(shift(-1.8, 0.1), shift(-1.0, 0.0));
    let check = check.expect("a 0.8 m correction is checked");
    let (et, er) = pose_error(&kept.target_from_source, &truth);
    eprintln!("{check:?}: {et:.4} m {er:.3} deg from the truth");
    assert_eq!(check.kept, CheckedEnd::Searched, "{check:?}");
    assert!(et < 0.02 && er < 0.2, "{et} m {er} deg");
}

#[test]
fn a_long_correction_to_the_true_pose_stands() {
    // The odometry's guess is off by a long move's error and the ICP's end is the truth. From
    // 0.6 m off the narrow schedule reaches the same minimum; from 1 m along the corridor it
    // ends elsewhere, and the evidence keeps the ICP's end.
    let (_, _, truth) = corridor_pair();
    for (dx_m, dy_m, compared) in [(0.5, 0.33, false), (1.0, 0.0, true)] {
        let guess = DAffine3::from_translation(DVec3::new(dx_m, dy_m, 0.0)) * truth;
        let (kept, check, truth) = check_end(guess, truth);
        let check = check.expect("a long correction is checked");
        eprintln!("guess off by ({dx_m}, {dy_m}) m: {check:?}");
        assert_eq!(check.kept, CheckedEnd::Icp, "{check:?}");
        assert_eq!(!check.scores.is_empty(), compared, "{check:?}");
        let (et, _) = pose_error(&kept.target_from_source, &truth);
        assert!(et < 1e-9, "the ICP's end was replaced: {et} m");
    }
}

#[test]
fn a_short_correction_is_not_checked() {
    let (_, _, truth) = corridor_pair();
    let guess = DAffine3::from_translation(DVec3::new(0.3, 0.2, 0.0)) * truth;
    let (kept, check, _) = check_end(guess, truth);
    assert!(check.is_none(), "{check:?}");
    assert_eq!(kept.target_from_source, truth);
}
