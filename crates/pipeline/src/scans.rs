//! Scans read for mapping: missing returns, no-echo readings, mixed pixels, isolated points and
//! far points dropped, each placed by its pose and all merged into one cloud in the world frame.

use crate::error::{PipelineError, Result};
use crate::mixed_pixels::MixedPixelConfig;
use crate::outliers::OutlierConfig;
use crate::scan_folder::{expand_files, ScanSource};
use cloud::{NamedPose, PointCloud};
use glam::{DAffine3, DVec3};
use registration::TransientConfig;
use std::path::{Path, PathBuf};

/// Reads scans, dropping missing returns, no-echo readings (a sensor's fixed range for "no
/// echo", found by [`crate::find_no_echo`]; reported on standard error with their count), an
/// organised scan's mixed pixels with the default [`MixedPixelConfig`], statistical outliers
/// with the default [`OutlierConfig`] (see [`read_scans_with`]) and points farther than
/// `max_range_m` from their scan's sensor. Files read in a local frame (georeferenced LAS/LAZ:
/// see [`interop::ScanSet::local_origin_m`]) are moved into the first such file's frame, which
/// is reported on standard error.
pub fn read_scans(sources: &[ScanSource], max_range_m: Option<f64>) -> Result<Vec<PointCloud>> {
    read_scans_with(
        sources,
        max_range_m,
        &OutlierConfig::default(),
        &MixedPixelConfig::default(),
    )
}

/// [`read_scans`] with the run's mixed-pixel and outlier removal (`[mixed_pixels]` and
/// `[outliers]` of the configuration): after the no-echo readings, an organised scan loses its
/// mixed pixels ([`crate::remove_mixed_pixels`]) and each scan its isolated points
/// ([`crate::remove_outliers`]), each reported on standard error with their count when there
/// are any; every point returned is finite (a scan that lost points also loses its organised
/// shape, as `without_invalid` does).
pub fn read_scans_with(
    sources: &[ScanSource],
    max_range_m: Option<f64>,
    outliers: &OutlierConfig,
    mixed_pixels: &MixedPixelConfig,
) -> Result<Vec<PointCloud>> {
    if let Some(r) = max_range_m {
        if !(r.is_finite() && r > 0.0) {
            return Err(PipelineError::bad_input(format!(
                "--max-range-m {r}: must be a positive length"
            )));
        }
    }
    let mut origin: Option<DVec3> = None;
    sources
        .iter()
        .map(|source| {
            let scan = match &source.loaded {
                Some(cloud) => cloud.clone(),
                None => read_one(&source.file, &mut origin)?,
            };
            // An organised scan keeps its grid until its mixed pixels are found (what is
            // dropped before becomes NaN), then loses its missing returns.
            let (scan, no_echo) = crate::no_echo::drop_no_echo(&scan);
            if let Some(found) = no_echo {
                eprintln!(
                    "note: {} ({}): {} no-echo readings at {:.3} m (the farthest range, shared by {:.1} % of the points) dropped",
                    source.file.display(),
                    source.name,
                    found.count,
                    found.range_m,
                    100.0 * found.count as f64 / (scan.valid_count() + found.count).max(1) as f64
                );
            }
            let (scan, mixed) = crate::mixed_pixels::remove_mixed_pixels(&scan, mixed_pixels);
            note_removed(
                source,
                mixed,
                scan.valid_count() + mixed,
                "mixed pixels (returns between two surfaces at a depth edge",
            );
            let scan = scan.without_invalid();
            let before = scan.valid_count();
            let (scan, removed) = crate::outliers::remove_outliers(&scan, outliers);
            note_removed(source, removed, before, "isolated points (statistical outliers");
            // The chain takes finite points only (as `without_invalid` leaves them): an
            // organised scan whose isolated points became NaN loses them here, and its shape.
            let scan = if removed > 0 {
                scan.without_invalid()
            } else {
                scan
            };
            Ok(match max_range_m {
                Some(r) => within_range(&scan, r as f32),
                None => scan,
            })
        })
        .collect()
}

