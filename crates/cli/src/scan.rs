//! `semsim scan`: virtual scans of a building from given poses, with ground truth and odometry.

use crate::config::SemsimConfig;
use crate::exit::bad_input;
use anyhow::Context;
use clap::Args;
use cloud::NamedPose;
use indicatif::{ProgressBar, ProgressStyle};
use scanner::{Building, BuildingGeometry, ScanPose, VirtualLaser};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `semsim scan`.
#[derive(Args)]
pub struct ScanArgs {
    /// The building description (TOML or JSON).
    #[arg(long, value_name = "FILE")]
    building: PathBuf,
    /// A scan pose `x,y,yaw_deg` (metres, degrees); repeat for a sequence.
    #[arg(long = "pose", value_name = "X,Y,YAW", required = true, value_parser = parse_pose)]
    poses: Vec<ScanPose>,
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Range noise sigma in metres (overrides the configuration).
    #[arg(long, value_name = "M")]
    noise: Option<f64>,
}

/// Parses `x,y,yaw_deg`.
pub fn parse_pose(s: &str) -> Result<ScanPose, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|f| {
            f.trim()
                .parse::<f64>()
                .map_err(|_| format!("'{f}' is not a number"))
        })
        .collect::<Result<_, _>>()?;
    match v.as_slice() {
        [x_m, y_m, yaw_deg] if v.iter().all(|x| x.is_finite()) => Ok(ScanPose {
            x_m: *x_m,
            y_m: *y_m,
            yaw_deg: *yaw_deg,
        }),
        _ => Err(format!(
            "expected three finite numbers x,y,yaw_deg, got '{s}'"
        )),
    }
}

/// Runs `semsim scan`.
pub fn run(a: ScanArgs, cfg: &SemsimConfig) -> anyhow::Result<()> {
    let building = Building::load(&a.building)?;
    let mut cfg = cfg.clone();
    if let Some(n) = a.noise {
        cfg.laser.range_noise_sigma_m = n;
    }
    std::fs::create_dir_all(&a.out).map_err(|e| cloud::CloudError::io(&a.out, e))?;
    let summary = write_scans(&building, &a.poses, &cfg, &a.out)?;
    summary.print();
    Ok(())
}

/// What `write_scans` wrote.
pub struct ScanSummary {
    /// Files written, in order.
    pub files: Vec<PathBuf>,
    /// Points per scan (valid returns).
    pub valid_points: Vec<usize>,
    /// Seconds spent scanning (ray casting only).
    pub scan_secs: f64,
    /// Rays per scan.
    pub rays_per_scan: usize,
}

impl ScanSummary {
    /// Prints a short summary.
    pub fn print(&self) {
        let n = self.valid_points.len();
        println!(
            "{n} scans of {} rays in {:.2} s ({:.1} ms per scan), {} returns",
            self.rays_per_scan,
            self.scan_secs,
            1e3 * self.scan_secs / n.max(1) as f64,
            self.valid_points.iter().sum::<usize>()
        );
        for f in &self.files {
            println!("  wrote {}", f.display());
        }
    }
}

/// Scans `building` from every pose and writes `scanNNN.pcd`, `poses.txt` (ground truth),
/// `odometry.txt`, `entities.json` and `config.toml` into `out`.
pub fn write_scans(
    building: &Building,
    poses: &[ScanPose],
    cfg: &SemsimConfig,
    out: &Path,
) -> anyhow::Result<ScanSummary> {
    let geometry = BuildingGeometry::new(building);
    check_poses(building, &geometry, poses, cfg.laser.mount_height_m)?;
    let laser = VirtualLaser::new(cfg.laser.clone())?;
    let odometry = scanner::odometry_from_truth(poses, &cfg.odometry)?;
    let bar = ProgressBar::new(poses.len() as u64).with_style(
        ProgressStyle::with_template(
            "{msg:>10} [{bar:30}] {pos}/{len} scans, {elapsed} (eta {eta})",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> "),
    );
    bar.set_message("scanning");
    let mut files = Vec::new();
    let mut valid_points = Vec::new();
    let mut truth = Vec::new();
    let mut odo = Vec::new();
    let mut scan_secs = 0.0;
    let h = cfg.laser.mount_height_m;
    for (k, pose) in poses.iter().enumerate() {
        let t0 = Instant::now();
        let scan = laser.scan(&geometry, pose, k as u64);
        scan_secs += t0.elapsed().as_secs_f64();
        let name = format!("scan{k:03}");
        let path = out.join(format!("{name}.pcd"));
        cloud::write_cloud(&path, &scan).with_context(|| format!("writing scan {k}"))?;
        valid_points.push(scan.valid_count());
        truth.push(NamedPose {
            name: name.clone(),
            world_from_scan: pose.world_from_scan(h),
        });
        odo.push(NamedPose {
            name,
            world_from_scan: odometry[k].world_from_scan(h),
        });
        files.push(path);
        bar.inc(1);
    }
    bar.finish_and_clear();
    let poses_path = out.join("poses.txt");
    cloud::write_poses(&poses_path, &truth)?;
    let odo_path = out.join("odometry.txt");
    cloud::write_poses(&odo_path, &odo)?;
    let entities_path = out.join("entities.json");
    let json = serde_json::to_string_pretty(geometry.entities()).context("serialising entities")?;
    cloud::write_bytes_atomically(&entities_path, json.as_bytes())?;
    cfg.write_beside(out)?;
    files.extend([poses_path, odo_path, entities_path, out.join("config.toml")]);
    Ok(ScanSummary {
        files,
        valid_points,
        scan_secs,
        rays_per_scan: cfg.laser.beams * cfg.laser.rotation_steps,
    })
}

/// Every pose must stand on the floor and outside every solid.
fn check_poses(
    b: &Building,
    g: &BuildingGeometry,
    poses: &[ScanPose],
    mount_height_m: f64,
) -> anyhow::Result<()> {
    for (k, p) in poses.iter().enumerate() {
        let (lo, hi) = (b.floor.min_m, b.floor.max_m);
        if p.x_m < lo[0] || p.x_m > hi[0] || p.y_m < lo[1] || p.y_m > hi[1] {
            return Err(bad_input(format!(
                "pose {k} ({},{}) lies outside the building's floor ({}..{}, {}..{})",
                p.x_m, p.y_m, lo[0], hi[0], lo[1], hi[1]
            )));
        }
        let sensor = glam::Vec3::new(p.x_m as f32, p.y_m as f32, mount_height_m as f32);
        if let Some(e) = g.entity_containing(sensor) {
            return Err(bad_input(format!(
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
