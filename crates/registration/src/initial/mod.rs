//! Initial alignment of a scan that comes without a usable guess (no odometry: a tripod
//! scanner, a stop-and-scan robot without wheel encoders): a global search for its yaw and
//! horizontal position against the map, whose best hypothesis the normal ICP then refines.
//!
//! Gravity is known (scanners are levelled), so the unknowns are the yaw and the translation.
//! The steps ([`align`]):
//! 1. [`columns`]: the vertical structure (walls, furniture sides) of the source and of the map
//!    projected to the horizontal plane, one point per occupied column of `cell_m`;
//! 2. [`correlate`]: every yaw of a full circle (steps that turn the source's far points by
//!    about a cell) and every sensor position within the source's reach of the previous
//!    sensor, scored by the likelihood of the source's structure in the map's (correlative
//!    scan matching);
//! 3. [`verify`]: the best distinct hypotheses (and the guess) refined in 3D by a coarse
//!    point-to-plane ICP on `cell_m` voxels and scored on the same source points: agreement
//!    with the map's surface minus contradiction of what either side saw free ([`seen`]);
//!    the best (among statistically indistinguishable scores, the nearest to the guess) is
//!    the start of the normal ICP.
//!
//! The scans must hold returns only: a laser's "no echo" readings written at a fixed range
//! (3DTK's 32.767 m) are rays through walls to nowhere and would call the walls free (the
//! pipeline drops them before registering).
//!
//! Why not yaw from a histogram of wall directions: it is cheaper, but it needs dominant
//! wall directions (it fails in round rooms, outdoors and in cluttered scans), it leaves the
//! translation to a local method (a 2 m move in a 5 m room is beyond ICP's basin), and its
//! 2- or 4-fold ambiguity needs a verification anyway. The alignment costs 0.2-1.5 s per
//! scan in a release build on 2 cores (search 15-500 ms, the coarse ICPs 0.1-1 s; measured by
//! `cargo test --release -p registration --test initial_alignment measure_initial_alignment_cost
//! -- --ignored --nocapture`) and only runs where configured ([`InitialAlignment`]).

mod choose;
mod columns;
mod correlate;
mod prefer;
mod seen;
mod verify;

use crate::error::{RegistrationError, Result};
use crate::target::Target;
use cloud::PointCloud;
use glam::{DAffine3, DQuat, DVec3, Vec3};
use serde::{Deserialize, Serialize};
use std::time::Instant;

use choose::choose;
pub(crate) use prefer::prefer;

/// When a sequence searches a scan's initial pose ([`crate::SequenceConfig::initial_alignment`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum InitialAlignment {
    /// Never: every scan starts from its guess (the odometry, or without odometry the previous
    /// scan's pose).
    Off,
    /// For every scan when the sequence has no odometry; with odometry, only for a scan whose
    /// ICP from the odometry fails (does not converge, ends below `min_fitness`, or finds no
    /// overlap), which is then registered again from the search's best hypothesis (the
    /// odometry's guess among them). A sequence with odometry whose scans all register costs nothing extra.
    #[default]
    Auto,
    /// For every scan, odometry or not (the odometry's guess is one hypothesis among the
    /// search's).
    Always,
}

/// What the initial alignment of one scan found and cost.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InitialAlignmentReport {
    /// Yaw hypotheses of the search (a full circle).
    pub yaw_steps: usize,
    /// Hypotheses verified by a coarse ICP (the guess included; 0 when the map has no
    /// surface on the search's cell to verify against, and the guess stands).
    pub verified: usize,
    /// The chosen hypothesis' score: agreement (the mean over the source's points of
    /// `1 - (r / g)^2` for a point within `g`, half a cell, of the map's surface) minus
    /// contradiction (structure of either side where the other saw free space, per source
    /// structure column). At most 1; higher is better.
    pub score: f64,
    /// The chosen hypothesis' fraction of source points within half a cell of the map.
    pub fitness: f64,
    /// Whether the guess (odometry, or the previous pose) won over the search's hypotheses.
    pub guess_won: bool,
    /// Wall time of the search (structure, free space seen, sweep).
    pub search_ms: f64,
    /// Wall time of the coarse ICPs and their scores.
    pub verify_ms: f64,
}

/// Hypotheses of the search verified in 3D (the guess comes on top).
const VERIFIED_HYPOTHESES: usize = 16;
/// Hypotheses closer than this in yaw and in position are one.
const DISTINCT_YAW_DEG: f64 = 10.0;
const DISTINCT_CELLS: f64 = 3.0;

/// The settings of one alignment.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Settings {
    /// The search's cell and the coarse ICP's voxel.
    pub(crate) cell_m: f64,
    /// The sequence's range weighting ([`crate::IcpConfig::range_knee_m`]).
    pub(crate) range_knee_m: f64,
}

