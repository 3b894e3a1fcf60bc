//! Registration settings: the method, the nearest-neighbour backend, the correspondence gate
//! and its schedule, the stop criteria, the robust kernel and the optional downsampling.
//!
//! The defaults were chosen by measurement (release build, 2 threads, two 162,841-point
//! virtual-laser scans of the default building 1 m and 5 degrees apart, started 0.3 m / 5
//! degrees off): see the crate documentation for the figures.

use crate::error::{RegistrationError, Result};
use cloud::check_range;
use serde::{Deserialize, Serialize};
use std::str::FromStr;

/// The error metric minimised per iteration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Point-to-point (Besl & McKay; closed-form SVD step of Arun/Horn/Umeyama), as in the
    /// 2009 paper.
    PointToPoint,
    /// Point-to-plane (Chen & Medioni), linearised small-angle Gauss-Newton step.
    PointToPlane,
    /// Generalized ICP (Segal, Haehnel & Thrun 2009), plane-to-plane Mahalanobis cost.
    Gicp,
}

impl Method {
    /// The short name accepted by [`FromStr`] (`p2p`, `p2plane`, `gicp`).
    pub fn short_name(self) -> &'static str {
        match self {
            Method::PointToPoint => "p2p",
            Method::PointToPlane => "p2plane",
            Method::Gicp => "gicp",
        }
    }

    /// Whether the target needs normals (point-to-plane) or covariances (GICP).
    pub(crate) fn needs_surface(self) -> bool {
        !matches!(self, Method::PointToPoint)
    }
}

/// The error of parsing a [`Method`] name.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown registration method '{0}' (expected p2p, p2plane or gicp)")]
pub struct ParseMethodError(pub String);

impl FromStr for Method {
    type Err = ParseMethodError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().replace('-', "_").as_str() {
            "p2p" | "point_to_point" => Ok(Method::PointToPoint),
            "p2plane" | "p2l" | "point_to_plane" => Ok(Method::PointToPlane),
            "gicp" | "generalized_icp" => Ok(Method::Gicp),
            _ => Err(ParseMethodError(s.to_string())),
        }
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.short_name())
    }
}

/// The nearest-neighbour structure over the target points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NnBackend {
    /// The paper's regular grid of buckets ([`crate::BucketGrid`]): exact within one bucket edge.
    Grid,
    /// An exact k-d tree ([`crate::KdTree`], kiddo).
    KdTree,
}

/// Where the ICP iterations run.
///
/// The GPU path (the `gpu` feature, on by default) finds the correspondences and reduces the
/// point-to-point SVD sums or the point-to-plane normal equations on the GPU (wgpu compute,
/// Vulkan); only the 3x3 SVD / 6x6 solve and the stop criteria run on the CPU, with the same
/// loop as the CPU path. GICP and `reject_worst_fraction > 0` run only on the CPU.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Device {
    /// A hardware GPU where there is one and the method runs there (point-to-point,
    /// point-to-plane); otherwise the CPU. A software rasteriser (Mesa's lavapipe) does not
    /// count: it is slower than the CPU path. [`crate::Registrar::description`] says which
    /// was chosen and why.
    #[default]
    Auto,
    /// Always the CPU.
    Cpu,
    /// Always a GPU, a software one (lavapipe) included; no adapter is
    /// [`RegistrationError::Gpu`], GICP or `reject_worst_fraction > 0` is
    /// [`RegistrationError::InvalidParameter`].
    Gpu,
}

impl Device {
    /// The name used in configuration files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Device::Auto => "auto",
            Device::Cpu => "cpu",
            Device::Gpu => "gpu",
        }
    }
}

impl std::fmt::Display for Device {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The error of parsing a [`Device`] name.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown device '{0}' (expected auto, cpu or gpu)")]
pub struct ParseDeviceError(pub String);

impl FromStr for Device {
    type Err = ParseDeviceError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "auto" => Ok(Device::Auto),
            "cpu" => Ok(Device::Cpu),
            "gpu" => Ok(Device::Gpu),
            _ => Err(ParseDeviceError(s.to_string())),
        }
    }
}

/// A robust kernel applied as iteratively re-weighted least squares weights on each pair's
/// residual (point distance for point-to-point and GICP, plane distance for point-to-plane).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum RobustKernel {
    /// Plain least squares: every accepted pair has weight 1.
    #[default]
    None,
    /// Huber: weight 1 up to `k_m`, then `k_m / |r|`.
    Huber {
        /// The residual (metres) where the quadratic part ends.
        k_m: f64,
    },
    /// Cauchy (Lorentzian): weight `1 / (1 + (r / k_m)^2)`.
    Cauchy {
        /// The residual scale (metres).
        k_m: f64,
    },
}

