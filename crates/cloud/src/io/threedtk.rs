//! 3DTK (The 3D Toolkit) scans and poses: `scanNNN.3d`, `scanNNN.pose`, `scanNNN.frames`.
//!
//! # Frames and units
//! 3DTK works in **centimetres** in a **left-handed** frame with x right, **y up**, z forward.
//! semsim works in metres in a right-handed frame with x forward, y left, z up. With the axis map
//!
//! ```text
//!       | 0  0  1 |
//!   P = |-1  0  0 |     x_rh = z_lh / 100,  y_rh = -x_lh / 100,  z_rh = y_lh / 100
//!       | 0  1  0 |
//! ```
//!
//! a point converts as `p_rh = P p_lh / 100` (`det P = -1`: the map flips handedness), and a
//! 3DTK transform `(R, t)` as `(P R Pᵀ, P t / 100)`, which is again a proper rotation.
//!
//! # Files
//! - `.3d`: ASCII, one point per line, `x y z [reflectance ...]`; the first extra column becomes
//!   the intensity. Old files start with a `W x H` line (e.g. `360 x 225`): it makes the cloud
//!   organised (`H` rows of `W` columns) when `W * H` equals the point count, and is ignored
//!   otherwise. Writing drops missing returns; it writes the `W x H` line only for an organised
//!   cloud without missing returns. Reading is strict where a cut-off file could pass for a
//!   shorter one: every line, the last included, ends with a newline (3DTK writes whole
//!   lines, so a last line without one means the file was cut, possibly inside a number), every
//!   point line has at least 3 numbers and as many used columns as the first, every coordinate
//!   is finite (3DTK has no missing-return marker; the error quotes the line as written) and a
//!   file without a point is an error ("no points").
//! - `.pose`: position `x y z` (cm), then orientation `rx ry rz` in degrees, the Euler angles of
//!   3DTK's `EulerToMatrix4` (see [`read_pose_3dtk`]).
//! - `.frames`: one line per registration step: the 16 numbers of a column-major 4x4 matrix
//!   (translation in cm in elements 13-15), then a type code. The last line is the final pose.
//!
//! Both pose readers return `world_from_scan` in semsim's frame.

use super::text::{read_file, shown, text};
use super::xyz::{
    check_columns, data_lines, max_point_lines, no_points, parse_columns, valid_points,
};
use crate::atomic::write_atomically;
use crate::cloud::{Organized, PointCloud};
use crate::error::{try_reserve, try_vec, CloudError, Result};
use crate::poses::affine_from_mat4;
use glam::{DAffine3, DMat3, DMat4, DVec3, DVec4, Vec3};
use std::io::Write;
use std::path::Path;

/// The axis map from 3DTK's frame to semsim's (columns are the images of x, y, z).
const P: DMat3 = DMat3::from_cols(
    DVec3::new(0.0, -1.0, 0.0),
    DVec3::new(0.0, 0.0, 1.0),
    DVec3::new(1.0, 0.0, 0.0),
);

/// Reads a 3DTK `.3d` scan into semsim's frame (metres, right-handed, z up).
pub fn read_3d(path: &Path) -> Result<PointCloud> {
    parse_3d(path, &read_file(path)?)
}

/// Reads the bytes of a `.3d` scan; `path` is for messages.
pub(crate) fn parse_3d(path: &Path, bytes: &[u8]) -> Result<PointCloud> {
    let text = text(path, bytes)?;
    check_last_line_complete(path, text)?;
    let mut lines = data_lines(text).peekable();
    let shape = lines.peek().and_then(|(_, l)| shape_line(l));
    if shape.is_some() {
        lines.next();
    }
    let cap = max_point_lines(text);
    let mut points = try_vec(path, cap, "the points")?;
    let mut intensity = Vec::new();
    let mut used = None;
    for (line_no, line) in lines {
        let (v, n) = parse_columns::<f64>(path, line_no, line, true)?;
        check_columns(path, line_no, n, *used.get_or_insert(n))?;
        let [x, y, z, i] = v;
        let p = (P * DVec3::new(x, y, z) / 100.0).as_vec3();
        if !p.is_finite() {
            let msg = format!(
                "'{}' is beyond the range of a coordinate in metres",
                shown(line)
            );
            return Err(CloudError::parse(path, line_no, msg));
        }
        points.push(p);
        if n == 4 {
            if intensity.capacity() == 0 {
                try_reserve(path, &mut intensity, cap, "the intensities")?;
            }
            intensity.push(i as f32);
        }
    }
    if points.is_empty() {
        return Err(no_points(path, "x y z [reflectance]"));
    }
    let mut cloud = PointCloud::from_points(points);
    cloud.intensity = (used == Some(4)).then_some(intensity);
    cloud.organized = shape.filter(|o| o.rows.checked_mul(o.cols) == Some(cloud.len()));
    cloud.check_finite(path)?;
    Ok(cloud)
}

