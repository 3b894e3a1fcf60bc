//! Writing a cloud as an E57 file with the `e57` crate: one scan, identity pose.
//!
//! The scan holds cartesian coordinates as f64 (every f32 exactly), intensity as f32 where
//! the cloud has it (with its minimum and maximum as the intensity limits), and for an
//! organised cloud every grid cell with `rowIndex`/`columnIndex`, missing returns written with
//! `cartesianInvalidState` 2 (coordinates 0). Labels, classification and the sensor pose are
//! not written.

use crate::error::{InteropError, Result};
use cloud::PointCloud;
use e57::{Record, RecordDataType, RecordName, RecordValue};
use std::io::Cursor;
use std::path::Path;

/// Writes `cloud` (validated and finite where unorganised) to `path` as E57.
pub(super) fn write_e57(path: &Path, cloud: &PointCloud) -> Result<()> {
    let bytes = encode_e57(path, cloud)?;
    cloud::write_bytes_atomically(path, &bytes)?;
    Ok(())
}

/// The E57 file's bytes.
fn encode_e57(path: &Path, cloud: &PointCloud) -> Result<Vec<u8>> {
    let fail = |e: e57::Error| InteropError::format(path, format!("writing E57: {e}"));
    let guid = content_guid(cloud);
    let mut bytes = Vec::new();
    {
        let mut writer = e57::E57Writer::new(Cursor::new(&mut bytes), &guid).map_err(fail)?;
        let mut prototype = vec![
            double(RecordName::CartesianX),
            double(RecordName::CartesianY),
            double(RecordName::CartesianZ),
        ];
        let organised = cloud.organized.filter(|o| o.rows > 0 && o.cols > 0);
        if let Some(o) = organised {
            prototype.push(integer(RecordName::CartesianInvalidState, 2));
            prototype.push(integer(RecordName::RowIndex, o.rows as i64 - 1));
            prototype.push(integer(RecordName::ColumnIndex, o.cols as i64 - 1));
        }
        let intensity = cloud.intensity.as_deref();
        if intensity.is_some() {
            prototype.push(Record {
                name: RecordName::Intensity,
                data_type: RecordDataType::Single {
                    min: None,
                    max: None,
                },
            });
        }
        let mut scan = writer
            .add_pointcloud(&format!("{guid}-scan0"), prototype)
            .map_err(fail)?;
        scan.set_name(Some(super::util::file_stem(path)));
        scan.set_description(Some("written by semsim".to_string()));
        if let Some(values) = intensity {
            let finite = values.iter().copied().filter(|v| v.is_finite());
            let min = finite.clone().fold(f32::INFINITY, f32::min);
            let max = finite.fold(f32::NEG_INFINITY, f32::max);
            if min <= max {
                scan.set_intensity_limits(Some(e57::IntensityLimits {
                    intensity_min: Some(RecordValue::Single(min)),
                    intensity_max: Some(RecordValue::Single(max)),
                }));
            }
        }
        for (i, p) in cloud.points.iter().enumerate() {
            let missing = !p.is_finite();
            let xyz = if missing { glam::Vec3::ZERO } else { *p };
            let mut values = vec![
                RecordValue::Double(f64::from(xyz.x)),
                RecordValue::Double(f64::from(xyz.y)),
                RecordValue::Double(f64::from(xyz.z)),
            ];
            if let Some(o) = organised {
                values.push(RecordValue::Integer(if missing { 2 } else { 0 }));
                values.push(RecordValue::Integer((i / o.cols) as i64));
                values.push(RecordValue::Integer((i % o.cols) as i64));
            }
            if let Some(v) = intensity {
                let value = v[i];
                values.push(RecordValue::Single(if value.is_finite() {
                    value
                } else {
                    0.0
                }));
            }
            scan.add_point(values).map_err(fail)?;
        }
        scan.finalize().map_err(fail)?;
        writer.finalize().map_err(fail)?;
    }
    Ok(bytes)
}

fn double(name: RecordName) -> Record {
    Record {
        name,
        data_type: RecordDataType::Double {
            min: None,
            max: None,
        },
    }
}

fn integer(name: RecordName, max: i64) -> Record {
    Record {
        name,
        data_type: RecordDataType::Integer { min: 0, max },
    }
}

/// A GUID for the file derived from its content (FNV-1a of the coordinates), so that writing
/// the same cloud twice gives the same file.
fn content_guid(cloud: &PointCloud) -> String {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    let mut feed = |bytes: &[u8]| {
        for b in bytes {
            hash ^= u64::from(*b);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    feed(&(cloud.points.len() as u64).to_le_bytes());
    for p in &cloud.points {
        for c in p.to_array() {
            feed(&c.to_le_bytes());
        }
    }
    let h = format!("{hash:016x}");
    format!("{{semsim-{}-{}}}", &h[..8], &h[8..])
}
