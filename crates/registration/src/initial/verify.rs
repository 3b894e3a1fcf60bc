//! The verification of pose hypotheses in 3D: each one refined by a coarse point-to-plane ICP
//! against the map downsampled to the search's cell, then scored on the same source points
//! with the same gate.
//!
//! The score is agreement minus weighted contradiction, both per source point (the same
//! points for every hypothesis):
//! - agreement: each source point scores `1 - (r / g)^2` for its plane distance `r` to the
//!   nearest map point within two cells (a truncated quadratic, as a robust M-estimator's
//!   cost, with `g` half a cell; 0 beyond `g` or without a neighbour), averaged over the
//!   source: it rewards overlap and residual at once;
//! - contradiction: the source's points that land where the map's sensors saw free space,
//!   and the map's that land where the source's sensor saw free space ([`SeenFree`]), per
//!   source point, weighted by the ratio of their log-likelihoods (see
//!   `contradiction_weight`). Without it a scan that sees new rooms
//!   loses to a wrong pose that puts all of it inside the mapped part (a corridor seen from
//!   its other end); with it, what only one side saw is no evidence either way.

use super::seen::SeenFree;
use crate::config::{Device, IcpConfig, Method, RobustKernel};
use crate::error::{RegistrationError, Result};
use crate::registrar::register_to;
use crate::target::Target;
use cloud::PointCloud;
use glam::{DAffine3, Vec3};
use rayon::prelude::*;

/// The probability that a laser ray passes a real surface without a return (glass, black
/// or wet surfaces, a person walking by): a conservative 5 %.
const SEE_THROUGH_PROBABILITY: f64 = 0.05;
/// The prior probability that a voxel neither cloud explains holds a surface.
const UNKNOWN_PRIOR: f64 = 0.5;

/// What one contradiction weighs against one agreeing point: their log-likelihood ratios
/// against the unknown, `ln(prior / see-through) / ln(1 / prior)` (3.3). A point near the
/// map's surface is likely under many poses (floors, ceilings and long walls agree with
/// most), a point where the other sensor's ray passed is unlikely under any but a wrong one.
fn contradiction_weight() -> f64 {
    (UNKNOWN_PRIOR / SEE_THROUGH_PROBABILITY).ln() / (1.0 / UNKNOWN_PRIOR).ln()
}

/// Iterations of each coarse ICP: the hypotheses start within about a cell and a yaw step of
/// a solution, and the fine ICP finishes the chosen one.
const COARSE_ITERATIONS: usize = 20;

/// A hypothesis after its coarse ICP.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Verified {
    /// The refined `world_from_scan`.
    pub(crate) world_from_scan: DAffine3,
    /// Agreement minus contradiction (at most 1; higher is better).
    pub(crate) score: f64,
    /// Fraction of the source points within half a cell of the map's surface.
    pub(crate) fitness: f64,
}

/// The coarse ICP's settings for search cell `cell_m`: point-to-plane on `cell_m` voxels, a
/// first gate of three cells (a hypothesis is off by about one) shrinking to one cell, the
/// sequence's range weighting, on the CPU (small clouds; and the choice between hypotheses
/// must not depend on the device).
pub(crate) fn coarse_config(cell_m: f64, range_knee_m: f64) -> IcpConfig {
    IcpConfig {
        method: Method::PointToPlane,
        bucket_size_m: 3.0 * cell_m,
        max_iterations: COARSE_ITERATIONS,
        max_correspondence_distance_m: 3.0 * cell_m,
        final_correspondence_distance_m: cell_m,
        kernel: RobustKernel::Cauchy { k_m: cell_m / 2.0 },
        normal_voxel_m: cell_m,
        neighbours_k: 10,
        source_voxel_m: Some(cell_m),
        target_voxel_m: Some(cell_m),
        min_fitness: 0.0,
        device: Device::Cpu,
        range_knee_m,
        ..IcpConfig::default()
    }
}

/// What each side saw, for the contradiction term.
pub(crate) struct Evidence {
    /// The map's points on the search's cell (world).
    pub(crate) map_points: Vec<Vec3>,
    /// Where the map's sensors saw free space (world).
    pub(crate) map_free: SeenFree,
    /// Where the source's sensor saw free space (its scan frame).
    pub(crate) source_free: SeenFree,
}

