//! Writing PCD: the header text and the data in each encoding. The fields, in order: `x y z`
//! (F4), `intensity` (F4), `label` (U4) + `class` (U1), `classification` (U1), each written
//! only where the cloud has that channel (`x y z` always).

use super::{lzf, PcdEncoding};
use crate::cloud::PointCloud;
use crate::error::{CloudError, Result};
use std::fmt::Write as _;
use std::io::Write;
use std::path::Path;

/// One output field: name, PCD size, PCD type, and its little-endian bytes for all points.
pub(super) struct OutColumn {
    name: &'static str,
    size: usize,
    ty: char,
    bytes: Vec<u8>,
}

pub(super) fn out_columns(cloud: &PointCloud) -> Vec<OutColumn> {
    fn col<T: Copy, const N: usize>(
        name: &'static str,
        ty: char,
        v: &[T],
        f: impl Fn(T) -> [u8; N],
    ) -> OutColumn {
        OutColumn {
            name,
            size: N,
            ty,
            bytes: v.iter().flat_map(|&x| f(x)).collect(),
        }
    }
    let p = &cloud.points;
    let mut out = vec![
        col("x", 'F', p, |p| p.x.to_le_bytes()),
        col("y", 'F', p, |p| p.y.to_le_bytes()),
        col("z", 'F', p, |p| p.z.to_le_bytes()),
    ];
    if let Some(i) = &cloud.intensity {
        out.push(col("intensity", 'F', i, f32::to_le_bytes));
    }
    if let Some(l) = &cloud.labels {
        out.push(col("label", 'U', l, |l| l.entity.to_le_bytes()));
        out.push(col("class", 'U', l, |l| [l.class.code()]));
    }
    if let Some(c) = &cloud.classification {
        out.push(col("classification", 'U', c, |c| [c]));
    }
    out
}

/// Array-of-structures order: point after point.
pub(super) fn interleave(columns: &[OutColumn], n: usize) -> Vec<u8> {
    let point_size: usize = columns.iter().map(|c| c.size).sum();
    let mut out = Vec::with_capacity(n * point_size);
    for i in 0..n {
        for c in columns {
            out.extend_from_slice(
                c.bytes
                    .get(i * c.size..(i + 1) * c.size)
                    .unwrap_or_default(),
            );
        }
    }
    out
}

/// Structure-of-arrays order, LZF-compressed, behind the two sizes.
pub(super) fn compressed_body(path: &Path, columns: &[OutColumn]) -> Result<Vec<u8>> {
    let raw: Vec<u8> = columns
        .iter()
        .flat_map(|c| c.bytes.iter().copied())
        .collect();
    let packed = lzf::compress(&raw);
    let too_big = |what: &str, len: usize| CloudError::Unsupported {
        path: path.to_path_buf(),
        msg: format!(
            "binary_compressed {what} size {len} bytes does not fit the 32-bit size field"
        ),
    };
    let c = u32::try_from(packed.len()).map_err(|_| too_big("compressed", packed.len()))?;
    let u = u32::try_from(raw.len()).map_err(|_| too_big("uncompressed", raw.len()))?;
    let mut out = Vec::with_capacity(packed.len() + 8);
    out.extend_from_slice(&c.to_le_bytes());
    out.extend_from_slice(&u.to_le_bytes());
    out.extend_from_slice(&packed);
    Ok(out)
}

/// A float as PCL writes it in text (`nan` for NaN), with the shortest exact decimal.
struct Num(f32);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.0.is_nan() {
            f.write_str("nan")
        } else {
            write!(f, "{}", self.0)
        }
    }
}

pub(super) fn write_ascii_body(w: &mut impl Write, cloud: &PointCloud) -> std::io::Result<()> {
    for (i, p) in cloud.points.iter().enumerate() {
        write!(w, "{} {} {}", Num(p.x), Num(p.y), Num(p.z))?;
        if let Some(v) = cloud.intensity.as_ref().and_then(|v| v.get(i)) {
            write!(w, " {}", Num(*v))?;
        }
        if let Some(l) = cloud.labels.as_ref().and_then(|v| v.get(i)) {
            write!(w, " {} {}", l.entity, l.class.code())?;
        }
        if let Some(c) = cloud.classification.as_ref().and_then(|v| v.get(i)) {
            write!(w, " {c}")?;
        }
        writeln!(w)?;
    }
    Ok(())
}

/// The header text for a cloud written with the given columns and encoding.
pub(super) fn header_text(
    cloud: &PointCloud,
    columns: &[OutColumn],
    encoding: PcdEncoding,
) -> String {
    let (rows, cols) = cloud
        .organized
        .map_or((1, cloud.len()), |o| (o.rows, o.cols));
    let join =
        |f: &dyn Fn(&OutColumn) -> String| columns.iter().map(f).collect::<Vec<_>>().join(" ");
    let (o, q) = (cloud.sensor_origin, cloud.sensor_orientation);
    let mut s = String::from(
        "# .PCD v0.7 - Point Cloud Data file format (written by semsim)\nVERSION 0.7\n",
    );
    let _ = writeln!(s, "FIELDS {}", join(&|c| c.name.to_string()));
    let _ = writeln!(s, "SIZE {}", join(&|c| c.size.to_string()));
    let _ = writeln!(s, "TYPE {}", join(&|c| c.ty.to_string()));
    let _ = writeln!(s, "COUNT {}", join(&|_| "1".to_string()));
    let _ = writeln!(s, "WIDTH {cols}\nHEIGHT {rows}");
    let vp = [o.x, o.y, o.z, q.w, q.x, q.y, q.z]
        .map(|v| Num(v).to_string())
        .join(" ");
    let _ = writeln!(
        s,
        "VIEWPOINT {vp}\nPOINTS {}\nDATA {}",
        cloud.len(),
        encoding.keyword()
    );
    s
}
