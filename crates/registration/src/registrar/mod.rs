//! The device an ICP runs on (`Device`), and [`Registrar`], which keeps it open across
//! registrations: on the GPU, the kernels stay compiled, the target (model) cloud stays
//! uploaded while registrations use the same [`Target`], and the buffers are reused; and the
//! one-call entry points [`register`] and [`register_to`], which open a device per call.
//!
//! The GPU path ([`on_gpu`]) replaces only the per-iteration correspondences and reductions of the
//! shared loop (the `icp` module): per iteration the 4x4 transform goes up and the
//! point-to-point SVD sums (17 floats) or the point-to-plane normal equations (30 floats) come
//! back, computed in f32 on points centred on the moved source centroid; the solve, the gate
//! schedule and the stop criteria run on the CPU in f64, exactly as on the CPU path.

#[cfg(feature = "gpu")]
mod on_gpu;

use crate::config::{Device, IcpConfig, Method};
use crate::error::{RegistrationError, Result};
use crate::icp::cpu::register_points_cpu;
use crate::icp::{finish, prepare_source};
use crate::result::IcpResult;
use crate::target::Target;
use cloud::PointCloud;
use glam::DAffine3;
use std::time::Instant;

/// Registers `source` to `target`: returns `target_from_source`, starting from the guess.
///
/// Prepares the target ([`Target::new`]) and calls [`register_to`]; see there for the errors.
/// Opens the device of `config.device` for this call; to reuse it (and the target's upload to
/// the GPU) across calls, use a [`Registrar`].
pub fn register(
    source: &PointCloud,
    target: &PointCloud,
    target_from_source_guess: DAffine3,
    config: &IcpConfig,
) -> Result<IcpResult> {
    Registrar::new(config)?.register(source, target, target_from_source_guess, config)
}

/// Registers `source` to a prepared target, starting from `target_from_source_guess`.
///
/// The settings that shape the target (`nn`, `bucket_size_m`, `target_voxel_m`, ...) are those
/// it was prepared with; `config.method` must be one the target was prepared for (a GICP target
/// serves every method, a point-to-plane target point-to-plane and point-to-point).
/// Opens the device of `config.device` for this call (see [`Registrar`] to keep it open).
///
/// Errors: [`RegistrationError::EmptyCloud`] / [`RegistrationError::NonFinite`] for a bad
/// source, [`RegistrationError::InvalidParameter`] for a bad config,
/// [`RegistrationError::NoOverlap`] when the first iteration finds (almost) no pairs, and
/// [`RegistrationError::NotConverged`] (carrying the result) when the iterations run out or the
/// fitness is below `min_fitness`; on the GPU, `RegistrationError::Gpu` for a device failure.
pub fn register_to(
    target: &Target,
    source: &PointCloud,
    target_from_source_guess: DAffine3,
    config: &IcpConfig,
) -> Result<IcpResult> {
    Registrar::new(config)?.register_to(target, source, target_from_source_guess, config)
}

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
    Gpu(Box<on_gpu::GpuBackend>),
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
        let backend = on_gpu::GpuBackend::open(auto)?;
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
        Err(RegistrationError::invalid(
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

    /// [`register`] on this device: prepares the target and registers `source` to it.
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
            Err(RegistrationError::NotConverged { mut result, reason }) => {
                total(&mut result);
                Err(RegistrationError::NotConverged { result, reason })
            }
            Err(e) => Err(e),
        }
    }

    /// [`register_to`] on this device. The GPU is used when one is open, the method
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
        let prepared = prepare_source(target, source, &target_from_source_guess, config)?;
        let result = match &mut self.backend {
            #[cfg(feature = "gpu")]
            Backend::Gpu(g) if config.device != Device::Cpu && cpu_only(config).is_none() => {
                let sensor = back_face_test(config, target).then_some(source.sensor_origin);
                g.register(target, &prepared, sensor, target_from_source_guess, config)?
            }
            _ => {
                if config.device == Device::Gpu {
                    return Err(RegistrationError::invalid(
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
                    &prepared,
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
fn auto_reason(e: &RegistrationError) -> String {
    #[cfg(feature = "gpu")]
    if let RegistrationError::Gpu {
        error: gpu::GpuError::NoAdapter(why),
        ..
    } = e
    {
        return format!("no hardware GPU ({why})");
    }
    format!("the GPU could not be used: {e}")
}