/// Settings of one ICP registration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct IcpConfig {
    /// The error metric.
    pub method: Method,
    /// The nearest-neighbour structure for correspondences.
    pub nn: NnBackend,
    /// Bucket edge of [`NnBackend::Grid`]; correspondences farther than this may be missed, so
    /// the defaults make it as wide as the gate (the grid is then exact).
    pub bucket_size_m: f64,
    /// Iteration limit; reaching it without meeting a stop criterion is
    /// [`RegistrationError::NotConverged`]. 100 by default: a scan that overlaps the map only
    /// along a corridor slides along it a few millimetres an iteration as its new parts come
    /// into the gate (generated office-106 of seeds 106-110: its 25th scan, a third of it
    /// paired, settled on the 42nd iteration 1.0 cm from the truth; 30 failed the sequence).
    /// A scan that converges stops long before; the limit bounds only the ones that do not.
    pub max_iterations: usize,
    /// Correspondence gate of the first iteration.
    pub max_correspondence_distance_m: f64,
    /// The smallest gate: after each iteration the gate shrinks to 3 x the RMSE, but never below
    /// this (set it equal to `max_correspondence_distance_m` to keep the gate fixed). The stop
    /// criteria are checked only on iterations that keep the gate.
    pub final_correspondence_distance_m: f64,
    /// Fraction (0..0.5) of the accepted pairs with the largest distances dropped each iteration.
    pub reject_worst_fraction: f64,
    /// Converged when an iteration moves the source by less than this ...
    pub translation_epsilon_m: f64,
    /// ... and turns it by less than this.
    pub rotation_epsilon_deg: f64,
    /// Also converged when the RMSE changes by less than this fraction between iterations.
    pub rmse_relative_epsilon: f64,
    /// Robust kernel (IRLS weights).
    pub kernel: RobustKernel,
    /// Neighbours used for each normal / covariance.
    pub neighbours_k: usize,
    /// Normals and covariances come from the `neighbours_k` nearest points of a copy of the
    /// cloud downsampled to this voxel edge (raw scans give degenerate, noise-dominated
    /// neighbourhoods along scan lines).
    pub normal_voxel_m: f64,
    /// Downsample the source to this voxel edge inside `register` (None: use every point).
    pub source_voxel_m: Option<f64>,
    /// Downsample the target to this voxel edge when preparing it (None: use every point).
    pub target_voxel_m: Option<f64>,
    /// A result whose fitness (fraction of source points with a correspondence) is below this
    /// is [`RegistrationError::NotConverged`].
    pub min_fitness: f64,
    /// Where the iterations run (see [`Device`]).
    pub device: Device,
    /// Against a target prepared with viewpoints (every sequence map, see
    /// `Target::with_viewpoints`), pairs whose target surface faces away from the source's
    /// sensor are no pairs (on the CPU and on the GPU alike).
    pub reject_back_faces: bool,
    /// Weights each source point by the inverse variance of a laser point at range `r` from
    /// its sensor: `w = 1 / (1 + (r / knee)^2)`. A point's error is its range noise
    /// (`sigma_r`) plus an angular error (`r * sigma_angle`: beam direction, encoder and mount
    /// calibration), so beyond `knee = sigma_r / sigma_angle` far points are less certain;
    /// a downsampled source (one point per voxel) would otherwise give them the weight of
    /// the dense, precise near field. 1 m: a SICK LMS 2xx-class scanner's ~5 mm range noise
    /// (1 sigma) over an angular uncertainty of half a 0.5 degree step of the scanner or of
    /// its rotating unit (5 mm / 0.0044 rad = 1.1 m). 0: every point weighs the same (the
    /// default for pairs, and the 2009 paper's ICP); sequences of stop-and-scan scans use 1 m
    /// (see [`crate::SequenceConfig`]).
    pub range_knee_m: f64,
}

impl Default for IcpConfig {
    fn default() -> Self {
        IcpConfig {
            method: Method::Gicp,
            nn: NnBackend::Grid,
            bucket_size_m: 1.0,
            max_iterations: 100,
            max_correspondence_distance_m: 1.0,
            final_correspondence_distance_m: 0.15,
            reject_worst_fraction: 0.0,
            translation_epsilon_m: 1e-4,
            rotation_epsilon_deg: 0.005,
            rmse_relative_epsilon: 1e-5,
            kernel: RobustKernel::None,
            neighbours_k: 15,
            normal_voxel_m: 0.1,
            source_voxel_m: Some(0.1),
            target_voxel_m: Some(0.1),
            min_fitness: 0.2,
            device: Device::Auto,
            reject_back_faces: true,
            range_knee_m: 0.0,
        }
    }
}

