//! Poses scored against ground truth. A sequence's world is its first scan's frame, which
//! may differ from the truth's, so both are taken relative to their first pose.

use glam::DAffine3;

/// Each pose's error (metres, degrees) against the truth, both relative to their first pose.
/// Empty if either is empty.
pub fn relative_pose_errors(truth: &[DAffine3], estimate: &[DAffine3]) -> Vec<(f64, f64)> {
    let (Some(t0), Some(e0)) = (truth.first(), estimate.first()) else {
        return Vec::new();
    };
    truth
        .iter()
        .zip(estimate)
        .map(|(t, e)| cloud::pose_error(&(t0.inverse() * *t), &(e0.inverse() * *e)))
        .collect()
}

/// The largest translation and the largest rotation error of [`relative_pose_errors`].
pub fn worst_pose_error(truth: &[DAffine3], estimate: &[DAffine3]) -> (f64, f64) {
    relative_pose_errors(truth, estimate)
        .into_iter()
        .fold((0.0, 0.0), |(m, d), (em, ed)| {
            (f64::max(m, em), f64::max(d, ed))
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn a_shifted_world_is_no_error_but_a_moved_scan_is() {
        let shift = DAffine3::from_translation(DVec3::new(5.0, -2.0, 0.0));
        let truth = [DAffine3::IDENTITY, DAffine3::from_translation(DVec3::X)];
        let est = [
            shift,
            shift * DAffine3::from_translation(DVec3::new(1.1, 0.0, 0.0)),
        ];
        let e = relative_pose_errors(&truth, &est);
        assert!(e[0].0 < 1e-12);
        assert!((e[1].0 - 0.1).abs() < 1e-9, "{e:?}");
        assert!((worst_pose_error(&truth, &est).0 - 0.1).abs() < 1e-9);
    }
}
