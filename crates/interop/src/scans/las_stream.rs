//! The decoding half of the LAS reader: point records streamed from the file (raw, or through
//! the `laz` crate's decompressor) a batch at a time, and parsed into column slices.

use super::las_check::LasLayout;
use super::source::ByteSource;
use super::util::{clean, try_vec};
use crate::error::{InteropError, Result};
use glam::{DVec3, Vec3};
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

/// Points decoded at a time (a buffer of at most 67 bytes each).
const BATCH_POINTS: usize = 16_384;

/// Column slices filled front to back.
pub(super) struct Slices<'a> {
    xyz: &'a mut [Vec3],
    intensity: &'a mut [f32],
    classes: &'a mut [u8],
    filled: usize,
    /// What the filled points showed.
    pub stats: RangeStats,
}

impl<'a> Slices<'a> {
    pub(super) fn new(
        xyz: &'a mut [Vec3],
        intensity: &'a mut [f32],
        classes: &'a mut [u8],
    ) -> Slices<'a> {
        Slices {
            xyz,
            intensity,
            classes,
            filled: 0,
            stats: RangeStats::default(),
        }
    }

    /// Parses whole records into the next free places (the caller sized the slices).
    pub(super) fn push(&mut self, parser: &RecordParser, records: &[u8], record_len: usize) {
        let n = records.len() / record_len;
        let range = self.filled..self.filled + n;
        parser.parse(
            records,
            record_len,
            &mut self.xyz[range.clone()],
            &mut self.intensity[range.clone()],
            &mut self.classes[range],
            &mut self.stats,
        );
        self.filled += n;
    }
}

/// Streams `count` point records from point `first` on, a batch at a time, to `sink`: read raw
/// from an uncompressed file, or decompressed by the `laz` crate.
pub(super) fn stream(
    path: &Path,
    src: &impl ByteSource,
    layout: &LasLayout,
    first: u64,
    count: u64,
    sink: &mut dyn FnMut(&[u8]) -> Result<()>,
) -> Result<()> {
    let io = |e: std::io::Error| InteropError::from(cloud::CloudError::io(path, e));
    let record_len = layout.record_len;
    let failed = |done: u64, e: &dyn std::fmt::Display| {
        InteropError::format(
            path,
            format!(
                "truncated or corrupt at point {} of {}: {}",
                first + done,
                layout.points,
                clean(&e.to_string())
            ),
        )
    };
    let mut buffer = try_vec::<u8>(path, BATCH_POINTS * record_len, "the LAS read buffer")?;
    buffer.resize(BATCH_POINTS * record_len, 0);
    let mut pump = |fill: &mut dyn FnMut(&mut [u8]) -> std::io::Result<()>| -> Result<()> {
        let mut done = 0u64;
        while done < count {
            let n = (BATCH_POINTS as u64).min(count - done) as usize;
            let bytes = &mut buffer[..n * record_len];
            fill(bytes).map_err(|e| failed(done, &e))?;
            sink(bytes)?;
            done += n as u64;
        }
        Ok(())
    };
    let mut reader = src.reader().map_err(io)?;
    if !layout.compressed {
        let start = first
            .checked_mul(record_len as u64)
            .and_then(|b| b.checked_add(layout.points_at))
            .ok_or_else(|| failed(0, &"beyond the file"))?;
        reader.seek(SeekFrom::Start(start)).map_err(io)?;
        return pump(&mut |bytes| reader.read_exact(bytes));
    }
    let vlr_data = layout.laz_vlr.as_deref().ok_or_else(|| {
        InteropError::format(
            path,
            "a LAZ file without the LASzip VLR (user \"laszip encoded\", record 22204)",
        )
    })?;
    let vlr = laz::LazVlr::from_buffer(vlr_data).map_err(|e| laz_error(path, &e))?;
    if vlr.items_size() as usize != record_len {
        return Err(InteropError::format(
            path,
            format!(
                "the LASzip VLR describes {}-byte points, the header {record_len}",
                vlr.items_size()
            ),
        ));
    }
    reader.seek(SeekFrom::Start(layout.points_at)).map_err(io)?;
    let mut decompressor =
        laz::LasZipDecompressor::new(reader, vlr).map_err(|e| laz_error(path, &e))?;
    if first > 0 {
        decompressor.seek(first).map_err(|e| laz_error(path, &e))?;
    }
    pump(&mut |bytes| decompressor.decompress_many(bytes))
}

pub(super) fn merge_bounds(a: Option<[DVec3; 2]>, b: Option<[DVec3; 2]>) -> Option<[DVec3; 2]> {
    match (a, b) {
        (Some([lo, hi]), Some([l, h])) => Some([lo.min(l), hi.max(h)]),
        (a, None) => a,
        (None, b) => b,
    }
}

/// What a filled range saw.
#[derive(Default)]
pub(super) struct RangeStats {
    /// The bounding box of the finite points in the file's frame (f64).
    pub bounds: Option<[DVec3; 2]>,
    /// Points whose f64 coordinates are not finite.
    pub non_finite: usize,
}

impl RangeStats {
    pub(super) fn merge(self, other: RangeStats) -> RangeStats {
        RangeStats {
            bounds: merge_bounds(self.bounds, other.bounds),
            non_finite: self.non_finite + other.non_finite,
        }
    }
}

/// Turns point records into columns.
#[derive(Clone)]
pub(super) struct RecordParser {
    scale: DVec3,
    offset: DVec3,
    origin: DVec3,
    /// Where the class is: byte 15, low five bits (formats 0-5), or all of byte 16 (6-10).
    extended: bool,
}

impl RecordParser {
    pub(super) fn new(layout: &LasLayout, origin: DVec3) -> RecordParser {
        RecordParser {
            scale: DVec3::from_array(layout.scale),
            offset: DVec3::from_array(layout.offset),
            origin,
            extended: layout.format >= 6,
        }
    }

    /// Parses `records` (whole records of `record_len` bytes) into the columns' slices.
    fn parse(
        &self,
        records: &[u8],
        record_len: usize,
        xyz: &mut [Vec3],
        intensity: &mut [f32],
        classes: &mut [u8],
        stats: &mut RangeStats,
    ) {
        let int_at =
            |r: &[u8], at: usize| i32::from_le_bytes([r[at], r[at + 1], r[at + 2], r[at + 3]]);
        for (k, record) in records.chunks_exact(record_len).enumerate() {
            let raw = DVec3::new(
                f64::from(int_at(record, 0)),
                f64::from(int_at(record, 4)),
                f64::from(int_at(record, 8)),
            );
            let p = raw * self.scale + self.offset;
            if p.is_finite() {
                stats.bounds = merge_bounds(stats.bounds, Some([p, p]));
                xyz[k] = (p - self.origin).as_vec3();
            } else {
                stats.non_finite += 1;
                xyz[k] = Vec3::NAN;
            }
            intensity[k] = f32::from(u16::from_le_bytes([record[12], record[13]]));
            classes[k] = if self.extended {
                record[16]
            } else {
                record[15] & 0x1f
            };
        }
    }
}

/// The `laz` crate's error as a format error, its text quoted with control characters escaped.
fn laz_error(path: &Path, error: &laz::LasZipError) -> InteropError {
    InteropError::format(
        path,
        format!("not a readable LAZ file: {}", clean(&error.to_string())),
    )
}
