//! Checks of a LAZ file's chunks before the `laz` crate decompresses them.
//!
//! Two things in the `laz` crate (0.9) trust the file: a LAS 1.4 (layered) chunk's layer sizes
//! size a buffer each before anything is read (a flipped byte asked for 4 GiB: found by the
//! corruption sweep of `tests/scans_bad_input.rs`), and with variable-size chunks the decoder
//! indexes the chunk table by chunk number without a bound (a header promising more points
//! than the table holds panics). So, before the `las` crate reads the file:
//! - with variable-size chunks, the chunk table must hold at least the header's point count;
//! - in a layered file, every chunk the decoder will reach must have its layers within the
//!   file. A layered chunk is the first point of each item uncompressed, a `u32` point count,
//!   a `u32` size per layer (9 for Point14, 1 for RGB14, 2 for RGBNIR14, 1 for WavePacket14,
//!   one per byte for Byte14), then the layers.
//!
//! The LASzip VLR (user `laszip encoded`, record 22204): compressor (u16: 2 point-wise
//! chunked, 3 layered chunked), coder (u16), version (4 bytes), options (u32), chunk size (u32,
//! `u32::MAX` for variable), two i64, the item count (u16) and per item its type, size and
//! version (u16 each).

use super::source::ByteSource;
use crate::error::{InteropError, Result};
use std::io::{Seek, SeekFrom};
use std::path::Path;

/// A VLR's header: reserved, user id, record id, length, description.
const VLR_HEADER: usize = 54;
/// The compressor codes that use chunks.
const POINTWISE_CHUNKED: u16 = 2;
const LAYERED_CHUNKED: u16 = 3;
const VARIABLE_CHUNK_SIZE: u32 = u32::MAX;

fn u16_at(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_le_bytes(
        b.get(at..at.checked_add(2)?)?.try_into().ok()?,
    ))
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(
        b.get(at..at.checked_add(4)?)?.try_into().ok()?,
    ))
}

/// The data of the LASzip VLR among the `count` VLRs from `at`.
fn laszip_vlr(bytes: &[u8], mut at: usize, count: u32) -> Option<&[u8]> {
    for _ in 0..count {
        let user = bytes.get(at + 2..at + 18)?;
        let record = u16_at(bytes, at + 18)?;
        let len = usize::from(u16_at(bytes, at + 20)?);
        let data = bytes.get(at + VLR_HEADER..at + VLR_HEADER + len)?;
        if user.starts_with(b"laszip encoded") && record == 22204 {
            return Some(data);
        }
        at += VLR_HEADER + len;
    }
    None
}

/// Checks the chunks of the LAZ file in `src` (see the module docs) and returns the LASzip
/// VLR's data. Where the file's structure is too broken to follow, returns what it found and
/// leaves the error to the `laz` crate.
pub(super) fn check_laz_chunks(
    path: &Path,
    src: &impl ByteSource,
    header_size: u64,
    vlr_count: u32,
    points_at: u64,
    points: u64,
) -> Result<Option<Vec<u8>>> {
    // The VLRs lie between the header and the point data (within the file: checked).
    let Some(vlrs) = src.bytes_at(header_size, points_at.saturating_sub(header_size) as usize)
    else {
        return Ok(None);
    };
    let Some(vlr) = laszip_vlr(&vlrs, 0, vlr_count) else {
        return Ok(None);
    };
    let found = Ok(Some(vlr.to_vec()));
    let (Some(compressor), Some(chunk_size), Some(item_count)) =
        (u16_at(vlr, 0), u32_at(vlr, 12), u16_at(vlr, 32))
    else {
        return found;
    };
    let items: Option<Vec<(u16, u16)>> = (0..usize::from(item_count))
        .map(|i| Some((u16_at(vlr, 34 + 6 * i)?, u16_at(vlr, 36 + 6 * i)?)))
        .collect();
    let Some(items) = items else {
        return found;
    };
    let bad = |msg: String| Err(InteropError::format(path, msg));
    let variable = chunk_size == VARIABLE_CHUNK_SIZE;
    let mut table = None;
    if compressor == POINTWISE_CHUNKED || compressor == LAYERED_CHUNKED {
        if let (Ok(laz_vlr), Ok(mut source)) = (laz::LazVlr::from_buffer(vlr), src.reader()) {
            if source.seek(SeekFrom::Start(points_at)).is_ok() {
                table = laz::laszip::ChunkTable::read_from(source, &laz_vlr)
                    .ok()
                    .map(|t| t.as_ref().to_vec());
            }
        }
    }
    if let (true, Some(entries)) = (variable, &table) {
        let listed = entries
            .iter()
            .fold(0u64, |sum, e| sum.saturating_add(e.point_count));
        if listed < points {
            return bad(format!(
                "the LAZ chunk table lists {listed} points, the header {points}"
            ));
        }
    }
    if compressor != LAYERED_CHUNKED {
        return found;
    }
    let mut layers = 0usize;
    for &(item_type, size) in &items {
        layers += match item_type {
            10 => 9,                 // Point14
            11 | 13 => 1,            // RGB14, WavePacket14
            12 => 2,                 // RGBNIR14
            14 => usize::from(size), // Byte14
            _ => return found,       // not layered: the laz crate refuses it
        };
    }
    let first_point: u64 = items.iter().map(|&(_, size)| u64::from(size)).sum();
    let len = src.len();
    let mut at = points_at + 8;
    let mut left = points;
    let mut chunk = 0usize;
    while left > 0 {
        let sizes_at = at + first_point + 4;
        let layers_at = sizes_at + 4 * layers as u64;
        let (Some(count), Some(sizes)) = (
            src.u32_at(at + first_point),
            src.bytes_at(sizes_at, 4 * layers),
        ) else {
            break; // The decoder stops at the end of the file.
        };
        let total = sizes
            .chunks_exact(4)
            .map(|s| u64::from(u32::from_le_bytes([s[0], s[1], s[2], s[3]])))
            .sum::<u64>();
        let remain = len - layers_at;
        if total > remain {
            return bad(format!(
                "LAZ chunk {chunk} at byte {at}: its layers claim {total} bytes, {remain} remain"
            ));
        }
        let chunk_points = match (variable, &table) {
            (true, Some(entries)) => entries.get(chunk).map_or(0, |e| e.point_count),
            (true, None) => u64::from(count),
            (false, _) => u64::from(chunk_size),
        };
        if chunk_points == 0 {
            break;
        }
        left = left.saturating_sub(chunk_points);
        at = layers_at + total;
        chunk += 1;
    }
    found
}
