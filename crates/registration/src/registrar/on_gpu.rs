//! The GPU's per-iteration sums (the `gpu` crate's kernels), in the loop shared with the CPU:
//! per iteration the 4x4 transform goes up and the point-to-point SVD sums (17 floats) or the
//! point-to-plane normal equations (30 floats) come back.

use crate::config::RobustKernel;
use crate::config::{IcpConfig, Method};
use crate::error::{RegistrationError, Result};
use crate::icp::point_to_point::CorrelationSums;
use crate::icp::{run_loop, PairSums, PreparedSource, StepSums};
use crate::linalg::System6;
use crate::result::IcpResult;
use crate::target::Target;
use glam::{DAffine3, DMat3, DMat4, DVec3, Vec3};
use gpu::{AdapterChoice, GpuContext, GpuIcp, GpuKernel};
use std::sync::OnceLock;

/// The adapters, looked up once per process: hardware only (for `auto`) and any.
static HARDWARE: OnceLock<std::result::Result<GpuContext, gpu::GpuError>> = OnceLock::new();
static ANY: OnceLock<std::result::Result<GpuContext, gpu::GpuError>> = OnceLock::new();

/// An open GPU with the ICP kernels compiled, and which target it holds.
pub(super) struct GpuBackend {
    icp: GpuIcp,
    pub(super) adapter: String,
    /// The target uploaded: its id and the bucket edge used.
    uploaded: Option<(u64, u32)>,
}

impl GpuBackend {
    /// Opens the best adapter (a hardware one only, if asked) and compiles the kernels.
    pub(super) fn open(hardware_only: bool) -> Result<GpuBackend> {
        let (cell, choice) = if hardware_only {
            (&HARDWARE, AdapterChoice::HardwareOnly)
        } else {
            (&ANY, AdapterChoice::Any)
        };
        let context = "opening a GPU";
        let ctx = cell
            .get_or_init(|| GpuContext::new(choice))
            .clone()
            .map_err(RegistrationError::gpu(context))?;
        let adapter = ctx.adapter_name();
        let icp = GpuIcp::new(ctx).map_err(RegistrationError::gpu("compiling the kernels"))?;
        Ok(GpuBackend {
            icp,
            adapter,
            uploaded: None,
        })
    }

    /// Registers prepared source points on the GPU (uploading the target if it is not the
    /// one held), in the loop shared with the CPU.
    pub(super) fn register(
        &mut self,
        target: &Target,
        prepared: &PreparedSource,
        sensor: Option<Vec3>,
        guess: DAffine3,
        config: &IcpConfig,
    ) -> Result<IcpResult> {
        // Buckets at least as wide as the first gate: the 27-bucket search is then exact.
        let bucket = target
            .bucket_size_m()
            .max(config.max_correspondence_distance_m) as f32;
        let key = (target.id(), bucket.to_bits());
        if self.uploaded != Some(key) {
            self.uploaded = None;
            let normals = (!target.normals().is_empty()).then_some(target.normals());
            self.icp
                .set_target(target.points(), normals, bucket)
                .map_err(RegistrationError::gpu("uploading the target cloud"))?;
            self.uploaded = Some(key);
        }
        let points = &prepared.points;
        self.icp
            .set_weighted_source(points, &prepared.weights)
            .map_err(RegistrationError::gpu("uploading the source cloud"))?;
        self.icp
            .set_back_face_test(sensor)
            .map_err(RegistrationError::gpu("setting up the back-face test"))?;
        let kernel = match config.kernel {
            RobustKernel::None => GpuKernel::None,
            RobustKernel::Huber { k_m } => GpuKernel::Huber(k_m as f32),
            RobustKernel::Cauchy { k_m } => GpuKernel::Cauchy(k_m as f32),
        };
        let mut pairs = GpuPairs {
            icp: &mut self.icp,
            method: config.method,
            kernel,
        };
        run_loop(config, points, guess, &mut pairs)
    }
}

/// The GPU's per-iteration pairs and sums for one registration.
struct GpuPairs<'a> {
    icp: &'a mut GpuIcp,
    method: Method,
    kernel: GpuKernel,
}

impl PairSums for GpuPairs<'_> {
    fn pair_sums(
        &mut self,
        t: &DAffine3,
        gate: f64,
        reference: DVec3,
    ) -> Result<(usize, StepSums)> {
        let m = DMat4::from(*t).as_mat4();
        let r = reference.as_vec3();
        match self.method {
            Method::PointToPoint => {
                let (s, _) = self
                    .icp
                    .p2p_sums_weighted(m, gate as f32, r, self.kernel)
                    .map_err(RegistrationError::gpu("computing point-to-point sums"))?;
                let pairs = s.count.round() as usize;
                let sums = CorrelationSums {
                    weight: s.weight,
                    sum_d: DVec3::from_array(s.sum_p),
                    sum_m: DVec3::from_array(s.sum_q),
                    // Row-major on the GPU; glam is column-major.
                    sum_dm: DMat3::from_cols_array(&s.sum_pq).transpose(),
                    sq_dist: s.sum_d2,
                    pairs,
                };
                Ok((pairs, StepSums::Svd(sums, reference)))
            }
            Method::PointToPlane => {
                let (s, _) = self
                    .icp
                    .p2plane_system(m, gate as f32, r, self.kernel)
                    .map_err(RegistrationError::gpu("computing point-to-plane sums"))?;
                let pairs = s.count.round() as usize;
                let mut sys = System6 {
                    b: s.jtr,
                    sq_dist: s.sum_d2,
                    pairs,
                    ..System6::default()
                };
                let mut k = 0;
                for a in 0..6 {
                    for b in a..6 {
                        sys.h[a][b] = s.jtj_upper[k];
                        k += 1;
                    }
                }
                Ok((pairs, StepSums::Normal(sys, reference)))
            }
            Method::Gicp => Err(RegistrationError::invalid(
                "device",
                f64::NAN,
                "GICP runs on the CPU only",
            )),
        }
    }
}
