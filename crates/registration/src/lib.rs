//! ICP registration of point clouds on the CPU for semsim: point-to-point (the 2009 paper's
//! method), point-to-plane and Generalized-ICP, with the paper's bucket grid or a k-d tree for
//! nearest neighbours, robust kernels, and sequential registration of scan series into a map.
//!
//! - [`register`] registers a source cloud to a target cloud from a guess of
//!   `target_from_source`; [`Target`] + [`register_to`] reuse a prepared target.
//! - [`register_sequence`] registers scans one after another against the growing map, starting
//!   each from the odometry; without odometry (and where ICP from the odometry fails) the
//!   initial alignment searches each scan's yaw and position against the map first
//!   ([`InitialAlignment`], `SequenceConfig::initial_alignment`); an ICP that moves a scan far
//!   from the odometry's guess is checked against a narrow-gate ICP from the guess and an ICP
//!   from the initial alignment's search ([`CorrectionCheck`]).
//! - [`IcpConfig`] holds every setting; its defaults are GICP on 10 cm voxels with a 1 m
//!   correspondence gate that adapts to 3 x RMSE (never below 0.15 m), and
//!   [`IcpConfig::point_to_point`] is the paper's method at full resolution.
//! - [`drop_transients`] takes out of registered scans what moved between them (a person
//!   walking past one scan): points no other scan saw, in space another scan saw through
//!   ([`TransientConfig`]).
//! - [`BucketGrid`] and [`KdTree`] implement [`NearestNeighbors`].
//! - [`Device`] (`IcpConfig::device`: `auto`, `cpu`, `gpu`) says where the iterations run;
//!   a [`Registrar`] keeps the device open (and, on a GPU, the target uploaded) across
//!   registrations. Point-to-point and point-to-plane run on the GPU through the `gpu` crate
//!   (feature `gpu`, default on); the loop is the same, only each iteration's correspondences
//!   and sums come from the GPU (f32, centred on the moved source centroid), and the result
//!   equals the CPU path's within 1e-7 m on the tests' pairs. `auto` ignores software
//!   adapters (lavapipe): they are slower than the CPU.
//!
//! # Pipeline
//! Missing returns (NaN in organised clouds) are skipped, the clouds optionally voxel-downsampled;
//! point-to-plane and GICP estimate normals / plane-regularised covariances on a copy
//! downsampled to `normal_voxel_m` (raw scan-line neighbourhoods are degenerate) and drop
//! degenerate target points. Each iteration finds the nearest target point of every moved source
//! point within the gate (rayon over source points, each search hinted with the point's previous
//! correspondence and its scan-order predecessor's match), optionally rejects the worst pairs,
//! solves one step (closed-form SVD, or 6x6 Gauss-Newton normal equations accumulated in f64 by
//! a parallel reduction, with IRLS kernel weights) and composes the increment. It stops when a
//! step moves less than `translation_epsilon_m` and `rotation_epsilon_deg`, the RMSE changes by
//! less than `rmse_relative_epsilon`, or, on the final gate, a step undoes the one before (a
//! pair leaving and entering the gate by turns); running out of iterations, or ending with a
//! fitness below `min_fitness`, is [`RegistrationError::NotConverged`], which carries the
//! result.
//!
//! # Choices
//! Measured (figures and conditions in `bench/results/README.md`, "Registration measurements";
//! rerun with `cargo test --release -p registration --test measure -- --ignored --nocapture`):
//! the grid is the default backend (hinted searches make it 2.5x faster
//! than the k-d tree per query); buckets as wide as the gate (the grid is then exact, and wider
//! buckets cost little once searches are hinted); buckets cut into at most 3 x 3 x 3 sub-cells
//! (finer cuts measured slower); GICP on 10 cm voxels as the default method.
//!
//! # Known limits
//! - Point-to-point ICP cannot pin the axis of a corridor (as the 2009 paper's method, Open3D's and
//!   small_gicp's): use point-to-plane or GICP there.
//! - Every method is local: from a guess farther off than the gate (or rotated so far that
//!   distant points move beyond it) it converges to a wrong pose with a good fitness. The
//!   initial alignment of sequences is global within the scan's reach of the previous scan's
//!   sensor, assuming levelled scans on one floor: a scan taken farther away than it sees, or
//!   one of several rooms that look alike from the same distance, can land in the wrong place.
//! - On the 2009 3DTK corridor scans, GICP and point-to-plane on 5 cm voxels land 1-1.5 degrees
//!   (pitch) from the 2009 registration, point-to-point on 2 cm voxels within 0.35 degrees.
//! - Max-range returns (e.g. 3DTK's 32.76 m "no echo" points) are not filtered here.
//!
//! ```
//! use cloud::PointCloud;
//! use glam::{DAffine3, DVec3, Vec3};
//! use registration::{register, IcpConfig, Method};
//!
//! // Three walls of a room corner, 2 cm apart, and the same seen from 5 cm further along x.
//! let mut wall = Vec::new();
//! for i in 0..60 {
//!     for j in 0..60 {
//!         let (a, b) = (i as f32 * 0.02, j as f32 * 0.02);
//!         wall.extend([Vec3::new(a, b, 0.0), Vec3::new(a, 0.0, b), Vec3::new(0.0, a, b)]);
//!     }
//! }
//! let target = PointCloud::from_points(wall.clone());
//! let source = PointCloud::from_points(wall.iter().map(|p| *p - Vec3::new(0.05, 0.0, 0.0)).collect());
//! let config = IcpConfig { method: Method::PointToPlane, ..IcpConfig::default() };
//! let result = register(&source, &target, DAffine3::IDENTITY, &config).unwrap();
//! assert!(result.target_from_source.translation.abs_diff_eq(DVec3::new(0.05, 0.0, 0.0), 1e-3));
//! assert!(result.converged && result.fitness > 0.9);
//! ```

#![warn(missing_docs)]

mod cells;
mod config;
mod covariance;
mod downsample;
mod error;
mod icp;
mod initial;
mod linalg;
mod long_correction;
mod nearest;
mod registrar;
mod result;
mod sequence;
mod target;
mod transients;

pub use config::{
    Device, IcpConfig, Method, NnBackend, ParseDeviceError, ParseMethodError, RobustKernel,
};
pub use error::{RegistrationError, Result};
pub use initial::{InitialAlignment, InitialAlignmentReport};
pub use long_correction::{CheckedEnd, CorrectionCheck, EndScore};
pub use nearest::grid::BucketGrid;
pub use nearest::kdtree::KdTree;
pub use nearest::NearestNeighbors;
pub use registrar::{register, register_to, Registrar};
pub use result::{IcpResult, IterationReport};
pub use sequence::{register_sequence, register_sequence_with, SequenceConfig, SequenceResult};
pub use target::Target;
pub use transients::{drop_transients, find_transients, TransientConfig};
