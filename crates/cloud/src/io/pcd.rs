//! PCD v0.7 (PCL's Point Cloud Data format): `DATA ascii`, `binary` and `binary_compressed`.
//!
//! Reading accepts any field layout PCL writes (padding fields `_`, `COUNT > 1`, rgb, normals...)
//! and takes `x y z`, an optional `intensity`, an optional `label` (the entity id), an
//! optional `class` (a [`crate::EntityClass`] code; class `Unknown` where only `label` is
//! present, entity 0 where only `class` is) and an optional `classification` (the ASPRS
//! class of LAS, the name PDAL writes it under; independent of `label` and `class`). semsim's
//! own types are `x y z` F4 or F8, `label` U of 1, 2 or 4 bytes, `class` U1 and
//! `classification` U1; any other numeric type is converted with a note (see
//! [`crate::read_cloud_with_notes`]): a `label` value that is not an entity id (e.g. a negative
//! `TYPE I` label) reads as no entity, a `class` field of another type holding a value that
//! is no class code is skipped, and so is a `classification` field holding a value that is
//! no integer 0..=255 (the cloud then has no classification). Fields semsim does not use are
//! skipped with a note (padding `_` silently); of a field with `COUNT > 1` the first value is
//! used. The only value errors: a `class` U1 code no class has, and a non-finite point in an
//! unorganised cloud.
//!
//! `HEIGHT > 1` makes the cloud organised (`HEIGHT` rows of `WIDTH` columns; `HEIGHT 1` means
//! unorganised), and `VIEWPOINT tx ty tz qw qx qy qz` is the sensor pose. Missing returns are
//! NaN points, allowed only in organised clouds. `binary_compressed` data is LZF-compressed in
//! structure-of-arrays field order behind two little-endian `u32` sizes (compressed,
//! uncompressed), as PCL writes it. No allocation is sized by a header number beyond what the
//! file's bytes can hold, and memory that cannot be had is a [`CloudError::OutOfMemory`] error.
//! The header is parsed in `pcd/header.rs`, the data read in `pcd/ascii.rs` and
//! `pcd/binary.rs`, and written by `pcd/write.rs`.
//!
//! Writing produces `x y z` (F4), `intensity` (F4) if present, `label` (U4) + `class` (U1)
//! if labels are present, and `classification` (U1) if the cloud has an ASPRS classification.
//!
//! The format is hand-written rather than taken from the `pcd-rs` crate: we need errors that name
//! the header line or the expected and found byte counts, arbitrary PCL field layouts, and
//! allocation-free slice decoding fast enough for large scans.

use super::asprs::AsprsConv;
use super::labels::LabelConv;
use super::lzf;
use super::scalar::Scalar;
use super::text::{print_notes, read_file, shown, strip_bom, Notes};
use crate::atomic::write_atomically;
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

mod ascii;
mod binary;
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
        PcdEncoding::Ascii => ascii::read_ascii(path, &h, &w, &mut conv, body)?,
        PcdEncoding::Binary => binary::read_binary(path, &h, &w, &mut conv, body)?,
        PcdEncoding::BinaryCompressed => binary::read_compressed(path, &h, &w, &mut conv, body)?,
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
        classification: ch.classification.and_then(|c| c.finish(&mut notes)),
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
/// class field), the class codes (with a class field) and the ASPRS classification (with a
/// classification field).
struct Channels {
    points: Vec<Vec3>,
    intensity: Option<Vec<f32>>,
    labels: Option<Vec<Label>>,
    codes: Option<Vec<u8>>,
    classification: Option<AsprsConv>,
}

/// The indices (into the header's fields) of the fields we read.
struct Wanted {
    xyz: [usize; 3],
    intensity: Option<usize>,
    label: Option<usize>,
    class: Option<usize>,
    classification: Option<usize>,
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
            classification: find("classification"),
        };
        let used: Vec<usize> = xyz
            .iter()
            .copied()
            .chain(w.intensity)
            .chain(w.label)
            .chain(w.class)
            .chain(w.classification)
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

    /// The collector of the header's `classification` field, if any, with room for `cap`
    /// points (bounded by the callers by what the data can hold).
    fn asprs(&self, path: &Path, h: &Header, cap: usize) -> Result<Option<AsprsConv>> {
        match self.classification.and_then(|i| h.fields.get(i)) {
            Some(f) => AsprsConv::new(path, describe(f), f.ty, cap).map(Some),
            None => Ok(None),
        }
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

fn truncated(path: &Path, msg: String) -> CloudError {
    CloudError::Truncated {
        path: path.to_path_buf(),
        msg,
    }
}
