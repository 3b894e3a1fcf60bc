//! PCD v0.7 (PCL's Point Cloud Data format): `DATA ascii`, `binary` and `binary_compressed`.
//!
//! Reading accepts any field layout PCL writes (padding fields `_`, `COUNT > 1`, rgb, normals...)
//! and takes `x y z`, an optional `intensity`, an optional `label` (the entity id) and an
//! optional `class` (a [`crate::EntityClass`] code; class `Unknown` where only `label` is
//! present, entity 0 where only `class` is). semsim's own types are `x y z` F4 or F8, `label` U
//! of 1, 2 or 4 bytes and `class` U1; any other numeric type is converted with a note (see
//! [`crate::read_cloud_with_notes`]): a `label` value that is not an entity id (e.g. a negative
//! `TYPE I` label) reads as no entity, and a `class` field of another type holding a value that
//! is no class code is skipped. Fields semsim does not use are skipped with a note (padding `_`
//! silently); of a field with `COUNT > 1` the first value is used. The only value errors: a
//! `class` U1 code no class has, and a non-finite point in an unorganised cloud.
//!
//! `HEIGHT > 1` makes the cloud organised (`HEIGHT` rows of `WIDTH` columns; `HEIGHT 1` means
//! unorganised), and `VIEWPOINT tx ty tz qw qx qy qz` is the sensor pose. Missing returns are
//! NaN points, allowed only in organised clouds. `binary_compressed` data is LZF-compressed in
//! structure-of-arrays field order behind two little-endian `u32` sizes (compressed,
//! uncompressed), as PCL writes it. No allocation is sized by a header number beyond what the
//! file's bytes can hold, and memory that cannot be had is a [`CloudError::OutOfMemory`] error.
//!
//! Writing produces `x y z` (F4), `intensity` (F4) if present, and `label` (U4) + `class` (U1)
//! if labels are present.
//!
//! The format is hand-written rather than taken from the `pcd-rs` crate: we need errors that name
//! the header line or the expected and found byte counts, arbitrary PCL field layouts, and
//! allocation-free slice decoding fast enough for large scans.

use super::labels::LabelConv;
use super::lzf::{self, LZF_MAX_RATIO};
use super::scalar::Scalar;
use super::text::{print_notes, read_file, shown, strip_bom, Notes};
use crate::atomic::write_atomically;
use crate::cloud::{Label, Organized, PointCloud};
use crate::error::{try_filled, try_vec, CloudError, Result};
use glam::{Quat, Vec3};
use std::io::Write;
use std::path::Path;

/// PCD data encodings (the `DATA` header line).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PcdEncoding {
    /// `DATA ascii`: one point per line.
    Ascii,
    /// `DATA binary`: little-endian, one point after the other.
    Binary,
    /// `DATA binary_compressed`: LZF-compressed, field after field.
    BinaryCompressed,
}

impl PcdEncoding {
    /// The keyword on the `DATA` line.
    pub fn keyword(self) -> &'static str {
        match self {
            PcdEncoding::Ascii => "ascii",
            PcdEncoding::Binary => "binary",
            PcdEncoding::BinaryCompressed => "binary_compressed",
        }
    }
}

mod header;
mod write;
use header::{Field, Header};

/// Reads a PCD file; notes on converted or skipped fields go to standard error.
pub fn read_pcd(path: &Path) -> Result<PointCloud> {
    let (cloud, notes) = parse_pcd(path, &read_file(path)?)?;
    print_notes(&notes);
    Ok(cloud)
}