/// Fails where the file's last line holds text but no newline: 3DTK writes whole lines, so
/// the file was cut short (possibly inside a number, which would read as a different one).
fn check_last_line_complete(path: &Path, text: &str) -> Result<()> {
    let last = text.rsplit('\n').next().unwrap_or_default();
    if last.trim().is_empty() {
        return Ok(());
    }
    let line = text.matches('\n').count() + 1;
    Err(CloudError::Truncated {
        path: path.to_path_buf(),
        msg: format!(
            "line {line} ('{}') does not end with a newline: the file was cut short (every line of a .3d file ends with one)",
            shown(last)
        ),
    })
}

/// Writes a 3DTK `.3d` scan (centimetres, left-handed, y up), missing returns dropped.
pub fn write_3d(path: &Path, cloud: &PointCloud) -> Result<()> {
    let shape = cloud
        .organized
        .filter(|_| cloud.valid_count() == cloud.len());
    let cloud = valid_points(path, cloud)?;
    write_atomically(path, |w| {
        let io = |e| CloudError::io(path, e);
        if let Some(o) = shape {
            writeln!(w, "{} x {}", o.cols, o.rows).map_err(io)?;
        }
        for (i, p) in cloud.points.iter().enumerate() {
            let q = point_to_3dtk(*p);
            write!(w, "{:.4} {:.4} {:.4}", q.x, q.y, q.z).map_err(io)?;
            if let Some(v) = cloud.intensity.as_ref().and_then(|v| v.get(i)) {
                write!(w, " {v}").map_err(io)?;
            }
            writeln!(w).map_err(io)?;
        }
        Ok(())
    })
}

/// Reads a 3DTK `.pose` file (position in cm, then Euler angles `rx ry rz` in degrees) as
/// `world_from_scan` in semsim's frame.
///
/// The rotation is 3DTK's `EulerToMatrix4`: with `s`/`c` the sines and cosines of `rx, ry, rz`,
/// the column-major matrix `m[0] = cy cz, m[1] = sx sy cz + cx sz, m[2] = -cx sy cz + sx sz,
/// m[4] = -cy sz, m[5] = -sx sy sz + cx cz, m[6] = cx sy sz + sx cz, m[8] = sy, m[9] = -sx cy,
/// m[10] = cx cy`.
pub fn read_pose_3dtk(path: &Path) -> Result<DAffine3> {
    parse_pose_3dtk(path, &read_file(path)?)
}

/// Reads the bytes of a `.pose` file; `path` is for messages.
pub(crate) fn parse_pose_3dtk(path: &Path, bytes: &[u8]) -> Result<DAffine3> {
    let text = text(path, bytes)?;
    let mut rows = Vec::with_capacity(2);
    for (line_no, line) in data_lines(text) {
        if rows.len() == 2 {
            let msg = "expected 2 lines (position in cm, orientation in degrees), found more";
            return Err(CloudError::parse(path, line_no, msg));
        }
        let v = numbers(path, line_no, line)?;
        let triple = <[f64; 3]>::try_from(v.as_slice()).map_err(|_| {
            CloudError::parse(
                path,
                line_no,
                format!("expected 3 numbers, found {}", v.len()),
            )
        })?;
        rows.push((line_no, DVec3::from_array(triple)));
    }
    let [(_, t), (line, angles)] = <[(usize, DVec3); 2]>::try_from(rows).map_err(|rows| {
        let msg = format!(
            "expected 2 lines (position in cm, orientation in degrees), found {}",
            rows.len()
        );
        CloudError::parse(path, rows.get(2).map_or(0, |r| r.0), msg)
    })?;
    let r = euler_3dtk(
        angles.x.to_radians(),
        angles.y.to_radians(),
        angles.z.to_radians(),
    );
    to_semsim(r, t, DVec4::W, path, line)
}

/// Reads a 3DTK `.frames` file: one `world_from_scan` per line (in semsim's frame), in file
/// order; the last is the final registration. A file without frames is an error.
pub fn read_frames_3dtk(path: &Path) -> Result<Vec<DAffine3>> {
    parse_frames_3dtk(path, &read_file(path)?)
}

