//! Reading LAS 1.0-1.4 and LAZ files: the header checked by our own code (`las_check`,
//! `laz_check`), the point records parsed by our own code, LAZ decompressed by the `laz` crate
//! (the `las` crate's decoder). Points stream from the file in batches: only the points' own
//! columns are kept (no copy of the file, no f64 copy of the points).
//!
//! * Positions: the integer coordinates with the header's scale and offset applied in f64.
//!   Georeferenced coordinates (UTM: hundreds of kilometres) do not fit in f32 to the
//!   millimetre, so where any point lies farther than [`LOCAL_EXTENT_M`] from zero on some axis,
//!   the points are moved to a local origin, the centre of their bounding box rounded to whole
//!   metres, subtracted in f64 before the conversion to f32. The origin is first taken from
//!   the header's bounds; the points' own bounds decide, and in a file whose header bounds are
//!   wrong the points are decoded a second time around the right origin. The origin is
//!   [`ScanSet::local_origin_m`], and a note names it. Within ±10 m of the origin f32 keeps
//!   better than 1 µm; at ±1 km about 0.06 mm.
//! * Intensity (u16) as f32, and the ASPRS classification (`cloud.classification`): every LAS
//!   file has both, so the cloud always does. Formats 0-5 keep the class in the low five bits
//!   of byte 15 (class 12, overlap, included); formats 6-10 in the whole byte 16.
//! * Points with non-finite coordinates (a scale of NaN) are skipped, with a note.
//! * LAZ with fixed-size chunks (what LASzip and laz-perf write) is decompressed in two halves
//!   on two threads, each starting at a chunk boundary.

use super::las_check::{check_las_header, LasLayout};
use super::las_stream::{stream, RangeStats, RecordParser, Slices};
use super::source::ByteSource;
use super::util::{clean, note};
use super::ScanSet;
use crate::error::{InteropError, Result};
use cloud::PointCloud;
use glam::{DVec3, Vec3};
use std::io::{Seek, SeekFrom};
use std::path::Path;

/// How far from zero (metres, on every axis) a file's points may lie and still be read without
/// a local origin: f32 keeps them to 2^-14 m (0.06 mm) there.
pub(super) const LOCAL_EXTENT_M: f64 = 1000.0;

/// Below this many points a LAZ file is decompressed on one thread.
const PARALLEL_MIN_POINTS: u64 = 200_000;

/// Reads the LAS or LAZ file in `src` (the header says which).
pub(super) fn read_las(path: &Path, src: &impl ByteSource) -> Result<ScanSet> {
    // 1. The header, checked before any decoder trusts it.
    let layout = check_las_header(path, src)?;
    // 2. The points around the origin the header's bounds suggest ...
    let guess = local_origin(header_bounds(&layout).into_iter());
    let mut columns = decode_guarded(path, src, &layout, guess)?;
    // 3. ... and again around the points' own origin where the header's bounds were wrong.
    let origin = local_origin(columns.bounds.into_iter().flatten());
    if origin != guess {
        columns = decode_guarded(path, src, &layout, origin)?;
    }
    // 4. Points that are no points (non-finite, or beyond f32 of the origin) dropped.
    let mut notes = Vec::new();
    let skipped = columns.compact();
    if columns.non_finite > 0 {
        notes.push(note(
            path,
            format!(
                "{} points with non-finite coordinates skipped",
                columns.non_finite
            ),
        ));
    }
    if skipped > columns.non_finite {
        notes.push(note(
            path,
            format!(
                "{} points beyond f32 range of the local origin skipped",
                skipped - columns.non_finite
            ),
        ));
    }
    if origin != DVec3::ZERO {
        notes.push(note(
            path,
            format!(
                "georeferenced coordinates: points are relative to the local origin ({}, {}, {}) m",
                origin.x, origin.y, origin.z
            ),
        ));
    }
    let mut cloud = PointCloud::from_points(columns.xyz);
    cloud.intensity = Some(columns.intensity);
    cloud.classification = Some(columns.classification);
    Ok(super::single_scan(path, cloud, origin, notes))
}

