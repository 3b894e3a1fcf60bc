//! `semsim demo`: the whole chain on the built-in default building.
//! Today: building -> virtual scans with ground truth and noisy odometry -> registration
//! from the odometry, with pose errors against ground truth.

use crate::config::SemsimConfig;
use clap::Args;
use scanner::{Building, ScanPose};
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `semsim demo`.
#[derive(Args)]
pub struct DemoArgs {
    /// Output folder.
    #[arg(long, value_name = "DIR", default_value = "semsim-demo")]
    out: PathBuf,
}

/// The demo's scan poses: down the corridor, through the half-open door, into the stair room.
pub fn demo_poses() -> Vec<ScanPose> {
    [
        (1.5, 0.0, 0.0),
        (4.0, 0.1, 0.0),
        (6.5, -0.1, 0.0),
        (9.0, 0.0, 0.0),
        (11.5, 0.1, 0.0),
        (14.4, 0.0, 45.0),
        (14.45, 1.2, 80.0),
        (14.9, 2.2, 0.0),
        (17.5, 2.5, 0.0),
    ]
    .into_iter()
    .map(|(x_m, y_m, yaw_deg)| ScanPose { x_m, y_m, yaw_deg })
    .collect()
}

/// Runs the demo.
pub fn run(a: DemoArgs, cfg: &SemsimConfig) -> anyhow::Result<()> {
    let t0 = Instant::now();
    let building = Building::default_building()?;
    std::fs::create_dir_all(&a.out).map_err(|e| cloud::CloudError::io(&a.out, e))?;
    let building_path = a.out.join("building.toml");
    building.save(&building_path)?;
    println!("semsim demo -> {}", a.out.display());
    println!("building: {}", crate::building_cmd::summary(&building));
    let summary = crate::scan::write_scans(&building, &demo_poses(), cfg, &a.out)?;
    summary.print();
    println!("  wrote {}", building_path.display());
    register_scans(&a.out, cfg)?;
    println!("simulation of the default scenario (world from the building description):");
    let scenario = sim::Scenario::default_scenario()?;
    let text = sim::Scenario::default_scenario_toml();
    let passed = crate::simulate::simulate(
        &building,
        &scenario,
        text,
        std::path::Path::new("."),
        &a.out.join("simulation"),
    )?;
    println!("verdict: {}", if passed { "PASSED" } else { "FAILED" });
    println!("done in {:.1} s", t0.elapsed().as_secs_f64());
    Ok(())
}

/// Registers the demo's scans from their noisy odometry into `out/registration/` and reports
/// the pose errors of odometry and registration against ground truth.
fn register_scans(out: &std::path::Path, cfg: &SemsimConfig) -> anyhow::Result<()> {
    let input = crate::register::collect_sequence(&[out.to_path_buf()], None, None)?;
    let scans = input
        .files
        .iter()
        .map(|f| cloud::read_cloud(f))
        .collect::<Result<Vec<_>, _>>()?;
    let reg_dir = out.join("registration");
    std::fs::create_dir_all(&reg_dir).map_err(|e| cloud::CloudError::io(&reg_dir, e))?;
    println!(
        "registration ({}) of {} scans from noisy odometry:",
        cfg.registration.icp.method.short_name(),
        scans.len()
    );
    crate::register::register_and_write(&input, &scans, &cfg.registration, &reg_dir)?;
    let registered = cloud::read_poses(&reg_dir.join("poses.txt"))?;
    let worst = |poses: &[glam::DAffine3]| {
        poses
            .iter()
            .zip(&input.truth)
            .fold((0.0f64, 0.0f64), |(m, d), (p, t)| {
                let (em, ed) = crate::register::pose_error(
                    &(input.truth[0].inverse() * *t),
                    &(poses[0].inverse() * *p),
                );
                (m.max(em), d.max(ed))
            })
    };
    let (om, od) = worst(&input.odometry);
    let reg: Vec<glam::DAffine3> = registered.iter().map(|p| p.world_from_scan).collect();
    let (rm, rd) = worst(&reg);
    println!(
        "worst pose error: odometry {om:.3} m / {od:.2} deg -> registered {rm:.4} m / {rd:.3} deg"
    );
    Ok(())
}
