//! Reading `ascii` data: one element item per line, the elements before the vertices skipped,
//! those after them counted.

use super::header::{Element, Kind};
use super::{declared, Reader};
use crate::error::{CloudError, Result};
use crate::io::scalar::Scalar;
use crate::io::text::{shown, Notes};
use std::path::Path;

#[allow(clippy::too_many_arguments)]
pub(super) fn read_ascii(
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
