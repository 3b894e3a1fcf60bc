//! PLY 1.0 (Stanford polygon format): `ascii`, `binary_little_endian`, `binary_big_endian`.
//!
//! Reading takes the `vertex` element: `x y z` (any scalar type; `float`, `double` and the
//! `float32`/`float64` aliases are the usual ones), an optional intensity (`intensity` or
//! `scalar_intensity`, any scalar type) and optional `label` (entity id) and `class`
//! ([`crate::EntityClass`] code). Other vertex properties, list properties included, are
//! skipped, as are the elements before `vertex`; reading stops after the vertex element
//! (faces and the like are ignored). PLY has no organised shape, so a non-finite point is an
//! error, and writing an organised cloud drops its missing returns.
//!
//! Writing produces `float x y z`, `float intensity` if present, and `uint label` +
//! `uchar class` if labels are present.
//!
//! Hand-written rather than taken from the `ply-rs-bw` crate: we want errors naming the header
//! line or the expected and found byte counts, a fixed set of properties decoded straight into
//! the cloud's arrays (no per-vertex property maps), and nothing to read after the vertices.

use super::scalar::{class_from_value, entity_from_value, Scalar};
use crate::atomic::write_atomically;
use crate::cloud::{Label, PointCloud};
use crate::error::{CloudError, Result};
use glam::Vec3;
use std::io::Write;
use std::path::Path;

/// PLY encodings (the `format` header line).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlyEncoding {
    /// `format ascii 1.0`: one element item per line.
    Ascii,
    /// `format binary_little_endian 1.0`.
    BinaryLittleEndian,
    /// `format binary_big_endian 1.0`.
    BinaryBigEndian,
}

impl PlyEncoding {
    /// The keyword on the `format` line.
    pub fn keyword(self) -> &'static str {
        match self {
            PlyEncoding::Ascii => "ascii",
            PlyEncoding::BinaryLittleEndian => "binary_little_endian",
            PlyEncoding::BinaryBigEndian => "binary_big_endian",
        }
    }
}

mod header;
use header::{Element, Kind};

/// Slots of the optional values we keep from a vertex (x y z are slots 0, 1, 2).
const INTENSITY: usize = 3;
const LABEL: usize = 4;
const CLASS: usize = 5;

/// Reads the vertices of a PLY file.
pub fn read_ply(path: &Path) -> Result<PointCloud> {
    let bytes = std::fs::read(path).map_err(|e| CloudError::io(path, e))?;
    let h = header::parse(path, &bytes)?;
    let before = h.elements.iter().take_while(|e| e.name != "vertex").count();
    let vertex = h.elements.get(before).ok_or_else(|| {
        CloudError::parse(path, h.end_line, "the header declares no vertex element")
    })?;
    let slots = slots(path, vertex)?;
    let body = bytes.get(h.data_offset..).unwrap_or_default();
    let skipped = h.elements.get(..before).unwrap_or_default();
    let mut reader = Reader::new(vertex.count, &slots);
    match h.encoding {
        PlyEncoding::Ascii => read_ascii(path, h.end_line, skipped, vertex, body, &mut reader)?,
        enc => read_binary(
            path,
            enc == PlyEncoding::BinaryBigEndian,
            skipped,
            vertex,
            body,
            &mut reader,
        )?,
    }
    let cloud = reader.finish();
    cloud.check_finite(path)?;
    Ok(cloud)
}

/// Writes a PLY file atomically (an organised cloud loses its missing returns).
pub fn write_ply(path: &Path, cloud: &PointCloud, encoding: PlyEncoding) -> Result<()> {
    let cloud = super::xyz::valid_points(path, cloud)?;
    let head = header::text(&cloud, encoding);
    write_atomically(path, |w| {
        let io = |e| CloudError::io(path, e);
        w.write_all(head.as_bytes()).map_err(io)?;
        match encoding {
            PlyEncoding::Ascii => write_ascii_body(w, &cloud),
            PlyEncoding::BinaryLittleEndian => w.write_all(&binary_body(&cloud, false)),
            PlyEncoding::BinaryBigEndian => w.write_all(&binary_body(&cloud, true)),
        }
        .map_err(io)
    })
}

