//! Registration of virtual-laser scan sequences with known truth: a corridor sequence with
//! noisy odometry (default building, 1 cm range noise, the same small 181 x 91 laser as
//! `synthetic.rs` so the debug build stays fast), and a synthetic thick wall whose far face must
//! not pull a room scan across it.

use cloud::pose_error;
use glam::{DAffine3, DVec3};
use registration::*;
use scanner::ScanPose;

const BEAMS: usize = 181;
const STEPS: usize = 91;

#[test]
fn a_sequence_with_noisy_odometry_follows_the_truth() {
    let building = scanner::Building::default_building().expect("building");
    let geometry = scanner::BuildingGeometry::new(&building);
    let laser_config = scanner::LaserConfig {
        beams: BEAMS,
        rotation_steps: STEPS,
        ..Default::default()
    };
    let mount = laser_config.mount_height_m;
    let laser = scanner::VirtualLaser::new(laser_config).expect("laser");
    let poses = [
        ScanPose {
            x_m: 4.0,
            y_m: 0.0,
            yaw_deg: 0.0,
        },
        ScanPose {
            x_m: 5.0,
            y_m: 0.2,
            yaw_deg: 4.0,
        },
        ScanPose {
            x_m: 6.0,
            y_m: -0.1,
            yaw_deg: -3.0,
        },
        ScanPose {
            x_m: 7.1,
            y_m: 0.1,
            yaw_deg: 2.0,
        },
    ];
    let scans: Vec<_> = poses
        .iter()
        .enumerate()
        .map(|(k, p)| laser.scan(&geometry, p, k as u64))
        .collect();
    let truth: Vec<DAffine3> = poses.iter().map(|p| p.world_from_scan(mount)).collect();
    // Odometry drifts: each step is 8 cm and 2 degrees off.
    let mut odometry = vec![truth[0]];
    for k in 1..truth.len() {
        let step = truth[k - 1].inverse() * truth[k];
        let drift = DAffine3::from_rotation_translation(
            glam::DQuat::from_rotation_z(2f64.to_radians()),
            DVec3::new(0.08, -0.03, 0.0),
        );
        let last = odometry[k - 1];
        odometry.push(last * step * drift);
    }
    let mut progress = Vec::new();
    let result = register_sequence(
        &scans,
        &odometry,
        &SequenceConfig::default(),
        &mut |d, t| progress.push((d, t)),
    )
    .expect("sequence");
    assert_eq!(progress, vec![(1, 4), (2, 4), (3, 4), (4, 4)]);
    assert_eq!(result.world_from_scan.len(), 4);
    assert!(result.results[0].is_none());
    for k in 1..4 {
        let ours = result.world_from_scan[0].inverse() * result.world_from_scan[k];
        let real = truth[0].inverse() * truth[k];
        let (et, er) = pose_error(&ours, &real);
        assert!(et < 0.01 && er < 0.1, "scan {k}: {et} m {er} deg");
        let odo = odometry[0].inverse() * odometry[k];
        assert!(
            pose_error(&odo, &real).0 > 0.05,
            "the odometry really was off"
        );
    }
    // The map is voxel-downsampled: no two points closer than a fraction of a voxel... and it
    // covers the corridor walls at y = +-1.2 m.
    let map = &result.map;
    assert!(map.len() > 5000 && map.organized.is_none());
    let near_wall = map
        .points
        .iter()
        .filter(|p| (p.y.abs() - 1.2).abs() < 0.03)
        .count();
    assert!(near_wall > 500, "{near_wall}");
    // Without odometry the identity chain still works for these small steps.
    let result = register_sequence(&scans[..2], &[], &SequenceConfig::default(), &mut |_, _| {})
        .expect("no odometry");
    let (et, er) = pose_error(&result.world_from_scan[1], &(truth[0].inverse() * truth[1]));
    assert!(et < 0.01 && er < 0.1, "{et} m {er} deg");
}

/// Points on an axis-aligned rectangle: `fixed` axis at `at`, the other two spanning the ranges.
fn plane(fixed: usize, at: f32, a: (f32, f32), b: (f32, f32), step: f32) -> Vec<glam::Vec3> {
    let mut out = Vec::new();
    let (na, nb) = (((a.1 - a.0) / step) as i32, ((b.1 - b.0) / step) as i32);
    for i in 0..=na {
        for j in 0..=nb {
            let (u, v) = (a.0 + i as f32 * step, b.0 + j as f32 * step);
            out.push(match fixed {
                0 => glam::Vec3::new(at, u, v),
                1 => glam::Vec3::new(u, at, v),
                _ => glam::Vec3::new(u, v, at),
            });
        }
    }
    out
}

/// Regression: a scan taken on the far side of a 20 cm wall (a room behind a corridor) was
/// registered with its face of the wall pulled onto the corridor's face, 15-20 cm off. The
/// sequence map remembers where each point was seen from, and pairs whose target surface faces
/// away from the source's sensor are rejected.
#[test]
fn room_scan_is_not_pulled_onto_the_far_face_of_a_thick_wall() {
    // Corridor side y < 0 (face at y = 0), room side y > 0.2 (face at y = 0.2), a doorway
    // (|x| < 0.5, z < 2) through which each side sees a patch of the other's far wall; floor,
    // ceiling and end walls at x = +-3 on both sides. Without the back-face test the room's
    // face of the wall is matched to the corridor's face, 20 cm off.
    let step = 0.05;
    let doorway = |p: &glam::Vec3| p.x.abs() < 0.5 && p.z < 2.0;
    let side = |face: f32, far: f32, span: (f32, f32)| -> Vec<glam::Vec3> {
        [
            plane(1, face, (-3.0, 3.0), (0.0, 2.5), step)
                .into_iter()
                .filter(|p| !doorway(p))
                .collect(),
            plane(1, far, (-3.0, 3.0), (0.0, 2.5), step),
            plane(2, 0.0, (-3.0, 3.0), span, step),
            plane(2, 2.5, (-3.0, 3.0), span, step),
            plane(0, 3.0, span, (0.0, 2.5), step),
            plane(0, -3.0, span, (0.0, 2.5), step),
        ]
        .concat()
    };
    let through = |far: f32| plane(1, far, (-1.0, 1.0), (0.0, 2.0), step);
    let corridor = [side(0.0, -3.0, (-3.0, 0.0)), through(3.0)].concat();
    let room = [side(0.2, 3.0, (0.2, 3.0)), through(-3.0)].concat();
    let sensors = [DVec3::new(0.0, -1.5, 1.0), DVec3::new(0.0, 1.6, 1.0)];
    let scans: Vec<cloud::PointCloud> = [corridor, room]
        .into_iter()
        .zip(sensors)
        .map(|(pts, s)| {
            let s = s.as_vec3();
            cloud::PointCloud::from_points(pts.into_iter().map(|p| p - s).collect())
        })
        .collect();
    let truth: Vec<DAffine3> = sensors
        .iter()
        .map(|s| DAffine3::from_translation(*s))
        .collect();
    // Odometry 5 cm off along x and z, exact along y.
    let guess = vec![
        truth[0],
        DAffine3::from_translation(DVec3::new(0.05, 0.0, 0.05)) * truth[1],
    ];
    let result = register_sequence(&scans, &guess, &SequenceConfig::default(), &mut |_, _| {})
        .expect("registers");
    let error = result.world_from_scan[1].translation - truth[1].translation;
    // (x is pinned only by the edges of the patch seen through the doorway: not tested.)
    assert!(error.y.abs() < 0.01, "pulled across the wall: {error:?}");
    assert!(error.z.abs() < 0.01, "{error:?}");
}
