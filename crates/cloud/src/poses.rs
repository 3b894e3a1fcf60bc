//! Pose files: one line per scan, `name` then the 16 numbers of the row-major 4x4
//! `world_from_scan` matrix (metres). Lines starting with `#` are comments.

use crate::atomic::write_atomically;
use crate::error::{CloudError, Result};
use crate::io::text::{read_file, shown, text};
use glam::{DAffine3, DMat4, DQuat};
use std::io::Write;
use std::path::Path;

/// A named `world_from_scan` pose.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedPose {
    /// The scan's name (its file stem, e.g. `scan000`).
    pub name: String,
    /// The scan's pose in the world.
    pub world_from_scan: DAffine3,
}

/// Reads a pose file (a UTF-8 byte-order mark is allowed).
pub fn read_poses(path: &Path) -> Result<Vec<NamedPose>> {
    parse_poses(path, &read_file(path)?)
}

/// Reads the bytes of a pose file; `path` is for messages.
pub(crate) fn parse_poses(path: &Path, bytes: &[u8]) -> Result<Vec<NamedPose>> {
    let text = text(path, bytes)?;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let mut fields = line.split_whitespace();
        let name = fields.next().unwrap_or_default().to_string();
        let numbers: Vec<f64> = fields
            .map(|f| {
                f.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| {
                        let msg = format!("'{}' is not a finite number", shown(f));
                        CloudError::parse(path, i + 1, msg)
                    })
            })
            .collect::<Result<_>>()?;
        if numbers.len() != 16 {
            return Err(CloudError::parse(
                path,
                i + 1,
                format!(
                    "expected a name and 16 numbers (row-major 4x4), found {} numbers",
                    numbers.len()
                ),
            ));
        }
        let m = DMat4::from_cols_array(&numbers.try_into().unwrap_or([0.0; 16])).transpose();
        out.push(NamedPose {
            name,
            world_from_scan: affine_from_mat4(m, path, i + 1)?,
        });
    }
    Ok(out)
}

/// Writes a pose file atomically.
pub fn write_poses(path: &Path, poses: &[NamedPose]) -> Result<()> {
    write_atomically(path, |w| {
        let io = |e| CloudError::io(path, e);
        writeln!(
            w,
            "# name, then world_from_scan as a row-major 4x4 matrix (metres)"
        )
        .map_err(io)?;
        for p in poses {
            write!(w, "{}", p.name).map_err(io)?;
            for v in DMat4::from(p.world_from_scan).transpose().to_cols_array() {
                write!(w, " {v:.9}").map_err(io)?;
            }
            writeln!(w).map_err(io)?;
        }
        Ok(())
    })
}

/// Converts a 4x4 matrix to a rigid affine transform, checking that the last row is `0 0 0 1`
/// and the rotation is orthonormal within 1e-3.
pub fn affine_from_mat4(m: DMat4, path: &Path, line: usize) -> Result<DAffine3> {
    let row3 = m.row(3);
    if (row3 - glam::DVec4::new(0.0, 0.0, 0.0, 1.0))
        .abs()
        .max_element()
        > 1e-9
    {
        return Err(CloudError::parse(
            path,
            line,
            "last matrix row must be 0 0 0 1",
        ));
    }
    let a = DAffine3::from_mat4(m);
    let r = a.matrix3;
    let err = (r.transpose() * r - glam::DMat3::IDENTITY)
        .to_cols_array()
        .iter()
        .fold(0.0f64, |acc, v| acc.max(v.abs()));
    if err > 1e-3 || r.determinant() < 0.0 {
        return Err(CloudError::parse(
            path,
            line,
            "the 3x3 part is not a rotation (not orthonormal or a reflection)",
        ));
    }
    Ok(a)
}

/// How far pose `b` is from pose `a`: the translation (m) and the rotation angle (deg) of
/// `a⁻¹ b`. Used to score registered poses against ground truth.
///
/// ```
/// use glam::{DAffine3, DVec3};
/// let a = DAffine3::IDENTITY;
/// let b = DAffine3::from_rotation_z(2f64.to_radians()) * DAffine3::from_translation(DVec3::X * 0.1);
/// let (m, deg) = cloud::pose_error(&a, &b);
/// assert!((m - 0.1).abs() < 1e-12 && (deg - 2.0).abs() < 1e-9);
/// ```
pub fn pose_error(a: &DAffine3, b: &DAffine3) -> (f64, f64) {
    let d = a.inverse() * *b;
    let angle = DQuat::from_mat3(&d.matrix3)
        .angle_between(DQuat::IDENTITY)
        .to_degrees();
    (d.translation.length(), angle)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DQuat, DVec3};

    #[test]
    fn poses_round_trip() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("poses.txt");
        let poses = vec![
            NamedPose {
                name: "scan000".into(),
                world_from_scan: DAffine3::IDENTITY,
            },
            NamedPose {
                name: "scan001".into(),
                world_from_scan: DAffine3::from_rotation_translation(
                    DQuat::from_euler(glam::EulerRot::ZYX, 0.3, 0.02, -0.01),
                    DVec3::new(1.5, -2.0, 0.4),
                ),
            },
        ];
        write_poses(&path, &poses).expect("write");
        let back = read_poses(&path).expect("read");
        assert_eq!(back.len(), 2);
        assert_eq!(back[1].name, "scan001");
        assert!(back[1]
            .world_from_scan
            .abs_diff_eq(poses[1].world_from_scan, 1e-8));
    }

    #[test]
    fn pose_with_fifteen_numbers_is_an_error_naming_the_line() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("p.txt");
        std::fs::write(&path, "# c\nscan 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0\n").expect("write");
        let e = read_poses(&path).expect_err("must fail").to_string();
        assert!(e.contains("p.txt:2") && e.contains("15 numbers"), "{e}");
    }
}