/// The best start for registering `source` (scan frame, its sensor at `sensor_origin`) to the
/// map (world frame, each point with the sensor position it was seen from), searched about the
/// previous scan's pose `previous` (`world_from_scan`, its sensor at `previous_sensor` in its
/// scan frame), with `guess` among the hypotheses.
pub(crate) fn align(
    map: &[Vec3],
    views: &[Vec3],
    source: &PointCloud,
    (previous, previous_sensor): (&DAffine3, Vec3),
    guess: &DAffine3,
    settings: Settings,
) -> Result<(DAffine3, InitialAlignmentReport)> {
    let Settings {
        cell_m,
        range_knee_m,
    } = settings;
    let start = Instant::now();
    // 1. Structure seen from above, levelled like the previous scan and relative to the
    //    sensors (heights are then heights above or below the sensor).
    let level = DQuat::from_affine3(previous);
    let sensor = source.sensor_origin.as_dvec3();
    let prev_sensor = previous.transform_point3(previous_sensor.as_dvec3());
    let cell = cell_m as f32;
    let levelled: Vec<Vec3> = source
        .points
        .iter()
        .filter(|p| p.is_finite())
        .map(|p| (level * (p.as_dvec3() - sensor)).as_vec3())
        .collect();
    let source_columns = columns::structure_columns(levelled.iter().copied(), cell);
    let map_columns = columns::structure_columns(
        map.iter().map(|p| (p.as_dvec3() - prev_sensor).as_vec3()),
        cell,
    );
    let map_columns: Vec<_> = map_columns
        .into_iter()
        .map(|p| p + prev_sensor.truncate().as_vec2())
        .collect();
    // 2. Every yaw and position, scored on the structure.
    let sweep = correlate::sweep(
        &source_columns,
        &map_columns,
        prev_sensor.truncate(),
        cell_m,
    );
    let yaw_steps = sweep.as_ref().map_or(0, |s| s.yaw_steps);
    let hypotheses = sweep.map_or_else(Vec::new, |s| distinct(s.hypotheses, cell_m));
    let mut starts = vec![*guess];
    starts.extend(hypotheses.iter().map(|h| {
        let turn = DQuat::from_rotation_z(h.yaw_rad) * level;
        let sensor_world = DVec3::new(h.sensor_xy.x, h.sensor_xy.y, prev_sensor.z);
        DAffine3::from_rotation_translation(turn, sensor_world - turn * sensor)
    }));
    let search_ms = start.elapsed().as_secs_f64() * 1e3;
    // 3. Each start refined by a coarse ICP and scored on the same points; the best wins,
    //    the nearest to the guess among the indistinguishable.
    let start = Instant::now();
    let config = verify::coarse_config(cell_m, range_knee_m);
    let map_cloud = PointCloud::from_points(map.to_vec());
    let target = match Target::with_viewpoints(&map_cloud, views, &config) {
        Ok(t) => t,
        // No surface on the search's cell (a map of a few scattered points): nothing to
        // verify against, the guess stands.
        Err(RegistrationError::EmptyCloud { .. }) => {
            let report = InitialAlignmentReport {
                yaw_steps,
                verified: 0,
                score: f64::NEG_INFINITY,
                fitness: 0.0,
                guess_won: true,
                search_ms,
                verify_ms: start.elapsed().as_secs_f64() * 1e3,
            };
            return Ok((*guess, report));
        }
        Err(e) => return Err(e),
    };
    let points = verify::points_on_cell(source, cell_m)?;
    // What each side saw free (for the contradictions); rays beyond twice the source's reach
    // (as the search's) are cut.
    let max_ray_m = 2.0 * correlate::reach(&source_columns, cell_m);
    let (map_points, map_views) =
        crate::downsample::voxel_downsample_with(map, views, cell_m, "initial_cell_m")?;
    let evidence = verify::Evidence::new(
        (map_points, map_views),
        &points,
        source.sensor_origin,
        cell_m,
        max_ray_m,
    );
    let verified = verify::verify(&target, source, &points, &starts, &config, &evidence)?;
    let (best, chosen) = choose(&verified, guess, sensor, points.len()).unwrap_or((
        0,
        verify::Verified {
            world_from_scan: *guess,
            score: f64::NEG_INFINITY,
            fitness: 0.0,
        },
    ));
    let report = InitialAlignmentReport {
        yaw_steps,
        verified: starts.len(),
        score: chosen.score,
        fitness: chosen.fitness,
        guess_won: best == 0,
        search_ms,
        verify_ms: start.elapsed().as_secs_f64() * 1e3,
    };
    Ok((chosen.world_from_scan, report))
}

/// The best [`VERIFIED_HYPOTHESES`] of `sorted` (best first) that differ from every better
/// one by [`DISTINCT_YAW_DEG`] in yaw or [`DISTINCT_CELLS`] in position.
fn distinct(sorted: Vec<correlate::Hypothesis>, cell_m: f64) -> Vec<correlate::Hypothesis> {
    let mut kept: Vec<correlate::Hypothesis> = Vec::new();
    for h in sorted {
        let same = |k: &correlate::Hypothesis| {
            let dyaw = (h.yaw_rad - k.yaw_rad + std::f64::consts::PI)
                .rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            dyaw.abs().to_degrees() < DISTINCT_YAW_DEG
                && (h.sensor_xy - k.sensor_xy).length() < DISTINCT_CELLS * cell_m
        };
        if !kept.iter().any(same) {
            kept.push(h);
            if kept.len() == VERIFIED_HYPOTHESES {
                break;
            }
        }
    }
    kept
}
