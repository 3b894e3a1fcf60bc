//! `nav_msgs/msg/Odometry` from CDR, and the odometry pose at a scan's time.
//!
//! The message: `header` (stamp, frame id), `child_frame_id` (string), `pose`
//! (`PoseWithCovariance`: position x, y, z and orientation x, y, z, w as float64, then 36
//! float64 of covariance), `twist` (`TwistWithCovariance`: 6 float64 and 36 of covariance).
//! Only the pose is kept; the rest is checked to be there. `pose.pose` is the child frame's
//! pose in the odometry frame.

use super::cdr::CdrReader;
use crate::scans::util::rigid_pose;
use glam::{DAffine3, DQuat};

/// A decoded message.
#[derive(Debug, Clone)]
pub(super) struct Odometry {
    /// `header.stamp` in nanoseconds since the epoch.
    pub stamp_ns: i64,
    /// `header.frame_id`: the odometry frame.
    pub frame_id: String,
    /// `child_frame_id`: the frame whose pose this is (the robot base).
    pub child_frame_id: String,
    /// `pose.pose`: the child frame in the odometry frame (`odom_from_child`).
    pub pose: DAffine3,
}

/// Decodes one CDR-encoded Odometry message; errors are text for the caller to place.
pub(super) fn decode_odometry(message: &[u8]) -> Result<Odometry, String> {
    let mut r = CdrReader::new(message)?;
    let (stamp_ns, frame_id) = r.header()?;
    let child_frame_id = r.string("child_frame_id")?;
    let mut values = [0.0f64; 7];
    for (value, what) in values.iter_mut().zip([
        "pose.pose.position.x",
        "pose.pose.position.y",
        "pose.pose.position.z",
        "pose.pose.orientation.x",
        "pose.pose.orientation.y",
        "pose.pose.orientation.z",
        "pose.pose.orientation.w",
    ]) {
        *value = r.f64(what)?;
    }
    r.skip_f64s(36, "pose.covariance")?;
    r.skip_f64s(6, "twist.twist")?;
    r.skip_f64s(36, "twist.covariance")?;
    let [px, py, pz, qx, qy, qz, qw] = values;
    let pose = rigid_pose([qx, qy, qz, qw], [px, py, pz]).ok_or_else(|| {
        format!(
            "pose.pose is not a rotation and translation (position {px} {py} {pz}, orientation x {qx} y {qy} z {qz} w {qw})"
        )
    })?;
    Ok(Odometry {
        stamp_ns,
        frame_id,
        child_frame_id,
        pose,
    })
}

/// The odometry pose at `stamp_ns` from messages sorted by stamp (at least one): interpolated
/// between the two messages around it (linear in translation, spherical-linear in rotation),
/// the nearest message's pose outside their time span. Also says whether it was outside.
pub(super) fn pose_at(sorted: &[Odometry], stamp_ns: i64) -> Option<(DAffine3, bool)> {
    let first = sorted.first()?;
    let last = sorted.last()?;
    if stamp_ns <= first.stamp_ns {
        return Some((first.pose, stamp_ns < first.stamp_ns));
    }
    if stamp_ns >= last.stamp_ns {
        return Some((last.pose, stamp_ns > last.stamp_ns));
    }
    // first.stamp < stamp < last.stamp: 1 <= after < len.
    let after = sorted.partition_point(|o| o.stamp_ns <= stamp_ns);
    let (a, b) = (&sorted[after - 1], &sorted[after]);
    if a.stamp_ns == stamp_ns {
        return Some((a.pose, false));
    }
    let t = (stamp_ns - a.stamp_ns) as f64 / (b.stamp_ns - a.stamp_ns) as f64;
    let ra = DQuat::from_mat3(&a.pose.matrix3);
    let rb = DQuat::from_mat3(&b.pose.matrix3);
    let rotation = ra.slerp(rb, t).normalize();
    let translation = a.pose.translation.lerp(b.pose.translation, t);
    let pose = DAffine3::from_rotation_translation(rotation, translation);
    // Translations near f64's range can overflow in between: take the earlier pose then.
    Some((if pose.is_finite() { pose } else { a.pose }, false))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn odom(stamp_ns: i64, x: f64, yaw: f64) -> Odometry {
        Odometry {
            stamp_ns,
            frame_id: "odom".into(),
            child_frame_id: "base_link".into(),
            pose: DAffine3::from_rotation_translation(
                DQuat::from_rotation_z(yaw),
                DVec3::new(x, 0.0, 0.0),
            ),
        }
    }

    #[test]
    fn interpolates_inside_and_clamps_outside() {
        let track = [odom(100, 0.0, 0.0), odom(200, 2.0, 1.0)];
        let (mid, outside) = pose_at(&track, 150).expect("a pose");
        assert!(!outside);
        assert!((mid.translation - DVec3::new(1.0, 0.0, 0.0)).length() < 1e-12);
        let expected = DQuat::from_rotation_z(0.5);
        assert!(DQuat::from_mat3(&mid.matrix3).dot(expected).abs() > 1.0 - 1e-12);
        assert_eq!(pose_at(&track, 200), Some((track[1].pose, false)));
        assert_eq!(pose_at(&track, 50), Some((track[0].pose, true)));
        assert_eq!(pose_at(&track, 250), Some((track[1].pose, true)));
        assert_eq!(pose_at(&[], 0), None);
    }

    #[test]
    fn decodes_a_little_endian_message() {
        let mut m = vec![0, 1, 0, 0];
        m.extend(3i32.to_le_bytes());
        m.extend(4u32.to_le_bytes());
        m.extend(5u32.to_le_bytes());
        m.extend(b"odom\0");
        m.extend([0, 0, 0]); // align to 4
        m.extend(5u32.to_le_bytes());
        m.extend(b"base\0");
        m.extend([0; 3]); // the payload so far is 29 bytes: pad to 32 for the float64s
        for v in [1.0f64, 2.0, 3.0, 0.0, 0.0, 0.0, 1.0] {
            m.extend(v.to_le_bytes());
        }
        m.extend([0u8; 78 * 8]);
        let o = decode_odometry(&m).expect("decodes");
        assert_eq!(o.stamp_ns, 3_000_000_004);
        assert_eq!(
            (o.frame_id.as_str(), o.child_frame_id.as_str()),
            ("odom", "base")
        );
        assert_eq!(o.pose.translation, DVec3::new(1.0, 2.0, 3.0));
        m.pop();
        assert!(decode_odometry(&m)
            .expect_err("short")
            .contains("twist.covariance"));
    }
}