/// For each vertex property, the slot its value goes to (x y z intensity label class), if kept.
fn slots(path: &Path, vertex: &Element) -> Result<Vec<Option<usize>>> {
    let find = |names: &[&str]| {
        vertex
            .props
            .iter()
            .position(|p| names.contains(&p.name.as_str()))
    };
    let mut slots = vec![None; vertex.props.len()];
    let wanted: [&[&str]; 6] = [
        &["x"],
        &["y"],
        &["z"],
        &["intensity", "scalar_intensity"],
        &["label"],
        &["class"],
    ];
    for (slot, names) in wanted.iter().enumerate() {
        let Some(p) = find(names) else {
            if slot <= 2 {
                let msg = format!("the vertex element has no property {}", names.join("/"));
                return Err(CloudError::parse(path, vertex.line, msg));
            }
            continue;
        };
        if let (Some(s), Some(prop)) = (slots.get_mut(p), vertex.props.get(p)) {
            if !matches!(prop.kind, Kind::Scalar(_)) {
                let msg = format!("vertex property {} must be a scalar, not a list", prop.name);
                return Err(CloudError::parse(path, prop.line, msg));
            }
            *s = Some(slot);
        }
    }
    Ok(slots)
}

/// Collects vertex values into the cloud's arrays.
struct Reader<'a> {
    slots: &'a [Option<usize>],
    has: [bool; 6],
    points: Vec<Vec3>,
    intensity: Vec<f32>,
    labels: Vec<Label>,
    /// The values of the vertex being read.
    cur: [f64; 6],
}

impl<'a> Reader<'a> {
    fn new(count: usize, slots: &'a [Option<usize>]) -> Self {
        let mut has = [false; 6];
        slots.iter().flatten().for_each(|&s| has[s.min(5)] = true);
        let cap = count.min(1 << 20);
        Reader {
            slots,
            has,
            points: Vec::with_capacity(cap),
            intensity: Vec::new(),
            labels: Vec::new(),
            cur: [0.0; 6],
        }
    }

    fn set(&mut self, prop: usize, v: f64) {
        if let Some(&Some(s)) = self.slots.get(prop) {
            self.cur[s.min(5)] = v;
        }
    }

    /// Stores the current vertex; the error message is for a bad label or class.
    fn push(&mut self) -> std::result::Result<(), String> {
        let [x, y, z, i, l, c] = self.cur;
        self.points.push(Vec3::new(x as f32, y as f32, z as f32));
        if self.has[INTENSITY] {
            self.intensity.push(i as f32);
        }
        if self.has[LABEL] || self.has[CLASS] {
            let label = Label {
                entity: entity_from_value(l)?,
                class: class_from_value(c)?,
            };
            self.labels.push(label);
        }
        self.cur = [0.0; 6];
        Ok(())
    }

    fn finish(self) -> PointCloud {
        let mut cloud = PointCloud::from_points(self.points);
        cloud.intensity = self.has[INTENSITY].then_some(self.intensity);
        cloud.labels = (self.has[LABEL] || self.has[CLASS]).then_some(self.labels);
        cloud
    }
}

fn read_binary(
    path: &Path,
    big: bool,
    skipped: &[Element],
    vertex: &Element,
    body: &[u8],
    r: &mut Reader,
) -> Result<()> {
    let mut pos = 0usize;
    for e in skipped {
        if e.props.iter().all(|p| matches!(p.kind, Kind::Scalar(_))) {
            // Fixed size: skip all items at once (also bounds a huge count of empty items).
            let size: usize = e.props.iter().map(|p| p.kind.min_size()).sum();
            pos = pos.saturating_add(e.count.saturating_mul(size));
            if pos > body.len() {
                let msg = format!(
                    "element {} ({} items) runs past the end of the file",
                    e.name, e.count
                );
                return Err(CloudError::Truncated {
                    path: path.to_path_buf(),
                    msg,
                });
            }
        } else {
            for _ in 0..e.count {
                pos = walk(path, e, body, pos, big, &mut |_, _| {})?;
            }
        }
    }
    let min = vertex
        .props
        .iter()
        .map(|p| p.kind.min_size())
        .sum::<usize>();
    let need = vertex.count.saturating_mul(min);
    let found = body.len().saturating_sub(pos);
    if need > found {
        let msg = format!(
            "{} vertices of at least {min} bytes need {need} bytes, found {found}",
            vertex.count
        );
        return Err(CloudError::Truncated {
            path: path.to_path_buf(),
            msg,
        });
    }
    for i in 0..vertex.count {
        pos = walk(path, vertex, body, pos, big, &mut |p, v| r.set(p, v))?;
        r.push()
            .map_err(|m| CloudError::parse(path, 0, format!("vertex {i}: {m}")))?;
    }
    Ok(())
}

