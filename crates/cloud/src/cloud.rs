//! The point cloud type: positions in metres (right-handed, z up) with optional
//! intensity, ground-truth labels and organised (rows x cols) shape.

use crate::class::EntityClass;
use crate::error::{CloudError, Result};
use glam::{Affine3A, DAffine3, Quat, Vec3};
use serde::{Deserialize, Serialize};

/// A per-point label: which entity of the building the point lies on, and its class.
/// Entity 0 means "no entity".
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub struct Label {
    /// Entity id (0 = none).
    pub entity: u32,
    /// Entity class.
    pub class: EntityClass,
}

/// The grid shape of an organised cloud: point `(row, col)` is at index `row * cols + col`.
/// For a rotating 2D laser a row is one line scan (`cols` beams) and there is one row per rotation step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Organized {
    /// Number of rows (PCD `HEIGHT`).
    pub rows: usize,
    /// Number of columns (PCD `WIDTH`).
    pub cols: usize,
}

/// An axis-aligned bounding box in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Minimum corner.
    pub min: Vec3,
    /// Maximum corner.
    pub max: Vec3,
}

impl Aabb {
    /// The box's extent along each axis.
    pub fn size(&self) -> Vec3 {
        self.max - self.min
    }
}

/// A point cloud. `points` is always present; the optional channels, when present,
/// have exactly one entry per point. In an organised cloud a missing return is a point
/// whose three coordinates are NaN (the PCL convention); unorganised clouds hold only finite points.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PointCloud {
    /// Positions in metres, in the cloud's frame (the sensor frame for a raw scan).
    pub points: Vec<Vec3>,
    /// Optional intensity per point.
    pub intensity: Option<Vec<f32>>,
    /// Optional label per point.
    pub labels: Option<Vec<Label>>,
    /// Optional ASPRS classification code per point (LAS `classification`: 2 ground, 6
    /// building...), kept from the files that carry it and written to the formats that can.
    pub classification: Option<Vec<u8>>,
    /// Organised shape, if the cloud is a grid.
    pub organized: Option<Organized>,
    /// Sensor origin in the cloud's frame (PCD `VIEWPOINT` translation).
    pub sensor_origin: Vec3,
    /// Sensor orientation in the cloud's frame (PCD `VIEWPOINT` rotation).
    pub sensor_orientation: Quat,
}

impl PointCloud {
    /// An unorganised cloud of the given points, sensor at the origin.
    pub fn from_points(points: Vec<Vec3>) -> Self {
        PointCloud {
            points,
            sensor_orientation: Quat::IDENTITY,
            ..Default::default()
        }
    }

    /// Number of points (missing returns of an organised cloud included).
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True if the cloud holds no point at all.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Checks that the channels and the organised shape agree with the point count.
    pub fn validate(&self) -> Result<()> {
        let n = self.points.len();
        if let Some(i) = &self.intensity {
            if i.len() != n {
                return Err(CloudError::Inconsistent(format!(
                    "{} intensities for {n} points",
                    i.len()
                )));
            }
        }
        if let Some(l) = &self.labels {
            if l.len() != n {
                return Err(CloudError::Inconsistent(format!(
                    "{} labels for {n} points",
                    l.len()
                )));
            }
        }
        if let Some(c) = &self.classification {
            if c.len() != n {
                return Err(CloudError::Inconsistent(format!(
                    "{} classifications for {n} points",
                    c.len()
                )));
            }
        }
        if let Some(o) = self.organized {
            if o.rows.checked_mul(o.cols) != Some(n) {
                return Err(CloudError::Inconsistent(format!(
                    "organised shape {} x {} does not hold {n} points",
                    o.rows, o.cols
                )));
            }
        }
        Ok(())
    }

    /// True where point `i` is a real return (all coordinates finite).
    pub fn is_valid(&self, i: usize) -> bool {
        self.points[i].is_finite()
    }

    /// Number of valid (finite) points.
    pub fn valid_count(&self) -> usize {
        self.points.iter().filter(|p| p.is_finite()).count()
    }

