//! PLY 1.0 (Stanford polygon format): `ascii`, `binary_little_endian`, `binary_big_endian`.
//!
//! Reading takes the `vertex` element: `x y z` (any scalar type; `float`, `double` and the
//! `float32`/`float64` aliases are the usual ones), an optional intensity (`intensity` or
//! `scalar_intensity`, any scalar type) and optional `label` (entity id) and `class`
//! ([`crate::EntityClass`] code). semsim's own types for these are `uchar`, `ushort` or `uint`
//! labels and `uchar` classes; other types are converted with a note, as in PCD (a label value
//! that is no entity id reads as no entity; a class property of another type holding a value
//! that is no class code is skipped). Other vertex properties, list properties included, and
//! the other elements are skipped with a note. The elements after `vertex` (faces and the
//! like) are not decoded, but the file must not hold more than its header declares: in ASCII
//! a non-blank line beyond the declared items is an error, in binary any byte beyond the
//! declared data but trailing whitespace. Elements after `vertex` cut short are noted, not
//! refused. PLY has no organised shape, so a non-finite point is an error, and writing an
//! organised cloud drops its missing returns.
//!
//! Writing produces `float x y z`, `float intensity` if present, and `uint label` +
//! `uchar class` if labels are present.
//!
//! Hand-written rather than taken from the `ply-rs-bw` crate: we want errors naming the header
//! line or the expected and found byte counts, a fixed set of properties decoded straight into
//! the cloud's arrays (no per-vertex property maps), and nothing to read after the vertices.

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

mod header;
use header::{Element, Kind};

/// Slots of the optional values we keep from a vertex (x y z are slots 0, 1, 2).
const INTENSITY: usize = 3;
const LABEL: usize = 4;
const CLASS: usize = 5;

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
        PlyEncoding::Ascii => read_ascii(
            path,
            h.end_line,
            skipped,
            vertex,
            after,
            body,
            &mut reader,
            &mut notes,
        )?,
        enc => read_binary(
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
            PlyEncoding::Ascii => write_ascii_body(w, &cloud),
            PlyEncoding::BinaryLittleEndian => w.write_all(&binary_body(&cloud, false)),
            PlyEncoding::BinaryBigEndian => w.write_all(&binary_body(&cloud, true)),
        }
        .map_err(io)
    })
}

