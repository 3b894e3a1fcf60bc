//! Writing a cloud as LAS 1.4 (point format 6) or LAZ with the `las` crate.
//!
//! Point format 6 holds the full 8-bit ASPRS classification and 16-bit intensity. Coordinates
//! are stored as integers of [`SCALE_M`] (0.1 mm) about an offset, the centre of the points'
//! bounding box rounded to whole metres; a cloud wider than the integers reach at that scale
//! (±214 km about the centre) gets a coarser scale, ten times at a time. Only finite points are
//! written: the missing returns and the shape of an organised cloud, labels and the sensor pose
//! are not (LAS has no place for them). Intensity is rounded to the nearest `u16` (clamped;
//! 0 where the cloud has none), the classification written as it is (0, "never classified",
//! where the cloud has none). Every point has return 1 of 1 and GPS time 0.

use crate::error::{InteropError, Result};
use cloud::PointCloud;
use glam::DVec3;
use las::point::{Classification, Format};
use las::{Builder, Point, Transform, Vector, Version};
use std::io::Cursor;
use std::path::Path;

/// The coordinate resolution written: 0.1 mm.
pub(super) const SCALE_M: f64 = 1e-4;

/// Writes `cloud` (validated) as LAS, or LAZ where `compressed`.
pub(super) fn write_las(path: &Path, cloud: &PointCloud, compressed: bool) -> Result<()> {
    let bytes = encode_las(path, cloud, compressed)?;
    cloud::write_bytes_atomically(path, &bytes)?;
    Ok(())
}

fn encode_las(path: &Path, cloud: &PointCloud, compressed: bool) -> Result<Vec<u8>> {
    let fail = |e: las::Error| InteropError::format(path, format!("writing LAS: {e}"));
    let finite = || cloud.points.iter().filter(|p| p.is_finite());
    let (lo, hi) = finite().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p.as_dvec3()), hi.max(p.as_dvec3())),
    );
    let offset = if lo.x <= hi.x {
        ((lo + hi) * 0.5).round()
    } else {
        DVec3::ZERO
    };
    let reach = if lo.x <= hi.x {
        (hi - offset).max(offset - lo).max_element()
    } else {
        0.0
    };
    let mut scale = SCALE_M;
    while reach / scale > f64::from(i32::MAX) - 1.0 {
        scale *= 10.0;
    }
    let mut builder = Builder::from(Version::new(1, 4));
    let mut format = Format::new(6).map_err(fail)?;
    format.is_compressed = compressed;
    builder.point_format = format;
    builder.system_identifier = "semsim".to_string();
    builder.generating_software = "semsim interop".to_string();
    let axis = |offset: f64| Transform { scale, offset };
    builder.transforms = Vector {
        x: axis(offset.x),
        y: axis(offset.y),
        z: axis(offset.z),
    };
    let header = builder.into_header().map_err(fail)?;
    let mut writer = las::Writer::new(Cursor::new(Vec::new()), header).map_err(fail)?;
    for (i, p) in cloud.points.iter().enumerate() {
        if !p.is_finite() {
            continue;
        }
        let intensity = cloud.intensity.as_ref().map_or(0, |v| to_u16(v[i]));
        let class = cloud.classification.as_ref().map_or(0, |c| c[i]);
        let point = Point {
            x: f64::from(p.x),
            y: f64::from(p.y),
            z: f64::from(p.z),
            intensity,
            return_number: 1,
            number_of_returns: 1,
            classification: classification(class),
            gps_time: Some(0.0),
            ..Default::default()
        };
        writer.write_point(point).map_err(fail)?;
    }
    let cursor = writer.into_inner().map_err(fail)?;
    Ok(cursor.into_inner())
}

/// The `las` crate's classification for a class byte. Class 12 (overlap) is written as the
/// byte 12 (the crate's constructor refuses it in favour of the overlap flag).
fn classification(class: u8) -> Classification {
    Classification::new(class).unwrap_or(Classification::Reserved(class))
}

/// An intensity rounded to the nearest `u16`, clamped; 0 for NaN.
fn to_u16(value: f32) -> u16 {
    if value.is_nan() {
        0
    } else {
        value.round().clamp(0.0, f32::from(u16::MAX)) as u16
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intensity_and_class_conversions() {
        assert_eq!(to_u16(12.4), 12);
        assert_eq!(to_u16(-3.0), 0);
        assert_eq!(to_u16(1e9), u16::MAX);
        assert_eq!(to_u16(f32::NAN), 0);
        assert_eq!(u8::from(classification(12)), 12);
        assert_eq!(u8::from(classification(2)), 2);
        assert_eq!(u8::from(classification(200)), 200);
    }
}
