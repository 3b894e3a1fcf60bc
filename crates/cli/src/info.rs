//! `semsim info FILE`: what a point cloud file holds.

use clap::Args;
use std::path::PathBuf;

/// Arguments of `semsim info`.
#[derive(Args)]
pub struct InfoArgs {
    /// The cloud to describe.
    file: PathBuf,
}

/// Prints points, shape, channels, bounding box and label classes.
pub fn run(a: InfoArgs) -> anyhow::Result<()> {
    let c = cloud::read_cloud(&a.file)?;
    println!("file:      {}", a.file.display());
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
    Ok(())
}
