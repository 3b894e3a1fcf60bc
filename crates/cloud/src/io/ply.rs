//! PLY 1.0 (Stanford polygon format): `ascii`, `binary_little_endian`, `binary_big_endian`.
//!
//! Reading takes the `vertex` element: `x y z` (any scalar type; `float`, `double` and the
//! `float32`/`float64` aliases are the usual ones), an optional intensity (`intensity` or
//! `scalar_intensity`, any scalar type), optional `label` (entity id) and `class`
//! ([`crate::EntityClass`] code), and an optional `classification` (the ASPRS class of LAS,
//! independent of `label` and `class`). semsim's own types for these are `uchar`, `ushort` or
//! `uint` labels, `uchar` classes and `uchar` classification; other types are converted with a
//! note, as in PCD (a label value that is no entity id reads as no entity; a class property of
//! another type holding a value that is no class code is skipped, and so is a classification
//! property holding a value that is no integer 0..=255, the cloud then having no
//! classification). Other vertex properties, list properties included, and
//! the other elements are skipped with a note. The elements after `vertex` (faces and the
//! like) are not decoded, but the file must not hold more than its header declares: in ASCII
//! a non-blank line beyond the declared items is an error, in binary any byte beyond the
//! declared data but trailing whitespace. Elements after `vertex` cut short are noted, not
//! refused. PLY has no organised shape, so a non-finite point is an error, and writing an
//! organised cloud drops its missing returns. The header is parsed and written in
//! `ply/header.rs`, the data read in `ply/ascii.rs` and `ply/binary.rs`, and written by
//! `ply/write.rs`.
//!
//! Writing produces `float x y z`, `float intensity` if present, `uint label` +
//! `uchar class` if labels are present, and `uchar classification` if the cloud has an ASPRS
//! classification.
//!
//! Hand-written rather than taken from the `ply-rs-bw` crate: we want errors naming the header
//! line or the expected and found byte counts, a fixed set of properties decoded straight into
//! the cloud's arrays (no per-vertex property maps), and nothing to read after the vertices.

use super::asprs::AsprsConv;
use super::labels::LabelConv;
use super::scalar::Scalar;
use super::text::{print_notes, read_file, shown, strip_bom, Notes};
use crate::atomic::write_atomically;
use crate::cloud::{Label, PointCloud};
use crate::error::{try_vec, CloudError, Result};
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

mod ascii;
mod binary;
mod header;
mod write;
use header::{Element, Kind};

/// Slots of the optional values we keep from a vertex (x y z are slots 0, 1, 2).
const INTENSITY: usize = 3;
const LABEL: usize = 4;
const CLASS: usize = 5;
const CLASSIFICATION: usize = 6;
/// The number of slots.
const SLOTS: usize = 7;

/// Reads the vertices of a PLY file; notes on converted or skipped properties go to standard
/// error.
pub fn read_ply(path: &Path) -> Result<PointCloud> {
    let (cloud, notes) = parse_ply(path, &read_file(path)?)?;
    print_notes(&notes);
    Ok(cloud)
}