/// The corners of the header's bounding box, where they are finite.
fn header_bounds(layout: &LasLayout) -> Vec<DVec3> {
    let (min, max) = layout.bounds;
    [DVec3::from_array(min), DVec3::from_array(max)]
        .into_iter()
        .filter(|p| p.is_finite())
        .collect()
}

/// The decoded points: f32 relative to the origin (NaN where not a point), intensity, class.
struct Columns {
    xyz: Vec<Vec3>,
    intensity: Vec<f32>,
    classification: Vec<u8>,
    /// The bounding box of the finite points in the file's frame (f64).
    bounds: Option<[DVec3; 2]>,
    /// Points whose f64 coordinates are not finite.
    non_finite: usize,
}

impl Columns {
    /// Drops the NaN points in place; returns how many.
    fn compact(&mut self) -> usize {
        let mut kept = 0;
        for i in 0..self.xyz.len() {
            if self.xyz[i].is_finite() {
                self.xyz[kept] = self.xyz[i];
                self.intensity[kept] = self.intensity[i];
                self.classification[kept] = self.classification[i];
                kept += 1;
            }
        }
        let skipped = self.xyz.len() - kept;
        self.xyz.truncate(kept);
        self.intensity.truncate(kept);
        self.classification.truncate(kept);
        skipped
    }
}

/// [`decode`] under `catch_unwind`: the `laz` crate's arithmetic decoder checks its state with
/// `debug_assert!`s that corrupt compressed data trips (in debug builds and under the fuzzer;
/// release builds do not check and the decoder reads on or fails at the end of the data).
/// Nothing can tell such data apart before decoding it, so a panic there becomes a format
/// error. Everything the crate trusts beyond that is checked before (`las_check`, `laz_check`).
fn decode_guarded(
    path: &Path,
    src: &impl ByteSource,
    layout: &LasLayout,
    origin: DVec3,
) -> Result<Columns> {
    let decoded = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        decode(path, src, layout, origin)
    }));
    decoded.map_err(|panic| {
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
    })?
}

/// Every point of the file: on two threads where [`parallel_split`] says so.
fn decode(
    path: &Path,
    src: &impl ByteSource,
    layout: &LasLayout,
    origin: DVec3,
) -> Result<Columns> {
    let parser = RecordParser::new(layout, origin);
    let mut columns = Columns {
        xyz: Vec::new(),
        intensity: Vec::new(),
        classification: Vec::new(),
        bounds: None,
        non_finite: 0,
    };
    let mut stats = RangeStats::default();
    // The count sizes the columns only where it is checked against the file's size (uncompressed)
    // or is no larger than the file's bytes (compressed: real LAZ takes more than a byte a point).
    let trusted = !layout.compressed || layout.points <= src.len();
    match parallel_split(src, layout).filter(|_| trusted) {
        Some(split) => {
            grow(path, &mut columns, layout.points as usize)?;
            let at = split as usize;
            let (xyz_a, xyz_b) = columns.xyz.split_at_mut(at);
            let (int_a, int_b) = columns.intensity.split_at_mut(at);
            let (cls_a, cls_b) = columns.classification.split_at_mut(at);
            let halves = std::thread::scope(|scope| {
                let second = scope.spawn(|| {
                    let n = xyz_b.len() as u64;
                    let mut out = Slices::new(xyz_b, int_b, cls_b);
                    stream(path, src, layout, split, n, &mut |records| {
                        out.push(&parser, records, layout.record_len);
                        Ok(())
                    })
                    .map(|()| out.stats)
                });
                let mut out = Slices::new(xyz_a, int_a, cls_a);
                let first = stream(path, src, layout, 0, split, &mut |records| {
                    out.push(&parser, records, layout.record_len);
                    Ok(())
                })
                .map(|()| out.stats);
                let second = second
                    .join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
                Ok::<_, InteropError>(first?.merge(second?))
            })?;
            stats = halves;
        }
        None => {
            let initial = if trusted { layout.points as usize } else { 0 };
            columns
                .xyz
                .try_reserve_exact(initial)
                .map_err(|_| oom(path))?;
            columns
                .intensity
                .try_reserve_exact(initial)
                .map_err(|_| oom(path))?;
            columns
                .classification
                .try_reserve_exact(initial)
                .map_err(|_| oom(path))?;
            stream(path, src, layout, 0, layout.points, &mut |records| {
                let n = records.len() / layout.record_len;
                let start = columns.xyz.len();
                grow(path, &mut columns, n)?;
                let mut out = Slices::new(
                    &mut columns.xyz[start..],
                    &mut columns.intensity[start..],
                    &mut columns.classification[start..],
                );
                out.push(&parser, records, layout.record_len);
                stats = std::mem::take(&mut stats).merge(out.stats);
                Ok(())
            })?;
        }
    }
    columns.bounds = stats.bounds;
    columns.non_finite = stats.non_finite;
    Ok(columns)
}

