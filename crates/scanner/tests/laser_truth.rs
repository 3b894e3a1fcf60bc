//! The virtual laser against ground truth: every return lies on the surface its label names,
//! and range errors follow the configured noise.

use cloud::PointCloud;
use scanner::{
    generate_building, Building, BuildingGeometry, GeneratorConfig, LaserConfig, ScanPose,
    VirtualLaser,
};

fn small_laser(sigma: f64) -> VirtualLaser {
    VirtualLaser::new(LaserConfig {
        beams: 181,
        rotation_steps: 91,
        range_noise_sigma_m: sigma,
        ..Default::default()
    })
    .expect("valid laser")
}

fn world_points(scan: &PointCloud, pose: &ScanPose, laser: &VirtualLaser) -> Vec<glam::Vec3> {
    let mut s = scan.clone();
    s.transform(&pose.world_from_scan(laser.config().mount_height_m));
    s.points
}

#[test]
fn noiseless_returns_lie_on_their_labelled_surface_within_1mm() {
    for seed in [3u64, 11, 29] {
        let building =
            generate_building(seed, &GeneratorConfig::default()).expect("valid building");
        let geometry = BuildingGeometry::new(&building);
        let laser = small_laser(0.0);
        let pose = ScanPose {
            x_m: 1.5,
            y_m: 0.0,
            yaw_deg: 20.0,
        };
        let scan = laser.scan(&geometry, &pose, 0);
        let labels = scan.labels.as_ref().expect("labelled");
        let pts = world_points(&scan, &pose, &laser);
        let mut checked = 0;
        let mut classes = std::collections::BTreeSet::new();
        for (p, l) in pts.iter().zip(labels) {
            if !p.is_finite() {
                assert_eq!(l.entity, 0, "missing return with a label");
                continue;
            }
            assert_ne!(l.entity, 0, "return without a label");
            let d = geometry.distance_to_entity(*p, l.entity);
            assert!(
                d < 1e-3,
                "seed {seed}: point {p} is {d} m from its entity {l:?}"
            );
            classes.insert(l.class.name());
            checked += 1;
        }
        assert!(checked > scan.len() / 2, "only {checked} returns");
        assert!(classes.len() >= 3, "classes seen: {classes:?}");
    }
}

#[test]
fn range_errors_follow_the_configured_noise() {
    let building = Building::default_building().expect("default");
    let geometry = BuildingGeometry::new(&building);
    let sigma = 0.01;
    let noisy = small_laser(sigma);
    let exact = small_laser(0.0);
    let pose = ScanPose {
        x_m: 4.0,
        y_m: 0.2,
        yaw_deg: -10.0,
    };
    let a = noisy.scan(&geometry, &pose, 1);
    let b = exact.scan(&geometry, &pose, 1);
    let errs: Vec<f64> = a
        .points
        .iter()
        .zip(&b.points)
        .filter(|(p, q)| p.is_finite() && q.is_finite())
        .map(|(p, q)| (p.length() - q.length()) as f64)
        .collect();
    assert!(errs.len() > 10_000);
    let n = errs.len() as f64;
    let mean = errs.iter().sum::<f64>() / n;
    let std = (errs.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / n).sqrt();
    assert!(mean.abs() < 0.1 * sigma, "mean range error {mean}");
    assert!(
        (std - sigma).abs() < 0.05 * sigma,
        "range error std {std}, configured {sigma}"
    );
    // Same seed and pose: identical scan.
    assert_eq!(noisy.scan(&geometry, &pose, 1).points.len(), a.points.len());
    let again = noisy.scan(&geometry, &pose, 1);
    assert!(again
        .points
        .iter()
        .zip(&a.points)
        .all(|(p, q)| p == q || (p.is_nan() && q.is_nan())));
}

#[test]
fn default_scan_is_organised_and_sees_floor_ceiling_walls_doors_stairs() {
    let building = Building::default_building().expect("default");
    let geometry = BuildingGeometry::new(&building);
    let laser = small_laser(0.0);
    let scan = laser.scan(
        &geometry,
        &ScanPose {
            x_m: 14.4,
            y_m: 0.0,
            yaw_deg: 90.0,
        },
        0,
    );
    let o = scan.organized.expect("organised");
    assert_eq!((o.rows, o.cols), (91, 181));
    let classes: std::collections::BTreeSet<_> = scan
        .labels
        .as_ref()
        .expect("labels")
        .iter()
        .map(|l| l.class.name())
        .collect();
    for c in [
        "floor",
        "ceiling",
        "wall",
        "door",
        "stairs",
        "wall_above_door",
    ] {
        assert!(classes.contains(c), "{c} not seen: {classes:?}");
    }
    assert!(geometry
        .entity_containing(glam::Vec3::new(0.0, 0.0, 1.0))
        .is_some_and(|e| e.name == "walls[2]"));
    assert!(geometry
        .entity_containing(glam::Vec3::new(2.0, 0.0, 1.0))
        .is_none());
}

#[test]
fn absurd_laser_parameters_are_rejected() {
    for cfg in [
        LaserConfig {
            beams: 0,
            ..Default::default()
        },
        LaserConfig {
            max_range_m: f64::NAN,
            ..Default::default()
        },
        LaserConfig {
            range_noise_sigma_m: -0.1,
            ..Default::default()
        },
        LaserConfig {
            beams: 20_000,
            rotation_steps: 20_000,
            ..Default::default()
        },
    ] {
        assert!(VirtualLaser::new(cfg).is_err());
    }
}