impl Evidence {
    /// What the map (`map_points` on the search's cell `cell_m`, each seen from
    /// `map_views[i]`) and the source (`source_points` on the cell, in its scan frame, seen
    /// from `source_sensor`) saw free, rays cut at `max_ray_m`.
    pub(crate) fn new(
        (map_points, map_views): (Vec<Vec3>, Vec<Vec3>),
        source_points: &[Vec3],
        source_sensor: Vec3,
        cell_m: f64,
        max_ray_m: f64,
    ) -> Evidence {
        let map_free = SeenFree::new(&map_points, &map_views, cell_m, max_ray_m);
        let sensors = vec![source_sensor; source_points.len()];
        let source_free = SeenFree::new(source_points, &sensors, cell_m, max_ray_m);
        Evidence {
            map_points,
            map_free,
            source_free,
        }
    }
}

/// The finite points of `source` on the search's cell `cell_m` (the points every hypothesis is
/// scored on).
pub(crate) fn points_on_cell(source: &PointCloud, cell_m: f64) -> Result<Vec<Vec3>> {
    let finite: Vec<Vec3> = source
        .points
        .iter()
        .copied()
        .filter(|p| p.is_finite())
        .collect();
    crate::downsample::voxel_downsample(&finite, cell_m, "initial_cell_m")
}

/// Refines and scores every start in `starts` (`world_from_scan` of `source`) against
/// `target`, prepared with [`coarse_config`]; `source_points` are the source's points on the
/// search's cell, the same for every hypothesis. A start whose ICP finds no overlap scores
/// `f64::NEG_INFINITY`.
pub(crate) fn verify(
    target: &Target,
    source: &PointCloud,
    source_points: &[Vec3],
    starts: &[DAffine3],
    config: &IcpConfig,
    evidence: &Evidence,
) -> Result<Vec<Verified>> {
    let cell_m = config.final_correspondence_distance_m;
    starts
        .par_iter()
        .map(|start| {
            let pose = match register_to(target, source, *start, config) {
                Ok(r) => r.target_from_source,
                Err(RegistrationError::NotConverged { result, .. }) => result.target_from_source,
                Err(RegistrationError::NoOverlap { .. }) => {
                    return Ok(Verified {
                        world_from_scan: *start,
                        score: f64::NEG_INFINITY,
                        fitness: 0.0,
                    })
                }
                Err(e) => return Err(e),
            };
            Ok(score(target, source_points, pose, cell_m, evidence))
        })
        .collect()
}

/// Scores `pose` (`world_from_scan` of the source) as it is: agreement with `target` (on the
/// search's cell `cell_m`) minus weighted contradiction, on `source_points`.
pub(crate) fn score(
    target: &Target,
    source_points: &[Vec3],
    pose: DAffine3,
    cell_m: f64,
    evidence: &Evidence,
) -> Verified {
    let (agreement, fitness) = agreement(target, source_points, &pose, cell_m);
    let against = contradiction(evidence, source_points, &pose);
    Verified {
        world_from_scan: pose,
        score: agreement - contradiction_weight() * against,
        fitness,
    }
}

/// The mean truncated agreement of `points` moved by `pose`, and the fraction within half a
/// cell.
fn agreement(target: &Target, points: &[Vec3], pose: &DAffine3, cell_m: f64) -> (f64, f64) {
    let gate = (2.0 * cell_m) as f32;
    let scale = cell_m / 2.0;
    let normals = target.normals();
    let (sum, close) = points
        .iter()
        .map(|p| {
            let q = pose.transform_point3(p.as_dvec3()).as_vec3();
            match target.nearest(q, gate) {
                Some((j, _)) => {
                    let j = j as usize;
                    let r = normals[j].dot(q - target.points()[j]).abs() as f64 / scale;
                    (1.0 - r.min(1.0).powi(2), (r < 1.0) as usize)
                }
                None => (0.0, 0),
            }
        })
        .fold((0.0, 0), |(c, n), (ci, ni)| (c + ci, n + ni));
    let n = points.len().max(1) as f64;
    (sum / n, close as f64 / n)
}

/// The points of either side that `pose` puts where the other side saw free space, per
/// source point.
fn contradiction(e: &Evidence, source_points: &[Vec3], pose: &DAffine3) -> f64 {
    let moved = |t: &DAffine3, p: &Vec3| t.transform_point3(p.as_dvec3()).as_vec3();
    let source = source_points
        .iter()
        .filter(|p| e.map_free.is_free(moved(pose, p)))
        .count();
    let back = pose.inverse();
    let map = e
        .map_points
        .iter()
        .filter(|m| e.source_free.is_free(moved(&back, m)))
        .count();
    (source + map) as f64 / source_points.len().max(1) as f64
}
