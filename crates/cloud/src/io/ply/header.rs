//! The PLY header: parsing (every error names its line) and writing.

use super::PlyEncoding;
use crate::error::{CloudError, Result};
use crate::io::scalar::Scalar;
use crate::io::text::shown;
use crate::PointCloud;
use std::path::Path;

/// A property's type.
pub(super) enum Kind {
    /// One value.
    Scalar(Scalar),
    /// A count, then that many items.
    List { count: Scalar, item: Scalar },
}

impl Kind {
    /// The fewest bytes the property can take in a binary file.
    pub fn min_size(&self) -> usize {
        match self {
            Kind::Scalar(t) => t.size(),
            Kind::List { count, .. } => count.size(),
        }
    }
}

/// A property of an element.
pub(super) struct Prop {
    pub name: String,
    pub kind: Kind,
    /// Its 1-based header line.
    pub line: usize,
}

/// An element: `count` items, each with the properties in order.
pub(super) struct Element {
    pub name: String,
    pub count: usize,
    pub props: Vec<Prop>,
    /// Its 1-based header line.
    pub line: usize,
}

/// A parsed header.
pub(super) struct Header {
    pub encoding: PlyEncoding,
    pub elements: Vec<Element>,
    /// Byte offset of the data (just after `end_header`).
    pub data_offset: usize,
    /// The line of `end_header`.
    pub end_line: usize,
}

/// Parses the header at the start of `bytes` (a byte-order mark already removed).
pub(super) fn parse(path: &Path, bytes: &[u8]) -> Result<Header> {
    let err = |line: usize, msg: String| CloudError::parse(path, line, msg);
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut pos = 0usize;
    let mut line_no = 0usize;
    loop {
        line_no += 1;
        let rest = bytes.get(pos..).unwrap_or_default();
        if rest.is_empty() {
            let msg = if line_no == 1 {
                "empty file, not a PLY file"
            } else {
                "the header ends without end_header"
            };
            return Err(err(line_no, msg.into()));
        }
        let len = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        pos += (len + 1).min(rest.len());
        let line = std::str::from_utf8(rest.get(..len).unwrap_or_default())
            .map_err(|_| err(line_no, "header line is not text".into()))?
            .trim();
        if line_no == 1 {
            if line != "ply" {
                return Err(err(
                    1,
                    "not a PLY file: the first line must be 'ply'".into(),
                ));
            }
            continue;
        }
        let toks: Vec<&str> = line.split_whitespace().collect();
        match toks.as_slice() {
            [] | ["comment", ..] | ["obj_info", ..] => {}
            ["format", enc, version] if version.starts_with('1') => {
                encoding = Some(match *enc {
                    "ascii" => PlyEncoding::Ascii,
                    "binary_little_endian" => PlyEncoding::BinaryLittleEndian,
                    "binary_big_endian" => PlyEncoding::BinaryBigEndian,
                    _ => return Err(err(line_no, format!("unknown format '{}'", shown(enc)))),
                });
            }
            ["format", ..] => {
                let msg = "expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'";
                return Err(err(line_no, msg.into()));
            }
            ["element", name, count] => {
                let count = count.parse().map_err(|_| {
                    err(
                        line_no,
                        format!("element count '{}' is not a number", shown(count)),
                    )
                })?;
                elements.push(Element {
                    name: (*name).into(),
                    count,
                    props: Vec::new(),
                    line: line_no,
                });
            }
            ["property", rest @ ..] => {
                let (kind, name) = match rest {
                    ["list", c, i, name] => (
                        Kind::List {
                            count: scalar(path, line_no, c)?,
                            item: scalar(path, line_no, i)?,
                        },
                        name,
                    ),
                    [t, name] => (Kind::Scalar(scalar(path, line_no, t)?), name),
                    _ => {
                        return Err(err(
                            line_no,
                            format!("malformed property line '{}'", shown(line)),
                        ))
                    }
                };
                let e = elements
                    .last_mut()
                    .ok_or_else(|| err(line_no, "property before any element".into()))?;
                e.props.push(Prop {
                    name: (*name).into(),
                    kind,
                    line: line_no,
                });
            }
            ["end_header"] => break,
            _ => {
                return Err(err(
                    line_no,
                    format!("unexpected header line '{}'", shown(line)),
                ))
            }
        }
    }
    let encoding = encoding.ok_or_else(|| err(line_no, "the header has no format line".into()))?;
    Ok(Header {
        encoding,
        elements,
        data_offset: pos,
        end_line: line_no,
    })
}

