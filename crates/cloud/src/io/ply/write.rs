//! Writing PLY vertex data. The properties, in order: `float x y z`, `float intensity`,
//! `uint label` + `uchar class`, `uchar classification`, each written only where the cloud
//! has that channel (`x y z` always), as the header from `header::text` declares them.

use crate::PointCloud;
use std::io::Write;

pub(super) fn ascii_body(w: &mut impl Write, cloud: &PointCloud) -> std::io::Result<()> {
    for (i, p) in cloud.points.iter().enumerate() {
        write!(w, "{} {} {}", p.x, p.y, p.z)?;
        if let Some(v) = cloud.intensity.as_ref().and_then(|v| v.get(i)) {
            write!(w, " {v}")?;
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

pub(super) fn binary_body(cloud: &PointCloud, big: bool) -> Vec<u8> {
    let f = |v: f32| {
        if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    };
    let mut out = Vec::with_capacity(cloud.len() * 22);
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
        if let Some(&c) = cloud.classification.as_ref().and_then(|v| v.get(i)) {
            out.push(c);
        }
    }
    out
}
