//! The registration's frame relative to the building's: the gauge a registration cannot know.
//!
//! A registration places its scans relative to the first one's odometry, which knows nothing of
//! the laser's mount tilt, so its frame is the building's turned by that tilt (a few tenths of
//! a degree, 10-20 cm at 30 m). Scoring a map made in that frame against the building needs the
//! two frames related first, as trajectory evaluations do (absolute trajectory error aligns the
//! estimated trajectory to the true one before measuring it): here by the rigid transform that
//! best maps the scans' true poses onto their registered ones. A mean over all scans, not the
//! first scan alone: that removes the frame's freedom only, and leaves the registration's
//! errors between scans (drift, a scan misplaced) in the score.

use cloud::NamedPose;
use glam::{DAffine3, DQuat, DVec3};

/// `input_from_building`: the rigid transform best taking the scans' `true_poses` (building
/// frame) onto their `registered` poses (the registration's frame), matching scans by name.
/// The rotation is the normalised mean of the per-scan rotation differences (quaternions on
/// one hemisphere), the translation the mean of the per-scan position differences after it.
/// `None` if no scan has both poses.
pub fn registration_frame(registered: &[NamedPose], true_poses: &[NamedPose]) -> Option<DAffine3> {
    let pairs: Vec<(DAffine3, DAffine3)> = registered
        .iter()
        .filter_map(|r| {
            true_poses
                .iter()
                .find(|t| t.name == r.name)
                .map(|t| (r.world_from_scan, t.world_from_scan))
        })
        .collect();
    let first = pairs.first()?;
    let difference = |(reg, truth): &(DAffine3, DAffine3)| {
        DQuat::from_mat3(&(reg.matrix3 * truth.matrix3.transpose()))
    };
    let reference = difference(first);
    let mut sum = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
    for p in &pairs {
        let q = difference(p);
        // q and -q are the same rotation: add each on the reference's hemisphere.
        sum += if q.dot(reference) < 0.0 { -q } else { q };
    }
    let rotation = sum.normalize();
    let translation = pairs
        .iter()
        .map(|(reg, truth)| reg.translation - rotation * truth.translation)
        .sum::<DVec3>()
        / pairs.len() as f64;
    Some(DAffine3::from_rotation_translation(rotation, translation))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pose(name: &str, world_from_scan: DAffine3) -> NamedPose {
        NamedPose {
            name: name.to_string(),
            world_from_scan,
        }
    }

    #[test]
    fn a_tilted_registration_frame_is_recovered_from_the_poses() {
        // The registration's frame: the building's turned by a 0.4 degree tilt about the first
        // scan's position, as a sequence anchored on tilt-free odometry is.
        let tilt = DQuat::from_euler(glam::EulerRot::XYZ, 0.004, -0.005, 0.0);
        let anchor = DVec3::new(7.0, 9.0, 0.5);
        let input_from_building = DAffine3::from_translation(anchor)
            * DAffine3::from_quat(tilt)
            * DAffine3::from_translation(-anchor);
        let truths: Vec<NamedPose> = (0..6)
            .map(|k| {
                let at = DVec3::new(7.0 + 3.0 * k as f64, 9.0 - k as f64, 0.5);
                let yaw = DQuat::from_rotation_z(0.3 * k as f64);
                pose(
                    &format!("scan{k:03}"),
                    DAffine3::from_rotation_translation(yaw, at),
                )
            })
            .collect();
        // Registered poses in reverse order: scans are matched by name.
        let registered: Vec<NamedPose> = truths
            .iter()
            .rev()
            .map(|t| pose(&t.name, input_from_building * t.world_from_scan))
            .collect();
        let found = registration_frame(&registered, &truths).expect("scans in common");
        let far = DVec3::new(40.0, -10.0, 3.0);
        let error =
            (found.transform_point3(far) - input_from_building.transform_point3(far)).length();
        assert!(error < 1e-9, "{error} m off at 40 m");
    }

    #[test]
    fn no_scan_in_common_is_no_frame() {
        let a = [pose("scan000", DAffine3::IDENTITY)];
        let b = [pose("other", DAffine3::IDENTITY)];
        assert!(registration_frame(&a, &b).is_none());
        assert!(registration_frame(&[], &b).is_none());
    }
}
