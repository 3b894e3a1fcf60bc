//! The ICP loop (Besl & McKay 1992, as in the 2009 paper): correspondences, one step of the
//! chosen method, composition of the increment, stop criteria.

use crate::config::{IcpConfig, Method};
use crate::correspondences::Correspondences;
use crate::covariance::estimate_surface;
use crate::downsample::{finite_points, voxel_downsample};
use crate::error::{RegistrationError, Result};
use crate::linalg::{increment, motion_size};
use crate::target::Target;
use crate::{gicp, point_to_plane, point_to_point};
use cloud::PointCloud;
use glam::{Affine3A, DAffine3, DMat4, Mat3, Vec3};
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
pub fn register(
    source: &PointCloud,
    target: &PointCloud,
    target_from_source_guess: DAffine3,
    config: &IcpConfig,
) -> Result<IcpResult> {
    let start = Instant::now();
    let prepared = Target::new(target, config)?;
    let total = |r: &mut IcpResult| r.total_ms = start.elapsed().as_secs_f64() * 1e3;
    match register_to(&prepared, source, target_from_source_guess, config) {
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

/// Registers `source` to a prepared target, starting from `target_from_source_guess`.
///
/// The settings that shape the target (`nn`, `bucket_size_m`, `target_voxel_m`, ...) are those
/// it was prepared with; `config.method` must be one the target was prepared for (a GICP target
/// serves every method, a point-to-plane target point-to-plane and point-to-point).
///
/// Errors: [`RegistrationError::EmptyCloud`] / [`RegistrationError::NonFinite`] for a bad
/// source, [`RegistrationError::InvalidParameter`] for a bad config,
/// [`RegistrationError::NoOverlap`] when the first iteration finds (almost) no pairs, and
/// [`RegistrationError::NotConverged`] (carrying the result) when the iterations run out or the
/// fitness is below `min_fitness`.
pub fn register_to(
    target: &Target,
    source: &PointCloud,
    target_from_source_guess: DAffine3,
    config: &IcpConfig,
) -> Result<IcpResult> {
    let start = Instant::now();
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
    let source_cov = if config.method == Method::Gicp {
        estimate_surface(&points, config.source_voxel_m, config, true)?.covariances
    } else {
        Vec::new()
    };
    let mut state = Loop {
        config,
        target,
        sensor: source.sensor_origin,
        source: &points,
        source_cov: &source_cov,
        corr: Correspondences::new(points.len()),
    };
    let mut result = state.run(target_from_source_guess)?;
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

/// The state of one registration.
struct Loop<'a> {
    config: &'a IcpConfig,
    target: &'a Target,
    /// The source's sensor position in the source frame.
    sensor: Vec3,
    source: &'a [Vec3],
    source_cov: &'a [Mat3],
    corr: Correspondences,
}

impl Loop<'_> {
    fn run(&mut self, guess: DAffine3) -> Result<IcpResult> {
        let c = self.config;
        let n = self.source.len();
        let mut t = guess;
        let mut gate = c.max_correspondence_distance_m;
        let mut reports = Vec::with_capacity(c.max_iterations.min(256));
        let mut prev_rmse: Option<f64> = None;
        let mut converged = false;
        let mut fitness = 0.0;
        for iteration in 0..c.max_iterations {
            let it_start = Instant::now();
            let t32 = Affine3A::from_mat4(DMat4::from(t).as_mat4());
            self.corr.find(
                self.target.index(),
                self.target.points(),
                self.source,
                &t32,
                gate as f32,
                self.target
                    .oriented_normals()
                    .map(|n| (n, t32.transform_point3(self.sensor))),
            );
            let matched = self.corr.matched;
            fitness = matched as f64 / n as f64;
            let needed = MIN_PAIRS.max((MIN_OVERLAP_FRACTION * n as f64).ceil() as usize);
            if iteration == 0 && matched < needed {
                return Err(RegistrationError::NoOverlap {
                    max_correspondence_distance_m: gate,
                    correspondences: matched,
                    needed,
                });
            }
            self.corr.reject_worst(c.reject_worst_fraction);
            let step = self.step(&t, &t32);
            let (step, pairs, sq_dist) = match step {
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

    /// One step of the configured method: the increment, the pairs used and their summed
    /// squared distances; `None` if the step is undetermined.
    fn step(&self, t: &DAffine3, t32: &Affine3A) -> Option<(DAffine3, usize, f64)> {
        let (c, target) = (self.config, self.target);
        match c.method {
            Method::PointToPoint => {
                let s = point_to_point::accumulate(
                    &self.corr,
                    self.source,
                    target.points(),
                    t32,
                    c.kernel,
                );
                Some((s.solve()?, s.pairs, s.sq_dist))
            }
            Method::PointToPlane => {
                let s = point_to_plane::accumulate(
                    &self.corr,
                    self.source,
                    target.points(),
                    target.normals(),
                    t32,
                    c.kernel,
                );
                Some((increment(&s.solve()?), s.pairs, s.sq_dist))
            }
            Method::Gicp => {
                let s = gicp::accumulate(
                    &self.corr,
                    self.source,
                    self.source_cov,
                    target.points(),
                    target.covariances(),
                    t,
                    c.kernel,
                );
                Some((increment(&s.solve()?), s.pairs, s.sq_dist))
            }
        }
    }
}