/// Reads the bytes of a PLY file (`path` is for messages), with the notes on what was
/// converted or skipped.
pub(crate) fn parse_ply(path: &Path, bytes: &[u8]) -> Result<(PointCloud, Vec<String>)> {
    let bytes = strip_bom(bytes);
    let h = header::parse(path, bytes)?;
    let before = h.elements.iter().take_while(|e| e.name != "vertex").count();
    let vertex = h.elements.get(before).ok_or_else(|| {
        CloudError::parse(path, h.end_line, "the header declares no vertex element")
    })?;
    let mut notes = Notes::new(path);
    let slots = slots(path, vertex, &mut notes)?;
    let others: Vec<String> = h
        .elements
        .iter()
        .enumerate()
        .filter(|&(k, _)| k != before)
        .map(|(_, e)| shown(&e.name))
        .collect();
    if !others.is_empty() {
        notes.add(format_args!(
            "element(s) {} not used by semsim (skipped)",
            others.join(", ")
        ));
    }
    let body = bytes.get(h.data_offset..).unwrap_or_default();
    let skipped = h.elements.get(..before).unwrap_or_default();
    let after = h.elements.get(before + 1..).unwrap_or_default();
    let binary = h.encoding != PlyEncoding::Ascii;
    let mut reader = Reader::new(path, vertex, &slots, body.len(), binary)?;
    match h.encoding {
        PlyEncoding::Ascii => ascii::read_ascii(
            path,
            h.end_line,
            skipped,
            vertex,
            after,
            body,
            &mut reader,
            &mut notes,
        )?,
        enc => binary::read_binary(
            path,
            enc == PlyEncoding::BinaryBigEndian,
            (skipped, vertex, after),
            body,
            &mut reader,
            &mut notes,
        )?,
    }
    let cloud = reader.finish(path, &mut notes)?;
    cloud.check_finite(path)?;
    Ok((cloud, notes.list))
}

/// Writes a PLY file atomically (an organised cloud loses its missing returns).
pub fn write_ply(path: &Path, cloud: &PointCloud, encoding: PlyEncoding) -> Result<()> {
    let cloud = super::xyz::valid_points(path, cloud)?;
    let head = header::text(&cloud, encoding);
    write_atomically(path, |w| {
        let io = |e| CloudError::io(path, e);
        w.write_all(head.as_bytes()).map_err(io)?;
        match encoding {
            PlyEncoding::Ascii => write::ascii_body(w, &cloud),
            PlyEncoding::BinaryLittleEndian => w.write_all(&write::binary_body(&cloud, false)),
            PlyEncoding::BinaryBigEndian => w.write_all(&write::binary_body(&cloud, true)),
        }
        .map_err(io)
    })
}

/// For each vertex property, the slot its value goes to (x y z intensity label class
/// classification), if kept; notes the properties skipped.
fn slots(path: &Path, vertex: &Element, notes: &mut Notes) -> Result<Vec<Option<usize>>> {
    let find = |names: &[&str]| {
        vertex
            .props
            .iter()
            .position(|p| names.contains(&p.name.as_str()))
    };
    let mut slots = vec![None; vertex.props.len()];
    let wanted: [&[&str]; SLOTS] = [
        &["x"],
        &["y"],
        &["z"],
        &["intensity", "scalar_intensity"],
        &["label"],
        &["class"],
        &["classification"],
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
                if slot <= 2 {
                    let msg = format!(
                        "vertex property {} must be a scalar, not a list",
                        shown(&prop.name)
                    );
                    return Err(CloudError::parse(path, prop.line, msg));
                }
                continue; // skipped with the others below
            }
            *s = Some(slot);
        }
    }
    let skipped: Vec<String> = vertex
        .props
        .iter()
        .zip(&slots)
        .filter(|(_, s)| s.is_none())
        .map(|(p, _)| shown(&p.name))
        .collect();
    if !skipped.is_empty() {
        notes.add(format_args!(
            "vertex property(ies) {} not used by semsim (skipped)",
            skipped.join(", ")
        ));
    }
    Ok(slots)
}

/// Collects vertex values into the cloud's arrays.
struct Reader<'a> {
    slots: &'a [Option<usize>],
    has: [bool; SLOTS],
    points: Vec<Vec3>,
    intensity: Vec<f32>,
    labels: Vec<Label>,
    codes: Vec<u8>,
    conv: LabelConv,
    classification: Option<AsprsConv>,
    /// The values of the vertex being read.
    cur: [f64; SLOTS],
}

