//! PCD v0.7 (PCL's Point Cloud Data format): `DATA ascii`, `binary` and `binary_compressed`.
//!
//! Reading accepts any field layout PCL writes (padding fields `_`, `COUNT > 1`, rgb, normals...)
//! and takes `x y z` (F4 or F8), an optional `intensity` (any numeric type), an optional `label`
//! (unsigned, the entity id) and an optional `class` (U1, a [`crate::EntityClass`] code; class
//! `Unknown` where only `label` is present, entity 0 where only `class` is). `HEIGHT > 1` makes
//! the cloud organised (`HEIGHT` rows of `WIDTH` columns; `HEIGHT 1` means unorganised), and
//! `VIEWPOINT tx ty tz qw qx qy qz` is the sensor pose. Missing returns are NaN points, allowed
//! only in organised clouds. `binary_compressed` data is LZF-compressed in structure-of-arrays
//! field order behind two little-endian `u32` sizes (compressed, uncompressed), as PCL writes it.
//!
//! Writing produces `x y z` (F4), `intensity` (F4) if present, and `label` (U4) + `class` (U1)
//! if labels are present.
//!
//! The format is hand-written rather than taken from the `pcd-rs` crate: we need errors that name
//! the header line or the expected and found byte counts, arbitrary PCL field layouts, and
//! allocation-free slice decoding fast enough for large scans.

use super::lzf;
use super::scalar::{class_from_value, entity_from_value, Scalar};
use crate::atomic::write_atomically;
use crate::class::EntityClass;
use crate::cloud::{Label, Organized, PointCloud};
use crate::error::{CloudError, Result};
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

/// Largest expansion of LZF data: a 3-byte back-reference yields at most 264 bytes.
const LZF_MAX_RATIO: usize = 88;

