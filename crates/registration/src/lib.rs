//! ICP registration of point clouds on the CPU for semsim: point-to-point (the 2009 paper's
//! method), point-to-plane and Generalized-ICP, with the paper's bucket grid or a k-d tree for
//! nearest neighbours, robust kernels, and sequential registration of scan series into a map.
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

mod cells;
mod config;
mod correspondences;
mod covariance;
mod downsample;
mod error;
mod gicp;
mod grid;
mod icp;
mod kdtree;
mod kernel;
mod linalg;
mod nearest;
mod point_to_plane;
mod point_to_point;
mod sequence;

pub use config::{IcpConfig, Method, NnBackend, ParseMethodError, RobustKernel};
pub use error::{RegistrationError, Result};
pub use grid::BucketGrid;
pub use icp::{register, register_to, IcpResult, IterationReport, Target};
pub use kdtree::KdTree;
pub use nearest::NearestNeighbors;
pub use sequence::{register_sequence, SequenceConfig, SequenceResult};
