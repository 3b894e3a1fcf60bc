//! `sensor_msgs/msg/PointCloud2` from CDR into a [`PointCloud`].
//!
//! The message: `header` (stamp, frame id), `height`, `width` (u32), `fields`
//! (`sequence<PointField{name string, offset u32, datatype u8, count u32}>`), `is_bigendian`
//! (bool), `point_step`, `row_step` (u32), `data` (`sequence<uint8>`), `is_dense` (bool).
//! Point `(row, col)` starts at byte `row * row_step + col * point_step` of `data`.
//!
//! The cloud takes the fields `x`, `y`, `z` (FLOAT32 = 7 or FLOAT64 = 8) and `intensity` where
//! present (any numeric datatype, 1-8, as f32); other fields are ignored. A cloud of more than
//! one row (`height > 1`) is organised (`rows = height`, `cols = width`) and keeps a point with
//! a non-finite coordinate as a missing return (all NaN); an unorganised one drops it.

use super::cdr::CdrReader;
use cloud::{Organized, PointCloud};
use glam::Vec3;

/// `sensor_msgs/msg/PointField` datatypes: INT8 1, UINT8 2, INT16 3, UINT16 4, INT32 5,
/// UINT32 6, FLOAT32 7, FLOAT64 8.
fn datatype_bytes(datatype: u8) -> Option<usize> {
    match datatype {
        1 | 2 => Some(1),
        3 | 4 => Some(2),
        5..=7 => Some(4),
        8 => Some(8),
        _ => None,
    }
}

/// A field of the point layout.
#[derive(Debug, Clone)]
struct Field {
    name: String,
    offset: u32,
    datatype: u8,
}

/// A decoded message.
#[derive(Debug)]
pub(super) struct DecodedCloud {
    /// The points, in the message's frame.
    pub cloud: PointCloud,
    /// `header.stamp` in nanoseconds since the epoch.
    pub stamp_ns: i64,
    /// `header.frame_id`.
    pub frame_id: String,
    /// Points of an unorganised cloud dropped for a non-finite coordinate.
    pub dropped: usize,
}

/// Decodes one CDR-encoded PointCloud2 message; errors are text for the caller to place.
pub(super) fn decode_pointcloud2(message: &[u8]) -> Result<DecodedCloud, String> {
    let mut r = CdrReader::new(message)?;
    let (stamp_ns, frame_id) = r.header()?;
    let height = r.u32("height")?;
    let width = r.u32("width")?;
    // A field takes at least a string length, an offset, a datatype and a count.
    let field_count = r.sequence_len(13, "fields")?;
    let mut fields = Vec::with_capacity(field_count);
    for _ in 0..field_count {
        let name = r.string("fields[].name")?;
        let offset = r.u32("fields[].offset")?;
        let datatype = r.u8("fields[].datatype")?;
        let _count = r.u32("fields[].count")?;
        fields.push(Field {
            name,
            offset,
            datatype,
        });
    }
    let big_endian = r.bool("is_bigendian")?;
    let point_step = r.u32("point_step")?;
    let row_step = r.u32("row_step")?;
    let data = r.byte_sequence("data")?;
    let _is_dense = r.bool("is_dense")?;

    let find = |name: &str| fields.iter().find(|f| f.name == name);
    let layout = |name: &str, float_only: bool| -> Result<Option<(usize, u8)>, String> {
        let Some(f) = find(name) else {
            return Ok(None);
        };
        let size = match datatype_bytes(f.datatype) {
            Some(s) if !float_only || f.datatype >= 7 => s,
            _ => {
                return Err(format!(
                    "field {name} has datatype {} (x, y, z must be FLOAT32 7 or FLOAT64 8, intensity 1-8)",
                    f.datatype
                ))
            }
        };
        if u64::from(f.offset) + size as u64 > u64::from(point_step) {
            return Err(format!(
                "field {name} (offset {}, {size} bytes) does not fit in point_step {point_step}",
                f.offset
            ));
        }
        Ok(Some((f.offset as usize, f.datatype)))
    };
    let mut xyz = [(0, 0); 3];
    for (slot, name) in xyz.iter_mut().zip(["x", "y", "z"]) {
        *slot = layout(name, true)?.ok_or_else(|| {
            let names: Vec<String> = fields.iter().map(|f| format!("{:?}", f.name)).collect();
            format!("no field {name:?} (fields: {})", names.join(", "))
        })?;
    }
    let intensity_field = layout("intensity", false)?;

    let (rows, cols) = (u64::from(height), u64::from(width));
    let count = rows * cols;
    let organised = height > 1;
    if count == 0 {
        return Ok(DecodedCloud {
            cloud: PointCloud::from_points(Vec::new()),
            stamp_ns,
            frame_id,
            dropped: 0,
        });
    }
    let row_bytes = cols * u64::from(point_step);
    if u64::from(row_step) < row_bytes && rows > 1 {
        return Err(format!(
            "row_step {row_step} is shorter than width {width} x point_step {point_step}"
        ));
    }
    let need = ((rows - 1) * u64::from(row_step)).saturating_add(row_bytes);
    if need > data.len() as u64 {
        return Err(format!(
            "data holds {} bytes, {height} x {width} points of {point_step} bytes (row_step {row_step}) need {need}",
            data.len()
        ));
    }
    // count <= data.len() / point_step, and point_step >= 4 (x fits in it).
    let count = count as usize;
    let mut points = Vec::with_capacity(count);
    let mut intensity = intensity_field.map(|_| Vec::with_capacity(count));
    let mut dropped = 0;
    for row in 0..height as usize {
        for col in 0..width as usize {
            let start = row * row_step as usize + col * point_step as usize;
            let point = &data[start..start + point_step as usize];
            let value =
                |(offset, datatype): (usize, u8)| number(point, offset, datatype, big_endian);
            let p = Vec3::new(
                value(xyz[0]) as f32,
                value(xyz[1]) as f32,
                value(xyz[2]) as f32,
            );
            if !p.is_finite() && !organised {
                dropped += 1;
                continue;
            }
            points.push(if p.is_finite() { p } else { Vec3::NAN });
            if let (Some(out), Some(field)) = (&mut intensity, intensity_field) {
                out.push(value(field) as f32);
            }
        }
    }
    let mut cloud = PointCloud::from_points(points);
    cloud.intensity = intensity;
    if organised {
        cloud.organized = Some(Organized {
            rows: height as usize,
            cols: width as usize,
        });
    }
    Ok(DecodedCloud {
        cloud,
        stamp_ns,
        frame_id,
        dropped,
    })
}

