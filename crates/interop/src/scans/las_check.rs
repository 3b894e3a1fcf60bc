//! Checks of a LAS/LAZ file's header before the `las` crate reads it.
//!
//! The `las` and `laz` crates size some allocations by numbers in the file (the first extended
//! VLR's length, the LAZ chunk count) and compute the end of the point records with unchecked
//! arithmetic. Reading those numbers here first and refusing the ones no file of this size
//! could hold turns a corrupt header into a format error instead of an abort or a panic.
//!
//! Layout of the public header block (LAS 1.0-1.4, little endian): `LASF` at 0, version major
//! and minor at 24 and 25, header size (u16) at 94, offset to the point data (u32) at 96, point
//! format (u8) at 104, record length (u16) at 105, legacy point count (u32) at 107; LAS 1.4 adds
//! the first extended VLR's offset (u64) at 235, the extended VLR count (u32) at 243 and the
//! 64-bit point count at 247.

use super::source::ByteSource;
use super::util::clean;
use crate::error::{InteropError, Result};
use std::path::Path;

/// The smallest public header block (LAS 1.0-1.2).
const MIN_HEADER_BYTES: usize = 227;
/// The LAS 1.4 public header block.
const LAS14_HEADER_BYTES: usize = 375;
/// An extended VLR's header: reserved, user id, record id, length (u64), description.
const EVLR_HEADER_BYTES: u64 = 60;
/// The shortest point record (format 0); every LAZ chunk starts with one uncompressed.
const MIN_RECORD_BYTES: u64 = 20;
/// The most points a LAZ file may claim per byte of compressed point data. Real LAZ data takes
/// one to ten bytes a point; even a chunk of identical points stays far below this rate.
pub(super) const LAZ_MAX_POINTS_PER_BYTE: u64 = 256;

/// What the header promises, as far as the reader needs it.
#[derive(Debug, Clone)]
pub(super) struct LasLayout {
    /// The point count to read (the legacy count where non-zero).
    pub points: u64,
    /// LAZ-compressed point data.
    pub compressed: bool,
    /// The byte where the point data starts.
    pub points_at: u64,
    /// The bytes of one point record.
    pub record_len: usize,
    /// The point data record format (0-10), compression bits cleared.
    pub format: u8,
    /// Scale and offset of the integer coordinates: `x = X * scale + offset`.
    pub scale: [f64; 3],
    /// See `scale`.
    pub offset: [f64; 3],
    /// The header's bounding box (minimum, maximum), which writers do not always keep.
    pub bounds: ([f64; 3], [f64; 3]),
    /// The LASzip VLR's data (compressed files).
    pub laz_vlr: Option<Vec<u8>>,
}

/// The shortest record of each point format 0-10 (LAS 1.4, table 7 onwards).
const FORMAT_RECORD_BYTES: [usize; 11] = [20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67];

fn u16_at(b: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([b[at], b[at + 1]])
}

fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

fn u64_at(b: &[u8], at: usize) -> Option<u64> {
    let bytes: [u8; 8] = b.get(at..at.checked_add(8)?)?.try_into().ok()?;
    Some(u64::from_le_bytes(bytes))
}

fn f64_at(b: &[u8], at: usize) -> f64 {
    u64_at(b, at).map_or(f64::NAN, f64::from_bits)
}