fn oom(path: &Path) -> InteropError {
    super::util::out_of_memory(path, "the LAS points")
}

/// Grows every column by `n` points (zeroed; amortised) or fails with an out-of-memory error.
fn grow(path: &Path, columns: &mut Columns, n: usize) -> Result<()> {
    columns.xyz.try_reserve(n).map_err(|_| oom(path))?;
    columns.intensity.try_reserve(n).map_err(|_| oom(path))?;
    columns
        .classification
        .try_reserve(n)
        .map_err(|_| oom(path))?;
    let len = columns.xyz.len() + n;
    columns.xyz.resize(len, Vec3::ZERO);
    columns.intensity.resize(len, 0.0);
    columns.classification.resize(len, 0);
    Ok(())
}

/// Where a LAZ file is split for two threads: the first point of the middle chunk, for files
/// with fixed-size chunks large enough to be worth it and a chunk table to seek with (the
/// second thread starts there; a file without a readable table decodes on one thread).
fn parallel_split(src: &impl ByteSource, layout: &LasLayout) -> Option<u64> {
    let vlr = laz::LazVlr::from_buffer(layout.laz_vlr.as_deref()?).ok()?;
    let chunk = u64::from(vlr.chunk_size());
    if !layout.compressed
        || vlr.uses_variable_size_chunks()
        || chunk == 0
        || layout.points < PARALLEL_MIN_POINTS.max(2 * chunk)
    {
        return None;
    }
    let chunks = layout.points.div_ceil(chunk);
    let split = chunks / 2 * chunk;
    let mut reader = src.reader().ok()?;
    reader.seek(SeekFrom::Start(layout.points_at)).ok()?;
    let table = laz::laszip::ChunkTable::read_from(reader, &vlr).ok()?;
    (table.as_ref().len() as u64 >= chunks).then_some(split)
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

    #[test]
    fn large_laz_files_with_a_chunk_table_split_at_a_chunk_boundary() {
        let dir = tempfile::tempdir().expect("temp dir");
        let n = 260_000;
        let cloud = PointCloud::from_points(
            (0..n)
                .map(|i| glam::Vec3::new(i as f32 * 1e-4, 1.0, 2.0))
                .collect(),
        );
        let path = dir.path().join("big.laz");
        crate::write_cloud(&path, &cloud).expect("write");
        let src = super::super::source::FileSource::open(&path).expect("open");
        let layout = check_las_header(&path, &src).expect("header");
        // The las crate writes 50,000-point chunks: 6 chunks, the second thread from chunk 3.
        assert_eq!(parallel_split(&src, &layout), Some(150_000));
        // Small files stay on one thread.
        let small = dir.path().join("small.laz");
        crate::write_cloud(
            &small,
            &PointCloud::from_points(cloud.points[..1000].to_vec()),
        )
        .expect("write");
        let src = super::super::source::FileSource::open(&small).expect("open");
        let layout = check_las_header(&small, &src).expect("header");
        assert_eq!(parallel_split(&src, &layout), None);
    }
}
