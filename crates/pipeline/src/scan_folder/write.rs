//! Writing a scan folder: virtual scans of a building from given poses, with ground truth,
//! odometry and the building's entities.

use super::{ENTITIES_FILE, ODOMETRY_FILE, TRUTH_FILE};
use crate::config::Config;
use crate::error::{to_json, PipelineError, Result};
use cloud::NamedPose;
use scanner::{Building, BuildingGeometry, ScanPose, VirtualLaser};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What [`write_scan_folder`] wrote.
#[derive(Debug, Clone)]
pub struct ScanFolderSummary {
    /// Files written, in order (scans first).
    pub files: Vec<PathBuf>,
    /// Points per scan (valid returns).
    pub valid_points: Vec<usize>,
    /// Seconds spent scanning (ray casting only).
    pub scan_secs: f64,
    /// Rays per scan.
    pub rays_per_scan: usize,
}

/// Scans `building` from every pose and writes `scanNNN.pcd`, `poses.txt` (ground truth),
/// `odometry.txt`, `entities.json` and `config.toml` into `out` (which must exist).
/// `progress(done, total)` is called after each scan.
pub fn write_scan_folder(
    building: &Building,
    poses: &[ScanPose],
    cfg: &Config,
    out: &Path,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<ScanFolderSummary> {
    // 1. Check every pose stands on the floor, outside every solid.
    let geometry = BuildingGeometry::new(building);
    check_poses(building, &geometry, poses, cfg.laser.mount_height_m)?;
    // 2. The laser and the odometry the robot would have measured between the poses.
    let laser = VirtualLaser::new(cfg.laser.clone())?;
    let odometry = scanner::odometry_from_truth(poses, &cfg.odometry)?;
    // 3. Scan from every pose and write each scan as it is made.
    let h = cfg.laser.mount_height_m;
    let (mut files, mut valid_points, mut truth, mut odo) = (vec![], vec![], vec![], vec![]);
    let mut scan_secs = 0.0;
    for (k, pose) in poses.iter().enumerate() {
        let t0 = Instant::now();
        let scan = laser.scan(&geometry, pose, k as u64);
        scan_secs += t0.elapsed().as_secs_f64();
        let name = format!("scan{k:03}");
        let path = out.join(format!("{name}.pcd"));
        cloud::write_cloud(&path, &scan)?;
        valid_points.push(scan.valid_count());
        truth.push(NamedPose {
            name: name.clone(),
            // The sensor's true pose (tilted by its mount, if the laser's realism tilts it).
            world_from_scan: laser.world_from_sensor(pose),
        });
        odo.push(NamedPose {
            name,
            world_from_scan: odometry[k].world_from_scan(h),
        });
        files.push(path);
        progress(k + 1, poses.len());
    }
    // 4. Ground truth, odometry, entities and the configuration beside the scans.
    let poses_path = out.join(TRUTH_FILE);
    cloud::write_poses(&poses_path, &truth)?;
    let odo_path = out.join(ODOMETRY_FILE);
    cloud::write_poses(&odo_path, &odo)?;
    let entities_path = out.join(ENTITIES_FILE);
    let json = to_json("the entities", &geometry.entities())?;
    cloud::write_bytes_atomically(&entities_path, json.as_bytes())?;
    cfg.write_beside(out)?;
    files.extend([poses_path, odo_path, entities_path, out.join("config.toml")]);
    Ok(ScanFolderSummary {
        files,
        valid_points,
        scan_secs,
        rays_per_scan: cfg.laser.beams * cfg.laser.rotation_steps,
    })
}

/// The largest heading accepted (ten turns): beyond it a number is a typo, and f64 loses the angle.
const MAX_YAW_DEG: f64 = 3600.0;

/// Every pose must stand on the floor and outside every solid, with a sensible heading.
fn check_poses(
    b: &Building,
    g: &BuildingGeometry,
    poses: &[ScanPose],
    mount_height_m: f64,
) -> Result<()> {
    for (k, p) in poses.iter().enumerate() {
        if !p.yaw_deg.is_finite() || p.yaw_deg.abs() > MAX_YAW_DEG {
            return Err(PipelineError::bad_input(format!(
                "pose {k}: yaw {} deg is not a heading (give one within -{MAX_YAW_DEG}..{MAX_YAW_DEG})",
                p.yaw_deg
            )));
        }
        let (lo, hi) = (b.floor.min_m, b.floor.max_m);
        if p.x_m < lo[0] || p.x_m > hi[0] || p.y_m < lo[1] || p.y_m > hi[1] {
            return Err(PipelineError::bad_input(format!(
                "pose {k} ({},{}) lies outside the building's floor ({}..{}, {}..{})",
                p.x_m, p.y_m, lo[0], hi[0], lo[1], hi[1]
            )));
        }
        let sensor = glam::Vec3::new(p.x_m as f32, p.y_m as f32, mount_height_m as f32);
        if let Some(e) = g.entity_containing(sensor) {
            return Err(PipelineError::bad_input(format!(
                "pose {k} ({},{}) puts the laser inside {} ({})",
                p.x_m,
                p.y_m,
                e.name,
                e.class.name()
            )));
        }
    }
    Ok(())
}
