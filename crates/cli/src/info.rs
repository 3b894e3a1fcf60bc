//! `semsim info FILE`: what a point cloud file holds (every scan of a multi-scan file).

use crate::scan_input::ScanReadArgs;
use clap::Args;
use cloud::PointCloud;
use std::path::PathBuf;

/// Arguments of `semsim info`.
#[derive(Args)]
pub struct InfoArgs {
    /// The cloud to describe (.pcd .ply .xyz .txt .3d .e57 .las .laz .mcap).
    file: PathBuf,
    #[command(flatten)]
    read: ScanReadArgs,
}

/// Prints points, shape, channels, bounding box and label classes of each scan.
pub fn run(a: InfoArgs) -> anyhow::Result<()> {
    let set = interop::read_scans(&a.file, &a.read.options())?;
    cloud::io::print_notes(&set.notes);
    println!("file:      {}", a.file.display());
    let o = set.local_origin_m;
    if o != glam::DVec3::ZERO {
        println!(
            "origin m:  {:.3} {:.3} {:.3} (coordinates below are relative to it)",
            o.x, o.y, o.z
        );
    }
    if set.scans.len() != 1 {
        println!("scans:     {}", set.scans.len());
    }
    for (k, scan) in set.scans.iter().enumerate() {
        if set.scans.len() != 1 {
            println!("scan {k}:    {}", scan.name);
        }
        if let Some(frame) = &scan.frame_id {
            println!("frame:     {frame}");
        }
        if let Some(ns) = scan.stamp_ns {
            println!("stamp s:   {:.9}", ns as f64 * 1e-9);
        }
        if let Some(pose) = scan.world_from_scan {
            let t = pose.translation;
            let (axis, angle) = glam::DQuat::from_mat3(&pose.matrix3).to_axis_angle();
            println!(
                "pose:      at {:.3} {:.3} {:.3} m, rotated {:.2} deg about ({:.3}, {:.3}, {:.3})",
                t.x,
                t.y,
                t.z,
                angle.to_degrees(),
                axis.x,
                axis.y,
                axis.z
            );
        }
        if let Some(odometry) = set.odometry.as_ref().and_then(|o| o.get(k)) {
            let t = odometry.translation;
            println!("odometry:  at {:.3} {:.3} {:.3} m", t.x, t.y, t.z);
        }
        describe(&scan.cloud);
    }
    Ok(())
}

/// Prints one cloud's points, shape, channels, bounds and labels.
fn describe(c: &PointCloud) {
    println!("points:    {} ({} valid)", c.len(), c.valid_count());
    match c.organized {
        Some(o) => println!("organised: {} rows x {} cols", o.rows, o.cols),
        None => println!("organised: no"),
    }
    println!(
        "intensity: {}",
        if c.intensity.is_some() { "yes" } else { "no" }
    );
    if let Some(b) = c.bounding_box() {
        let (lo, hi) = (b.min, b.max);
        println!(
            "bounds m:  x {:.3}..{:.3}  y {:.3}..{:.3}  z {:.3}..{:.3}",
            lo.x, hi.x, lo.y, hi.y, lo.z, hi.z
        );
    }
    if let Some(labels) = &c.labels {
        let mut counts = std::collections::BTreeMap::new();
        for l in labels {
            *counts.entry(l.class.name()).or_insert(0usize) += 1;
        }
        let list: Vec<String> = counts.iter().map(|(k, v)| format!("{k} {v}")).collect();
        println!("labels:    {}", list.join(", "));
    }
    if let Some(classes) = &c.classification {
        let mut counts = std::collections::BTreeMap::new();
        for &code in classes {
            *counts.entry(code).or_insert(0usize) += 1;
        }
        let list: Vec<String> = counts.iter().map(|(k, v)| format!("{k}: {v}")).collect();
        println!("ASPRS classes: {}", list.join(", "));
    }
}
