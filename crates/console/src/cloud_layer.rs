//! The registered point cloud as an optional layer of the page (`--cloud map.pcd`): read,
//! downsampled on the server with a voxel grid to at most [`MAX_CLOUD_POINTS`] points, and sent
//! as one compact binary body (`/api/cloud.bin`: little-endian `f32` x, y, z per point in
//! semsim's frame, then one class code byte per point) described by `/api/cloud.json` (point
//! count, voxel edge, whether classes are known, height range). The page colours it by class
//! (the world's class colours) or by height.

use crate::error::{ConsoleError, Result};
use axum::body::Bytes;
use cloud::{EntityClass, PointCloud};
use serde::Serialize;
use std::path::Path;

/// The most points sent to a page: enough to show a building's surfaces at a few centimetres,
/// few enough that software WebGL still draws it and the body stays under 3 MB (13 bytes a
/// point).
pub const MAX_CLOUD_POINTS: usize = 200_000;

/// The smallest voxel edge tried first (m): finer than a laser scanner's range noise, so a
/// cloud that already fits is kept as is.
const FIRST_VOXEL_M: f64 = 0.02;

/// What `/api/cloud.json` says about the layer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CloudInfo {
    /// The file it came from (its name only).
    pub source: String,
    /// Points in the file (finite ones).
    pub points_in_file: usize,
    /// Points sent.
    pub points: usize,
    /// The voxel edge used (m).
    pub voxel_m: f64,
    /// Whether the points carry classes (the PCD `class` field): else every code is unknown.
    pub classes: bool,
    /// The lowest point's height (m).
    pub z_min_m: f64,
    /// The highest point's height (m).
    pub z_max_m: f64,
}

/// A downsampled cloud ready to serve.
#[derive(Clone)]
pub struct CloudLayer {
    /// What it is.
    pub info: CloudInfo,
    /// `/api/cloud.bin`: positions (`f32` x, y, z, little-endian), then class codes (`u8`).
    pub bytes: Bytes,
}

impl std::fmt::Debug for CloudLayer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CloudLayer")
            .field("info", &self.info)
            .field("bytes", &self.bytes.len())
            .finish()
    }
}

impl CloudLayer {
    /// Reads a cloud file (any format semsim reads) and downsamples it to at most
    /// `max_points` points; errors name the file.
    pub fn from_file(path: &Path, max_points: usize) -> Result<CloudLayer> {
        let cloud = cloud::io::read_cloud(path)?;
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        CloudLayer::from_cloud(&cloud, &name, max_points).map_err(|msg| ConsoleError::CloudLayer {
            path: path.to_path_buf(),
            msg,
        })
    }

    /// Downsamples `cloud` to at most `max_points` (at least 1) points: a voxel grid whose
    /// edge grows until the count fits (a surface's count goes with the edge squared), then,
    /// should a pathological cloud still not fit, every k-th point.
    pub fn from_cloud(
        cloud: &PointCloud,
        source: &str,
        max_points: usize,
    ) -> std::result::Result<CloudLayer, String> {
        let max_points = max_points.max(1);
        let finite = cloud.without_invalid();
        if finite.is_empty() {
            return Err("the cloud has no finite point".into());
        }
        let mut voxel_m = FIRST_VOXEL_M;
        let mut down = cloud::voxel_downsample(&finite, voxel_m).map_err(|e| e.to_string())?;
        for _ in 0..16 {
            if down.len() <= max_points {
                break;
            }
            let ratio = down.len() as f64 / max_points as f64;
            voxel_m *= ratio.sqrt().max(1.1) * 1.02;
            down = cloud::voxel_downsample(&finite, voxel_m).map_err(|e| e.to_string())?;
        }
        if down.len() > max_points {
            let keep: Vec<usize> = (0..down.len())
                .step_by(down.len().div_ceil(max_points))
                .collect();
            down = down.select(&keep);
        }
        Ok(CloudLayer::encode(&down, source, finite.len(), voxel_m))
    }