fn scalar(path: &Path, line: usize, name: &str) -> Result<Scalar> {
    Ok(match name {
        "char" | "int8" => Scalar::I8,
        "uchar" | "uint8" => Scalar::U8,
        "short" | "int16" => Scalar::I16,
        "ushort" | "uint16" => Scalar::U16,
        "int" | "int32" => Scalar::I32,
        "uint" | "uint32" => Scalar::U32,
        "float" | "float32" => Scalar::F32,
        "double" | "float64" => Scalar::F64,
        _ => {
            return Err(CloudError::parse(
                path,
                line,
                format!("unknown property type '{}'", shown(name)),
            ))
        }
    })
}

/// The header text for a cloud (all of whose points are written).
pub(super) fn text(cloud: &PointCloud, encoding: PlyEncoding) -> String {
    let mut s = format!(
        "ply\nformat {} 1.0\ncomment written by semsim\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n",
        encoding.keyword(),
        cloud.len()
    );
    if cloud.intensity.is_some() {
        s.push_str("property float intensity\n");
    }
    if cloud.labels.is_some() {
        s.push_str("property uint label\nproperty uchar class\n");
    }
    if cloud.classification.is_some() {
        s.push_str("property uchar classification\n");
    }
    s.push_str("end_header\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "ply\nformat binary_big_endian 1.0\ncomment hi\nelement camera 1\nproperty float32 view_px\nelement vertex 3\nproperty double x\nproperty float64 y\nproperty float z\nproperty list uchar int idx\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n";

    fn err_line(s: &str) -> (usize, String) {
        match parse(Path::new("h.ply"), s.as_bytes()) {
            Err(CloudError::Parse { line, msg, .. }) => (line, msg),
            Err(e) => panic!("expected a parse error, got {e}"),
            Ok(_) => panic!("expected a parse error"),
        }
    }

    #[test]
    fn parses_elements_properties_and_aliases() {
        let h = parse(Path::new("h.ply"), GOOD.as_bytes()).expect("valid");
        assert_eq!(h.encoding, PlyEncoding::BinaryBigEndian);
        assert_eq!(h.end_line, 13);
        assert_eq!(h.data_offset, GOOD.len());
        let names: Vec<&str> = h.elements.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(names, ["camera", "vertex", "face"]);
        let v = &h.elements[1];
        assert_eq!((v.count, v.props.len(), v.line), (3, 4, 6));
        assert!(matches!(v.props[0].kind, Kind::Scalar(Scalar::F64)));
        assert!(matches!(
            v.props[3].kind,
            Kind::List {
                count: Scalar::U8,
                item: Scalar::I32
            }
        ));
        assert_eq!(v.props[3].kind.min_size(), 1);
    }

    #[test]
    fn bad_headers_name_their_line() {
        assert_eq!(err_line(&GOOD.replacen("ply", "plx", 1)).0, 1);
        assert_eq!(err_line("").0, 1);
        assert_eq!(
            err_line(&GOOD.replace("binary_big_endian", "binary_middle_endian")).0,
            2
        );
        assert_eq!(err_line(&GOOD.replace(" 1.0", "")).0, 2);
        let (line, msg) = err_line(&GOOD.replace("format binary_big_endian 1.0\n", ""));
        assert!(line == 12 && msg.contains("no format"), "{line} {msg}");
        assert_eq!(err_line(&GOOD.replace("end_header\n", "")).0, 13);
        assert_eq!(
            err_line(&GOOD.replace("property float z", "property quad z")).0,
            9
        );
        assert_eq!(
            err_line(&GOOD.replace("element vertex 3", "element vertex -3")).0,
            6
        );
        assert_eq!(err_line(&GOOD.replace("element camera 1\n", "")).0, 4);
        assert_eq!(err_line(&GOOD.replace("comment hi", "hello")).0, 3);
    }
}
