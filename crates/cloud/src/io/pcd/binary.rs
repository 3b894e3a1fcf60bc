//! Reading `DATA binary` (point after point) and `DATA binary_compressed` (LZF, field after
//! field): both decoded column by column, straight from the bytes.

use super::header::{Field, Header};
use super::{truncated, Channels, Wanted};
use crate::cloud::Label;
use crate::error::{try_filled, try_vec, CloudError, Result};
use crate::io::labels::LabelConv;
use crate::io::lzf::{self, LZF_MAX_RATIO};
use glam::Vec3;
use std::path::Path;

pub(super) fn read_binary(
    path: &Path,
    h: &Header,
    w: &Wanted,
    conv: &mut LabelConv,
    body: &[u8],
) -> Result<Channels> {
    let need = h.points * h.point_size; // checked when the header was parsed
    if body.len() < need {
        return Err(truncated(
            path,
            format!(
                "DATA binary: {} points of {} bytes need {need} bytes, found {}",
                h.points,
                h.point_size,
                body.len()
            ),
        ));
    }
    decode_binary(path, h, w, conv, body, |f| (f.offset, h.point_size))
}

pub(super) fn read_compressed(
    path: &Path,
    h: &Header,
    w: &Wanted,
    conv: &mut LabelConv,
    body: &[u8],
) -> Result<Channels> {
    let size = |k: usize| {
        body.get(k..k + 4)
            .and_then(|b| b.try_into().ok())
            .map(u32::from_le_bytes)
    };
    let (Some(compressed), Some(uncompressed)) = (size(0), size(4)) else {
        return Err(truncated(
            path,
            format!(
                "DATA binary_compressed: expected an 8-byte size prefix, found {} bytes",
                body.len()
            ),
        ));
    };
    let (compressed, uncompressed) = (compressed as usize, uncompressed as usize);
    let need = h.points * h.point_size;
    if uncompressed != need {
        return Err(CloudError::parse(
            path,
            h.data_line,
            format!(
                "binary_compressed: uncompressed size {uncompressed} bytes, but {} points of {} bytes need {need}",
                h.points, h.point_size
            ),
        ));
    }
    let found = body.len() - 8;
    let Some(data) = body.get(8..8 + compressed) else {
        return Err(truncated(
            path,
            format!("DATA binary_compressed: expected {compressed} bytes of compressed data, found {found}"),
        ));
    };
    if need > compressed.saturating_mul(LZF_MAX_RATIO) {
        return Err(truncated(
            path,
            format!("DATA binary_compressed: {compressed} compressed bytes cannot expand to the {need} bytes promised (LZF expands at most {LZF_MAX_RATIO}-fold)"),
        ));
    }
    let mut raw = try_vec(path, need, "the decompressed binary_compressed data")?;
    lzf::decompress_into(data, need, &mut raw).map_err(|msg| {
        CloudError::parse(
            path,
            0,
            format!("corrupt binary_compressed (LZF) data: {msg}"),
        )
    })?;
    decode_binary(path, h, w, conv, &raw, |f| {
        (h.points * f.offset, f.ty.size() * f.count)
    })
}

/// Decodes the wanted fields from binary data in which field `f` of point `i` starts at byte
/// `start + i * stride`, with `(start, stride) = layout(f)`. The data holds all points (checked
/// by the callers), so every allocation here is at most a few times the data's size.
fn decode_binary(
    path: &Path,
    h: &Header,
    w: &Wanted,
    conv: &mut LabelConv,
    data: &[u8],
    layout: impl Fn(&Field) -> (usize, usize),
) -> Result<Channels> {
    let n = h.points;
    let field = |index: usize| {
        let f = h.fields.get(index)?;
        let (start, stride) = layout(f);
        Some((f.ty, data.get(start..).unwrap_or_default(), stride))
    };
    let short = |index: usize| truncated(path, format!("field {index} does not fit the data"));
    let mut points = try_filled(path, n, Vec3::ZERO, "the points")?;
    for (axis, &index) in w.xyz.iter().enumerate() {
        field(index)
            .and_then(|(ty, src, stride)| {
                ty.decode_into(src, stride, &mut points, |p, v| p[axis] = v as f32)
            })
            .ok_or_else(|| short(index))?;
    }
    let intensity = match w.intensity {
        Some(index) => {
            let mut v = try_filled(path, n, 0f32, "the intensities")?;
            field(index)
                .and_then(|(ty, src, stride)| {
                    ty.decode_into(src, stride, &mut v, |o, x| *o = x as f32)
                })
                .ok_or_else(|| short(index))?;
            Some(v)
        }
        None => None,
    };
    let mut classification = w.asprs(path, h, n)?;
    if let (Some(c), Some(index)) = (&mut classification, w.classification) {
        field(index)
            .and_then(|(ty, src, stride)| c.decode(ty, src, stride, n))
            .ok_or_else(|| short(index))?;
    }
    if !conv.any() {
        return Ok(Channels {
            points,
            intensity,
            labels: None,
            codes: None,
            classification,
        });
    }
    let mut labels = try_filled(path, n, Label::default(), "the labels")?;
    if let Some(index) = w.label {
        let mut i = 0;
        field(index)
            .and_then(|(ty, src, stride)| {
                ty.decode_into(src, stride, &mut labels, |l, v| {
                    l.entity = conv.entity(i, v);
                    i += 1;
                })
            })
            .ok_or_else(|| short(index))?;
    }
    let codes = match w.class {
        Some(index) => {
            let mut codes = try_filled(path, n, 0u8, "the class codes")?;
            let mut i = 0;
            field(index)
                .and_then(|(ty, src, stride)| {
                    ty.decode_into(src, stride, &mut codes, |c, v| {
                        *c = conv.class_code(i, v, 0);
                        i += 1;
                    })
                })
                .ok_or_else(|| short(index))?;
            Some(codes)
        }
        None => None,
    };
    Ok(Channels {
        points,
        intensity,
        labels: Some(labels),
        codes,
        classification,
    })
}
