//! The device an ICP runs on ([`Device`]), and [`Registrar`], which keeps it open across
//! registrations: on the GPU, the kernels stay compiled, the target (model) cloud stays
//! uploaded while registrations use the same [`Target`], and the buffers are reused.
//!
//! The GPU path replaces only the per-iteration correspondences and reductions of the shared
//! loop ([`crate::icp`]): per iteration the 4x4 transform goes up and the point-to-point SVD
//! sums (17 floats) or the point-to-plane normal equations (30 floats) come back, computed in
//! f32 on points centred on the moved source centroid; the solve, the gate schedule and the
//! stop criteria run on the CPU in f64, exactly as on the CPU path.

use crate::config::{Device, IcpConfig, Method};
use crate::error::Result;
use crate::icp::{finish, prepare_source, register_points_cpu, IcpResult};
use crate::target::Target;
use cloud::PointCloud;
use glam::DAffine3;
use std::time::Instant;

/// An open device for ICP, reused across registrations (and by
/// [`crate::register_sequence_with`] across the scans of a sequence).
///
/// ```
/// use registration::{Device, IcpConfig, Method, Registrar};
///
/// let config = IcpConfig { method: Method::PointToPlane, device: Device::Cpu, ..IcpConfig::default() };
/// let registrar = Registrar::new(&config).unwrap();
/// assert!(!registrar.uses_gpu());
/// assert_eq!(registrar.description(), "CPU (device = cpu)");
/// ```
pub struct Registrar {
    backend: Backend,
    description: String,
}

enum Backend {
    Cpu,
    #[cfg(feature = "gpu")]
    Gpu(Box<gpu_path::GpuBackend>),
}

impl Registrar {
    /// Opens the device `config.device` asks for:
    ///
    /// - [`Device::Cpu`]: the CPU.
    /// - [`Device::Gpu`]: the best GPU adapter, a software one (lavapipe) included; none is
    ///   `RegistrationError::Gpu` (holding `gpu::GpuError::NoAdapter`).
    /// - [`Device::Auto`]: a hardware GPU if the method runs there (point-to-point,
    ///   point-to-plane without `reject_worst_fraction`) and one is present; otherwise the CPU,
    ///   with the reason in [`Registrar::description`]. A software adapter is not used: lavapipe
    ///   is several times slower than the CPU path.
    ///
    /// The adapter is looked up once per process; every `Registrar` compiles its own kernels.
    pub fn new(config: &IcpConfig) -> Result<Registrar> {
        config.validate()?;
        let cpu = |why: String| Registrar {
            backend: Backend::Cpu,
            description: format!("CPU ({why})"),
        };
        match config.device {
            Device::Cpu => Ok(cpu("device = cpu".into())),
            Device::Gpu => Self::open_gpu(false),
            Device::Auto => {
                if let Some(why) = cpu_only(config) {
                    return Ok(cpu(format!("auto: {why}")));
                }
                if !cfg!(feature = "gpu") {
                    return Ok(cpu("auto: built without the `gpu` feature".into()));
                }
                match Self::open_gpu(true) {
                    Ok(r) => Ok(r),
                    Err(e) => Ok(cpu(format!("auto: {}", auto_reason(&e)))),
                }
            }
        }
    }

    #[cfg(feature = "gpu")]
    fn open_gpu(auto: bool) -> Result<Registrar> {
        let backend = gpu_path::GpuBackend::open(auto)?;
        let description = format!(
            "GPU: {}{}",
            backend.adapter,
            if auto { " (auto)" } else { "" }
        );
        Ok(Registrar {
            backend: Backend::Gpu(Box::new(backend)),
            description,
        })
    }

    #[cfg(not(feature = "gpu"))]
    fn open_gpu(_auto: bool) -> Result<Registrar> {
        Err(crate::error::RegistrationError::invalid(
            "device",
            f64::NAN,
            "this build has no GPU support (the registration crate's `gpu` feature is off)",
        ))
    }

    /// Whether a GPU is open (registrations whose method runs there use it).
    pub fn uses_gpu(&self) -> bool {
        !matches!(self.backend, Backend::Cpu)
    }

    /// What runs the registrations, e.g. `GPU: NVIDIA H100 (discrete GPU, Vulkan)` or
    /// `CPU (auto: no hardware GPU (only software adapters: llvmpipe ...))`.
    pub fn description(&self) -> &str {
        &self.description
    }

