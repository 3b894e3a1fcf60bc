//! Reading `binary_little_endian` and `binary_big_endian` data: the elements before the
//! vertices skipped, the vertices walked property by property, the elements after them checked
//! to end the data.

use super::header::{Element, Kind};
use super::{declared, Reader};
use crate::error::{CloudError, Result};
use crate::io::text::{shown, Notes};
use std::path::Path;

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

pub(super) fn read_binary(
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
