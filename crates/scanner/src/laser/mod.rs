//! The virtual 3D laser: a 2D line scanner whose scan plane is vertical, rotated step by step
//! about the vertical axis (the original robot's stop-and-scan sensor, 541 beams x 301 steps).
//!
//! Scan frame: origin at the rotation centre (mounted `mount_height_m` above the floor), x forward,
//! z up. Row `j` of the organised output is the line scan at rotation step `j`; column `i` is beam `i`.
//! Beam `i` has elevation `line_center_elevation_deg - line_fov_deg/2 + i * line_fov_deg/(beams-1)`
//! in that plane, so the default 270 degree fan centred on the zenith sees everything but a 45
//! degree cone under the robot, and 180 degrees of rotation cover all azimuths.
//!
//! By default the laser is ideal (exact geometry plus constant gaussian range noise). Its
//! [`Realism`] section makes it a real sensor: range noise growing with range and incidence
//! ([`RangeNoise`]), lost returns from received power, grazing incidence and glass
//! ([`Returns`]), mixed pixels at depth edges ([`MixedPixels`]), people walking by
//! ([`People`]), a tilted mount ([`Mount`]) and a no-echo value. Every random draw comes from [`cloud::Rng`] streams keyed
//! by the seed, the pose and the beam, so a scan is the same bit for bit whatever the thread
//! count.

mod beam;
mod mixed;
mod mount;
mod noise;
mod people;
mod realism;
mod returns;

use crate::error::Result;
use crate::geometry::BuildingGeometry;
use crate::pose::ScanPose;
use beam::{Beam, Scene};
use cloud::check_range;
use cloud::Rng;
use cloud::{Label, Organized, PointCloud};
use glam::{DAffine3, DQuat, DVec3, Quat, Vec2, Vec3};
use people::Walkers;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

pub use mixed::MixedPixels;
pub use mount::Mount;
pub use noise::RangeNoise;
pub use people::People;
pub use realism::{Realism, PRESETS};
pub use returns::Returns;

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
    /// How real the sensor is: `"ideal"` (the default), `"real"`, or a table of values.
    pub realism: Realism,
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
            realism: Realism::off(),
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
        c.realism.validate(c.max_range_m)?;
        Ok(())
    }
}

/// Salt of the random streams of the mixed pixels (per beam).
const MIXED_SALT: u64 = 0x6D69_7865_645F_7078;
/// Salt of the random stream of the walking people (per scan).
const PEOPLE_SALT: u64 = 0x7065_6F70_6C65_5F31;

