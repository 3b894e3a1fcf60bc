//! Helpers of the GPU parity tests (`gpu_parity.rs`, `gpu_sequence_and_correspondences.rs`):
//! opening the GPU or skipping, stop criteria tight enough to reach the loop's fixed point, and
//! the synthetic and real pairs both files register.

use super::scan_pair_at;
use cloud::PointCloud;
use glam::{DAffine3, DQuat, DVec3};
use registration::*;
use scanner::ScanPose;

/// Opens the GPU path, or says why the test is skipped (no adapter at all).
pub fn gpu_or_skip(test: &str) -> bool {
    let config = IcpConfig {
        method: Method::PointToPoint,
        device: Device::Gpu,
        ..IcpConfig::default()
    };
    match Registrar::new(&config) {
        Ok(r) => {
            eprintln!("{test}: {}", r.description());
            true
        }
        Err(RegistrationError::Gpu {
            error: gpu::GpuError::NoAdapter(why),
            ..
        }) => {
            eprintln!("{test}: SKIPPED: no GPU adapter at all ({why})");
            false
        }
        Err(e) => panic!("{test}: opening the GPU failed: {e}"),
    }
}

/// `config` with stop criteria tight enough to reach the fixed point.
pub fn tight(config: IcpConfig) -> IcpConfig {
    IcpConfig {
        translation_epsilon_m: 1e-6,
        rotation_epsilon_deg: 1e-5,
        rmse_relative_epsilon: 0.0,
        max_iterations: 100,
        ..config
    }
}

/// Room B of the default building, scanned 1 m and 5 degrees apart.
pub fn room_pair() -> (PointCloud, PointCloud, DAffine3) {
    scan_pair_at(
        181,
        91,
        ScanPose {
            x_m: 8.5,
            y_m: 3.8,
            yaw_deg: 0.0,
        },
        ScanPose {
            x_m: 9.5,
            y_m: 3.8,
            yaw_deg: 5.0,
        },
    )
}

/// PCL's two room scans (target, source) from the real-data folder `dir`, and the rough guess
/// of `target_from_source` PCL's tutorial starts from.
pub fn pcl_room_pair(dir: &std::path::Path) -> (PointCloud, PointCloud, DAffine3) {
    let dir = dir.join("pcl-room");
    let target = cloud::read_cloud(&dir.join("room_scan1.pcd")).expect("scan1");
    let source = cloud::read_cloud(&dir.join("room_scan2.pcd")).expect("scan2");
    #[allow(clippy::approx_constant)]
    let guess = DAffine3::from_rotation_translation(
        DQuat::from_rotation_z(0.6931),
        DVec3::new(1.79387, 0.720047, 0.0),
    );
    (target, source, guess)
}
