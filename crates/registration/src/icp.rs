//! The ICP loop (Besl & McKay 1992, as in the 2009 paper): correspondences, one step of the
//! chosen method, composition of the increment, stop criteria.
//!
//! The loop ([`run_loop`]) is shared by the devices: per iteration it asks a [`PairSums`] for
//! the correspondences of the current transform within the current gate, reduced to the
//! method's sums (point-to-point SVD sums or 6x6 normal equations) centred on the moved source
//! centroid; the CPU ([`CpuPairs`]) and the GPU (`crate::device`) differ only there. Solving,
//! composing, the gate schedule and the stop criteria are common.

use crate::config::{IcpConfig, Method};
use crate::correspondences::Correspondences;
use crate::covariance::estimate_surface;
use crate::device::Registrar;
use crate::downsample::{finite_points, voxel_downsample};
use crate::error::{RegistrationError, Result};
use crate::linalg::{increment, motion_size, System6};
use crate::point_to_point::CorrelationSums;
use crate::target::Target;
use crate::{gicp, point_to_plane, point_to_point};
use cloud::PointCloud;
use glam::{Affine3A, DAffine3, DMat4, DVec3, Mat3, Vec3};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Fewest pairs a step needs (six parameters).
const MIN_PAIRS: usize = 6;
/// The first iteration must match at least this fraction of the source (and [`MIN_PAIRS`]),
/// else the clouds do not overlap.
const MIN_OVERLAP_FRACTION: f64 = 0.01;
/// The gate follows this multiple of the last RMSE (never growing, never below the final gate).
const GATE_RMSE_FACTOR: f64 = 3.0;
/// A proposed gate less than this fraction smaller than the current one keeps the current one;
/// the stop criteria are checked only while the gate is kept.
const GATE_MIN_SHRINK: f64 = 0.9;

/// One iteration's figures.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IterationReport {
    /// Iteration number, from 0.
    pub iteration: usize,
    /// Accepted pairs used by the step.
    pub correspondences: usize,
    /// Root mean square point distance of the accepted pairs, before this iteration's update.
    pub rmse_m: f64,
    /// Wall time of the iteration.
    pub time_ms: f64,
}

/// The outcome of a registration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IcpResult {
    /// The estimated transform taking source coordinates to target coordinates.
    pub target_from_source: DAffine3,
    /// Per-iteration figures.
    pub iterations: Vec<IterationReport>,
    /// Whether a stop criterion was met (always true in an `Ok` result).
    pub converged: bool,
    /// RMSE of the last iteration's accepted pairs.
    pub rmse_m: f64,
    /// Fraction of the (downsampled) source points with a correspondence in the last iteration.
    pub fitness: f64,
    /// Wall time of the whole call (target preparation included for [`register`]).
    pub total_ms: f64,
}

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

/// The checks of [`register_to`] and the source's preparation: its finite (downsampled) points.
pub(crate) fn prepare_source(
    target: &Target,
    source: &PointCloud,
    target_from_source_guess: &DAffine3,
    config: &IcpConfig,
) -> Result<Vec<Vec3>> {
    config.validate()?;
    if !target.supports(config.method) {
        return Err(RegistrationError::invalid(
            "method",
            f64::NAN,
            format!(
                "the target was prepared for {} and has no surface estimates for {}",
                target.prepared_for(),
                config.method
            ),
        ));
    }
    if !target_from_source_guess.is_finite() {
        return Err(RegistrationError::invalid(
            "target_from_source_guess",
            f64::NAN,
            "must be finite",
        ));
    }
    let mut points = finite_points(source, "source")?;
    if let Some(v) = config.source_voxel_m {
        points = voxel_downsample(&points, v, "source_voxel_m")?;
    }
    Ok(points)
}

/// The CPU registration of prepared source points.
pub(crate) fn register_points_cpu(
    target: &Target,
    sensor: Vec3,
    points: &[Vec3],
    guess: DAffine3,
    config: &IcpConfig,
) -> Result<IcpResult> {
    let source_cov = if config.method == Method::Gicp {
        estimate_surface(points, config.source_voxel_m, config, true)?.covariances
    } else {
        Vec::new()
    };
    let mut pairs = CpuPairs {
        config,
        target,
        sensor,
        source: points,
        source_cov: &source_cov,
        corr: Correspondences::new(points.len()),
    };
    run_loop(config, points, guess, &mut pairs)
}

