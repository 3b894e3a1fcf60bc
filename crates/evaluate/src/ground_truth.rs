//! Whether a cloud carries the ground-truth labels of a building: the labels the virtual
//! laser gave its points, with the points placed in the building's frame.

use cloud::PointCloud;
use glam::DAffine3;
use scanner::{Building, BuildingGeometry};

/// At most this many labelled points are sampled.
const SAMPLE_POINTS: usize = 2000;
/// A sampled point lies on its label's entity if it is within this distance of it.
const ON_ENTITY_M: f32 = 0.1;
/// At least this fraction of the sampled points must lie on their label's entity.
const MIN_ON_FRACTION: f64 = 0.9;

/// Why a cloud cannot be evaluated against a building.
#[derive(Debug, thiserror::Error)]
pub enum EvalError {
    /// The cloud carries no labels at all.
    #[error("--cloud: the scans carry no labels; give the scans with their ground-truth labels")]
    NoLabels,
    /// Too few of its labelled points lie on the building's entity of their label.
    #[error(
        "--cloud: only {on} of {sampled} sampled labelled points lie on the building's entity of \
         their label: these are not its ground-truth labels (a map's labels.pcd holds the \
         map's own ids), or the scans are not placed (give --poses); give the scans as \
         `semsim scan` or `semsim demo` wrote them"
    )]
    NotGroundTruth {
        /// Sampled points on their label's entity.
        on: usize,
        /// Labelled points sampled.
        sampled: usize,
    },
}

impl cloud::BadInput for EvalError {
    /// Always: the cloud given is at fault.
    fn is_bad_input(&self) -> bool {
        true
    }
}

/// Checks that `cloud` carries `building`'s ground-truth labels: up to 2000 of its labelled
/// points, evenly sampled, lie within 10 cm of the building's entity of their label, 90 % of
/// them at least.
pub fn check_ground_truth(cloud: &PointCloud, building: &Building) -> Result<(), EvalError> {
    check_ground_truth_in_frame(cloud, building, DAffine3::IDENTITY)
}

/// As [`check_ground_truth`] for a cloud in a frame `building_from_input` away from the
/// building's (a registration's frame: see [`crate::registration_frame`]).
pub fn check_ground_truth_in_frame(
    cloud: &PointCloud,
    building: &Building,
    building_from_input: DAffine3,
) -> Result<(), EvalError> {
    let Some(labels) = &cloud.labels else {
        return Err(EvalError::NoLabels);
    };
    let geometry = BuildingGeometry::new(building);
    let labelled: Vec<usize> = (0..labels.len())
        .filter(|&i| labels[i].entity != 0 && cloud.points[i].is_finite())
        .collect();
    let sample: Vec<usize> = labelled
        .iter()
        .copied()
        .step_by((labelled.len() / SAMPLE_POINTS).max(1))
        .collect();
    let on = sample
        .iter()
        .filter(|&&i| {
            let p = building_from_input.transform_point3(cloud.points[i].as_dvec3());
            geometry.distance_to_entity(p.as_vec3(), labels[i].entity) <= ON_ENTITY_M
        })
        .count();
    if sample.is_empty() || (on as f64) < MIN_ON_FRACTION * sample.len() as f64 {
        return Err(EvalError::NotGroundTruth {
            on,
            sampled: sample.len(),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cloud_without_labels_is_not_ground_truth() {
        let building = Building::default_building().expect("built-in building");
        let cloud = PointCloud::from_points(vec![glam::Vec3::ZERO]);
        let e = check_ground_truth(&cloud, &building).unwrap_err();
        assert!(e
            .to_string()
            .starts_with("--cloud: the scans carry no labels"));
        assert!(cloud::BadInput::is_bad_input(&e));
    }

    #[test]
    fn labels_off_their_entities_are_not_ground_truth() {
        let building = Building::default_building().expect("built-in building");
        let mut cloud = PointCloud::from_points(vec![glam::Vec3::new(1e3, 1e3, 1e3); 10]);
        cloud.labels = Some(vec![
            cloud::Label {
                entity: 1,
                class: cloud::EntityClass::Wall,
            };
            10
        ]);
        let e = check_ground_truth(&cloud, &building).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--cloud: only 0 of 10 sampled labelled points lie on the building's entity of their \
             label: these are not its ground-truth labels (a map's labels.pcd holds the map's own \
             ids), or the scans are not placed (give --poses); give the scans as `semsim scan` or \
             `semsim demo` wrote them"
        );
    }
}