/// Reads one binary item of `e` at `pos`, handing each scalar property's value to `f`;
/// returns the position after it.
fn walk(
    path: &Path,
    e: &Element,
    body: &[u8],
    mut pos: usize,
    big: bool,
    f: &mut dyn FnMut(usize, f64),
) -> Result<usize> {
    let short = |pos: usize| {
        CloudError::Truncated {
        path: path.to_path_buf(),
        msg: format!("element {} ends past the end of the file ({} bytes of data, needed more at byte {pos})", e.name, body.len()),
    }
    };
    for (k, p) in e.props.iter().enumerate() {
        let at = body.get(pos..).unwrap_or_default();
        match p.kind {
            Kind::Scalar(t) => {
                f(k, t.decode(at, big).ok_or_else(|| short(pos))?);
                pos += t.size();
            }
            Kind::List { count, item } => {
                let n = count.decode(at, big).ok_or_else(|| short(pos))?;
                let bytes = (n.max(0.0) as usize).saturating_mul(item.size());
                pos = pos.saturating_add(count.size()).saturating_add(bytes);
                if pos > body.len() {
                    return Err(short(pos));
                }
            }
        }
    }
    Ok(pos)
}

fn read_ascii(
    path: &Path,
    end_line: usize,
    skipped: &[Element],
    vertex: &Element,
    body: &[u8],
    r: &mut Reader,
) -> Result<()> {
    let text = String::from_utf8_lossy(body);
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(k, l)| (end_line + 1 + k, l))
        .filter(|(_, l)| !l.trim().is_empty());
    let to_skip: usize = skipped.iter().map(|e| e.count).sum();
    for _ in 0..to_skip {
        if lines.next().is_none() {
            let msg = format!(
                "the file ends in the elements before the {} vertices",
                vertex.count
            );
            return Err(CloudError::Truncated {
                path: path.to_path_buf(),
                msg,
            });
        }
    }
    for i in 0..vertex.count {
        let Some((line_no, line)) = lines.next() else {
            let msg = format!("expected {} vertices, found {i}", vertex.count);
            return Err(CloudError::Truncated {
                path: path.to_path_buf(),
                msg,
            });
        };
        let mut toks = line.split_whitespace();
        for (k, p) in vertex.props.iter().enumerate() {
            let mut next = |t: Scalar| {
                let tok = toks.next().unwrap_or_default();
                t.parse(tok).ok_or_else(|| {
                    let what = if tok.is_empty() {
                        "missing".to_string()
                    } else {
                        format!("'{tok}' is not a valid")
                    };
                    CloudError::parse(
                        path,
                        line_no,
                        format!("{what} value of vertex property {}", p.name),
                    )
                })
            };
            match p.kind {
                Kind::Scalar(t) => {
                    let v = next(t)?;
                    r.set(k, v);
                }
                Kind::List { count, item } => {
                    let n = next(count)?;
                    for _ in 0..n.max(0.0) as usize {
                        next(item)?;
                    }
                }
            }
        }
        r.push()
            .map_err(|m| CloudError::parse(path, line_no, format!("vertex {i}: {m}")))?;
    }
    Ok(())
}

fn write_ascii_body(w: &mut impl Write, cloud: &PointCloud) -> std::io::Result<()> {
    for (i, p) in cloud.points.iter().enumerate() {
        write!(w, "{} {} {}", p.x, p.y, p.z)?;
        if let Some(v) = cloud.intensity.as_ref().and_then(|v| v.get(i)) {
            write!(w, " {v}")?;
        }
        if let Some(l) = cloud.labels.as_ref().and_then(|v| v.get(i)) {
            write!(w, " {} {}", l.entity, l.class.code())?;
        }
        writeln!(w)?;
    }
    Ok(())
}

fn binary_body(cloud: &PointCloud, big: bool) -> Vec<u8> {
    let f = |v: f32| {
        if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    let mut out = Vec::with_capacity(cloud.len() * 21);
    for (i, p) in cloud.points.iter().enumerate() {
        [p.x, p.y, p.z]
            .iter()
            .for_each(|&v| out.extend_from_slice(&f(v)));
        if let Some(&v) = cloud.intensity.as_ref().and_then(|v| v.get(i)) {
            out.extend_from_slice(&f(v));
        }
        if let Some(l) = cloud.labels.as_ref().and_then(|v| v.get(i)) {
            let e = if big {
                l.entity.to_be_bytes()
            } else {
                l.entity.to_le_bytes()
            };
            out.extend_from_slice(&e);
            out.push(l.class.code());
        }
    }
    out
}