/// Turns a finished loop into the outcome: an unconverged or unfit result is
/// [`RegistrationError::NotConverged`].
pub(crate) fn finish(
    mut result: IcpResult,
    start: Instant,
    config: &IcpConfig,
) -> Result<IcpResult> {
    result.total_ms = start.elapsed().as_secs_f64() * 1e3;
    if !result.converged {
        let reason = format!(
            "no stop criterion met in {} iterations",
            config.max_iterations
        );
        return Err(RegistrationError::NotConverged {
            result: Box::new(result),
            reason,
        });
    }
    if result.fitness < config.min_fitness {
        let reason = format!(
            "fitness {:.3} is below min_fitness {}",
            result.fitness, config.min_fitness
        );
        return Err(RegistrationError::NotConverged {
            result: Box::new(result),
            reason,
        });
    }
    Ok(result)
}

/// The sums one step is solved from, with the point they are centred on (the increment they
/// give rotates about it). Built once per iteration, so the size difference does not matter.
#[allow(clippy::large_enum_variant)]
pub(crate) enum StepSums {
    /// Point-to-point: the closed-form SVD step.
    Svd(CorrelationSums, DVec3),
    /// Point-to-plane and GICP: 6x6 Gauss-Newton normal equations.
    Normal(System6, DVec3),
}

impl StepSums {
    /// The increment (in the absolute frame), the pairs used and their summed squared
    /// distances; `None` if the step is undetermined.
    fn solve(&self) -> Option<(DAffine3, usize, f64)> {
        let (centred, reference, pairs, sq_dist) = match self {
            StepSums::Svd(s, r) => (s.solve()?, *r, s.pairs, s.sq_dist),
            StepSums::Normal(s, r) => (increment(&s.solve()?), *r, s.pairs, s.sq_dist),
        };
        let step = DAffine3::from_translation(reference)
            * centred
            * DAffine3::from_translation(-reference);
        step.is_finite().then_some((step, pairs, sq_dist))
    }
}

/// The per-iteration work that differs between devices.
pub(crate) trait PairSums {
    /// Finds the nearest target point of every source point moved by `target_from_source`
    /// within `gate`, and reduces the pairs to the method's sums centred on `reference`.
    /// Returns the number of correspondences found (before any rejection) and the sums.
    fn pair_sums(
        &mut self,
        target_from_source: &DAffine3,
        gate: f64,
        reference: DVec3,
    ) -> Result<(usize, StepSums)>;
}

/// The CPU's correspondences (rayon, hinted grid or k-d tree searches) and reductions.
struct CpuPairs<'a> {
    config: &'a IcpConfig,
    target: &'a Target,
    /// The source's sensor position in the source frame.
    sensor: Vec3,
    source: &'a [Vec3],
    source_cov: &'a [Mat3],
    corr: Correspondences,
}

impl PairSums for CpuPairs<'_> {
    fn pair_sums(
        &mut self,
        t: &DAffine3,
        gate: f64,
        reference: DVec3,
    ) -> Result<(usize, StepSums)> {
        let (c, target) = (self.config, self.target);
        let t32 = Affine3A::from_mat4(DMat4::from(*t).as_mat4());
        self.corr.find(
            target.index(),
            target.points(),
            self.source,
            &t32,
            gate as f32,
            target
                .oriented_normals()
                .filter(|_| c.reject_back_faces)
                .map(|n| (n, t32.transform_point3(self.sensor))),
        );
        let matched = self.corr.matched;
        self.corr.reject_worst(c.reject_worst_fraction);
        let sums = match c.method {
            Method::PointToPoint => StepSums::Svd(
                point_to_point::accumulate(
                    &self.corr,
                    self.source,
                    target.points(),
                    &t32,
                    c.kernel,
                    reference,
                ),
                reference,
            ),
            Method::PointToPlane => StepSums::Normal(
                point_to_plane::accumulate(
                    &self.corr,
                    self.source,
                    target.points(),
                    target.normals(),
                    &t32,
                    c.kernel,
                    reference,
                ),
                reference,
            ),
            // GICP linearises about the origin (its Jacobian uses the absolute moved point).
            Method::Gicp => StepSums::Normal(
                gicp::accumulate(
                    &self.corr,
                    self.source,
                    self.source_cov,
                    target.points(),
                    target.covariances(),
                    t,
                    c.kernel,
                ),
                DVec3::ZERO,
            ),
        };
        Ok((matched, sums))
    }
}

