//! Reading E57 files (ASTM E2807) with the `e57` crate: every scan (`data3D` entry) with its
//! pose, organised shape and intensity.
//!
//! * Coordinates: cartesian where the scan has them, else spherical converted to cartesian
//!   (`x = r cos(elevation) cos(azimuth)`, `y = r cos(elevation) sin(azimuth)`,
//!   `z = r sin(elevation)`). A point whose coordinates are invalid (invalid state 2), only a
//!   direction (state 1) or not finite in f32 is a missing return: skipped in an unorganised
//!   scan, an all-NaN point in an organised one.
//! * Pose: the scan's `pose` (rotation quaternion, translation) is `world_from_scan`; a scan
//!   without one has the identity, as the standard says. The points stay in the scan frame.
//! * Organised shape: a scan with `rowIndex` and `columnIndex` becomes a grid of
//!   `max row + 1` rows and `max column + 1` columns, cells without a point missing returns.
//!   A grid that does not fit (negative indices, two points in one cell, or more than
//!   16 cells a point plus 65,536) falls back to an unorganised cloud, with a note.
//! * Intensity: the stored value as f32 (integer, scaled integer or float), not normalised by
//!   the scan's intensity limits; 0 where a point's intensity is marked invalid (with a note).
//! * Colour, time stamps and return indices are not kept (a note says so for colour).

use super::source::ByteSource;
use super::util::{clean, note, rigid_pose, try_filled, try_push, try_vec};
use super::{ImportedScan, ScanSet};
use crate::error::{InteropError, Result};
use cloud::{Organized, PointCloud};
use glam::{DAffine3, DVec3, Vec3};
use std::path::Path;

/// Grid cells allowed per point (plus [`GRID_SLACK`]) before an organised scan is read
/// unorganised: scanners omit the cells of missing returns (sky), but not most of them.
const GRID_CELLS_PER_POINT: u64 = 16;
/// Cells allowed beyond [`GRID_CELLS_PER_POINT`] (small scans with sparse grids).
const GRID_SLACK: u64 = 65_536;

/// Reads every scan of the E57 file in `src`, streaming its pages (the file is never held whole).
pub(super) fn read_e57(path: &Path, src: &impl ByteSource) -> Result<ScanSet> {
    let file_bytes = src.len();
    let io = |e: std::io::Error| InteropError::from(cloud::CloudError::io(path, e));
    let mut reader =
        e57::E57Reader::new(src.reader().map_err(io)?).map_err(|e| e57_error(path, "", e))?;
    let descriptors = reader.pointclouds();
    let mut scans = Vec::new();
    let mut notes = Vec::new();
    if descriptors.is_empty() {
        notes.push(note(path, "the E57 file holds no scan (no data3D entry)"));
    }
    for (index, descriptor) in descriptors.iter().enumerate() {
        let name = descriptor
            .name
            .as_deref()
            .map(|n| clean(n.trim()))
            .filter(|n| !n.is_empty())
            .unwrap_or_else(|| format!("scan{index}"));
        let label = format!("scan {index} ({name:?})");
        if !descriptor.has_cartesian() && !descriptor.has_spherical() {
            notes.push(note(
                path,
                format!("{label} has neither cartesian nor spherical coordinates; skipped"),
            ));
            continue;
        }
        let max_records = file_bytes.saturating_mul(8);
        if descriptor.records > max_records {
            return Err(InteropError::format(
                path,
                format!(
                    "{label} claims {} points, more than its {} bytes can hold (at least a bit a point)",
                    descriptor.records, file_bytes
                ),
            ));
        }
        let world_from_scan = match &descriptor.transform {
            None => DAffine3::IDENTITY,
            Some(t) => {
                let q = &t.rotation;
                let tr = &t.translation;
                rigid_pose([q.x, q.y, q.z, q.w], [tr.x, tr.y, tr.z]).ok_or_else(|| {
                    InteropError::format(
                        path,
                        format!(
                            "{label}: the pose is not a rotation and translation (quaternion w {} x {} y {} z {}, translation {} {} {})",
                            q.w, q.x, q.y, q.z, tr.x, tr.y, tr.z
                        ),
                    )
                })?
            }
        };
        if descriptor.has_color() {
            notes.push(note(path, format!("{label}: colour not kept")));
        }
        // Room for the points up front where the count is plausible for the file's size (no
        // real E57 point takes less than two bytes), so the columns never move as they grow.
        let reserve = descriptor.records.min(file_bytes / 2) as usize;
        let raw = read_points(path, &mut reader, descriptor, &label, reserve)?;
        let cloud = build_cloud(path, raw, &label, &mut notes)?;
        scans.push(ImportedScan {
            name,
            cloud,
            world_from_scan: Some(world_from_scan),
            stamp_ns: None,
            frame_id: None,
        });
    }
    Ok(ScanSet {
        scans,
        local_origin_m: DVec3::ZERO,
        odometry: None,
        notes,
    })
}

