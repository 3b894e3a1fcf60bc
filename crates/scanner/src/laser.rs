//! The virtual 3D laser: a 2D line scanner whose scan plane is vertical, rotated step by step
//! about the vertical axis (the original robot's stop-and-scan sensor, 541 beams x 301 steps).
//!
//! Scan frame: origin at the rotation centre (mounted `mount_height_m` above the floor), x forward,
//! z up. Row `j` of the organised output is the line scan at rotation step `j`; column `i` is beam `i`.
//! Beam `i` has elevation `line_center_elevation_deg - line_fov_deg/2 + i * line_fov_deg/(beams-1)`
//! in that plane, so the default 270 degree fan centred on the zenith sees everything but a 45
//! degree cone under the robot, and 180 degrees of rotation cover all azimuths.

use crate::error::Result;
use crate::geometry::BuildingGeometry;
use crate::pose::ScanPose;
use cloud::check_range;
use cloud::Rng;
use cloud::{Label, Organized, PointCloud};
use glam::{DVec3, Quat, Vec3};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Configuration of the virtual laser.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LaserConfig {
    /// Beams per line scan (columns).
    pub beams: usize,
    /// Angular width of the line scan's fan.
    pub line_fov_deg: f64,
    /// Elevation of the fan's centre (90 = zenith).
    pub line_center_elevation_deg: f64,
    /// Rotation steps about the vertical axis (rows).
    pub rotation_steps: usize,
    /// Total rotation covered by the steps.
    pub rotation_fov_deg: f64,
    /// Returns beyond this are missing.
    pub max_range_m: f64,
    /// Returns nearer than this are missing.
    pub min_range_m: f64,
    /// Standard deviation of the gaussian range noise.
    pub range_noise_sigma_m: f64,
    /// Height of the rotation centre above the floor.
    pub mount_height_m: f64,
    /// Seed of the range noise (each pose also mixes in its index).
    pub noise_seed: u64,
}

impl Default for LaserConfig {
    fn default() -> Self {
        LaserConfig {
            beams: 541,
            line_fov_deg: 270.0,
            line_center_elevation_deg: 90.0,
            rotation_steps: 301,
            rotation_fov_deg: 180.0,
            max_range_m: 30.0,
            min_range_m: 0.05,
            range_noise_sigma_m: 0.01,
            mount_height_m: 0.5,
            noise_seed: 1,
        }
    }
}

impl LaserConfig {
    /// Checks every parameter's range.
    pub fn validate(&self) -> Result<()> {
        let c = self;
        check_range(
            "beams",
            c.beams as f64,
            2.0,
            20_000.0,
            "2..20000 beams per line",
        )?;
        check_range(
            "rotation_steps",
            c.rotation_steps as f64,
            1.0,
            20_000.0,
            "1..20000 steps",
        )?;
        let rays = (c.beams * c.rotation_steps) as f64;
        check_range(
            "beams*rotation_steps",
            rays,
            2.0,
            50e6,
            "at most 50 million rays per scan",
        )?;
        check_range(
            "line_fov_deg",
            c.line_fov_deg,
            1e-3,
            360.0,
            "within (0, 360]",
        )?;
        check_range(
            "rotation_fov_deg",
            c.rotation_fov_deg,
            0.0,
            360.0,
            "within [0, 360]",
        )?;
        check_range(
            "line_center_elevation_deg",
            c.line_center_elevation_deg,
            -180.0,
            180.0,
            "within -180..180",
        )?;
        check_range(
            "max_range_m",
            c.max_range_m,
            0.1,
            10_000.0,
            "within 0.1..10000 m",
        )?;
        check_range(
            "min_range_m",
            c.min_range_m,
            0.0,
            c.max_range_m,
            "within 0..max_range_m",
        )?;
        check_range(
            "range_noise_sigma_m",
            c.range_noise_sigma_m,
            0.0,
            1.0,
            "within 0..1 m",
        )?;
        check_range(
            "mount_height_m",
            c.mount_height_m,
            0.0,
            50.0,
            "within 0..50 m",
        )?;
        Ok(())
    }
}

/// A configured virtual laser with its precomputed beam directions.
pub struct VirtualLaser {
    config: LaserConfig,
    /// Unit beam directions in the scan frame, row-major (rotation step, beam).
    dirs_in_scan: Vec<Vec3>,
}

impl VirtualLaser {
    /// Checks the configuration and precomputes the beam directions.
    pub fn new(config: LaserConfig) -> Result<VirtualLaser> {
        let c = &config;
        c.validate()?;
        let beam_step = c.line_fov_deg / (c.beams - 1) as f64;
        let rot_step = c.rotation_fov_deg / c.rotation_steps as f64;
        let first = c.line_center_elevation_deg - c.line_fov_deg / 2.0;
        let mut dirs_in_scan = Vec::with_capacity(c.beams * c.rotation_steps);
        for j in 0..c.rotation_steps {
            let (sp, cp) = (j as f64 * rot_step).to_radians().sin_cos();
            for i in 0..c.beams {
                let (st, ct) = (first + i as f64 * beam_step).to_radians().sin_cos();
                dirs_in_scan.push(DVec3::new(ct * cp, ct * sp, st).as_vec3());
            }
        }
        Ok(VirtualLaser {
            config,
            dirs_in_scan,
        })
    }

    /// The configuration in use.
    pub fn config(&self) -> &LaserConfig {
        &self.config
    }

    /// Scans `geometry` from `pose`. Points are in the scan frame, organised
    /// `rotation_steps x beams`, missing returns NaN, every point labelled with the surface it hit.
    /// `pose_index` varies the noise between poses deterministically.
    pub fn scan(
        &self,
        geometry: &BuildingGeometry,
        pose: &ScanPose,
        pose_index: u64,
    ) -> PointCloud {
        let c = &self.config;
        let world_from_scan = pose.world_from_scan(c.mount_height_m);
        let origin = world_from_scan.translation.as_vec3();
        let rot = Quat::from_rotation_z(pose.yaw_deg.to_radians() as f32);
        let seed = c.noise_seed ^ pose_index.wrapping_mul(0x2545_F491_4F6C_DD1D);
        let (min_r, max_r, sigma) = (
            c.min_range_m as f32,
            c.max_range_m as f32,
            c.range_noise_sigma_m,
        );
        let cast = |(i, d): (usize, &Vec3)| -> (Vec3, Label) {
            match geometry.cast_ray(origin, rot * *d, max_r) {
                Some((toi, label)) if toi >= min_r => {
                    let noise = if sigma > 0.0 {
                        sigma * Rng::stream(seed, i as u64).gaussian()
                    } else {
                        0.0
                    };
                    (*d * (toi + noise as f32), label)
                }
                _ => (Vec3::NAN, Label::default()),
            }
        };
        let (points, labels): (Vec<Vec3>, Vec<Label>) = self
            .dirs_in_scan
            .par_iter()
            .enumerate()
            .with_min_len(1024)
            .map(cast)
            .unzip();
        PointCloud {
            points,
            intensity: None,
            labels: Some(labels),
            classification: None,
            organized: Some(Organized {
                rows: c.rotation_steps,
                cols: c.beams,
            }),
            sensor_origin: Vec3::ZERO,
            sensor_orientation: Quat::IDENTITY,
        }
    }
}