/// The seed of one scan: the laser's seed mixed with the pose's index.
fn scan_seed(noise_seed: u64, pose_index: u64) -> u64 {
    noise_seed ^ pose_index.wrapping_mul(0x2545_F491_4F6C_DD1D)
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

    /// The true pose of the frame the scan's points are in: the scan frame of `pose`, tilted
    /// by the mount (the same as `pose.world_from_scan(mount_height_m)` for a level mount).
    /// This is the ground truth a scan folder records.
    pub fn world_from_sensor(&self, pose: &ScanPose) -> DAffine3 {
        let world_from_scan = pose.world_from_scan(self.config.mount_height_m);
        let mount = &self.config.realism.mount;
        if *mount == Mount::off() {
            // Exactly the level pose (not multiplied by an identity, which turns -0 into 0).
            return world_from_scan;
        }
        world_from_scan * DAffine3::from_quat(mount.scan_from_sensor())
    }

    /// Scans `geometry` from `pose`. Points are in the sensor frame (the scan frame, tilted by
    /// the mount if the realism says so: see [`Self::world_from_sensor`]), organised
    /// `rotation_steps x beams`, missing returns NaN (or at the no-echo range), every point
    /// labelled with the surface it hit (unknown where no building surface explains it).
    /// `pose_index` varies the noise between poses deterministically.
    pub fn scan(
        &self,
        geometry: &BuildingGeometry,
        pose: &ScanPose,
        pose_index: u64,
    ) -> PointCloud {
        let c = &self.config;
        let seed = scan_seed(c.noise_seed, pose_index);
        let (points, labels) = if c.realism.is_off() {
            self.scan_ideal(geometry, pose, seed)
        } else {
            self.scan_real(geometry, pose, seed)
        };
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

    /// Where the walking people of the scan from `pose` (the `pose_index`-th) are at each
    /// rotation step: one list of centres on the floor (world frame) per row of the scan, one
    /// centre per person (the ground truth of their streaks; empty lists without people).
    pub fn people_at(
        &self,
        geometry: &BuildingGeometry,
        pose: &ScanPose,
        pose_index: u64,
    ) -> Vec<Vec<Vec2>> {
        let seed = scan_seed(self.config.noise_seed, pose_index);
        self.walkers(geometry, pose, seed).at
    }

    /// The people of one scan, drawn from the scan's seed.
    fn walkers(&self, geometry: &BuildingGeometry, pose: &ScanPose, seed: u64) -> Walkers {
        self.config.realism.people.walk(
            geometry,
            Vec2::new(pose.x_m as f32, pose.y_m as f32),
            self.config.rotation_steps,
            &mut Rng::new(seed ^ PEOPLE_SALT),
        )
    }

    /// The ideal laser: exact geometry plus constant gaussian range noise.
    fn scan_ideal(
        &self,
        geometry: &BuildingGeometry,
        pose: &ScanPose,
        seed: u64,
    ) -> (Vec<Vec3>, Vec<Label>) {
        let c = &self.config;
        let world_from_scan = pose.world_from_scan(c.mount_height_m);
        let origin = world_from_scan.translation.as_vec3();
        let rot = Quat::from_rotation_z(pose.yaw_deg.to_radians() as f32);
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
        self.dirs_in_scan
            .par_iter()
            .enumerate()
            .with_min_len(1024)
            .map(cast)
            .unzip()
    }

    /// The realistic laser, in three steps.
    fn scan_real(
        &self,
        geometry: &BuildingGeometry,
        pose: &ScanPose,
        seed: u64,
    ) -> (Vec<Vec3>, Vec<Label>) {
        let c = &self.config;
        let r = &c.realism;
        let (rows, cols) = (c.rotation_steps, c.beams);
        // 1. The scene: the tilted sensor, and the people of this scan on their walk.
        let world_from_sensor = self.world_from_sensor(pose);
        let origin = world_from_sensor.translation.as_vec3();
        let walkers = self.walkers(geometry, pose, seed);
        let scene = Scene {
            geometry,
            walkers,
            origin,
            world_from_sensor: (DQuat::from_rotation_z(pose.yaw_deg.to_radians())
                * r.mount.scan_from_sensor())
            .as_quat(),
            min_range_m: c.min_range_m as f32,
            max_range_m: c.max_range_m as f32,
            sigma0_m: c.range_noise_sigma_m,
            realism: r,
        };
        // 2. Every beam: first surface, its fate, noise (one random stream per beam).
        let mut beams: Vec<Beam> = self
            .dirs_in_scan
            .par_iter()
            .enumerate()
            .with_min_len(1024)
            .map(|(i, d)| scene.trace(i / cols, *d, &mut Rng::stream(seed, i as u64)))
            .collect();
        // 3. Mixed pixels: beams next to a depth edge looked at again with their footprint.
        if r.mixed.probability > 0.0 && r.beam_divergence_mrad > 0.0 {
            let first_t: Vec<f32> = beams.iter().map(|b| b.first_t).collect();
            let first_id: Vec<u32> = beams.iter().map(|b| b.first_id).collect();
            let candidates = r.mixed.edge_candidates(&first_t, &first_id, rows, cols);
            let divergence = (r.beam_divergence_mrad * 1e-3) as f32;
            let mixed: Vec<(usize, f32)> = candidates
                .par_iter()
                .filter(|&&k| beams[k].from_first)
                .filter_map(|&k| {
                    let d = self.dirs_in_scan[k];
                    let (mut t, mut ids) = ([first_t[k]; 5], [first_id[k]; 5]);
                    let rim = MixedPixels::footprint_rim(d, divergence);
                    for ((t, id), e) in t[1..].iter_mut().zip(&mut ids[1..]).zip(rim) {
                        let dir = scene.world_from_sensor * e;
                        let s =
                            scene.first_surface(k / cols, origin, dir, scene.max_range_m, true)?;
                        (*t, *id) = (s.t, s.id);
                    }
                    let mut rng = Rng::stream(seed ^ MIXED_SALT, k as u64);
                    Some((k, r.mixed.mixed_range(&t, &ids, &mut rng)?))
                })
                .collect();
            for (k, range) in mixed {
                beams[k].point = self.dirs_in_scan[k] * range;
                beams[k].label = Label::default();
            }
        }
        beams.into_iter().map(|b| (b.point, b.label)).unzip()
    }
}
