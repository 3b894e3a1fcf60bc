//! Bad input gives the right error variant and never panics.

mod common;

use cloud::{Organized, PointCloud};
use common::*;
use glam::{DAffine3, DVec3, Vec3};
use registration::*;

fn box_cloud() -> PointCloud {
    // Points on the six faces of a 4 x 3 x 2.5 m room, 5 cm apart.
    let mut pts = Vec::new();
    let (sx, sy, sz) = (4.0f32, 3.0f32, 2.5f32);
    let step = 0.05;
    let n = |len: f32| (len / step) as usize;
    for i in 0..=n(sx) {
        for j in 0..=n(sy) {
            let (x, y) = (i as f32 * step, j as f32 * step);
            pts.push(Vec3::new(x, y, 0.0));
            pts.push(Vec3::new(x, y, sz));
        }
        for k in 0..=n(sz) {
            let (x, z) = (i as f32 * step, k as f32 * step);
            pts.push(Vec3::new(x, 0.0, z));
            pts.push(Vec3::new(x, sy, z));
        }
    }
    for j in 0..=n(sy) {
        for k in 0..=n(sz) {
            let (y, z) = (j as f32 * step, k as f32 * step);
            pts.push(Vec3::new(0.0, y, z));
            pts.push(Vec3::new(sx, y, z));
        }
    }
    PointCloud::from_points(pts)
}

#[test]
fn empty_clouds_are_named() {
    let room = box_cloud();
    let empty = PointCloud::default();
    for method in [Method::PointToPoint, Method::PointToPlane, Method::Gicp] {
        let c = IcpConfig {
            method,
            ..IcpConfig::default()
        };
        match register(&empty, &room, DAffine3::IDENTITY, &c) {
            Err(RegistrationError::EmptyCloud { which }) => assert_eq!(which, "source"),
            other => panic!("{other:?}"),
        }
        match register(&room, &empty, DAffine3::IDENTITY, &c) {
            Err(RegistrationError::EmptyCloud { which }) => assert_eq!(which, "target"),
            other => panic!("{other:?}"),
        }
    }
    // An organised cloud of missing returns only is empty too.
    let missing = PointCloud {
        points: vec![Vec3::NAN; 6],
        organized: Some(Organized { rows: 2, cols: 3 }),
        ..PointCloud::default()
    };
    assert!(matches!(
        register(&missing, &room, DAffine3::IDENTITY, &IcpConfig::default()),
        Err(RegistrationError::EmptyCloud { .. })
    ));
}

#[test]
fn nan_in_an_unorganised_cloud_is_an_error_but_missing_returns_are_skipped() {
    let room = box_cloud();
    let mut bad = room.clone();
    bad.points[17] = Vec3::new(1.0, f32::NAN, 0.0);
    match register(&bad, &room, DAffine3::IDENTITY, &IcpConfig::default()) {
        Err(RegistrationError::NonFinite { which, index }) => {
            assert_eq!((which.as_str(), index), ("source", 17))
        }
        other => panic!("{other:?}"),
    }
    bad.points[17] = Vec3::new(f32::INFINITY, 0.0, 0.0);
    assert!(matches!(
        register(&room, &bad, DAffine3::IDENTITY, &IcpConfig::default()),
        Err(RegistrationError::NonFinite { index: 17, .. })
    ));
    // The same cloud organised, with NaN missing returns: registers.
    let mut organised = room.clone();
    organised.points.push(Vec3::NAN);
    organised.points[17] = Vec3::NAN;
    let n = organised.points.len();
    organised.organized = Some(Organized { rows: 1, cols: n });
    let shift = DAffine3::from_translation(DVec3::new(0.05, -0.03, 0.02));
    let r = register(&organised, &room, shift, &IcpConfig::default()).expect("registers");
    assert!(
        r.target_from_source.translation.length() < 0.005,
        "{:?}",
        r.target_from_source
    );
}

#[test]
fn clouds_without_overlap_are_no_overlap() {
    let room = box_cloud();
    let far = DAffine3::from_translation(DVec3::new(100.0, 0.0, 0.0));
    for method in [Method::PointToPoint, Method::PointToPlane, Method::Gicp] {
        for nn in [NnBackend::Grid, NnBackend::KdTree] {
            let c = IcpConfig {
                method,
                nn,
                ..IcpConfig::default()
            };
            match register(&room, &room, far, &c) {
                Err(RegistrationError::NoOverlap {
                    max_correspondence_distance_m,
                    correspondences,
                    ..
                }) => {
                    assert_eq!(
                        max_correspondence_distance_m,
                        c.max_correspondence_distance_m
                    );
                    assert_eq!(correspondences, 0);
                }
                other => panic!("{method} {nn:?}: {other:?}"),
            }
        }
    }
}