    /// [`crate::register`] on this device: prepares the target and registers `source` to it.
    pub fn register(
        &mut self,
        source: &PointCloud,
        target: &PointCloud,
        target_from_source_guess: DAffine3,
        config: &IcpConfig,
    ) -> Result<IcpResult> {
        let start = Instant::now();
        let prepared = Target::new(target, config)?;
        let total = |r: &mut IcpResult| r.total_ms = start.elapsed().as_secs_f64() * 1e3;
        match self.register_to(&prepared, source, target_from_source_guess, config) {
            Ok(mut r) => {
                total(&mut r);
                Ok(r)
            }
            Err(crate::RegistrationError::NotConverged { mut result, reason }) => {
                total(&mut result);
                Err(crate::RegistrationError::NotConverged { result, reason })
            }
            Err(e) => Err(e),
        }
    }

    /// [`crate::register_to`] on this device. The GPU is used when one is open, the method
    /// runs there and `config.device` is not [`Device::Cpu`]; the target is uploaded only when
    /// it differs from the last one registered against.
    pub fn register_to(
        &mut self,
        target: &Target,
        source: &PointCloud,
        target_from_source_guess: DAffine3,
        config: &IcpConfig,
    ) -> Result<IcpResult> {
        let start = Instant::now();
        let points = prepare_source(target, source, &target_from_source_guess, config)?;
        let result = match &mut self.backend {
            #[cfg(feature = "gpu")]
            Backend::Gpu(g) if config.device != Device::Cpu && cpu_only(config).is_none() => {
                let sensor = back_face_test(config, target).then_some(source.sensor_origin);
                g.register(target, &points, sensor, target_from_source_guess, config)?
            }
            _ => {
                if config.device == Device::Gpu {
                    return Err(crate::error::RegistrationError::invalid(
                        "device",
                        f64::NAN,
                        format!(
                            "device = gpu, but this Registrar runs on the {}",
                            self.description
                        ),
                    ));
                }
                register_points_cpu(
                    target,
                    source.sensor_origin,
                    &points,
                    target_from_source_guess,
                    config,
                )?
            }
        };
        finish(result, start, config)
    }
}

impl std::fmt::Debug for Registrar {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Registrar")
            .field("device", &self.description)
            .finish()
    }
}

/// Whether registering against `target` with `config` applies the back-face test.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
fn back_face_test(config: &IcpConfig, target: &Target) -> bool {
    config.reject_back_faces && target.oriented_normals().is_some()
}

/// Why `config` must run on the CPU whatever the device, if it must.
fn cpu_only(config: &IcpConfig) -> Option<String> {
    if config.method == Method::Gicp {
        return Some("GICP runs on the CPU only".into());
    }
    if config.reject_worst_fraction > 0.0 {
        return Some("reject_worst_fraction > 0 runs on the CPU only".into());
    }
    None
}

/// The CPU fallback's reason for `auto` from the error of opening a hardware GPU.
fn auto_reason(e: &crate::RegistrationError) -> String {
    #[cfg(feature = "gpu")]
    if let crate::RegistrationError::Gpu {
        error: gpu::GpuError::NoAdapter(why),
        ..
    } = e
    {
        return format!("no hardware GPU ({why})");
    }
    format!("the GPU could not be used: {e}")
}

/// The GPU's per-iteration sums, in the loop shared with the CPU.
#[cfg(feature = "gpu")]
mod gpu_path {
    use super::*;
    use crate::config::RobustKernel;
    use crate::error::RegistrationError;
    use crate::icp::{run_loop, PairSums, StepSums};
    use crate::linalg::System6;
    use crate::point_to_point::CorrelationSums;
    use glam::{DMat3, DMat4, DVec3, Vec3};
    use gpu::{AdapterChoice, GpuContext, GpuIcp, GpuKernel};
    use std::sync::OnceLock;

    /// The adapters, looked up once per process: hardware only (for `auto`) and any.
    static HARDWARE: OnceLock<std::result::Result<GpuContext, gpu::GpuError>> = OnceLock::new();
    static ANY: OnceLock<std::result::Result<GpuContext, gpu::GpuError>> = OnceLock::new();

    pub(super) struct GpuBackend {
        icp: GpuIcp,
        pub(super) adapter: String,
        /// The target uploaded: its id and the bucket edge used.
        uploaded: Option<(u64, u32)>,
    }

    impl GpuBackend {
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

        pub(super) fn register(
            &mut self,
            target: &Target,
            points: &[Vec3],
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
            self.icp
                .set_source(points)
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
}
