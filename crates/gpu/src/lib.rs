//! GPU registration kernels for semsim: the 2009 paper's parallel nearest-neighbour ICP as
//! wgpu compute shaders (WGSL), portable across vendors and runnable on Mesa's software Vulkan
//! driver (lavapipe) where there is no GPU.
//!
//! One invocation per data point transforms it, finds its bucket in the model cloud's grid,
//! searches that bucket and the 26 around it, and the pairs are reduced on the GPU into the
//! point-to-point SVD sums or the point-to-plane 6x6 normal equations, so only a few dozen floats
//! come back per iteration. The ICP loop itself (SVD, solve, stop criteria) lives in the
//! `registration` crate.
//!
//! ```no_run
//! use gpu::{AdapterChoice, GpuContext, GpuIcp};
//! use glam::{Mat4, Vec3};
//!
//! let points: Vec<Vec3> = (0..1000).map(|i| Vec3::new(i as f32 * 0.01, 0.0, 0.0)).collect();
//! let mut icp = GpuIcp::new(GpuContext::new(AdapterChoice::Any)?)?;
//! icp.set_target(&points, None, 0.2)?;
//! icp.set_source(&points)?;
//! let (sums, _times) = icp.p2p_sums(Mat4::IDENTITY, 0.5, Vec3::ZERO)?;
//! assert_eq!(sums.count as usize, 1000);
//! # Ok::<(), gpu::GpuError>(())
//! ```

#![warn(missing_docs)]

mod context;
mod error;
mod grid;
mod icp_kernels;

pub use context::{AdapterChoice, GpuContext};
pub use error::{GpuError, Result};
pub use icp_kernels::{GpuIcp, GpuKernel, P2pSums, PlaneSystem, StageTimes};