/// Reads a PCD file.
pub fn read_pcd(path: &Path) -> Result<PointCloud> {
    let bytes = std::fs::read(path).map_err(|e| CloudError::io(path, e))?;
    let h = header::parse(path, &bytes)?;
    let body = bytes.get(h.data_offset..).unwrap_or_default();
    let w = Wanted::find(path, &h)?;
    let (points, intensity, labels) = match h.encoding {
        PcdEncoding::Ascii => read_ascii(path, &h, &w, body)?,
        PcdEncoding::Binary => read_binary(path, &h, &w, body)?,
        PcdEncoding::BinaryCompressed => read_compressed(path, &h, &w, body)?,
    };
    let [tx, ty, tz, qw, qx, qy, qz] = h.viewpoint;
    let cloud = PointCloud {
        points,
        intensity,
        labels,
        organized: (h.height > 1).then_some(Organized {
            rows: h.height,
            cols: h.width,
        }),
        sensor_origin: Vec3::new(tx, ty, tz),
        sensor_orientation: Quat::from_xyzw(qx, qy, qz, qw),
    };
    cloud.check_finite(path)?;
    Ok(cloud)
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

type Channels = (Vec<Vec3>, Option<Vec<f32>>, Option<Vec<Label>>);

/// The indices (into the header's fields) of the fields we read.
struct Wanted {
    xyz: [usize; 3],
    intensity: Option<usize>,
    label: Option<usize>,
    class: Option<usize>,
}

impl Wanted {
    fn find(path: &Path, h: &Header) -> Result<Self> {
        let find = |name: &str| h.fields.iter().position(|f| f.name == name);
        let type_err = |name: &str, want: &str| {
            CloudError::parse(path, h.type_line, format!("field {name} must have {want}"))
        };
        let mut xyz = [0; 3];
        for (slot, name) in xyz.iter_mut().zip(["x", "y", "z"]) {
            *slot = find(name).ok_or_else(|| {
                CloudError::parse(
                    path,
                    h.fields_line,
                    format!("no field {name} (FIELDS must include x y z)"),
                )
            })?;
            if !h.fields.get(*slot).is_some_and(|f| f.ty.is_float()) {
                return Err(type_err(name, "TYPE F and SIZE 4 or 8"));
            }
        }
        let label = find("label");
        let entity_type = |f: &Field| f.ty.is_unsigned() && f.ty.size() <= 4;
        if label.is_some_and(|i| !h.fields.get(i).is_some_and(entity_type)) {
            return Err(type_err("label", "TYPE U and SIZE 1, 2 or 4"));
        }
        let class = find("class");
        if class.is_some_and(|i| !h.fields.get(i).is_some_and(|f| f.ty == Scalar::U8)) {
            return Err(type_err("class", "TYPE U and SIZE 1"));
        }
        Ok(Wanted {
            xyz,
            intensity: find("intensity"),
            label,
            class,
        })
    }
}

fn read_binary(path: &Path, h: &Header, w: &Wanted, body: &[u8]) -> Result<Channels> {
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
    decode_binary(path, h, w, body, |f| (f.offset, h.point_size))
}

fn read_compressed(path: &Path, h: &Header, w: &Wanted, body: &[u8]) -> Result<Channels> {
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
    if need > compressed.saturating_mul(LZF_MAX_RATIO) + LZF_MAX_RATIO {
        return Err(truncated(
            path,
            format!("DATA binary_compressed: {compressed} compressed bytes cannot expand to the {need} bytes promised"),
        ));
    }
    let raw = lzf::decompress(data, need).map_err(|msg| {
        CloudError::parse(
            path,
            0,
            format!("corrupt binary_compressed (LZF) data: {msg}"),
        )
    })?;
    decode_binary(path, h, w, &raw, |f| {
        (h.points * f.offset, f.ty.size() * f.count)
    })
}

/// Decodes the wanted fields from binary data in which field `f` of point `i` starts at byte
/// `start + i * stride`, with `(start, stride) = layout(f)`.
fn decode_binary(
    path: &Path,
    h: &Header,
    w: &Wanted,
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
    let mut points = vec![Vec3::ZERO; n];
    for (axis, &index) in w.xyz.iter().enumerate() {
        field(index)
            .and_then(|(ty, src, stride)| {
                ty.decode_into(src, stride, &mut points, |p, v| p[axis] = v as f32)
            })
            .ok_or_else(|| short(index))?;
    }
    let column = |index: usize| {
        let (ty, src, stride) = field(index).ok_or_else(|| short(index))?;
        ty.decode_column(src, stride, n, |v| v as f32)
            .ok_or_else(|| short(index))
    };
    let intensity = w.intensity.map(column).transpose()?;
    if w.label.is_none() && w.class.is_none() {
        return Ok((points, intensity, None));
    }
    let mut labels = vec![Label::default(); n];
    // `label` is U of at most 4 bytes and `class` is U1 (checked with the header): exact casts.
    if let Some(index) = w.label {
        field(index)
            .and_then(|(ty, src, stride)| {
                ty.decode_into(src, stride, &mut labels, |l, v| l.entity = v as u32)
            })
            .ok_or_else(|| short(index))?;
    }
    if let Some(index) = w.class {
        let (ty, src, stride) = field(index).ok_or_else(|| short(index))?;
        let codes = ty
            .decode_column(src, stride, n, |v| v as u8)
            .ok_or_else(|| short(index))?;
        for (i, (l, &c)) in labels.iter_mut().zip(&codes).enumerate() {
            l.class = EntityClass::from_code(c).ok_or_else(|| {
                let msg = format!("point {i}: unknown surface class code {c}");
                CloudError::parse(path, 0, msg)
            })?;
        }
    }
    Ok((points, intensity, Some(labels)))
}

fn make_label(entity: f64, class: f64) -> std::result::Result<Label, String> {
    Ok(Label {
        entity: entity_from_value(entity)?,
        class: class_from_value(class)?,
    })
}

fn read_ascii(path: &Path, h: &Header, w: &Wanted, body: &[u8]) -> Result<Channels> {
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
    // Token index of each field's first element.
    let mut first = Vec::with_capacity(h.fields.len());
    let total = h.fields.iter().fold(0, |acc, f| {
        first.push(acc);
        acc + f.count
    });
    let tok = |i: usize| first.get(i).copied().unwrap_or(0);
    let cap = h.points.min(body.len() / 2 + 1);
    let (mut points, mut intensity, mut labels) = (Vec::with_capacity(cap), Vec::new(), Vec::new());
    let mut toks: Vec<&str> = Vec::with_capacity(total);
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
                    let msg = format!("'{t}' is not a valid value of field {name}");
                    CloudError::parse(path, line_no, msg)
                })
        };
        let [x, y, z] = [value(w.xyz[0])?, value(w.xyz[1])?, value(w.xyz[2])?];
        points.push(Vec3::new(x as f32, y as f32, z as f32));
        if let Some(i) = w.intensity {
            intensity.push(value(i)? as f32);
        }
        if w.label.is_some() || w.class.is_some() {
            let entity = w.label.map(value).transpose()?.unwrap_or(0.0);
            let class = w.class.map(value).transpose()?.unwrap_or(0.0);
            let label = make_label(entity, class).map_err(|msg| {
                CloudError::parse(path, line_no, format!("point {}: {msg}", points.len() - 1))
            })?;
            labels.push(label);
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
    let has_labels = w.label.is_some() || w.class.is_some();
    Ok((
        points,
        w.intensity.map(|_| intensity),
        has_labels.then_some(labels),
    ))
}

fn truncated(path: &Path, msg: String) -> CloudError {
    CloudError::Truncated {
        path: path.to_path_buf(),
        msg,
    }
}
