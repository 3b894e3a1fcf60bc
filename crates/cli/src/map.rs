//! `semsim map`: a (registered) cloud -> the semantic map, its labelled cloud and the pictures
//! of every stage; and `semsim eval map`: a semantic map against a building's ground truth.

use crate::exit::bad_input;
use crate::scan_input::ScanReadArgs;
use anyhow::Context;
use clap::{Args, Subcommand};
use pipeline::{build_map, merge_scan_files, write_map, Config};
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `semsim map`.
#[derive(Args)]
pub struct MapArgs {
    /// The cloud(s): one registered map, or scans placed with --poses.
    #[arg(required = true, value_name = "CLOUD")]
    clouds: Vec<PathBuf>,
    /// A pose file (`name` + row-major 4x4 `world_from_scan` per line, as `semsim register`
    /// writes): each scan is placed by the pose of its file stem (or by order).
    #[arg(long, value_name = "FILE")]
    poses: Option<PathBuf>,
    /// Drop points farther than this from their scan's sensor (e.g. 30 for 3DTK's no-echo
    /// readings at 32.7 m).
    #[arg(long, value_name = "M")]
    max_range_m: Option<f64>,
    /// Downsample the merged cloud to this voxel edge first (labels.pcd is then the
    /// downsampled cloud).
    #[arg(long, value_name = "M")]
    voxel_m: Option<f64>,
    /// Output folder.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    #[command(flatten)]
    read: ScanReadArgs,
}

/// `semsim eval ...`.
#[derive(Subcommand)]
pub enum EvalCommand {
    /// Score a semantic map against the building it was scanned in: per-class precision,
    /// recall and F1, wall endpoint errors, stairs step counts and rise/run errors.
    Map(EvalMapArgs),
}

/// Arguments of `semsim eval map`.
#[derive(Args)]
pub struct EvalMapArgs {
    /// The semantic map (semantic_map.json).
    #[arg(value_name = "MAP")]
    map: PathBuf,
    /// The building description (TOML/JSON) it was scanned in; "default" for the built-in one.
    #[arg(long, value_name = "FILE")]
    building: PathBuf,
    /// The scans the map was made from, with their ground-truth labels (as `semsim scan` and
    /// `semsim demo` write them; not the map's labels.pcd, whose labels are the map's own):
    /// only what they saw is expected. Without them every element of the building is expected.
    #[arg(long, value_name = "FILE", num_args = 1..)]
    cloud: Vec<PathBuf>,
    /// World poses of the `--cloud` scans (as for `semsim map`); without it they are taken as
    /// given (already in the world frame).
    #[arg(long, value_name = "FILE", requires = "cloud")]
    poses: Option<PathBuf>,
    /// The scans' true poses (`poses.txt` as `semsim scan` wrote it) when --poses are a
    /// registration's: the registration's frame (turned by the laser mount's tilt, which
    /// odometry does not know) is related to the building's before scoring, as trajectory
    /// evaluations align trajectories first.
    #[arg(long, value_name = "FILE", requires = "poses")]
    true_poses: Option<PathBuf>,
    /// Print the full evaluation as JSON instead of the table.
    #[arg(long)]
    json: bool,
}

/// Runs `semsim map`.
pub fn run(a: MapArgs, cfg: &Config) -> anyhow::Result<()> {
    if let Some(v) = a.voxel_m {
        if !(v.is_finite() && v > 0.0 && v <= 10.0) {
            return Err(bad_input(format!(
                "--voxel-m {v}: must be a length within (0, 10] m"
            )));
        }
    }
    pipeline::check_output_dir(&a.out)?;
    let t0 = Instant::now();
    let mut cloud = merge_scan_files(
        &a.clouds,
        a.poses.as_deref(),
        a.max_range_m,
        &a.read.options(),
        &cfg.outliers,
        &cfg.mixed_pixels,
        &cfg.transients,
    )?;
    if let Some(v) = a.voxel_m {
        cloud = cloud::voxel_downsample(&cloud, v)?;
    }
    println!(
        "semantic map of {} points from {} file(s) (read in {:.0} ms)",
        cloud.len(),
        a.clouds.len(),
        t0.elapsed().as_secs_f64() * 1e3
    );
    let output = build_map(&cloud, &cfg.semantic)?;
    std::fs::create_dir_all(&a.out).map_err(|e| cloud::CloudError::io(&a.out, e))?;
    write_map(&output, &cloud, &a.out)?;
    cfg.write_beside(&a.out)?;
    crate::print::map(&output);
    crate::print::map_written(&a.out);
    Ok(())
}

/// Runs `semsim eval ...`.
pub fn run_eval(c: EvalCommand) -> anyhow::Result<()> {
    let EvalCommand::Map(a) = c;
    let ev = pipeline::score_map_file(
        &a.map,
        &a.building,
        &a.cloud,
        a.poses.as_deref(),
        a.true_poses.as_deref(),
    )?;
    if a.json {
        let text = serde_json::to_string_pretty(&ev).context("serialising the evaluation")?;
        println!("{text}");
    } else {
        println!("{ev}");
    }
    Ok(())
}
