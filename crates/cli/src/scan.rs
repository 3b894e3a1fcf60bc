//! `semsim scan`: virtual scans of a building from given poses, with ground truth and odometry.

use clap::Args;
use pipeline::{write_scan_folder, Config, ScanFolderSummary};
use scanner::{Building, ScanPose};
use std::path::PathBuf;

/// Arguments of `semsim scan`.
#[derive(Args)]
pub struct ScanArgs {
    /// The building description (TOML or JSON).
    #[arg(long, value_name = "FILE")]
    building: PathBuf,
    /// A scan pose `x,y,yaw_deg` (metres, degrees); repeat for a sequence.
    #[arg(long = "pose", value_name = "X,Y,YAW", required_unless_present = "survey",
          conflicts_with = "survey", value_parser = parse_pose)]
    poses: Vec<ScanPose>,
    /// Choose the poses as a surveyor would (along corridors, into every room through an open
    /// door, each scan near an earlier one) instead of giving them with --pose.
    #[arg(long)]
    survey: bool,
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Range noise sigma in metres (overrides the configuration).
    #[arg(long, value_name = "M")]
    noise: Option<f64>,
    /// The laser: `ideal` (exact geometry) or `real` (a SICK LMS 200's noise, dropouts,
    /// mixed pixels, glass, walking people, a tilted mount, no-echo readings; see the README).
    #[arg(long = "laser", value_name = "PRESET", value_parser = scanner::PRESETS)]
    laser: Option<String>,
}

/// Parses `x,y,yaw_deg`.
fn parse_pose(s: &str) -> Result<ScanPose, String> {
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
pub fn run(a: ScanArgs, cfg: &Config) -> anyhow::Result<()> {
    pipeline::check_output_dir(&a.out)?;
    let building = Building::load(&a.building)?;
    let poses = if a.survey {
        let poses = scanner::survey_poses(&building, &cfg.survey)
            .map_err(|e| anyhow::Error::from(e).context(a.building.display().to_string()))?;
        println!("survey: {} poses", poses.len());
        poses
    } else {
        a.poses
    };
    let mut cfg = cfg.clone();
    if let Some(n) = a.noise {
        cfg.laser.range_noise_sigma_m = n;
    }
    if let Some(preset) = &a.laser {
        cfg.laser.realism = scanner::Realism::preset(preset).unwrap_or_default();
    }
    std::fs::create_dir_all(&a.out).map_err(|e| cloud::CloudError::io(&a.out, e))?;
    let bar = crate::progress::scan_bar(poses.len(), "scanning");
    let summary = write_scan_folder(&building, &poses, &cfg, &a.out, &mut |done, _| {
        bar.set_position(done as u64)
    })?;
    bar.finish_and_clear();
    print_summary(&summary);
    Ok(())
}

/// Prints how many scans were made, how fast, and the files written.
pub fn print_summary(s: &ScanFolderSummary) {
    let n = s.valid_points.len();
    println!(
        "{n} scans of {} rays in {:.2} s ({:.1} ms per scan), {} returns",
        s.rays_per_scan,
        s.scan_secs,
        1e3 * s.scan_secs / n.max(1) as f64,
        s.valid_points.iter().sum::<usize>()
    );
    for f in &s.files {
        println!("  wrote {}", f.display());
    }
}