impl<'a> Reader<'a> {
    /// Room for the vertices, but never more than `body_len` bytes can hold: a vertex takes at
    /// least its properties' smallest sizes in binary, two bytes per property in ASCII.
    fn new(
        path: &Path,
        vertex: &Element,
        slots: &'a [Option<usize>],
        body_len: usize,
        binary: bool,
    ) -> Result<Self> {
        let mut has = [false; SLOTS];
        slots
            .iter()
            .flatten()
            .for_each(|&s| has[s.min(SLOTS - 1)] = true);
        let min: usize = if binary {
            vertex.props.iter().map(|p| p.kind.min_size()).sum()
        } else {
            2 * vertex.props.len()
        };
        let cap = vertex.count.min(body_len / min.max(1) + 1);
        let described = |slot: usize| {
            let k = slots.iter().position(|&s| s == Some(slot))?;
            let p = vertex.props.get(k)?;
            match p.kind {
                Kind::Scalar(t) => Some((
                    format!("vertex property {} ({})", shown(&p.name), t.ply_name()),
                    t,
                )),
                Kind::List { .. } => None,
            }
        };
        let own =
            |slot: usize, own: fn(Scalar) -> bool| described(slot).map(|(desc, t)| (desc, own(t)));
        let conv = LabelConv::new(
            own(LABEL, |t| t.is_unsigned() && t.size() <= 4),
            own(CLASS, |t| t == Scalar::U8),
        );
        let classification = match described(CLASSIFICATION) {
            Some((desc, t)) => Some(AsprsConv::new(path, desc, t, cap)?),
            None => None,
        };
        Ok(Reader {
            slots,
            has,
            points: try_vec(path, cap, "the points")?,
            intensity: room(path, has[INTENSITY], cap, "the intensities")?,
            labels: room(path, conv.any(), cap, "the labels")?,
            codes: room(path, conv.has_class(), cap, "the class codes")?,
            conv,
            classification,
            cur: [0.0; SLOTS],
        })
    }

    fn set(&mut self, prop: usize, v: f64) {
        if let Some(&Some(s)) = self.slots.get(prop) {
            self.cur[s.min(SLOTS - 1)] = v;
        }
    }

    /// Stores the current vertex, read at `line` (0 in binary data).
    fn push(&mut self, line: usize) {
        let [x, y, z, i, l, c, asprs] = self.cur;
        let index = self.points.len();
        self.points.push(Vec3::new(x as f32, y as f32, z as f32));
        if self.has[INTENSITY] {
            self.intensity.push(i as f32);
        }
        if self.conv.any() {
            let entity = if self.has[LABEL] {
                self.conv.entity(index, l)
            } else {
                0
            };
            self.labels.push(Label {
                entity,
                ..Label::default()
            });
        }
        if self.conv.has_class() {
            self.codes.push(self.conv.class_code(index, c, line));
        }
        if let Some(a) = &mut self.classification {
            a.push(asprs);
        }
        self.cur = [0.0; SLOTS];
    }

    fn finish(self, path: &Path, notes: &mut Notes) -> Result<PointCloud> {
        let codes = self.conv.has_class().then_some(self.codes);
        let labels = self.conv.finish(path, self.labels, codes, notes)?;
        let mut cloud = PointCloud::from_points(self.points);
        cloud.intensity = self.has[INTENSITY].then_some(self.intensity);
        cloud.labels = labels;
        cloud.classification = self.classification.and_then(|c| c.finish(notes));
        Ok(cloud)
    }
}

/// An empty vector with room for `cap` items where `on`, else an empty one.
fn room<T>(path: &Path, on: bool, cap: usize, what: &str) -> Result<Vec<T>> {
    if on {
        try_vec(path, cap, what)
    } else {
        Ok(Vec::new())
    }
}

/// The declared items as a message shows them: `vertex 3, face 1`.
fn declared(elements: &[&[Element]]) -> String {
    let parts: Vec<String> = elements
        .iter()
        .flat_map(|e| e.iter())
        .map(|e| format!("{} {}", shown(&e.name), e.count))
        .collect();
    parts.join(", ")
}
