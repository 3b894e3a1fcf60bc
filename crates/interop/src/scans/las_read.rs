//! Reading LAS 1.0-1.4 and LAZ files with the `las` crate (LAZ through its `laz` feature).
//!
//! * Positions come as f64 with the header's scale and offset applied. Georeferenced
//!   coordinates (UTM: hundreds of kilometres) do not fit in f32 to the millimetre, so where any
//!   point lies farther than [`LOCAL_EXTENT_M`] from zero on some axis, the reader moves the
//!   points to a local origin, the centre of their bounding box rounded to whole metres
//!   (computed in f64 from the points themselves, not the header's bounds, which writers do not
//!   always keep), subtracts it in f64 and only then converts to f32. The origin is
//!   [`ScanSet::local_origin_m`], and a note names it. Within ±10 m of the origin f32 keeps
//!   better than 1 µm; at ±1 km about 0.06 mm.
//! * Intensity (u16) as f32, and the ASPRS classification (`cloud.classification`): every LAS
//!   file has both, so the cloud always does. Class 12 (overlap) of the legacy formats 0-5 reads
//!   as 12; in the LAS 1.4 formats 6-10 the `las` crate reads class 12 as 1 with the overlap
//!   flag, so it reads as 1 there.
//! * Points with non-finite coordinates (a scale of NaN) are skipped, with a note.

use super::las_check::{check_las_header, LasLayout};
use super::util::{clean, note, try_push, try_vec};
use super::ScanSet;
use crate::error::{InteropError, Result};
use cloud::PointCloud;
use glam::DVec3;
use std::io::Cursor;
use std::path::Path;

/// How far from zero (metres, on every axis) a file's points may lie and still be read without
/// a local origin: f32 keeps them to 2^-14 m (0.06 mm) there.
pub(super) const LOCAL_EXTENT_M: f64 = 1000.0;

/// Reads the LAS or LAZ file in `bytes` (the header says which).
pub(super) fn parse_las(path: &Path, bytes: Vec<u8>) -> Result<ScanSet> {
    let layout = check_las_header(path, &bytes)?;
    let data_bytes = bytes.len();
    let decoded = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        decode(path, bytes, layout, data_bytes)
    }));
    let (xyz, intensity, classification) = decoded.map_err(|panic| {
        let what = panic
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        InteropError::format(
            path,
            format!(
                "not a readable LAS/LAZ file: the decoder's consistency check failed on corrupt data ({})",
                clean(&what)
            ),
        )
    })??;
    let mut notes = Vec::new();
    let mut keep: Vec<usize> = (0..xyz.len()).filter(|&i| xyz[i].is_finite()).collect();
    if keep.len() < xyz.len() {
        notes.push(note(
            path,
            format!(
                "{} points with non-finite coordinates skipped",
                xyz.len() - keep.len()
            ),
        ));
    }
    let origin = local_origin(keep.iter().map(|&i| xyz[i]));
    if origin != DVec3::ZERO {
        notes.push(note(
            path,
            format!(
                "georeferenced coordinates: points are relative to the local origin ({}, {}, {}) m",
                origin.x, origin.y, origin.z
            ),
        ));
    }
    // Points too far from the origin for f32 (a corrupt scale) are skipped too.
    let far = keep.len();
    keep.retain(|&i| (xyz[i] - origin).as_vec3().is_finite());
    if keep.len() < far {
        notes.push(note(
            path,
            format!(
                "{} points beyond f32 range of the local origin skipped",
                far - keep.len()
            ),
        ));
    }
    let mut points = try_vec(path, keep.len(), "the LAS points")?;
    points.extend(keep.iter().map(|&i| (xyz[i] - origin).as_vec3()));
    let mut cloud = PointCloud::from_points(points);
    cloud.intensity = Some(keep.iter().map(|&i| intensity[i]).collect());
    cloud.classification = Some(keep.iter().map(|&i| classification[i]).collect());
    Ok(super::single_scan(path, cloud, origin, notes))
}

type Columns = (Vec<DVec3>, Vec<f32>, Vec<u8>);

