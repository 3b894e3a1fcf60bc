//! Which of a few finished registrations of one scan the evidence prefers, scored as the
//! initial alignment scores its hypotheses ([`super::verify`]: agreement with the map's
//! surface minus contradiction of what either side saw free) but without refining them: they
//! are the ends of full ICPs. Among scores that cannot be told apart, the pose nearest the
//! guess wins ([`super::choose`]).

use super::{choose::choose, columns, correlate, verify};
use crate::downsample::voxel_downsample_with;
use crate::error::{RegistrationError, Result};
use crate::target::Target;
use cloud::PointCloud;
use glam::{DAffine3, DQuat, Vec3};

/// The index into `poses` (each a `world_from_scan` of `source`) that the map (`map`, each
/// point seen from `views[i]`) supports best, with every pose's score; `None` when the map
/// has no surface on the cell to score against.
pub(crate) fn prefer(
    map: &[Vec3],
    views: &[Vec3],
    source: &PointCloud,
    poses: &[DAffine3],
    guess: &DAffine3,
    (cell_m, range_knee_m): (f64, f64),
) -> Result<Option<(usize, Vec<f64>)>> {
    let config = verify::coarse_config(cell_m, range_knee_m);
    let map_cloud = PointCloud::from_points(map.to_vec());
    let target = match Target::with_viewpoints(&map_cloud, views, &config) {
        Ok(t) => t,
        Err(RegistrationError::EmptyCloud { .. }) => return Ok(None),
        Err(e) => return Err(e),
    };
    // The source on the cell, and its reach (rays beyond twice it are cut, as the search's).
    let points = verify::points_on_cell(source, cell_m)?;
    let sensor = source.sensor_origin;
    let level = DQuat::from_affine3(guess);
    let levelled = points
        .iter()
        .map(|p| (level * (p.as_dvec3() - sensor.as_dvec3())).as_vec3());
    let structure = columns::structure_columns(levelled, cell_m as f32);
    let max_ray_m = 2.0 * correlate::reach(&structure, cell_m);
    let evidence = verify::Evidence::new(
        voxel_downsample_with(map, views, cell_m, "initial_cell_m")?,
        &points,
        sensor,
        cell_m,
        max_ray_m,
    );
    let verified: Vec<verify::Verified> = poses
        .iter()
        .map(|pose| verify::score(&target, &points, *pose, cell_m, &evidence))
        .collect();
    let scores = verified.iter().map(|v| v.score).collect();
    Ok(choose(&verified, guess, sensor.as_dvec3(), points.len()).map(|(i, _)| (i, scores)))
}