/// Reads the bytes of a PCD file (`path` is for messages), with the notes on what was
/// converted or skipped.
pub(crate) fn parse_pcd(path: &Path, bytes: &[u8]) -> Result<(PointCloud, Vec<String>)> {
    let bytes = strip_bom(bytes);
    let h = header::parse(path, bytes)?;
    let body = bytes.get(h.data_offset..).unwrap_or_default();
    let mut notes = Notes::new(path);
    let w = Wanted::find(&h, &mut notes);
    let mut conv = w.label_conv(&h);
    let ch = match h.encoding {
        PcdEncoding::Ascii => read_ascii(path, &h, &w, &mut conv, body)?,
        PcdEncoding::Binary => read_binary(path, &h, &w, &mut conv, body)?,
        PcdEncoding::BinaryCompressed => read_compressed(path, &h, &w, &mut conv, body)?,
    };
    let labels = match ch.labels {
        Some(labels) => conv.finish(path, labels, ch.codes, &mut notes)?,
        None => None,
    };
    let [tx, ty, tz, qw, qx, qy, qz] = h.viewpoint;
    let cloud = PointCloud {
        points: ch.points,
        intensity: ch.intensity,
        labels,
        classification: None,
        organized: (h.height > 1).then_some(Organized {
            rows: h.height,
            cols: h.width,
        }),
        sensor_origin: Vec3::new(tx, ty, tz),
        sensor_orientation: Quat::from_xyzw(qx, qy, qz, qw),
    };
    cloud.check_finite(path)?;
    Ok((cloud, notes.list))
}

/// Writes a PCD file atomically. An unorganised cloud must hold only finite points.
pub fn write_pcd(path: &Path, cloud: &PointCloud, encoding: PcdEncoding) -> Result<()> {
    cloud.validate()?;
    cloud.check_finite(path)?;
    let columns = write::out_columns(cloud);
    let head = write::header_text(cloud, &columns, encoding);
    let body = match encoding {
        PcdEncoding::Ascii => Vec::new(),
        PcdEncoding::Binary => write::interleave(&columns, cloud.len()),
        PcdEncoding::BinaryCompressed => write::compressed_body(path, &columns)?,
    };
    write_atomically(path, |w| {
        let io = |e| CloudError::io(path, e);
        w.write_all(head.as_bytes()).map_err(io)?;
        if encoding == PcdEncoding::Ascii {
            write::write_ascii_body(w, cloud).map_err(io)
        } else {
            w.write_all(&body).map_err(io)
        }
    })
}

/// What the data holds: points, intensities, labels with their entity ids (with a label or a
/// class field) and the class codes (with a class field).
struct Channels {
    points: Vec<Vec3>,
    intensity: Option<Vec<f32>>,
    labels: Option<Vec<Label>>,
    codes: Option<Vec<u8>>,
}

/// The indices (into the header's fields) of the fields we read.
struct Wanted {
    xyz: [usize; 3],
    intensity: Option<usize>,
    label: Option<usize>,
    class: Option<usize>,
}

impl Wanted {
    /// The fields semsim reads (`x y z` are checked to exist when the header is parsed),
    /// noting those of other types than semsim's own, with `COUNT > 1`, and those skipped.
    fn find(h: &Header, notes: &mut Notes) -> Self {
        let find = |name: &str| h.fields.iter().position(|f| f.name == name);
        let xyz = [find("x"), find("y"), find("z")].map(Option::unwrap_or_default);
        let w = Wanted {
            xyz,
            intensity: find("intensity"),
            label: find("label"),
            class: find("class"),
        };
        let used: Vec<usize> = xyz
            .iter()
            .copied()
            .chain(w.intensity)
            .chain(w.label)
            .chain(w.class)
            .collect();
        for &i in &used {
            let Some(f) = h.fields.get(i) else { continue };
            if xyz.contains(&i) && !f.ty.is_float() {
                notes.add(format_args!("{} read as metres", describe(f)));
            }
            if f.count > 1 {
                notes.add(format_args!(
                    "field {} has COUNT {}: only the first value of each point is used",
                    shown(&f.name),
                    f.count
                ));
            }
        }
        let skipped: Vec<String> = (0..h.fields.len())
            .filter(|i| !used.contains(i))
            .filter_map(|i| h.fields.get(i))
            .filter(|f| f.name != "_")
            .map(|f| shown(&f.name))
            .collect();
        if !skipped.is_empty() {
            notes.add(format_args!(
                "field(s) {} not used by semsim (skipped)",
                skipped.join(", ")
            ));
        }
        w
    }

    /// The label conversion for the header's `label` and `class` fields.
    fn label_conv(&self, h: &Header) -> LabelConv {
        let field = |i: Option<usize>| i.and_then(|i| h.fields.get(i));
        let entity =
            field(self.label).map(|f| (describe(f), f.ty.is_unsigned() && f.ty.size() <= 4));
        let class = field(self.class).map(|f| (describe(f), f.ty == Scalar::U8));
        LabelConv::new(entity, class)
    }
}