    fn encode(down: &PointCloud, source: &str, points_in_file: usize, voxel_m: f64) -> Self {
        let n = down.len();
        let mut bytes = Vec::with_capacity(n * 13);
        let (mut z_min, mut z_max) = (f32::INFINITY, f32::NEG_INFINITY);
        for p in &down.points {
            for c in [p.x, p.y, p.z] {
                bytes.extend_from_slice(&c.to_le_bytes());
            }
            z_min = z_min.min(p.z);
            z_max = z_max.max(p.z);
        }
        match &down.labels {
            Some(labels) => bytes.extend(labels.iter().map(|l| l.class.code())),
            None => bytes.extend(std::iter::repeat_n(EntityClass::Unknown.code(), n)),
        }
        CloudLayer {
            info: CloudInfo {
                source: source.to_string(),
                points_in_file,
                points: n,
                voxel_m,
                classes: down.labels.is_some(),
                z_min_m: f64::from(z_min),
                z_max_m: f64::from(z_max),
            },
            bytes: Bytes::from(bytes),
        }
    }

    /// `/api/cloud.json`.
    pub fn info_json(&self) -> String {
        serde_json::to_string(&self.info).unwrap_or_else(|_| "null".into())
    }
}

/// The class codes by name, for the page (`/api/cloud.json` has the codes only).
pub(crate) fn class_names_json() -> String {
    let names: Vec<(u8, &str)> = (0..=u8::MAX)
        .filter_map(EntityClass::from_code)
        .map(|c| (c.code(), c.name()))
        .collect();
    serde_json::to_string(&names).unwrap_or_else(|_| "[]".into())
}

#[cfg(test)]
mod tests {
    use super::*;
    use cloud::Label;
    use glam::Vec3;

    /// A 10 m x 3 m wall sampled every 5 mm: 1.2 million points.
    fn dense_wall() -> PointCloud {
        let mut points = vec![];
        for i in 0..2000 {
            for j in 0..600 {
                points.push(Vec3::new(i as f32 * 0.005, 1.0, j as f32 * 0.005));
            }
        }
        let mut c = PointCloud::from_points(points);
        c.labels = Some(vec![
            Label {
                entity: 3,
                class: EntityClass::Wall,
            };
            c.points.len()
        ]);
        c
    }

    #[test]
    fn a_dense_cloud_is_downsampled_under_the_bound_and_keeps_its_classes() {
        let c = dense_wall();
        let layer = CloudLayer::from_cloud(&c, "wall.pcd", 20_000).expect("layer");
        let info = &layer.info;
        assert!(info.points <= 20_000 && info.points > 5_000, "{info:?}");
        assert_eq!(info.points_in_file, 1_200_000);
        assert!(info.classes);
        assert_eq!(layer.bytes.len(), info.points * 13);
        // The class codes follow the positions.
        let codes = &layer.bytes[info.points * 12..];
        assert!(codes.iter().all(|c| *c == EntityClass::Wall.code()));
        // The positions are the wall's (y = 1, 0 <= z <= 3), little-endian f32.
        let y = f32::from_le_bytes(layer.bytes[4..8].try_into().expect("4 bytes"));
        assert!((y - 1.0).abs() < 1e-4, "{y}");
        assert!(info.z_min_m >= 0.0 && info.z_max_m <= 3.0 && info.z_max_m > 2.5);
    }

    #[test]
    fn a_small_cloud_without_classes_is_kept_and_marked_unknown() {
        let c = PointCloud::from_points(vec![Vec3::ZERO, Vec3::new(1.0, 0.0, 2.0)]);
        let layer = CloudLayer::from_cloud(&c, "two.pcd", MAX_CLOUD_POINTS).expect("layer");
        assert_eq!(layer.info.points, 2);
        assert!(!layer.info.classes);
        assert_eq!(&layer.bytes[24..], &[EntityClass::Unknown.code(); 2]);
        assert!(CloudLayer::from_cloud(&PointCloud::default(), "none", 10).is_err());
        assert!(class_names_json().contains("\"wall\""));
    }
}