#[test]
fn absurd_configurations_are_invalid_parameters() {
    let room = box_cloud();
    let cases = [
        (
            "max_iterations",
            IcpConfig {
                max_iterations: 0,
                ..IcpConfig::default()
            },
        ),
        (
            "max_iterations",
            IcpConfig {
                max_iterations: 20_000,
                ..IcpConfig::default()
            },
        ),
        (
            "max_correspondence_distance_m",
            IcpConfig {
                max_correspondence_distance_m: -0.5,
                ..IcpConfig::default()
            },
        ),
        (
            "max_correspondence_distance_m",
            IcpConfig {
                max_correspondence_distance_m: f64::NAN,
                ..IcpConfig::default()
            },
        ),
        (
            "source_voxel_m",
            IcpConfig {
                source_voxel_m: Some(0.0),
                ..IcpConfig::default()
            },
        ),
        (
            "target_voxel_m",
            IcpConfig {
                target_voxel_m: Some(-1.0),
                ..IcpConfig::default()
            },
        ),
        (
            "bucket_size_m",
            IcpConfig {
                bucket_size_m: f64::INFINITY,
                ..IcpConfig::default()
            },
        ),
        (
            "kernel.k_m",
            IcpConfig {
                kernel: RobustKernel::Huber { k_m: -1.0 },
                ..IcpConfig::default()
            },
        ),
    ];
    for (name, c) in cases {
        match register(&room, &room, DAffine3::IDENTITY, &c) {
            Err(RegistrationError::InvalidParameter(cloud::InvalidParameter {
                name: n, ..
            })) => assert_eq!(n, name),
            other => panic!("{name}: {other:?}"),
        }
    }
    // A bucket so small for the cloud's extent that the grid would span over 2^40 buckets.
    let wide = PointCloud::from_points(vec![Vec3::ZERO, Vec3::new(5000.0, 5000.0, 100.0)]);
    let c = IcpConfig {
        bucket_size_m: 0.001,
        method: Method::PointToPoint,
        target_voxel_m: None,
        ..IcpConfig::default()
    };
    assert!(matches!(
        Target::new(&wide, &c),
        Err(RegistrationError::InvalidParameter(p)) if p.name == "bucket_size_m"
    ));
    // A non-finite guess.
    let nan = DAffine3::from_translation(DVec3::new(f64::NAN, 0.0, 0.0));
    assert!(matches!(
        register(&room, &room, nan, &IcpConfig::default()),
        Err(RegistrationError::InvalidParameter(_))
    ));
}

#[test]
fn sequence_inputs_are_checked() {
    let room = box_cloud();
    let scans = vec![room.clone(), room.clone()];
    let config = SequenceConfig::default();
    assert!(matches!(
        register_sequence(&[], &[], &config, &mut |_, _| {}),
        Err(RegistrationError::EmptyCloud { .. })
    ));
    assert!(matches!(
        register_sequence(&scans, &[DAffine3::IDENTITY], &config, &mut |_, _| {}),
        Err(RegistrationError::Mismatch {
            what: "world_from_scan_guess",
            ..
        })
    ));
    let bad = SequenceConfig {
        map_voxel_m: 0.0,
        ..SequenceConfig::default()
    };
    assert!(matches!(
        register_sequence(&scans, &[], &bad, &mut |_, _| {}),
        Err(RegistrationError::InvalidParameter(p)) if p.name == "map_voxel_m"
    ));
    let mut nan_scan = room.clone();
    nan_scan.points[3] = Vec3::NAN;
    match register_sequence(&[room.clone(), nan_scan], &[], &config, &mut |_, _| {}) {
        Err(RegistrationError::NonFinite { which, index: 3 }) => assert_eq!(which, "scan 1"),
        other => panic!("{other:?}"),
    }
    // Two copies of the same room: the second lands on the first.
    let r = register_sequence(&scans, &[], &config, &mut |_, _| {}).expect("registers");
    assert!(r.world_from_scan[1].abs_diff_eq(DAffine3::IDENTITY, 1e-3));
}

#[test]
fn not_converged_errors_display_their_reason() {
    let (target, source, truth) = scan_pair(61, 31);
    let config = IcpConfig {
        max_iterations: 1,
        ..IcpConfig::point_to_point()
    };
    let e = register(&source, &target, standard_start(&truth), &config).expect_err("1 iteration");
    let text = e.to_string();
    assert!(
        text.contains("did not converge") && text.contains("1 iterations"),
        "{text}"
    );
}