/// Reports on standard error that `count` of a scan's `of` points, `what` (an open
/// parenthesis the share closes), were removed; nothing when none were.
fn note_removed(source: &ScanSource, count: usize, of: usize, what: &str) {
    if count > 0 {
        eprintln!(
            "note: {} ({}): {count} {what}, {:.2} % of the points) removed",
            source.file.display(),
            source.name,
            100.0 * count as f64 / of.max(1) as f64
        );
    }
}

/// Reads a one-scan file, moving it from its local frame into the sequence's (the first local
/// origin met).
fn read_one(file: &Path, origin: &mut Option<DVec3>) -> Result<PointCloud> {
    let set = interop::read_scans(file, &interop::ReadOptions::default())?;
    cloud::io::print_notes(&set.notes);
    let local_origin_m = set.local_origin_m;
    let mut cloud = match <[_; 1]>::try_from(set.scans) {
        Ok([one]) => one.cloud,
        Err(scans) => {
            // Not expected (multi-scan files are read when expanded): placed and merged.
            let poses: Vec<Option<DAffine3>> = scans.iter().map(|s| s.world_from_scan).collect();
            let sources: Vec<ScanSource> = scans
                .iter()
                .map(|s| ScanSource::file(Path::new(&s.name)))
                .collect();
            let clouds = scans.into_iter().map(|s| s.cloud).collect();
            place_and_merge(
                &sources,
                clouds,
                recorded_poses(&sources, &poses).as_deref(),
                &TransientConfig::default(),
            )?
        }
    };
    if local_origin_m != DVec3::ZERO {
        let first = *origin.get_or_insert(local_origin_m);
        if first == local_origin_m {
            eprintln!(
                "note: {}: coordinates are relative to the local origin ({:.3}, {:.3}, {:.3}) m",
                file.display(),
                first.x,
                first.y,
                first.z
            );
        } else {
            cloud.transform(&DAffine3::from_translation(local_origin_m - first));
        }
    }
    Ok(cloud)
}

/// The points of `scan` at most `max_range_m` from its sensor.
fn within_range(scan: &PointCloud, max_range_m: f32) -> PointCloud {
    let keep: Vec<usize> = (0..scan.len())
        .filter(|&i| scan.points[i].distance(scan.sensor_origin) <= max_range_m)
        .collect();
    scan.select(&keep)
}

/// Places each scan with its pose (the pose named by the scan's name, else the pose at the
/// same position), drops what moved between them (with poses: [`crate::drop_transients`],
/// reported on standard error with the count) and merges them; labels are kept if every scan
/// has them.
pub fn place_and_merge(
    sources: &[ScanSource],
    scans: Vec<PointCloud>,
    poses: Option<&[NamedPose]>,
    transients: &TransientConfig,
) -> Result<PointCloud> {
    let placed = place_scans(sources, scans, poses, transients)?;
    let mut merged = PointCloud::default();
    let mut labels = Vec::new();
    let mut all_labelled = true;
    for mut scan in placed {
        all_labelled &= scan.labels.is_some();
        labels.extend(scan.labels.take().unwrap_or_default());
        merged.points.extend(scan.points);
    }
    merged.labels = all_labelled.then_some(labels);
    Ok(merged)
}

/// The scans of [`place_and_merge`], placed and without what moved, not merged.
pub(crate) fn place_scans(
    sources: &[ScanSource],
    scans: Vec<PointCloud>,
    poses: Option<&[NamedPose]>,
    transients: &TransientConfig,
) -> Result<Vec<PointCloud>> {
    if let Some(p) = poses {
        let by_name = sources
            .iter()
            .all(|f| p.iter().any(|q| f.is_named(&q.name)));
        if !by_name && p.len() != sources.len() {
            return Err(PipelineError::bad_input(format!(
                "{} poses for {} clouds, and not every cloud's name names a pose",
                p.len(),
                sources.len()
            )));
        }
    }
    let mut placed = Vec::with_capacity(scans.len());
    for (k, (f, mut scan)) in sources.iter().zip(scans).enumerate() {
        if let Some(p) = poses {
            let pose = p
                .iter()
                .find(|q| f.is_named(&q.name))
                .or_else(|| p.get(k))
                .map(|q| q.world_from_scan)
                .ok_or_else(|| PipelineError::bad_input(format!("no pose for {}", f.name)))?;
            scan.transform(&pose);
        }
        placed.push(scan);
    }
    // Scans placed by their poses know where their sensors stood: what one saw and another saw
    // through moved in between.
    if poses.is_some() {
        let dropped;
        (placed, dropped) = crate::drop_transients(placed, transients);
        report_transients(sources, &dropped);
    }
    Ok(placed)
}

