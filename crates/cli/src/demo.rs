//! `semsim demo`: the whole chain on the built-in default building.
//! Today: building -> virtual scans with ground truth and noisy odometry.

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
        (14.6, 2.9, 60.0),
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
    println!("done in {:.1} s", t0.elapsed().as_secs_f64());
    Ok(())
}