/// The ICP loop over `source` (its prepared points), common to every device.
pub(crate) fn run_loop(
    c: &IcpConfig,
    source: &[Vec3],
    guess: DAffine3,
    pairs_of: &mut dyn PairSums,
) -> Result<IcpResult> {
    let n = source.len();
    // The sums are centred on the moved source centroid (rounded to f32, as the GPU gets it):
    // small coordinates keep the GPU's f32 sums precise and the normal equations conditioned.
    let centroid = source.iter().map(|p| p.as_dvec3()).sum::<DVec3>() / n.max(1) as f64;
    let mut t = guess;
    let mut gate = c.max_correspondence_distance_m;
    let mut reports = Vec::with_capacity(c.max_iterations.min(256));
    let mut prev_rmse: Option<f64> = None;
    let mut converged = false;
    let mut fitness = 0.0;
    for iteration in 0..c.max_iterations {
        let it_start = Instant::now();
        let reference = t.transform_point3(centroid).as_vec3().as_dvec3();
        let (matched, sums) = pairs_of.pair_sums(&t, gate, reference)?;
        fitness = matched as f64 / n as f64;
        let needed = MIN_PAIRS.max((MIN_OVERLAP_FRACTION * n as f64).ceil() as usize);
        if iteration == 0 && matched < needed {
            return Err(RegistrationError::NoOverlap {
                max_correspondence_distance_m: gate,
                correspondences: matched,
                needed,
            });
        }
        let (step, pairs, sq_dist) = match sums.solve() {
            Some(s) if s.1 >= MIN_PAIRS => s,
            other => {
                let pairs = other.map_or(0, |s| s.1);
                let result = IcpResult {
                    target_from_source: t,
                    iterations: reports,
                    converged: false,
                    rmse_m: f64::NAN,
                    fitness,
                    total_ms: 0.0,
                };
                return Err(RegistrationError::NotConverged {
                    result: Box::new(result),
                    reason: format!(
                        "iteration {iteration}: {pairs} usable pairs, the step is undetermined"
                    ),
                });
            }
        };
        t = step * t;
        let rmse = (sq_dist / pairs as f64).sqrt();
        reports.push(IterationReport {
            iteration,
            correspondences: pairs,
            rmse_m: rmse,
            time_ms: it_start.elapsed().as_secs_f64() * 1e3,
        });
        // Adaptive gate: shrink towards GATE_RMSE_FACTOR x RMSE (a large misalignment keeps
        // a wide gate until it is resolved); test for convergence only on a settled gate.
        let proposed = (GATE_RMSE_FACTOR * rmse)
            .min(gate)
            .max(c.final_correspondence_distance_m);
        if proposed < GATE_MIN_SHRINK * gate {
            gate = proposed;
            prev_rmse = None;
            continue;
        }
        let (dt, deg) = motion_size(&step);
        let small_step = dt < c.translation_epsilon_m && deg < c.rotation_epsilon_deg;
        let flat_rmse = prev_rmse
            .is_some_and(|p: f64| p > 0.0 && ((p - rmse) / p).abs() < c.rmse_relative_epsilon)
            || rmse == 0.0;
        if small_step || flat_rmse {
            converged = true;
            break;
        }
        prev_rmse = Some(rmse);
    }
    let rmse_m = reports.last().map_or(f64::NAN, |r| r.rmse_m);
    Ok(IcpResult {
        target_from_source: t,
        iterations: reports,
        converged,
        rmse_m,
        fitness,
        total_ms: 0.0,
    })
}
