//! XYZ / TXT: one point per line, columns `x y z [intensity]` in metres, separated by
//! whitespace or commas. Blank lines and lines starting with `#` are skipped; columns after the
//! fourth are ignored. Whether there is an intensity is decided by the first point line, and
//! every later line must have the same number of used columns (3, or 4 and more). A file
//! without any point line is an error ("no points"); a UTF-8 byte-order mark is allowed.
//!
//! The format has no organised shape and no labels: writing drops the labels and the missing
//! returns of an organised cloud, and numbers are written as the shortest decimal that reads
//! back to the same `f32`, so a write-read round trip is exact.

use super::text::{read_file, shown, text};
use crate::atomic::write_atomically;
use crate::cloud::PointCloud;
use crate::error::{try_reserve, try_vec, CloudError, Result};
use glam::Vec3;
use std::borrow::Cow;
use std::io::Write;
use std::path::Path;
use std::str::FromStr;

/// Reads an XYZ/TXT file; a NaN or infinite coordinate is a [`CloudError::NonFinite`] error.
pub fn read_xyz(path: &Path) -> Result<PointCloud> {
    parse_xyz(path, &read_file(path)?)
}

/// Reads the bytes of an XYZ/TXT file; `path` is for messages.
pub(crate) fn parse_xyz(path: &Path, bytes: &[u8]) -> Result<PointCloud> {
    let text = text(path, bytes)?;
    let cap = max_point_lines(text);
    let mut points = try_vec(path, cap, "the points")?;
    let mut intensity = Vec::new();
    let mut used = None;
    for (line_no, line) in data_lines(text) {
        let (v, n) = parse_columns::<f32>(path, line_no, line, false)?;
        let first = *used.get_or_insert(n);
        check_columns(path, line_no, n, first)?;
        let [x, y, z, i] = v;
        points.push(Vec3::new(x, y, z));
        if n == 4 {
            if intensity.capacity() == 0 {
                try_reserve(path, &mut intensity, cap, "the intensities")?;
            }
            intensity.push(i);
        }
    }
    if points.is_empty() {
        return Err(no_points(path, "x y z [intensity]"));
    }
    let mut cloud = PointCloud::from_points(points);
    cloud.intensity = (used == Some(4)).then_some(intensity);
    cloud.check_finite(path)?;
    Ok(cloud)
}

/// The error for a text cloud without a single point line.
pub(super) fn no_points(path: &Path, columns: &str) -> CloudError {
    CloudError::parse(
        path,
        0,
        format!("no points (the file has no line of numbers {columns})"),
    )
}

/// The most point lines `text` can hold: a point line takes at least 6 bytes (`1 2 3` and its
/// newline), so the points allocated never exceed what the file's bytes can hold.
pub(super) fn max_point_lines(text: &str) -> usize {
    (text.len() + 1) / 6
}

/// Writes an XYZ file atomically: `x y z [intensity]` per line, missing returns dropped.
pub fn write_xyz(path: &Path, cloud: &PointCloud) -> Result<()> {
    let cloud = valid_points(path, cloud)?;
    write_atomically(path, |w| {
        let io = |e| CloudError::io(path, e);
        for (i, p) in cloud.points.iter().enumerate() {
            write!(w, "{} {} {}", p.x, p.y, p.z).map_err(io)?;
            if let Some(v) = cloud.intensity.as_ref().and_then(|v| v.get(i)) {
                write!(w, " {v}").map_err(io)?;
            }
            writeln!(w).map_err(io)?;
        }
        Ok(())
    })
}

