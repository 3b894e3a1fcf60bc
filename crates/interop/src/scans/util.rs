//! What the scan readers share: reading a file, naming it, quoting text from it, and growing
//! vectors without aborting when memory runs out.

use crate::error::{InteropError, Result};
use std::path::Path;

/// The whole file, or the `cloud` crate's I/O error naming it.
pub(super) fn read_file(path: &Path) -> Result<Vec<u8>> {
    if path.is_dir() {
        return Err(cloud::CloudError::io(
            path,
            std::io::Error::new(std::io::ErrorKind::IsADirectory, "is a folder, not a file"),
        )
        .into());
    }
    std::fs::read(path).map_err(|e| cloud::CloudError::io(path, e).into())
}

/// The file name without extension (`scan` for a path without one).
pub(super) fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| clean(&s.to_string_lossy()))
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "scan".to_string())
}

/// Text from a file or a library made safe to print: control characters escaped (`\n`,
/// `\u{1b}`), everything else kept.
pub(super) fn clean(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// A note about the file: `path: text`.
pub(super) fn note(path: &Path, text: impl std::fmt::Display) -> String {
    format!("{}: {text}", path.display())
}

/// The out-of-memory error for `what`.
pub(super) fn out_of_memory(path: &Path, what: &str) -> InteropError {
    InteropError::OutOfMemory {
        path: path.to_path_buf(),
        what: what.to_string(),
    }
}

/// An empty vector with room for `n` items, or [`InteropError::OutOfMemory`].
pub(super) fn try_vec<T>(path: &Path, n: usize, what: &str) -> Result<Vec<T>> {
    let mut v = Vec::new();
    v.try_reserve_exact(n)
        .map_err(|_| out_of_memory(path, what))?;
    Ok(v)
}

/// Pushes `item`, growing the vector (amortised) with `try_reserve` so that a failed
/// allocation is an error rather than an abort.
pub(super) fn try_push<T>(path: &Path, v: &mut Vec<T>, item: T, what: &str) -> Result<()> {
    if v.len() == v.capacity() {
        v.try_reserve(1).map_err(|_| out_of_memory(path, what))?;
    }
    v.push(item);
    Ok(())
}

/// `n` copies of `value`, or [`InteropError::OutOfMemory`].
pub(super) fn try_filled<T: Clone>(path: &Path, n: usize, value: T, what: &str) -> Result<Vec<T>> {
    let mut v = try_vec(path, n, what)?;
    v.resize(n, value);
    Ok(v)
}

/// A rigid pose from a quaternion (any length but zero) and a translation, or `None` where
/// either is not finite or the quaternion is (nearly) zero.
pub(super) fn rigid_pose(quat_xyzw: [f64; 4], translation: [f64; 3]) -> Option<glam::DAffine3> {
    let q = glam::DQuat::from_xyzw(quat_xyzw[0], quat_xyzw[1], quat_xyzw[2], quat_xyzw[3]);
    let t = glam::DVec3::from_array(translation);
    let length = q.length();
    if !q.is_finite() || !t.is_finite() || !length.is_finite() || length < 1e-9 {
        return None;
    }
    Some(glam::DAffine3::from_rotation_translation(q / length, t))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clean_escapes_control_characters_only() {
        assert_eq!(clean("a\nb\u{1b}c é"), "a\\nb\\u{1b}c é");
    }

    #[test]
    fn rigid_pose_normalises_and_refuses_zero() {
        let p = rigid_pose([0.0, 0.0, 0.0, 2.0], [1.0, 2.0, 3.0]).expect("a pose");
        assert!((p.matrix3.determinant() - 1.0).abs() < 1e-12);
        assert!(rigid_pose([0.0; 4], [0.0; 3]).is_none());
        assert!(rigid_pose([f64::NAN, 0.0, 0.0, 1.0], [0.0; 3]).is_none());
    }
}
