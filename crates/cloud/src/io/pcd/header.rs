//! The PCD header: parsing (every error names its line) and writing.

use super::PcdEncoding;
use crate::error::{CloudError, Result};
use crate::io::scalar::Scalar;
use crate::io::text::shown;
use std::path::Path;

/// One field of the file's point layout.
pub(super) struct Field {
    pub name: String,
    pub ty: Scalar,
    pub count: usize,
    /// Byte offset within a point (array-of-structures layout).
    pub offset: usize,
}

/// A parsed header, checked for consistency.
pub(super) struct Header {
    pub fields: Vec<Field>,
    /// Bytes per point (sum of SIZE x COUNT).
    pub point_size: usize,
    pub width: usize,
    pub height: usize,
    /// `WIDTH x HEIGHT`; `points * point_size` does not overflow.
    pub points: usize,
    /// tx ty tz qw qx qy qz.
    pub viewpoint: [f32; 7],
    pub encoding: PcdEncoding,
    /// Byte offset of the data (just after the `DATA` line).
    pub data_offset: usize,
    pub data_line: usize,
}

/// A header line's values with its 1-based line number.
type Entry<'a> = Option<(usize, Vec<&'a str>)>;

#[derive(Default)]
struct Lines<'a> {
    fields: Entry<'a>,
    sizes: Entry<'a>,
    types: Entry<'a>,
    counts: Entry<'a>,
    width: Entry<'a>,
    height: Entry<'a>,
    points: Entry<'a>,
    viewpoint: Entry<'a>,
}

/// Parses the header at the start of `bytes` (a byte-order mark already removed).
pub(super) fn parse(path: &Path, bytes: &[u8]) -> Result<Header> {
    let err = |line: usize, msg: String| CloudError::parse(path, line, msg);
    let mut lines = Lines::default();
    let mut pos = 0usize;
    let mut line_no = 0usize;
    let (encoding, data_line) = loop {
        line_no += 1;
        let rest = bytes.get(pos..).unwrap_or_default();
        if rest.is_empty() {
            return Err(err(line_no, "the header ends without a DATA line".into()));
        }
        let len = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        pos += (len + 1).min(rest.len());
        let line = std::str::from_utf8(rest.get(..len).unwrap_or_default())
            .map_err(|_| err(line_no, "header line is not text".into()))?
            .trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let mut tokens = line.split_whitespace();
        let key = tokens.next().unwrap_or_default();
        let entry = Some((line_no, tokens.collect::<Vec<&str>>()));
        match key {
            "VERSION" => {}
            "FIELDS" | "COLUMNS" => lines.fields = entry,
            "SIZE" => lines.sizes = entry,
            "TYPE" => lines.types = entry,
            "COUNT" => lines.counts = entry,
            "WIDTH" => lines.width = entry,
            "HEIGHT" => lines.height = entry,
            "POINTS" => lines.points = entry,
            "VIEWPOINT" => lines.viewpoint = entry,
            "DATA" => {
                let enc = match entry.as_ref().and_then(|(_, v)| v.first().copied()) {
                    Some("ascii") => PcdEncoding::Ascii,
                    Some("binary") => PcdEncoding::Binary,
                    Some("binary_compressed") => PcdEncoding::BinaryCompressed,
                    other => {
                        let msg = format!(
                            "DATA must be ascii, binary or binary_compressed, found '{}'",
                            shown(other.unwrap_or_default())
                        );
                        return Err(err(line_no, msg));
                    }
                };
                break (enc, line_no);
            }
            _ => {
                let msg = format!("unknown header keyword '{}'", shown(key));
                return Err(err(line_no, msg));
            }
        }
    };
    build(path, lines, encoding, data_line, pos)
}