/// A scan's points as the file has them: NaN where invalid, grid cells where given.
struct RawScan {
    points: Vec<Vec3>,
    intensity: Option<Vec<f32>>,
    cells: Option<Vec<(i64, i64)>>,
    invalid_intensity: usize,
}

fn read_points<R: std::io::Read + std::io::Seek>(
    path: &Path,
    reader: &mut e57::E57Reader<R>,
    descriptor: &e57::PointCloud,
    label: &str,
    reserve: usize,
) -> Result<RawScan> {
    let mut iter = reader
        .pointcloud_simple(descriptor)
        .map_err(|e| e57_error(path, &format!("{label}: "), e))?;
    iter.apply_pose(false);
    iter.spherical_to_cartesian(true);
    iter.normalize_intensity(false);
    iter.intensity_to_color(false);
    let mut raw = RawScan {
        points: try_vec(path, reserve, "the E57 points")?,
        intensity: match descriptor.has_intensity() {
            true => Some(try_vec(path, reserve, "the E57 intensities")?),
            false => None,
        },
        cells: match descriptor.has_row_column() {
            true => Some(try_vec(path, reserve, "the E57 row/column indices")?),
            false => None,
        },
        invalid_intensity: 0,
    };
    for (i, point) in iter.enumerate() {
        let p = point.map_err(|e| e57_error(path, &format!("{label}, point {i}: "), e))?;
        let xyz = match p.cartesian {
            e57::CartesianCoordinate::Valid { x, y, z } => {
                let v = DVec3::new(x, y, z).as_vec3();
                if v.is_finite() {
                    v
                } else {
                    Vec3::NAN
                }
            }
            _ => Vec3::NAN,
        };
        try_push(path, &mut raw.points, xyz, "the E57 points")?;
        if let Some(intensity) = &mut raw.intensity {
            let value = p.intensity.filter(|v| v.is_finite()).unwrap_or_else(|| {
                raw.invalid_intensity += 1;
                0.0
            });
            try_push(path, intensity, value, "the E57 intensities")?;
        }
        if let Some(cells) = &mut raw.cells {
            try_push(path, cells, (p.row, p.column), "the E57 row/column indices")?;
        }
    }
    Ok(raw)
}

/// The cloud of a scan: organised where its row/column indices make a sensible grid.
fn build_cloud(
    path: &Path,
    raw: RawScan,
    label: &str,
    notes: &mut Vec<String>,
) -> Result<PointCloud> {
    if raw.invalid_intensity > 0 {
        notes.push(note(
            path,
            format!(
                "{label}: {} points with invalid intensity read as 0",
                raw.invalid_intensity
            ),
        ));
    }
    if let Some(cells) = &raw.cells {
        match grid_shape(cells, raw.points.len()) {
            Ok(Some(shape)) => {
                if let Some(cloud) = fill_grid(path, &raw, cells, shape)? {
                    return Ok(cloud);
                }
                notes.push(note(
                    path,
                    format!("{label}: two points share a row/column cell; read unorganised"),
                ));
            }
            Ok(None) => {}
            Err(why) => notes.push(note(path, format!("{label}: {why}; read unorganised"))),
        }
    }
    // Unorganised: the points without valid coordinates dropped in place.
    let RawScan {
        mut points,
        mut intensity,
        ..
    } = raw;
    let mut kept = 0;
    for i in 0..points.len() {
        if points[i].is_finite() {
            points[kept] = points[i];
            if let Some(values) = &mut intensity {
                values[kept] = values[i];
            }
            kept += 1;
        }
    }
    let skipped = points.len() - kept;
    if skipped > 0 {
        notes.push(note(
            path,
            format!("{label}: {skipped} points without valid coordinates skipped"),
        ));
    }
    points.truncate(kept);
    if let Some(values) = &mut intensity {
        values.truncate(kept);
    }
    let mut cloud = PointCloud::from_points(points);
    cloud.intensity = intensity;
    Ok(cloud)
}