/// Checks the header of the LAS/LAZ file in `src`, returning what it promises.
pub(super) fn check_las_header(path: &Path, src: &impl ByteSource) -> Result<LasLayout> {
    let bad = |msg: String| InteropError::format(path, msg);
    let len = src.len();
    if len < MIN_HEADER_BYTES as u64 {
        return Err(bad(format!(
            "truncated: {len} bytes, a LAS header takes at least {MIN_HEADER_BYTES}"
        )));
    }
    let head_len = len.min(LAS14_HEADER_BYTES as u64) as usize;
    let bytes = &src
        .bytes_at(0, head_len)
        .ok_or_else(|| bad("the header could not be read".to_string()))?;
    if &bytes[..4] != b"LASF" {
        return Err(bad(format!(
            "not a LAS/LAZ file: it starts with {:?}, not \"LASF\"",
            clean(&String::from_utf8_lossy(&bytes[..4]))
        )));
    }
    let (major, minor) = (bytes[24], bytes[25]);
    if major != 1 || minor > 4 {
        return Err(InteropError::unsupported(
            path,
            format!("LAS version {major}.{minor} (semsim reads LAS 1.0 to 1.4)"),
        ));
    }
    let header_size = u64::from(u16_at(bytes, 94));
    let offset_to_points = u64::from(u32_at(bytes, 96));
    let format_id = bytes[104];
    let record_len = u64::from(u16_at(bytes, 105));
    let legacy_points = u64::from(u32_at(bytes, 107));
    // The las crate reads the whole header of the version (227, 235 or 375 bytes) whatever
    // the header size says.
    let version_header = match minor {
        0..=2 => 227,
        3 => 235,
        _ => 375,
    };
    if header_size < version_header || header_size > len {
        return Err(bad(format!(
            "header size {header_size} is not between {version_header} (LAS 1.{minor}) and the file's {len} bytes"
        )));
    }
    if offset_to_points < header_size || offset_to_points > len {
        return Err(bad(format!(
            "the point data offset {offset_to_points} lies outside the file ({len} bytes, header {header_size})"
        )));
    }
    let mut points = legacy_points;
    if minor >= 4 {
        let (Some(evlr_start), Some(large_count)) = (u64_at(bytes, 235), u64_at(bytes, 247)) else {
            return Err(bad(format!(
                "truncated: {len} bytes, a LAS 1.4 header takes 375"
            )));
        };
        if points == 0 {
            points = large_count;
        }
        let evlr_count = u64::from(u32_at(bytes, 243));
        if evlr_start > 0 && evlr_count > 0 {
            check_first_evlr(path, src, evlr_start)?;
        }
    }
    if record_len < MIN_RECORD_BYTES {
        return Err(bad(format!(
            "point record length {record_len} is shorter than any point format ({MIN_RECORD_BYTES} bytes)"
        )));
    }
    let data_bytes = len - offset_to_points;
    // The las crate's test: bit 7 of the point format marks LAZ.
    let compressed = format_id & 0x80 != 0;
    // The las crate computes offset + points * record length unchecked.
    let total = points
        .checked_mul(record_len)
        .and_then(|b| b.checked_add(offset_to_points));
    let format = format_id & 0x3f;
    let Some(&min_record) = FORMAT_RECORD_BYTES.get(usize::from(format)) else {
        return Err(InteropError::unsupported(
            path,
            format!("point data record format {format} (LAS 1.4 defines 0 to 10)"),
        ));
    };
    if (record_len as usize) < min_record {
        return Err(bad(format!(
            "point record length {record_len} is shorter than point format {format}'s {min_record} bytes"
        )));
    }
    let mut laz_vlr = None;
    if compressed {
        if total.is_none() || points > data_bytes.saturating_mul(LAZ_MAX_POINTS_PER_BYTE) {
            return Err(bad(format!(
                "the header claims {points} points, more than {LAZ_MAX_POINTS_PER_BYTE} a byte of the {data_bytes} bytes of compressed point data"
            )));
        }
        check_chunk_table(path, src, offset_to_points)?;
        laz_vlr = super::laz_check::check_laz_chunks(
            path,
            src,
            header_size,
            u32_at(bytes, 100),
            offset_to_points,
            points,
        )?;
    } else {
        match points.checked_mul(record_len) {
            Some(need) if need <= data_bytes => {}
            _ => {
                return Err(bad(format!(
                    "truncated: the header promises {points} points of {record_len} bytes, the file holds {data_bytes} bytes of point data"
                )));
            }
        }
    }
    let triple = |at: usize| {
        [
            f64_at(bytes, at),
            f64_at(bytes, at + 8),
            f64_at(bytes, at + 16),
        ]
    };
    let (max, min) = (
        [f64_at(bytes, 179), f64_at(bytes, 195), f64_at(bytes, 211)],
        [f64_at(bytes, 187), f64_at(bytes, 203), f64_at(bytes, 219)],
    );
    Ok(LasLayout {
        points,
        compressed,
        points_at: offset_to_points,
        record_len: record_len as usize,
        format,
        scale: triple(131),
        offset: triple(155),
        bounds: (min, max),
        laz_vlr,
    })
}

/// The `las` crate reads the first extended VLR whole: its length must fit in the file.
fn check_first_evlr(path: &Path, src: &impl ByteSource, start: u64) -> Result<()> {
    let len = src.len();
    let record = start.checked_add(20).and_then(|a| src.u64_at(a));
    let fits = record.is_some_and(|r| {
        start
            .checked_add(EVLR_HEADER_BYTES)
            .and_then(|a| a.checked_add(r))
            .is_some_and(|end| end <= len)
    });
    if !fits {
        return Err(InteropError::format(
            path,
            format!(
                "truncated: the extended VLR at byte {start} does not fit in the file's {len} bytes"
            ),
        ));
    }
    Ok(())
}

/// The `laz` crate allocates the chunk table by the count it finds at the table's offset (the
/// first 8 bytes of the point data, else the last 8 of the file): every chunk starts with an
/// uncompressed point, so no more chunks than that fit in the point data.
fn check_chunk_table(path: &Path, src: &impl ByteSource, points_at: u64) -> Result<()> {
    let len = src.len();
    let Some(mut table) = src.u64_at(points_at) else {
        return Ok(()); // The laz crate fails to read the offset.
    };
    if table as i64 <= points_at as i64 {
        match src.u64_at(len.saturating_sub(8)) {
            Some(t) if t as i64 > points_at as i64 => table = t,
            _ => return Ok(()), // No chunk table: the laz crate reads without one.
        }
    }
    let Some(chunks) = table.checked_add(4).and_then(|a| src.u32_at(a)) else {
        return Ok(()); // Beyond the file: the laz crate fails to read it.
    };
    let chunks = u64::from(chunks);
    let most = (len - points_at) / MIN_RECORD_BYTES + 1;
    if chunks > most {
        return Err(InteropError::format(
            path,
            format!(
                "the LAZ chunk table at byte {table} lists {chunks} chunks, more than the {} bytes of point data can hold",
                len - points_at
            ),
        ));
    }
    Ok(())
}