/// `field label (TYPE I, SIZE 4)`.
fn describe(f: &Field) -> String {
    format!(
        "field {} (TYPE {}, SIZE {})",
        shown(&f.name),
        f.ty.pcd_letter(),
        f.ty.size()
    )
}

fn read_binary(
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

fn read_compressed(
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
    if !conv.any() {
        return Ok(Channels {
            points,
            intensity,
            labels: None,
            codes: None,
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
    })
}

fn read_ascii(
    path: &Path,
    h: &Header,
    w: &Wanted,
    conv: &mut LabelConv,
    body: &[u8],
) -> Result<Channels> {
    let text = std::str::from_utf8(body).map_err(|e| {
        let line = h.data_line
            + 1
            + body
                .get(..e.valid_up_to())
                .unwrap_or_default()
                .iter()
                .filter(|&&b| b == b'\n')
                .count();
        CloudError::parse(path, line, "DATA ascii line is not UTF-8 text")
    })?;
    // Token index of each field's first element (the counts' sum cannot overflow: it is at
    // most the point size, checked with the header).
    let mut first = Vec::with_capacity(h.fields.len());
    let total = h.fields.iter().fold(0usize, |acc, f| {
        first.push(acc);
        acc.saturating_add(f.count)
    });
    let tok = |i: usize| first.get(i).copied().unwrap_or(0);
    // A point line takes at least two bytes per value (the value and a space or newline), so
    // no more points than that are allocated, whatever WIDTH, HEIGHT and COUNT say.
    let cap = h
        .points
        .min(body.len() / total.saturating_mul(2).max(1) + 1);
    let mut points = try_vec(path, cap, "the points")?;
    let mut intensity = if w.intensity.is_some() {
        try_vec(path, cap, "the intensities")?
    } else {
        Vec::new()
    };
    let mut labels = if conv.any() {
        try_vec(path, cap, "the labels")?
    } else {
        Vec::new()
    };
    let mut codes = if conv.has_class() {
        try_vec(path, cap, "the class codes")?
    } else {
        Vec::new()
    };
    let mut toks: Vec<&str> = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line_no = h.data_line + 1 + k;
        toks.clear();
        toks.extend(line.split_whitespace());
        if toks.is_empty() {
            continue;
        }
        if points.len() == h.points {
            return Err(CloudError::parse(
                path,
                line_no,
                format!("more data than the {} points the header promises", h.points),
            ));
        }
        if toks.len() != total {
            return Err(CloudError::parse(
                path,
                line_no,
                format!("expected {total} values, found {}", toks.len()),
            ));
        }
        let value = |field: usize| -> Result<f64> {
            let t = toks.get(tok(field)).copied().unwrap_or_default();
            h.fields
                .get(field)
                .and_then(|f| f.ty.parse(t))
                .ok_or_else(|| {
                    let name = h.fields.get(field).map_or("?", |f| f.name.as_str());
                    let msg = format!(
                        "'{}' is not a valid value of field {}",
                        shown(t),
                        shown(name)
                    );
                    CloudError::parse(path, line_no, msg)
                })
        };
        let [x, y, z] = [value(w.xyz[0])?, value(w.xyz[1])?, value(w.xyz[2])?];
        let i = points.len();
        points.push(Vec3::new(x as f32, y as f32, z as f32));
        if let Some(f) = w.intensity {
            intensity.push(value(f)? as f32);
        }
        if conv.any() {
            let entity = match w.label {
                Some(f) => conv.entity(i, value(f)?),
                None => 0,
            };
            labels.push(Label {
                entity,
                ..Label::default()
            });
        }
        if let Some(f) = w.class {
            codes.push(conv.class_code(i, value(f)?, line_no));
            conv.class_error(path)?;
        }
    }
    if points.len() < h.points {
        return Err(truncated(
            path,
            format!(
                "DATA ascii: expected {} points, found {}",
                h.points,
                points.len()
            ),
        ));
    }
    Ok(Channels {
        points,
        intensity: w.intensity.map(|_| intensity),
        labels: conv.any().then_some(labels),
        codes: conv.has_class().then_some(codes),
    })
}

fn truncated(path: &Path, msg: String) -> CloudError {
    CloudError::Truncated {
        path: path.to_path_buf(),
        msg,
    }
}
