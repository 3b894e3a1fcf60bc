//! The outcome of a registration: the transform, its figures per iteration, and whether it
//! converged.

use glam::DAffine3;
use serde::{Deserialize, Serialize};

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
    /// Wall time of the whole call (target preparation included for [`crate::register`]).
    pub total_ms: f64,
}