/// The non-blank, non-comment lines, trimmed, with their 1-based line numbers.
pub(super) fn data_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines()
        .enumerate()
        .map(|(k, l)| (k + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'))
}

/// The first four numbers of a line (separated by whitespace or commas) and how many of those
/// four there are (at least 3, else an error).
///
/// With `finite`, a NaN or infinite number is an error naming the line and the text as written.
pub(super) fn parse_columns<T: FromStr + Copy + Default + Finite>(
    path: &Path,
    line_no: usize,
    line: &str,
    finite: bool,
) -> Result<([T; 4], usize)> {
    let mut v = [T::default(); 4];
    let mut n = 0;
    let tokens = line
        .split(|c: char| c.is_whitespace() || c == ',')
        .filter(|t| !t.is_empty());
    for (slot, tok) in v.iter_mut().zip(tokens) {
        *slot = tok.parse().map_err(|_| {
            CloudError::parse(path, line_no, format!("'{}' is not a number", shown(tok)))
        })?;
        if finite && !slot.finite() {
            let msg = format!("'{}' is not a finite number", shown(tok));
            return Err(CloudError::parse(path, line_no, msg));
        }
        n += 1;
    }
    if n < 3 {
        let msg = format!(
            "expected at least 3 columns (x y z), found {n} in '{}'",
            shown(line)
        );
        return Err(CloudError::parse(path, line_no, msg));
    }
    Ok((v, n))
}

/// Numbers that can be checked for being finite.
pub(super) trait Finite {
    fn finite(self) -> bool;
}

impl Finite for f32 {
    fn finite(self) -> bool {
        self.is_finite()
    }
}

impl Finite for f64 {
    fn finite(self) -> bool {
        self.is_finite()
    }
}

/// Fails unless a line uses as many columns (3, or 4 with intensity) as the first point line.
pub(super) fn check_columns(path: &Path, line_no: usize, n: usize, first: usize) -> Result<()> {
    if n == first {
        return Ok(());
    }
    let msg = format!(
        "{n} columns, but the first point line has {first} (x y z, then an optional intensity)"
    );
    Err(CloudError::parse(path, line_no, msg))
}

/// The cloud to write in a format without organised shape: checked, missing returns dropped.
pub(super) fn valid_points<'a>(path: &Path, cloud: &'a PointCloud) -> Result<Cow<'a, PointCloud>> {
    cloud.validate()?;
    let out = match cloud.organized {
        Some(_) => Cow::Owned(cloud.without_invalid()),
        None => Cow::Borrowed(cloud),
    };
    out.check_finite(path)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_str(text: &str) -> Result<PointCloud> {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("t.xyz");
        std::fs::write(&path, text).expect("write");
        read_xyz(&path)
    }

    #[test]
    fn a_file_without_points_is_an_error() {
        for text in ["", "\n\n", "# only a comment\n"] {
            let e = read_str(text).expect_err("no points").to_string();
            assert!(e.contains("t.xyz: no points"), "{e}");
        }
    }

    #[test]
    fn reads_comments_commas_and_intensity() {
        let c = read_str("# header\n\n1 2 3 0.5\n4,5,6,7 99\n  -1e-3\t0 2.5 1\n").expect("valid");
        assert_eq!(c.len(), 3);
        assert_eq!(c.points[1], Vec3::new(4.0, 5.0, 6.0));
        assert_eq!(c.intensity, Some(vec![0.5, 7.0, 1.0]));
        assert_eq!(c.organized, None);
    }

    #[test]
    fn errors_name_the_line_and_the_text() {
        let e = read_str("1 2 3\n1 2 abc\n").expect_err("bad").to_string();
        assert!(e.contains("t.xyz:2") && e.contains("'abc'"), "{e}");
        let e = read_str("1 2 3\n1 2\n").expect_err("short").to_string();
        assert!(e.contains(":2:") && e.contains("at least 3 columns"), "{e}");
        let e = read_str("1 2 3\n1 2 3 4\n").expect_err("mixed").to_string();
        assert!(e.contains(":2:"), "{e}");
        assert!(matches!(
            read_str("1 2 3\n1 inf 3\n"),
            Err(CloudError::NonFinite { index: 1, .. })
        ));
    }
}
