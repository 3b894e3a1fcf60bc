//! Helpers shared by the integration tests: virtual-laser scan pairs with known truth, pose
//! errors, deterministic perturbations, and the real-data folder.
#![allow(dead_code)]

use cloud::PointCloud;
use glam::{DAffine3, DQuat, DVec3};
use scanner::{Building, BuildingGeometry, LaserConfig, ScanPose, VirtualLaser};
use std::path::PathBuf;

/// Helpers of the GPU parity tests.
#[cfg(feature = "gpu")]
pub mod parity;

/// Where the target is scanned (in the corridor of the default building).
pub const TARGET_POSE: ScanPose = ScanPose {
    x_m: 6.5,
    y_m: 0.0,
    yaw_deg: 0.0,
};
/// Where the source is scanned: 1 m along the corridor and turned 5 degrees.
pub const SOURCE_POSE: ScanPose = ScanPose {
    x_m: 7.5,
    y_m: 0.0,
    yaw_deg: 5.0,
};

/// Two scans of the default building (`beams` x `steps`, 1 cm range noise) from
/// [`TARGET_POSE`] and [`SOURCE_POSE`], and the true `target_from_source`.
pub fn scan_pair(beams: usize, steps: usize) -> (PointCloud, PointCloud, DAffine3) {
    scan_pair_at(beams, steps, TARGET_POSE, SOURCE_POSE)
}

/// As [`scan_pair`], from given poses.
pub fn scan_pair_at(
    beams: usize,
    steps: usize,
    target_pose: ScanPose,
    source_pose: ScanPose,
) -> (PointCloud, PointCloud, DAffine3) {
    let building = Building::default_building().expect("default building");
    let geometry = BuildingGeometry::new(&building);
    let config = LaserConfig {
        beams,
        rotation_steps: steps,
        ..LaserConfig::default()
    };
    let mount = config.mount_height_m;
    let laser = VirtualLaser::new(config).expect("laser");
    let target = laser.scan(&geometry, &target_pose, 0);
    let source = laser.scan(&geometry, &source_pose, 1);
    let truth = target_pose.world_from_scan(mount).inverse() * source_pose.world_from_scan(mount);
    (target, source, truth)
}

/// `truth` moved by `trans_m` along `dir` and turned by `rot_deg` about `axis` (applied in
/// the target frame, about the source origin's position).
pub fn perturb(truth: &DAffine3, trans_m: f64, dir: DVec3, rot_deg: f64, axis: DVec3) -> DAffine3 {
    let rot = DQuat::from_axis_angle(axis.normalize(), rot_deg.to_radians());
    let center = truth.translation;
    let about = DAffine3::from_translation(center)
        * DAffine3::from_quat(rot)
        * DAffine3::from_translation(-center);
    DAffine3::from_translation(dir.normalize() * trans_m) * about * *truth
}

/// The anchors' start: 0.3 m and 5 degrees off the truth.
pub fn standard_start(truth: &DAffine3) -> DAffine3 {
    perturb(
        truth,
        0.3,
        DVec3::new(1.0, 1.0, 0.3),
        5.0,
        DVec3::new(0.1, -0.1, 1.0),
    )
}

/// A small deterministic generator (SplitMix64) in [0, 1).
pub struct Rng(pub u64);

impl Rng {
    pub fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A uniformly random unit vector.
    pub fn unit(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(self.next_f64(), self.next_f64(), self.next_f64()) * 2.0 - 1.0;
            let l = v.length();
            if l > 1e-3 && l <= 1.0 {
                return v / l;
            }
        }
    }
}

/// The real scans folder, or None (with a message) if it is absent.
pub fn real_data(test: &str) -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/real");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!(
            "{test}: SKIPPED: real data folder {} is absent",
            dir.display()
        );
        None
    }
}