fn build<'a>(
    path: &Path,
    l: Lines<'a>,
    encoding: PcdEncoding,
    data_line: usize,
    data_offset: usize,
) -> Result<Header> {
    let err = |line: usize, msg: String| CloudError::parse(path, line, msg);
    let need = |name: &str, e: Entry<'a>| {
        e.ok_or_else(|| err(data_line, format!("the header has no {name} line")))
    };
    let (fields_line, names) = need("FIELDS", l.fields)?;
    let (size_line, sizes) = need("SIZE", l.sizes)?;
    let (type_line, types) = need("TYPE", l.types)?;
    let (count_line, counts) = l.counts.unwrap_or((data_line, vec!["1"; names.len()]));
    for (key, line, n) in [
        ("SIZE", size_line, sizes.len()),
        ("TYPE", type_line, types.len()),
        ("COUNT", count_line, counts.len()),
    ] {
        if n != names.len() {
            return Err(err(
                line,
                format!("{key} has {n} entries for {} FIELDS", names.len()),
            ));
        }
    }
    let mut fields = Vec::with_capacity(names.len());
    let mut offset = 0usize;
    for (((name, size), ty), count) in names.iter().zip(&sizes).zip(&types).zip(&counts) {
        let size: usize = size
            .parse()
            .map_err(|_| err(size_line, format!("SIZE '{}' is not a number", shown(size))))?;
        let ty = scalar(ty, size).ok_or_else(|| {
            err(type_line, format!("field {}: TYPE {} with SIZE {size} is not supported (F: 4 or 8; I, U: 1, 2, 4 or 8)", shown(name), shown(ty)))
        })?;
        let count = count.parse::<usize>().ok().filter(|&c| c > 0);
        let count = count.ok_or_else(|| {
            err(
                count_line,
                format!("field {}: COUNT must be a positive integer", shown(name)),
            )
        })?;
        fields.push(Field {
            name: (*name).to_string(),
            ty,
            count,
            offset,
        });
        offset = count
            .checked_mul(size)
            .and_then(|b| offset.checked_add(b))
            .ok_or_else(|| err(count_line, "the point size overflows".into()))?;
    }
    for axis in ["x", "y", "z"] {
        if !fields.iter().any(|f| f.name == axis) {
            let msg = format!("no field {axis} (FIELDS must include x y z)");
            return Err(err(fields_line, msg));
        }
    }
    let (width_line, width) = one_number(path, &need("WIDTH", l.width)?)?;
    let (height_line, height) = match &l.height {
        Some(e) => one_number(path, e)?,
        None => (data_line, 1),
    };
    let wh = width.checked_mul(height).ok_or_else(|| {
        err(
            height_line.max(width_line),
            format!("WIDTH {width} x HEIGHT {height} overflows"),
        )
    })?;
    let points_line = match &l.points {
        Some(e) => {
            let (line, points) = one_number(path, e)?;
            if points != wh {
                let msg = format!(
                    "POINTS {points} differs from WIDTH x HEIGHT = {width} x {height} = {wh}"
                );
                return Err(err(line, msg));
            }
            line
        }
        None => data_line,
    };
    if wh.checked_mul(offset).is_none() {
        return Err(err(
            points_line,
            format!("{wh} points of {offset} bytes overflow the address space"),
        ));
    }
    Ok(Header {
        fields,
        point_size: offset,
        width,
        height,
        points: wh,
        viewpoint: viewpoint(path, l.viewpoint)?,
        encoding,
        data_offset,
        data_line,
    })
}

fn scalar(ty: &str, size: usize) -> Option<Scalar> {
    Some(match (ty, size) {
        ("F", 4) => Scalar::F32,
        ("F", 8) => Scalar::F64,
        ("U", 1) => Scalar::U8,
        ("U", 2) => Scalar::U16,
        ("U", 4) => Scalar::U32,
        ("U", 8) => Scalar::U64,
        ("I", 1) => Scalar::I8,
        ("I", 2) => Scalar::I16,
        ("I", 4) => Scalar::I32,
        ("I", 8) => Scalar::I64,
        _ => return None,
    })
}

fn one_number(path: &Path, (line, vals): &(usize, Vec<&str>)) -> Result<(usize, usize)> {
    match vals.as_slice() {
        [v] => v.parse().map(|n| (*line, n)).map_err(|_| {
            let msg = format!("'{}' is not a non-negative integer", shown(v));
            CloudError::parse(path, *line, msg)
        }),
        _ => Err(CloudError::parse(
            path,
            *line,
            format!("expected one number, found {}", vals.len()),
        )),
    }
}