/// For each vertex property, the slot its value goes to (x y z intensity label class), if kept;
/// notes the properties skipped.
fn slots(path: &Path, vertex: &Element, notes: &mut Notes) -> Result<Vec<Option<usize>>> {
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
    has: [bool; 6],
    points: Vec<Vec3>,
    intensity: Vec<f32>,
    labels: Vec<Label>,
    codes: Vec<u8>,
    conv: LabelConv,
    /// The values of the vertex being read.
    cur: [f64; 6],
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
        let mut has = [false; 6];
        slots.iter().flatten().for_each(|&s| has[s.min(5)] = true);
        let min: usize = if binary {
            vertex.props.iter().map(|p| p.kind.min_size()).sum()
        } else {
            2 * vertex.props.len()
        };
        let cap = vertex.count.min(body_len / min.max(1) + 1);
        let described = |slot: usize, own: fn(Scalar) -> bool| {
            let k = slots.iter().position(|&s| s == Some(slot))?;
            match vertex.props.get(k)?.kind {
                Kind::Scalar(t) => Some((
                    format!(
                        "vertex property {} ({})",
                        shown(&vertex.props.get(k)?.name),
                        t.ply_name()
                    ),
                    own(t),
                )),
                Kind::List { .. } => None,
            }
        };
        let conv = LabelConv::new(
            described(LABEL, |t| t.is_unsigned() && t.size() <= 4),
            described(CLASS, |t| t == Scalar::U8),
        );
        Ok(Reader {
            slots,
            has,
            points: try_vec(path, cap, "the points")?,
            intensity: room(path, has[INTENSITY], cap, "the intensities")?,
            labels: room(path, conv.any(), cap, "the labels")?,
            codes: room(path, conv.has_class(), cap, "the class codes")?,
            conv,
            cur: [0.0; 6],
        })
    }

    fn set(&mut self, prop: usize, v: f64) {
        if let Some(&Some(s)) = self.slots.get(prop) {
            self.cur[s.min(5)] = v;
        }
    }

    /// Stores the current vertex, read at `line` (0 in binary data).
    fn push(&mut self, line: usize) {
        let [x, y, z, i, l, c] = self.cur;
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
        self.cur = [0.0; 6];
    }

    fn finish(self, path: &Path, notes: &mut Notes) -> Result<PointCloud> {
        let codes = self.conv.has_class().then_some(self.codes);
        let labels = self.conv.finish(path, self.labels, codes, notes)?;
        let mut cloud = PointCloud::from_points(self.points);
        cloud.intensity = self.has[INTENSITY].then_some(self.intensity);
        cloud.labels = labels;
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

/// Skips the binary items of `elements` from `pos`; the position after them.
fn skip_binary(
    path: &Path,
    elements: &[Element],
    body: &[u8],
    mut pos: usize,
    big: bool,
) -> Result<usize> {
    for e in elements {
        if e.props.iter().all(|p| matches!(p.kind, Kind::Scalar(_))) {
            // Fixed size: skip all items at once (also bounds a huge count of empty items).
            let size: usize = e.props.iter().map(|p| p.kind.min_size()).sum();
            pos = pos.saturating_add(e.count.saturating_mul(size));
            if pos > body.len() {
                let msg = format!(
                    "element {} ({} items) runs past the end of the file",
                    shown(&e.name),
                    e.count
                );
                return Err(CloudError::Truncated {
                    path: path.to_path_buf(),
                    msg,
                });
            }
        } else {
            // Each item takes at least one byte (a list's count), so this ends within the data.
            for _ in 0..e.count {
                pos = walk(path, e, body, pos, big, &mut |_, _| {})?;
            }
        }
    }
    Ok(pos)
}

fn read_binary(
    path: &Path,
    big: bool,
    (skipped, vertex, after): (&[Element], &Element, &[Element]),
    body: &[u8],
    r: &mut Reader,
    notes: &mut Notes,
) -> Result<()> {
    let mut pos = skip_binary(path, skipped, body, 0, big)?;
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
    for _ in 0..vertex.count {
        pos = walk(path, vertex, body, pos, big, &mut |p, v| r.set(p, v))?;
        r.push(0);
    }
    r.conv.class_error(path)?;
    match skip_binary(path, after, body, pos, big) {
        Ok(end) => {
            let rest = body.get(end..).unwrap_or_default();
            if !rest.iter().all(u8::is_ascii_whitespace) {
                let msg = format!(
                    "{} bytes after the data the header declares ({}): more vertices than declared, or a wrong element count",
                    rest.len(),
                    declared(&[std::slice::from_ref(vertex), after])
                );
                return Err(CloudError::parse(path, 0, msg));
            }
        }
        Err(_) => notes.add(format_args!(
            "the elements after the vertices ({}) are cut short (ignored)",
            declared(&[after])
        )),
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
        msg: format!("element {} ends past the end of the file ({} bytes of data, needed more at byte {pos})", shown(&e.name), body.len()),
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

#[allow(clippy::too_many_arguments)]
fn read_ascii(
    path: &Path,
    end_line: usize,
    skipped: &[Element],
    vertex: &Element,
    after: &[Element],
    body: &[u8],
    r: &mut Reader,
    notes: &mut Notes,
) -> Result<()> {
    let text = String::from_utf8_lossy(body);
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(k, l)| (end_line + 1 + k, l))
        .filter(|(_, l)| !l.trim().is_empty());
    let to_skip = skipped
        .iter()
        .fold(0usize, |n, e| n.saturating_add(e.count));
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
                        format!("'{}' is not a valid", shown(tok))
                    };
                    CloudError::parse(
                        path,
                        line_no,
                        format!("{what} value of vertex property {}", shown(&p.name)),
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
        r.push(line_no);
        r.conv.class_error(path)?;
    }
    // The items after the vertices take one line each; nothing may follow them.
    let to_skip = after.iter().fold(0usize, |n, e| n.saturating_add(e.count));
    let mut found = 0usize;
    while found < to_skip && lines.next().is_some() {
        found += 1;
    }
    if found < to_skip {
        notes.add(format_args!(
            "the elements after the vertices ({}) are cut short: {found} of {to_skip} lines (ignored)",
            declared(&[after])
        ));
    } else if let Some((line_no, _)) = lines.next() {
        let msg = format!(
            "a line beyond the items the header declares ({}): more vertices than declared, or a wrong element count",
            declared(&[std::slice::from_ref(vertex), after])
        );
        return Err(CloudError::parse(path, line_no, msg));
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