/// The `las` crate's part: the header again, then every point.
///
/// Run under `catch_unwind` by [`parse_las`]: the `laz` crate's arithmetic decoder checks its
/// state with `debug_assert!`s that corrupt compressed data trips (in debug builds and under
/// the fuzzer; release builds do not check and the decoder reads on or fails at the end of
/// the data). Nothing can tell such data apart before decoding it, so a panic there becomes a
/// format error. Everything the crates trust beyond that is checked before (`las_check`,
/// `laz_check`).
fn decode(path: &Path, bytes: Vec<u8>, layout: LasLayout, data_bytes: usize) -> Result<Columns> {
    let mut reader = las::Reader::new(Cursor::new(bytes)).map_err(|e| las_error(path, "", &e))?;
    let header = reader.header();
    let count = header.number_of_points();
    if count > layout.points {
        return Err(InteropError::format(
            path,
            format!(
                "the header's point count {count} disagrees with {}",
                layout.points
            ),
        ));
    }
    let legacy_format = !header.point_format().is_extended;
    read_points(path, &mut reader, layout, data_bytes, legacy_format)
}

/// Every point's position (f64), intensity and class byte.
fn read_points(
    path: &Path,
    reader: &mut las::Reader,
    layout: LasLayout,
    file_bytes: usize,
    legacy_format: bool,
) -> Result<Columns> {
    // Uncompressed: the count is checked against the file. LAZ: grow as points decode.
    let initial = if layout.compressed {
        (layout.points as usize).min(file_bytes)
    } else {
        layout.points as usize
    };
    let mut xyz = try_vec(path, initial, "the LAS points")?;
    let mut intensity = try_vec(path, initial, "the LAS intensities")?;
    let mut classification = try_vec(path, initial, "the LAS classes")?;
    for i in 0..layout.points {
        let point = match reader.read_point() {
            Ok(Some(p)) => p,
            Ok(None) => {
                return Err(InteropError::format(
                    path,
                    format!("truncated: {i} of {} points", layout.points),
                ))
            }
            Err(e) => return Err(las_error(path, &format!("point {i}: "), &e)),
        };
        let mut class = u8::from(point.classification);
        if legacy_format && point.is_overlap && class == 1 {
            class = 12; // The las crate reads the legacy overlap class 12 as 1 + overlap.
        }
        try_push(
            path,
            &mut xyz,
            DVec3::new(point.x, point.y, point.z),
            "the LAS points",
        )?;
        try_push(
            path,
            &mut intensity,
            f32::from(point.intensity),
            "the LAS intensities",
        )?;
        try_push(path, &mut classification, class, "the LAS classes")?;
    }
    Ok((xyz, intensity, classification))
}

/// Zero where every point lies within [`LOCAL_EXTENT_M`] of zero on every axis, else the centre
/// of the points' bounding box rounded to whole metres.
pub(super) fn local_origin(points: impl Iterator<Item = DVec3>) -> DVec3 {
    let mut bounds: Option<(DVec3, DVec3)> = None;
    for p in points {
        bounds = Some(match bounds {
            None => (p, p),
            Some((lo, hi)) => (lo.min(p), hi.max(p)),
        });
    }
    let Some((lo, hi)) = bounds else {
        return DVec3::ZERO;
    };
    let centre = (lo * 0.5 + hi * 0.5).round();
    if lo.abs().max(hi.abs()).max_element() <= LOCAL_EXTENT_M || !centre.is_finite() {
        return DVec3::ZERO;
    }
    centre
}

/// The `las` crate's error as a format error, its text quoted with control characters escaped.
fn las_error(path: &Path, context: &str, error: &las::Error) -> InteropError {
    InteropError::format(
        path,
        format!(
            "not a readable LAS/LAZ file: {context}{}",
            clean(&error.to_string())
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn local_origin_only_for_far_points() {
        let near = [DVec3::new(-5.0, 2.0, 0.0), DVec3::new(900.0, -999.0, 3.0)];
        assert_eq!(local_origin(near.into_iter()), DVec3::ZERO);
        let far = [
            DVec3::new(500_000.2, 5_400_000.7, 100.0),
            DVec3::new(500_010.2, 5_400_020.7, 110.0),
        ];
        assert_eq!(
            local_origin(far.into_iter()),
            DVec3::new(500_005.0, 5_400_011.0, 105.0)
        );
        assert_eq!(local_origin(std::iter::empty()), DVec3::ZERO);
    }
}
