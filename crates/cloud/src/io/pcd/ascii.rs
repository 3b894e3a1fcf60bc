//! Reading `DATA ascii`: one point per line, the values of each field in header order.

use super::header::Header;
use super::{truncated, Channels, Wanted};
use crate::cloud::Label;
use crate::error::{try_vec, CloudError, Result};
use crate::io::labels::LabelConv;
use crate::io::text::shown;
use glam::Vec3;
use std::path::Path;

pub(super) fn read_ascii(
    path: &Path,
    h: &Header,
    w: &Wanted,
    conv: &mut LabelConv,
    body: &[u8],
) -> Result<Channels> {
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
    // Token index of each field's first element (the counts' sum cannot overflow: it is at
    // most the point size, checked with the header).
    let mut first = Vec::with_capacity(h.fields.len());
    let total = h.fields.iter().fold(0usize, |acc, f| {
        first.push(acc);
        acc.saturating_add(f.count)
    });
    let tok = |i: usize| first.get(i).copied().unwrap_or(0);
    // A point line takes at least two bytes per value (the value and a space or newline), so
    // no more points than that are allocated, whatever WIDTH, HEIGHT and COUNT say.
    let cap = h
        .points
        .min(body.len() / total.saturating_mul(2).max(1) + 1);
    let mut points = try_vec(path, cap, "the points")?;
    let mut intensity = if w.intensity.is_some() {
        try_vec(path, cap, "the intensities")?
    } else {
        Vec::new()
    };
    let mut labels = if conv.any() {
        try_vec(path, cap, "the labels")?
    } else {
        Vec::new()
    };
    let mut codes = if conv.has_class() {
        try_vec(path, cap, "the class codes")?
    } else {
        Vec::new()
    };
    let mut classification = w.asprs(path, h, cap)?;
    let mut toks: Vec<&str> = Vec::new();
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
                    let msg = format!(
                        "'{}' is not a valid value of field {}",
                        shown(t),
                        shown(name)
                    );
                    CloudError::parse(path, line_no, msg)
                })
        };
        let [x, y, z] = [value(w.xyz[0])?, value(w.xyz[1])?, value(w.xyz[2])?];
        let i = points.len();
        points.push(Vec3::new(x as f32, y as f32, z as f32));
        if let Some(f) = w.intensity {
            intensity.push(value(f)? as f32);
        }
        if conv.any() {
            let entity = match w.label {
                Some(f) => conv.entity(i, value(f)?),
                None => 0,
            };
            labels.push(Label {
                entity,
                ..Label::default()
            });
        }
        if let Some(f) = w.class {
            codes.push(conv.class_code(i, value(f)?, line_no));
            conv.class_error(path)?;
        }
        if let (Some(c), Some(f)) = (&mut classification, w.classification) {
            c.push(value(f)?);
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
    Ok(Channels {
        points,
        intensity: w.intensity.map(|_| intensity),
        labels: conv.any().then_some(labels),
        codes: conv.has_class().then_some(codes),
        classification,
    })
}