/// Reads the bytes of a `.frames` file; `path` is for messages.
pub(crate) fn parse_frames_3dtk(path: &Path, bytes: &[u8]) -> Result<Vec<DAffine3>> {
    let text = text(path, bytes)?;
    let mut out = Vec::new();
    for (line_no, line) in data_lines(text) {
        let v = numbers(path, line_no, line)?;
        let m = v
            .get(..16)
            .and_then(|m| <[f64; 16]>::try_from(m).ok())
            .filter(|_| v.len() <= 17);
        let Some(m) = m else {
            let msg = format!(
                "expected 16 matrix entries and a type code, found {} numbers",
                v.len()
            );
            return Err(CloudError::parse(path, line_no, msg));
        };
        let m = DMat4::from_cols_array(&m);
        out.push(to_semsim(
            DMat3::from_mat4(m),
            m.w_axis.truncate(),
            m.row(3),
            path,
            line_no,
        )?);
    }
    if out.is_empty() {
        return Err(CloudError::parse(path, 0, "no frame lines"));
    }
    Ok(out)
}

/// 3DTK's `EulerToMatrix4` rotation for angles in radians.
fn euler_3dtk(rx: f64, ry: f64, rz: f64) -> DMat3 {
    let ((sx, cx), (sy, cy), (sz, cz)) = (rx.sin_cos(), ry.sin_cos(), rz.sin_cos());
    DMat3::from_cols_array(&[
        cy * cz,
        sx * sy * cz + cx * sz,
        -cx * sy * cz + sx * sz,
        -cy * sz,
        -sx * sy * sz + cx * cz,
        cx * sy * sz + sx * cz,
        sy,
        -sx * cy,
        cx * cy,
    ])
}

/// Converts a 3DTK transform (rotation, translation in cm, bottom row) to semsim's frame,
/// checking it is rigid.
fn to_semsim(r: DMat3, t_cm: DVec3, bottom: DVec4, path: &Path, line: usize) -> Result<DAffine3> {
    let r = P * r * P.transpose();
    let t = P * t_cm / 100.0;
    let m = DMat4::from_cols(
        r.x_axis.extend(bottom.x),
        r.y_axis.extend(bottom.y),
        r.z_axis.extend(bottom.z),
        t.extend(bottom.w),
    );
    affine_from_mat4(m, path, line)
}

/// The numbers of a line, all finite, else a parse error naming the line and the token.
fn numbers(path: &Path, line_no: usize, line: &str) -> Result<Vec<f64>> {
    line.split_whitespace()
        .map(|t| {
            t.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    let msg = format!("'{}' is not a finite number", shown(t));
                    CloudError::parse(path, line_no, msg)
                })
        })
        .collect()
}

/// `W x H` (also `WxH`): the organised shape, `H` rows of `W` columns.
fn shape_line(line: &str) -> Option<Organized> {
    let compact: String = line.chars().filter(|c| !c.is_whitespace()).collect();
    let (w, h) = compact.split_once(['x', 'X'])?;
    Some(Organized {
        rows: h.parse().ok()?,
        cols: w.parse().ok()?,
    })
}

/// A point of semsim's frame in 3DTK's (cm), for tests and tools.
pub fn point_to_3dtk(p: Vec3) -> DVec3 {
    P.transpose() * p.as_dvec3() * 100.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_map_matches_the_documented_formulas() {
        let p = P * DVec3::new(1.0, 2.0, 3.0);
        assert_eq!(p, DVec3::new(3.0, -1.0, 2.0));
        assert!((P.determinant() + 1.0).abs() < 1e-12);
        assert_eq!(
            point_to_3dtk(Vec3::new(0.03, -0.01, 0.02)).round(),
            DVec3::new(1.0, 2.0, 3.0)
        );
    }

    #[test]
    fn euler_matrix_is_a_rotation_and_yaw_turns_about_up() {
        let r = euler_3dtk(0.1, -0.2, 0.3);
        assert!((r.determinant() - 1.0).abs() < 1e-12);
        assert!((r.transpose() * r).abs_diff_eq(DMat3::IDENTITY, 1e-12));
        // A 3DTK yaw (about y, up) becomes a rotation about semsim's z.
        let ry = P * euler_3dtk(0.0, 0.5, 0.0) * P.transpose();
        assert!((ry * DVec3::Z).abs_diff_eq(DVec3::Z, 1e-12));
    }

    #[test]
    fn shape_lines() {
        assert_eq!(
            shape_line("360 x 225"),
            Some(Organized {
                rows: 225,
                cols: 360
            })
        );
        assert_eq!(shape_line("4x2"), Some(Organized { rows: 2, cols: 4 }));
        assert_eq!(shape_line("1 2 3"), None);
        assert_eq!(shape_line("1.5 x 2"), None);
    }
}
