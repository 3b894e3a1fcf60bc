//! One cloud from the scans of a file ([`super::read_cloud`]): each scan placed by its pose
//! (in f64, then back to f32) and the scans concatenated.
//!
//! A single scan keeps its organised shape and channels. Several scans lose the organised
//! shape (their missing returns are dropped), keep a channel (intensity, classification,
//! labels) only where every scan has it, and get the sensor pose of the set's frame (origin,
//! identity); the notes say what was dropped and which scans had no pose (used as they are).

use super::util::{note, try_vec};
use super::{ImportedScan, ScanSet};
use crate::error::Result;
use cloud::PointCloud;
use glam::{DAffine3, DQuat, Vec3};
use std::path::Path;

/// The scans of `set` as one cloud, with the set's notes and the merge's own.
pub(super) fn merge_scans(path: &Path, set: ScanSet) -> Result<(PointCloud, Vec<String>)> {
    let ScanSet {
        scans, mut notes, ..
    } = set;
    if scans.len() <= 1 {
        let Some(scan) = scans.into_iter().next() else {
            notes.push(note(path, "the file holds no scan: the cloud is empty"));
            return Ok((PointCloud::from_points(Vec::new()), notes));
        };
        let mut cloud = scan.cloud;
        if let Some(pose) = scan.world_from_scan {
            place(&mut cloud, &pose);
        }
        if cloud.organized.is_none() && cloud.valid_count() < cloud.len() {
            notes.push(note(
                path,
                format!(
                    "{} points placed beyond f32 range by the scan's pose dropped",
                    cloud.len() - cloud.valid_count()
                ),
            ));
            cloud = cloud.without_invalid();
        }
        return Ok((cloud, notes));
    }
    let unposed: Vec<&str> = scans
        .iter()
        .filter(|s| s.world_from_scan.is_none())
        .map(|s| s.name.as_str())
        .collect();
    if !unposed.is_empty() {
        notes.push(note(
            path,
            format!(
                "{} of {} scans have no pose and are merged as they are (first: {:?})",
                unposed.len(),
                scans.len(),
                unposed[0]
            ),
        ));
    }
    let total: usize = scans.iter().map(|s| s.cloud.valid_count()).sum();
    let missing: usize = scans.iter().map(|s| s.cloud.len()).sum::<usize>() - total;
    let all = |has: fn(&PointCloud) -> bool| scans.iter().all(|s| has(&s.cloud));
    let any = |has: fn(&PointCloud) -> bool| scans.iter().any(|s| has(&s.cloud));
    let keep_intensity = all(|c| c.intensity.is_some());
    let keep_class = all(|c| c.classification.is_some());
    let keep_labels = all(|c| c.labels.is_some());
    for (kept, present, what) in [
        (keep_intensity, any(|c| c.intensity.is_some()), "intensity"),
        (
            keep_class,
            any(|c| c.classification.is_some()),
            "classification",
        ),
        (keep_labels, any(|c| c.labels.is_some()), "labels"),
    ] {
        if present && !kept {
            notes.push(note(path, format!("{what} dropped: not every scan has it")));
        }
    }
    let mut merged = PointCloud::from_points(try_vec(path, total, "the merged points")?);
    let mut intensity = keep_intensity.then(Vec::new);
    let mut classification = keep_class.then(Vec::new);
    let mut labels = keep_labels.then(Vec::new);
    for ImportedScan {
        mut cloud,
        world_from_scan,
        ..
    } in scans
    {
        if let Some(pose) = world_from_scan {
            place(&mut cloud, &pose);
        }
        for i in (0..cloud.len()).filter(|&i| cloud.is_valid(i)) {
            merged.points.push(cloud.points[i]);
            if let (Some(out), Some(v)) = (&mut intensity, &cloud.intensity) {
                out.push(v[i]);
            }
            if let (Some(out), Some(v)) = (&mut classification, &cloud.classification) {
                out.push(v[i]);
            }
            if let (Some(out), Some(v)) = (&mut labels, &cloud.labels) {
                out.push(v[i]);
            }
        }
    }
    merged.intensity = intensity;
    merged.classification = classification;
    merged.labels = labels;
    if missing > 0 {
        notes.push(note(
            path,
            format!("{missing} missing returns of organised scans dropped in the merge"),
        ));
    }
    Ok((merged, notes))
}

/// Applies `world_from_scan` to the points (in f64; NaN stays NaN) and the sensor pose.
pub(super) fn place(cloud: &mut PointCloud, world_from_scan: &DAffine3) {
    if *world_from_scan == DAffine3::IDENTITY {
        return;
    }
    for p in &mut cloud.points {
        let placed = world_from_scan.transform_point3(p.as_dvec3()).as_vec3();
        // Missing returns stay missing; a point the pose moves beyond f32 becomes one.
        *p = if placed.is_finite() {
            placed
        } else {
            Vec3::NAN
        };
    }
    cloud.sensor_origin = world_from_scan
        .transform_point3(cloud.sensor_origin.as_dvec3())
        .as_vec3();
    let rotation = DQuat::from_mat3(&world_from_scan.matrix3);
    cloud.sensor_orientation = (rotation * cloud.sensor_orientation.as_dquat())
        .normalize()
        .as_quat();
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec3, Quat};

    fn scan(points: Vec<Vec3>, pose: Option<DAffine3>) -> ImportedScan {
        ImportedScan {
            name: "s".into(),
            cloud: PointCloud::from_points(points),
            world_from_scan: pose,
            stamp_ns: None,
            frame_id: None,
        }
    }

    #[test]
    fn scans_are_placed_and_missing_returns_dropped() {
        let mut organised = scan(vec![Vec3::X, Vec3::NAN], Some(DAffine3::IDENTITY));
        organised.cloud.organized = Some(cloud::Organized { rows: 1, cols: 2 });
        organised.cloud.intensity = Some(vec![1.0, 2.0]);
        let moved = scan(
            vec![Vec3::X],
            Some(DAffine3::from_translation(DVec3::new(0.0, 10.0, 0.0))),
        );
        let set = ScanSet {
            scans: vec![organised, moved],
            local_origin_m: DVec3::ZERO,
            odometry: None,
            notes: vec![],
        };
        let (cloud, notes) = merge_scans(Path::new("a.e57"), set).expect("merges");
        assert_eq!(cloud.points, vec![Vec3::X, Vec3::new(1.0, 10.0, 0.0)]);
        assert!(cloud.intensity.is_none() && cloud.organized.is_none());
        assert_eq!(notes.len(), 2, "{notes:?}");
        assert!(notes.iter().all(|n| n.starts_with("a.e57: ")));
    }

    #[test]
    fn placing_turns_the_sensor_pose() {
        let mut cloud = PointCloud::from_points(vec![Vec3::X]);
        let pose = DAffine3::from_rotation_z(std::f64::consts::FRAC_PI_2);
        place(&mut cloud, &pose);
        assert!((cloud.points[0] - Vec3::Y).length() < 1e-6);
        let expected = Quat::from_rotation_z(std::f32::consts::FRAC_PI_2);
        assert!(cloud.sensor_orientation.dot(expected).abs() > 0.999_999);
    }
}