    /// The bounding box of the finite points, `None` if there is none.
    pub fn bounding_box(&self) -> Option<Aabb> {
        let mut it = self.points.iter().filter(|p| p.is_finite());
        let first = *it.next()?;
        let (min, max) = it.fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        Some(Aabb { min, max })
    }

    /// A copy without missing returns (and so without organised shape).
    pub fn without_invalid(&self) -> PointCloud {
        let keep: Vec<usize> = (0..self.len()).filter(|&i| self.is_valid(i)).collect();
        let mut out = self.select(&keep);
        if keep.len() == self.len() {
            out.organized = self.organized;
        }
        out
    }

    /// The points at the given indices, with their channels, unorganised.
    pub fn select(&self, indices: &[usize]) -> PointCloud {
        PointCloud {
            points: indices.iter().map(|&i| self.points[i]).collect(),
            intensity: self
                .intensity
                .as_ref()
                .map(|v| indices.iter().map(|&i| v[i]).collect()),
            labels: self
                .labels
                .as_ref()
                .map(|v| indices.iter().map(|&i| v[i]).collect()),
            classification: self
                .classification
                .as_ref()
                .map(|v| indices.iter().map(|&i| v[i]).collect()),
            organized: None,
            sensor_origin: self.sensor_origin,
            sensor_orientation: self.sensor_orientation,
        }
    }

    /// Applies `target_from_cloud` to every point and to the sensor pose (NaN stays NaN).
    pub fn transform(&mut self, target_from_cloud: &DAffine3) {
        let t = Affine3A::from_mat4(target_from_cloud.to_mat4_f32());
        for p in &mut self.points {
            *p = t.transform_point3(*p);
        }
        self.sensor_origin = t.transform_point3(self.sensor_origin);
        let (_, rot, _) = target_from_cloud.to_scale_rotation_translation();
        self.sensor_orientation = (rot.as_quat() * self.sensor_orientation).normalize();
    }

    /// Fails with [`CloudError::NonFinite`] if an unorganised cloud holds a non-finite point,
    /// or an organised one a point that is neither finite nor all-NaN.
    pub fn check_finite(&self, path: &std::path::Path) -> Result<()> {
        for (index, p) in self.points.iter().enumerate() {
            let missing = self.organized.is_some() && p.x.is_nan() && p.y.is_nan() && p.z.is_nan();
            if !p.is_finite() && !missing {
                return Err(CloudError::NonFinite {
                    path: path.to_path_buf(),
                    index,
                    value: p.to_array(),
                });
            }
        }
        Ok(())
    }
}

trait ToMat4F32 {
    fn to_mat4_f32(&self) -> glam::Mat4;
}

impl ToMat4F32 for DAffine3 {
    fn to_mat4_f32(&self) -> glam::Mat4 {
        glam::DMat4::from(*self).as_mat4()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounding_box_ignores_missing_returns() {
        let mut c = PointCloud::from_points(vec![
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::NAN,
            Vec3::new(-1.0, 5.0, 0.0),
            Vec3::new(0.0, 0.0, 0.0),
        ]);
        c.organized = Some(Organized { rows: 2, cols: 2 });
        let b = c.bounding_box().expect("has points");
        assert_eq!(b.min, Vec3::new(-1.0, 0.0, 0.0));
        assert_eq!(b.max, Vec3::new(1.0, 5.0, 3.0));
        assert_eq!(c.valid_count(), 3);
        assert!(c.check_finite(std::path::Path::new("x")).is_ok());
        c.organized = None;
        assert!(matches!(
            c.check_finite(std::path::Path::new("x")),
            Err(CloudError::NonFinite { index: 1, .. })
        ));
    }

    #[test]
    fn transform_moves_points_and_sensor() {
        let mut c = PointCloud::from_points(vec![Vec3::X]);
        let t = DAffine3::from_rotation_translation(
            glam::DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2),
            glam::DVec3::new(1.0, 0.0, 0.5),
        );
        c.transform(&t);
        assert!((c.points[0] - Vec3::new(1.0, 1.0, 0.5)).length() < 1e-6);
        assert!((c.sensor_origin - Vec3::new(1.0, 0.0, 0.5)).length() < 1e-6);
    }
}