/// Says on standard error how many points of something that moved each scan lost.
pub(crate) fn report_transients(sources: &[ScanSource], dropped: &[usize]) {
    for (f, n) in sources.iter().zip(dropped).filter(|(_, n)| **n > 0) {
        eprintln!(
            "note: {} ({}): {n} points of something that moved (seen by this scan only where another scan saw through, or by one other where two more did) dropped",
            f.file.display(),
            f.name
        );
    }
}

/// Reads the scans (as [`read_scans_with`] does, with `outliers`), places each by the pose
/// file `poses` (if given; else by the poses the files record, as E57 scans do) and merges
/// them, without what moved between placed scans (`transients`).
pub fn merge_scan_files(
    files: &[PathBuf],
    poses: Option<&Path>,
    max_range_m: Option<f64>,
    options: &interop::ReadOptions,
    outliers: &OutlierConfig,
    mixed_pixels: &MixedPixelConfig,
    transients: &TransientConfig,
) -> Result<PointCloud> {
    let expanded = expand_files(files, options)?;
    let named = match poses {
        Some(p) => Some(cloud::read_poses(p)?),
        None => recorded_poses(&expanded.scans, &expanded.own_poses),
    };
    let scans = read_scans_with(&expanded.scans, max_range_m, outliers, mixed_pixels)?;
    place_and_merge(&expanded.scans, scans, named.as_deref(), transients).map_err(|e| {
        match (e, poses) {
            (PipelineError::BadInput(msg), Some(p)) => {
                PipelineError::BadInput(format!("{}: {msg}", p.display()))
            }
            (e, _) => e,
        }
    })
}

/// The poses the files record for their scans, named after the scans (identity for a scan
/// without one), if any scan has one.
fn recorded_poses(
    sources: &[ScanSource],
    own_poses: &[Option<DAffine3>],
) -> Option<Vec<NamedPose>> {
    own_poses.iter().any(Option::is_some).then(|| {
        sources
            .iter()
            .zip(own_poses)
            .map(|(s, p)| NamedPose {
                name: s.name.clone(),
                world_from_scan: p.unwrap_or(DAffine3::IDENTITY),
            })
            .collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn far_points_are_dropped_and_scans_are_placed_by_name_before_order() {
        let mut a = PointCloud::from_points(vec![Vec3::X, Vec3::X * 40.0]);
        a.sensor_origin = Vec3::ZERO;
        let a = within_range(&a, 30.0);
        assert_eq!(a.points, vec![Vec3::X]);
        let b = PointCloud::from_points(vec![Vec3::Y]);
        let files = vec![
            ScanSource::file(Path::new("a.pcd")),
            ScanSource::file(Path::new("b.pcd")),
        ];
        let poses = vec![
            NamedPose {
                name: "b".into(),
                world_from_scan: DAffine3::from_translation(DVec3::Z),
            },
            NamedPose {
                name: "a".into(),
                world_from_scan: DAffine3::IDENTITY,
            },
        ];
        let off = TransientConfig::default();
        let m = place_and_merge(&files, vec![a, b], Some(&poses), &off).expect("merges");
        assert_eq!(m.points, vec![Vec3::X, Vec3::new(0.0, 1.0, 1.0)]);
        let with_ext = vec![NamedPose {
            name: "a.pcd".into(),
            world_from_scan: DAffine3::from_translation(DVec3::Z),
        }];
        let m = place_and_merge(
            &files[..1],
            vec![PointCloud::from_points(vec![Vec3::X])],
            Some(&with_ext),
            &off,
        )
        .expect("a pose named with the file's extension matches");
        assert_eq!(m.points, vec![Vec3::new(1.0, 0.0, 1.0)]);
    }
}