/// The number of `datatype` at `offset` of `point` (which holds it: checked by the layout).
fn number(point: &[u8], offset: usize, datatype: u8, big_endian: bool) -> f64 {
    fn bytes<const N: usize>(point: &[u8], offset: usize, big_endian: bool) -> [u8; N] {
        let mut b = [0u8; N];
        b.copy_from_slice(&point[offset..offset + N]);
        if big_endian {
            b.reverse();
        }
        b
    }
    match datatype {
        1 => f64::from(point[offset] as i8),
        2 => f64::from(point[offset]),
        3 => f64::from(i16::from_le_bytes(bytes(point, offset, big_endian))),
        4 => f64::from(u16::from_le_bytes(bytes(point, offset, big_endian))),
        5 => f64::from(i32::from_le_bytes(bytes(point, offset, big_endian))),
        6 => f64::from(u32::from_le_bytes(bytes(point, offset, big_endian))),
        7 => f64::from(f32::from_le_bytes(bytes(point, offset, big_endian))),
        _ => f64::from_le_bytes(bytes(point, offset, big_endian)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A little-endian PointCloud2 of `rows` x `cols` FLOAT32 x, y, z and UINT16 intensity.
    fn message(rows: u32, cols: u32, points: &[[f32; 3]], big_endian: bool) -> Vec<u8> {
        let mut m = vec![0, u8::from(!big_endian), 0, 0];
        let put32 = |m: &mut Vec<u8>, v: u32| {
            while (m.len() - 4) & 3 != 0 {
                m.push(0);
            }
            m.extend(if big_endian {
                v.to_be_bytes()
            } else {
                v.to_le_bytes()
            });
        };
        put32(&mut m, 7); // sec
        put32(&mut m, 5); // nanosec
        put32(&mut m, 5); // frame_id length, NUL counted
        m.extend(b"lida\0");
        put32(&mut m, rows);
        put32(&mut m, cols);
        put32(&mut m, 4);
        for (name, offset, datatype) in [
            ("x", 0, 7u8),
            ("y", 4, 7),
            ("z", 8, 7),
            ("intensity", 12, 4),
        ] {
            put32(&mut m, name.len() as u32 + 1);
            m.extend(name.as_bytes());
            m.push(0);
            put32(&mut m, offset);
            m.push(datatype);
            put32(&mut m, 1);
        }
        m.push(u8::from(big_endian));
        put32(&mut m, 16);
        put32(&mut m, 16 * cols);
        put32(&mut m, points.len() as u32 * 16);
        for (i, p) in points.iter().enumerate() {
            for c in p {
                m.extend(if big_endian {
                    c.to_be_bytes()
                } else {
                    c.to_le_bytes()
                });
            }
            let v = i as u16 * 10;
            m.extend(if big_endian {
                v.to_be_bytes()
            } else {
                v.to_le_bytes()
            });
            m.extend([0, 0]);
        }
        m.push(1);
        m
    }

    #[test]
    fn organised_keeps_missing_returns_unorganised_drops_them() {
        let pts = [
            [1.0, 2.0, 3.0],
            [f32::NAN, 0.0, 0.0],
            [4.0, 5.0, 6.0],
            [7.0, 8.0, 9.0],
        ];
        for big_endian in [false, true] {
            let d = decode_pointcloud2(&message(2, 2, &pts, big_endian)).expect("decodes");
            assert_eq!(d.stamp_ns, 7_000_000_005);
            assert_eq!(d.frame_id, "lida");
            assert_eq!(d.cloud.organized, Some(Organized { rows: 2, cols: 2 }));
            assert!(d.cloud.points[1].is_nan());
            assert_eq!(d.cloud.points[3], Vec3::new(7.0, 8.0, 9.0));
            assert_eq!(d.cloud.intensity, Some(vec![0.0, 10.0, 20.0, 30.0]));
            let d = decode_pointcloud2(&message(1, 4, &pts, big_endian)).expect("decodes");
            assert_eq!(d.cloud.len(), 3);
            assert_eq!(d.dropped, 1);
            assert_eq!(d.cloud.intensity, Some(vec![0.0, 20.0, 30.0]));
        }
    }

    #[test]
    fn short_data_is_refused_before_reading() {
        let pts = [[1.0, 2.0, 3.0]];
        let e = decode_pointcloud2(&message(2, 2, &pts, false)).expect_err("short");
        assert!(e.contains("data holds 16 bytes"), "{e}");
        let mut m = message(1, 1, &pts, false);
        m.truncate(m.len() - 9);
        assert!(decode_pointcloud2(&m)
            .expect_err("truncated")
            .contains("truncated"));
    }
}
