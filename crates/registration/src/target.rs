//! The prepared target: its points (downsampled if configured), their nearest-neighbour
//! structure and, for point-to-plane and GICP, their normals and covariances, built once and
//! reused by every registration against it.

use crate::config::{IcpConfig, Method, NnBackend};
use crate::covariance::{estimate_surface, Surface};
use crate::downsample::{finite_points, voxel_downsample_with};
use crate::error::{RegistrationError, Result};
use crate::nearest::{NearestNeighbors, NnIndex};
use cloud::PointCloud;
use glam::{Mat3, Vec3};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Source of [`Target`] ids (a GPU keeps a target uploaded while its id is the same).
static NEXT_ID: AtomicU64 = AtomicU64::new(1);

/// A target cloud prepared for registration: its points (downsampled if configured), their
/// nearest-neighbour structure and, for point-to-plane and GICP, their normals and
/// covariances. Build it once and register many sources against it with [`crate::register_to`].
pub struct Target {
    points: Vec<Vec3>,
    index: NnIndex,
    normals: Vec<Vec3>,
    covariances: Vec<Mat3>,
    method: Method,
    oriented: bool,
    build_ms: f64,
    bucket_size_m: f64,
    id: u64,
}

impl Target {
    /// Prepares `cloud` as a target with the preparation settings of `config` (`method`, `nn`,
    /// `bucket_size_m`, `target_voxel_m`, `normal_voxel_m`, `neighbours_k`). For point-to-plane
    /// and GICP, points whose neighbourhood is degenerate are left out.
    pub fn new(cloud: &PointCloud, config: &IcpConfig) -> Result<Target> {
        Target::build(cloud, None, config)
    }

    /// As [`Target::new`], with the sensor position (in the target frame) each point was seen
    /// from. For point-to-plane and GICP the normals are then oriented towards their sensor,
    /// and registration rejects every pair whose target point faces away from the source's
    /// sensor (`PointCloud::sensor_origin` moved by the current estimate): a laser cannot see
    /// the back of a surface. This keeps the inside face of a wall from being matched to its
    /// outside face, the classic failure of scans taken on both sides of a thin wall.
    /// Point-to-point targets have no normals and ignore the viewpoints.
    pub fn with_viewpoints(
        cloud: &PointCloud,
        viewpoints: &[Vec3],
        config: &IcpConfig,
    ) -> Result<Target> {
        if viewpoints.len() != cloud.len() {
            return Err(RegistrationError::Mismatch {
                what: "viewpoints",
                msg: format!(
                    "{} viewpoints for {} target points",
                    viewpoints.len(),
                    cloud.len()
                ),
            });
        }
        Target::build(cloud, Some(viewpoints), config)
    }

    fn build(
        cloud: &PointCloud,
        viewpoints: Option<&[Vec3]>,
        config: &IcpConfig,
    ) -> Result<Target> {
        config.validate()?;
        let start = Instant::now();
        let mut points = finite_points(cloud, "target")?;
        let mut views: Vec<Vec3> = match viewpoints {
            Some(v) => cloud
                .points
                .iter()
                .zip(v)
                .filter(|(p, _)| p.is_finite())
                .map(|(_, v)| *v)
                .collect(),
            None => vec![Vec3::ZERO; points.len()],
        };
        if let Some(v) = config.target_voxel_m {
            (points, views) = voxel_downsample_with(&points, &views, v, "target_voxel_m")?;
        }
        let (mut normals, mut covariances) = (Vec::new(), Vec::new());
        let oriented = viewpoints.is_some() && config.method.needs_surface();
        if config.method.needs_surface() {
            let gicp = config.method == Method::Gicp;
            let Surface {
                normals: n,
                covariances: c,
            } = estimate_surface(&points, config.target_voxel_m, config, gicp)?;
            let keep: Vec<usize> = (0..points.len()).filter(|&i| n[i] != Vec3::ZERO).collect();
            normals = keep
                .iter()
                .map(|&i| {
                    let facing = oriented && n[i].dot(views[i] - points[i]) < 0.0;
                    if facing {
                        -n[i]
                    } else {
                        n[i]
                    }
                })
                .collect();
            points = keep.iter().map(|&i| points[i]).collect();
            if gicp {
                covariances = keep.iter().map(|&i| c[i]).collect();
            }
            if points.is_empty() {
                return Err(RegistrationError::EmptyCloud {
                    which: "target (no point with a non-degenerate neighbourhood)".into(),
                });
            }
        }
        let index = NnIndex::build(&points, config.nn, config.bucket_size_m)?;
        Ok(Target {
            points,
            index,
            normals,
            covariances,
            method: config.method,
            oriented,
            build_ms: start.elapsed().as_secs_f64() * 1e3,
            bucket_size_m: config.bucket_size_m,
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
        })
    }

    /// The target points used for correspondences.
    pub fn points(&self) -> &[Vec3] {
        &self.points
    }

    /// Number of target points used.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True if no point is used (never for a built target).
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The nearest-neighbour backend in use.
    pub fn backend(&self) -> NnBackend {
        match self.index {
            NnIndex::Grid(_) => NnBackend::Grid,
            NnIndex::KdTree(_) => NnBackend::KdTree,
        }
    }

    /// The nearest target point (index into [`Target::points`], squared distance) within
    /// `max_distance_m`.
    pub fn nearest(&self, query: Vec3, max_distance_m: f32) -> Option<(u32, f32)> {
        self.index.nearest(query, max_distance_m)
    }

    /// Time spent preparing the target.
    pub fn build_ms(&self) -> f64 {
        self.build_ms
    }

    /// The method the target was prepared for.
    pub fn prepared_for(&self) -> Method {
        self.method
    }

    /// The bucket edge the target was prepared with.
    #[cfg_attr(not(feature = "gpu"), allow(dead_code))]
    pub(crate) fn bucket_size_m(&self) -> f64 {
        self.bucket_size_m
    }

    /// Unique per prepared target (a target never changes after preparation).
    #[cfg_attr(not(feature = "gpu"), allow(dead_code))]
    pub(crate) fn id(&self) -> u64 {
        self.id
    }

    pub(crate) fn index(&self) -> &NnIndex {
        &self.index
    }

    pub(crate) fn normals(&self) -> &[Vec3] {
        &self.normals
    }

    /// The oriented normals, if the target was prepared with viewpoints (see
    /// [`Target::with_viewpoints`]).
    pub(crate) fn oriented_normals(&self) -> Option<&[Vec3]> {
        self.oriented.then_some(self.normals.as_slice())
    }

    pub(crate) fn covariances(&self) -> &[Mat3] {
        &self.covariances
    }

    /// Whether the target was prepared with what `method` needs.
    pub(crate) fn supports(&self, method: Method) -> bool {
        match method {
            Method::PointToPoint => true,
            Method::PointToPlane => self.method != Method::PointToPoint,
            Method::Gicp => self.method == Method::Gicp,
        }
    }
}

impl std::fmt::Debug for Target {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Target")
            .field("points", &self.points.len())
            .field("backend", &self.backend())
            .field("prepared_for", &self.method)
            .field("build_ms", &self.build_ms)
            .finish()
    }
}
