//! Scans read for mapping: missing returns and far points dropped, each placed by its pose
//! and all merged into one cloud in the world frame.

use crate::error::{PipelineError, Result};
use crate::scan_folder::names_scan;
use cloud::{NamedPose, PointCloud};
use std::path::{Path, PathBuf};

/// Reads scans, dropping missing returns and points farther than `max_range_m` from their
/// scan's sensor.
pub fn read_scans(files: &[PathBuf], max_range_m: Option<f64>) -> Result<Vec<PointCloud>> {
    if let Some(r) = max_range_m {
        if !(r.is_finite() && r > 0.0) {
            return Err(PipelineError::bad_input(format!(
                "--max-range-m {r}: must be a positive length"
            )));
        }
    }
    files
        .iter()
        .map(|f| {
            let scan = cloud::read_cloud(f)?.without_invalid();
            Ok(match max_range_m {
                Some(r) => within_range(&scan, r as f32),
                None => scan,
            })
        })
        .collect()
}

/// The points of `scan` at most `max_range_m` from its sensor.
fn within_range(scan: &PointCloud, max_range_m: f32) -> PointCloud {
    let keep: Vec<usize> = (0..scan.len())
        .filter(|&i| scan.points[i].distance(scan.sensor_origin) <= max_range_m)
        .collect();
    scan.select(&keep)
}

/// Places each scan with its pose (the pose named by the file's stem, else the pose at the
/// same position) and merges them; labels are kept if every scan has them.
pub fn place_and_merge(
    files: &[PathBuf],
    scans: Vec<PointCloud>,
    poses: Option<&[NamedPose]>,
) -> Result<PointCloud> {
    if let Some(p) = poses {
        let by_name = files
            .iter()
            .all(|f| p.iter().any(|q| names_scan(&q.name, f)));
        if !by_name && p.len() != files.len() {
            return Err(PipelineError::bad_input(format!(
                "{} poses for {} clouds, and not every cloud's file stem names a pose",
                p.len(),
                files.len()
            )));
        }
    }
    let mut merged = PointCloud::default();
    let mut labels = Vec::new();
    let mut all_labelled = true;
    for (k, (f, mut scan)) in files.iter().zip(scans).enumerate() {
        if let Some(p) = poses {
            let pose = p
                .iter()
                .find(|q| names_scan(&q.name, f))
                .or_else(|| p.get(k))
                .map(|q| q.world_from_scan)
                .ok_or_else(|| PipelineError::bad_input(format!("no pose for {}", f.display())))?;
            scan.transform(&pose);
        }
        all_labelled &= scan.labels.is_some();
        labels.extend(scan.labels.take().unwrap_or_default());
        merged.points.extend(scan.points);
    }
    merged.labels = all_labelled.then_some(labels);
    Ok(merged)
}

/// Reads the scans, places each by the pose file `poses` (if given) and merges them.
pub fn merge_scan_files(
    files: &[PathBuf],
    poses: Option<&Path>,
    max_range_m: Option<f64>,
) -> Result<PointCloud> {
    let named = poses.map(cloud::read_poses).transpose()?;
    let scans = read_scans(files, max_range_m)?;
    place_and_merge(files, scans, named.as_deref()).map_err(|e| match (e, poses) {
        (PipelineError::BadInput(msg), Some(p)) => {
            PipelineError::BadInput(format!("{}: {msg}", p.display()))
        }
        (e, _) => e,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DAffine3, DVec3, Vec3};

    #[test]
    fn far_points_are_dropped_and_scans_are_placed_by_name_before_order() {
        let mut a = PointCloud::from_points(vec![Vec3::X, Vec3::X * 40.0]);
        a.sensor_origin = Vec3::ZERO;
        let a = within_range(&a, 30.0);
        assert_eq!(a.points, vec![Vec3::X]);
        let b = PointCloud::from_points(vec![Vec3::Y]);
        let files = vec![PathBuf::from("a.pcd"), PathBuf::from("b.pcd")];
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
        let m = place_and_merge(&files, vec![a, b], Some(&poses)).expect("merges");
        assert_eq!(m.points, vec![Vec3::X, Vec3::new(0.0, 1.0, 1.0)]);
        let with_ext = vec![NamedPose {
            name: "a.pcd".into(),
            world_from_scan: DAffine3::from_translation(DVec3::Z),
        }];
        let m = place_and_merge(
            &files[..1],
            vec![PointCloud::from_points(vec![Vec3::X])],
            Some(&with_ext),
        )
        .expect("a pose named with the file's extension matches");
        assert_eq!(m.points, vec![Vec3::new(1.0, 0.0, 1.0)]);
    }
}