/// The grid of the row/column indices: `Ok(None)` for no point, `Err(why)` where the indices
/// make no sensible grid.
fn grid_shape(cells: &[(i64, i64)], n: usize) -> std::result::Result<Option<Organized>, String> {
    let Some(&(r0, c0)) = cells.first() else {
        return Ok(None);
    };
    let (mut min_r, mut max_r, mut min_c, mut max_c) = (r0, r0, c0, c0);
    for &(r, c) in cells {
        min_r = min_r.min(r);
        max_r = max_r.max(r);
        min_c = min_c.min(c);
        max_c = max_c.max(c);
    }
    if min_r < 0 || min_c < 0 {
        return Err(format!(
            "negative row/column index (rows {min_r}..={max_r}, columns {min_c}..={max_c})"
        ));
    }
    let rows = (max_r as u64).saturating_add(1);
    let cols = (max_c as u64).saturating_add(1);
    let limit = (n as u64)
        .saturating_mul(GRID_CELLS_PER_POINT)
        .saturating_add(GRID_SLACK)
        .min(1 << 31);
    match rows.checked_mul(cols) {
        Some(total) if total <= limit => Ok(Some(Organized {
            rows: rows as usize,
            cols: cols as usize,
        })),
        _ => Err(format!(
            "a grid of {rows} x {cols} cells is too sparse for {n} points"
        )),
    }
}

/// The organised cloud, or `None` where two points share a cell.
fn fill_grid(
    path: &Path,
    raw: &RawScan,
    cells: &[(i64, i64)],
    shape: Organized,
) -> Result<Option<PointCloud>> {
    let total = shape.rows * shape.cols;
    let mut points = try_filled(path, total, Vec3::NAN, "the E57 grid")?;
    let mut taken = try_filled(path, total, false, "the E57 grid")?;
    let mut intensity = match raw.intensity {
        Some(_) => Some(try_filled(path, total, 0.0f32, "the E57 grid intensities")?),
        None => None,
    };
    for (i, &(r, c)) in cells.iter().enumerate() {
        // In range: grid_shape checked 0 <= r < rows and 0 <= c < cols.
        let cell = r as usize * shape.cols + c as usize;
        if taken[cell] {
            return Ok(None);
        }
        taken[cell] = true;
        points[cell] = raw.points[i];
        if let (Some(grid), Some(values)) = (&mut intensity, &raw.intensity) {
            grid[cell] = values[i];
        }
    }
    let mut cloud = PointCloud::from_points(points);
    cloud.intensity = intensity;
    cloud.organized = Some(shape);
    Ok(Some(cloud))
}

/// The `e57` crate's error as ours: a feature the crate lacks is unsupported, everything else
/// a format error; the crate's text is quoted with control characters escaped.
fn e57_error(path: &Path, context: &str, error: e57::Error) -> InteropError {
    let text = clean(&error.to_string());
    match error {
        e57::Error::NotImplemented { .. } => {
            InteropError::unsupported(path, format!("E57: {context}{text}"))
        }
        _ => InteropError::format(path, format!("not a readable E57 file: {context}{text}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_shape_refuses_sparse_and_negative_grids() {
        let cells = [(0, 0), (0, 1), (1, 0), (1, 1)];
        assert_eq!(
            grid_shape(&cells, 4),
            Ok(Some(Organized { rows: 2, cols: 2 }))
        );
        assert!(grid_shape(&[(-1, 0)], 1).is_err());
        assert!(grid_shape(&[(0, 0), (1_000_000, 1_000_000)], 2).is_err());
        assert_eq!(grid_shape(&[], 0), Ok(None));
    }
}