impl IcpConfig {
    /// Plain point-to-point ICP at full resolution, as in the 2009 paper and the reference
    /// benchmarks: a fixed 0.5 m gate (and 0.5 m buckets, so the grid is exact), no
    /// downsampling, up to 100 iterations; the other settings at their defaults.
    pub fn point_to_point() -> Self {
        IcpConfig {
            method: Method::PointToPoint,
            bucket_size_m: 0.5,
            max_correspondence_distance_m: 0.5,
            final_correspondence_distance_m: 0.5,
            source_voxel_m: None,
            target_voxel_m: None,
            max_iterations: 100,
            ..IcpConfig::default()
        }
    }

    /// Checks every value for a meaningful range.
    pub fn validate(&self) -> Result<()> {
        positive("bucket_size_m", self.bucket_size_m, 1e-3, 1e4)?;
        positive(
            "max_correspondence_distance_m",
            self.max_correspondence_distance_m,
            1e-5,
            1e5,
        )?;
        positive(
            "final_correspondence_distance_m",
            self.final_correspondence_distance_m,
            1e-5,
            self.max_correspondence_distance_m,
        )?;
        let iterations = self.max_iterations as f64;
        check_range(
            "max_iterations",
            iterations,
            1.0,
            10_000.0,
            "must be within 1..=10000",
        )?;
        let f = self.reject_worst_fraction;
        if !(f.is_finite() && (0.0..0.5).contains(&f)) {
            return Err(RegistrationError::invalid(
                "reject_worst_fraction",
                f,
                "must be within [0, 0.5)",
            ));
        }
        non_negative("translation_epsilon_m", self.translation_epsilon_m)?;
        non_negative("rotation_epsilon_deg", self.rotation_epsilon_deg)?;
        non_negative("rmse_relative_epsilon", self.rmse_relative_epsilon)?;
        match self.kernel {
            RobustKernel::None => {}
            RobustKernel::Huber { k_m } | RobustKernel::Cauchy { k_m } => {
                positive("kernel.k_m", k_m, 1e-6, 1e5)?
            }
        }
        let k = self.neighbours_k as f64;
        check_range("neighbours_k", k, 3.0, 100.0, "must be within 3..=100")?;
        positive("normal_voxel_m", self.normal_voxel_m, 1e-4, 100.0)?;
        if let Some(v) = self.source_voxel_m {
            positive("source_voxel_m", v, 1e-4, 100.0)?;
        }
        if self.range_knee_m != 0.0 {
            positive("range_knee_m", self.range_knee_m, 1e-3, 1e4)?;
        }
        if let Some(v) = self.target_voxel_m {
            positive("target_voxel_m", v, 1e-4, 100.0)?;
        }
        check_range(
            "min_fitness",
            self.min_fitness,
            0.0,
            1.0,
            "must be within [0, 1]",
        )?;
        if self.device == Device::Gpu {
            if !cfg!(feature = "gpu") {
                return Err(RegistrationError::UnsupportedChoice {
                    name: "device",
                    choice: "gpu".into(),
                    msg: "this build has no GPU support (the registration crate's `gpu` feature \
                          is off); use device = cpu or auto",
                });
            }
            if self.method == Method::Gicp {
                return Err(RegistrationError::UnsupportedChoice {
                    name: "device",
                    choice: "gpu".into(),
                    msg: "the GPU runs point-to-point and point-to-plane only; GICP runs on the \
                          CPU (use device = cpu or auto, or method p2p / p2plane)",
                });
            }
            if self.reject_worst_fraction > 0.0 {
                return Err(RegistrationError::invalid(
                    "reject_worst_fraction",
                    self.reject_worst_fraction,
                    "must be 0 with device = gpu (the GPU reduction cannot drop the worst \
                     pairs); use device = cpu or auto",
                ));
            }
        }
        Ok(())
    }
}

/// `value` must be finite and within `[lo, hi]`.
fn positive(name: &'static str, value: f64, lo: f64, hi: f64) -> Result<()> {
    let msg = format!("must be a finite value within [{lo}, {hi}]");
    Ok(check_range(name, value, lo, hi, msg)?)
}

/// `value` must be finite and not negative.
fn non_negative(name: &'static str, value: f64) -> Result<()> {
    let msg = "must be finite and not negative";
    Ok(check_range(name, value, 0.0, f64::INFINITY, msg)?)
}

#[cfg(test)]
#[path = "config_tests.rs"]
mod tests;