fn viewpoint(path: &Path, entry: Entry<'_>) -> Result<[f32; 7]> {
    let Some((line, vals)) = entry else {
        return Ok([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0]);
    };
    let err = |msg: &str| CloudError::parse(path, line, format!("VIEWPOINT: {msg}"));
    let nums: Vec<f32> = vals
        .iter()
        .filter_map(|v| v.parse::<f32>().ok().filter(|v| v.is_finite()))
        .collect();
    let Ok(v) = <[f32; 7]>::try_from(nums) else {
        return Err(err("expected 7 finite numbers: tx ty tz qw qx qy qz"));
    };
    // In f64: the squares of large f32 components would overflow in f32.
    let [tx, ty, tz, q @ ..] = v;
    let q = q.map(f64::from);
    let norm = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    if norm < 1e-6 {
        return Err(err("the orientation quaternion is zero"));
    }
    let q = if (norm - 1.0).abs() > 1e-5 {
        q.map(|c| (c / norm) as f32)
    } else {
        q.map(|c| c as f32)
    };
    Ok([tx, ty, tz, q[0], q[1], q[2], q[3]])
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "# comment\nVERSION .7\nFIELDS x y z _ rgb\nSIZE 4 4 8 1 4\nTYPE F F F U U\nCOUNT 1 1 1 3 1\nWIDTH 2\nHEIGHT 3\nVIEWPOINT 1 2 3 0 0 0 2\nPOINTS 6\nDATA binary\n";

    fn parse_str(s: &str) -> Result<Header> {
        parse(Path::new("h.pcd"), s.as_bytes())
    }

    fn err_line(s: &str) -> (usize, String) {
        match parse_str(s) {
            Err(CloudError::Parse { line, msg, .. }) => (line, msg),
            other => panic!("expected a parse error, got {:?}", other.map(|h| h.points)),
        }
    }

    #[test]
    fn parses_a_pcl_style_layout() {
        let h = parse_str(GOOD).expect("valid");
        let offsets: Vec<usize> = h.fields.iter().map(|f| f.offset).collect();
        assert_eq!(offsets, [0, 4, 8, 16, 19]);
        assert_eq!(h.point_size, 23);
        assert_eq!((h.width, h.height, h.points), (2, 3, 6));
        assert_eq!(h.fields[2].ty, Scalar::F64);
        assert_eq!(h.data_offset, GOOD.len());
        assert_eq!(h.data_line, 11);
        // A non-unit quaternion is normalised.
        assert_eq!(h.viewpoint, [1.0, 2.0, 3.0, 0.0, 0.0, 0.0, 1.0]);
    }

    #[test]
    fn bad_headers_name_their_line() {
        let (line, msg) = err_line(&GOOD.replace("POINTS 6", "POINTS 7"));
        assert_eq!(line, 10);
        assert!(msg.contains("POINTS 7") && msg.contains("2 x 3"), "{msg}");
        assert_eq!(
            err_line(&GOOD.replace("TYPE F F F U U", "TYPE F F F U X")).0,
            5
        );
        assert_eq!(
            err_line(&GOOD.replace("SIZE 4 4 8 1 4", "SIZE 4 4 8 1")).0,
            4
        );
        assert_eq!(
            err_line(&GOOD.replace("COUNT 1 1 1 3 1", "COUNT 1 1 1 0 1")).0,
            6
        );
        assert_eq!(err_line(&GOOD.replace("WIDTH 2", "WIDTH two")).0, 7);
        assert_eq!(err_line(&GOOD.replace("VERSION .7", "FOO 1")).0, 2);
        assert_eq!(err_line(&GOOD.replace("DATA binary", "DATA zip")).0, 11);
        assert_eq!(
            err_line(&GOOD.replace("VIEWPOINT 1 2 3 0 0 0 2", "VIEWPOINT 1 2")).0,
            9
        );
        assert_eq!(err_line(&GOOD.replace("DATA binary\n", "")).0, 11);
        assert!(err_line(&GOOD.replace("WIDTH 2\n", ""))
            .1
            .contains("no WIDTH"));
        assert!(err_line("\u{0}\u{1}\u{2}")
            .1
            .contains("unknown header keyword"));
    }

    #[test]
    fn absurd_sizes_are_refused_before_any_allocation() {
        let huge = GOOD
            .replace("WIDTH 2", "WIDTH 18446744073709551615")
            .replace("POINTS 6", "POINTS 18446744073709551615")
            .replace("HEIGHT 3", "HEIGHT 1");
        assert!(err_line(&huge).1.contains("overflow"));
        let h = parse_str(
            &GOOD
                .replace("WIDTH 2", "WIDTH 1000000000000")
                .replace("POINTS 6\n", ""),
        )
        .expect("fits the address space");
        assert_eq!(h.points, 3_000_000_000_000);
    }
}
