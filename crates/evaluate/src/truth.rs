//! The ground truth in the map frame: the building's entities by name and the points the
//! scans saw on each.

use cloud::PointCloud;
use glam::{DAffine3, DVec3};
use scanner::{Building, BuildingGeometry};
use semantic::SemanticMap;
use std::collections::HashMap;

/// The ground truth in the map frame: true entity ids by name and their observed points.
pub(crate) struct Truth {
    /// The building's frame in the map frame: the map's levelling after the registration's
    /// frame (the identity where the scans were placed by their true poses).
    map_from_building: DAffine3,
    building_from_map: DAffine3,
    id_of: HashMap<String, u32>,
    seen: HashMap<u32, Vec<DVec3>>,
    /// True if an observed (labelled) cloud was given.
    pub observed: bool,
}

impl Truth {
    /// The truth of `building` for `map`, whose input cloud was in a frame that is
    /// `input_from_building` from the building's (the identity for scans placed by their true
    /// poses), with the labelled `observed` cloud in that input frame.
    pub fn new(
        map: &SemanticMap,
        building: &Building,
        observed: Option<&PointCloud>,
        input_from_building: DAffine3,
    ) -> Truth {
        let geometry = BuildingGeometry::new(building);
        let map_from_input = map.input_from_map().inverse();
        let mut t = Truth {
            map_from_building: map_from_input * input_from_building,
            building_from_map: (map_from_input * input_from_building).inverse(),
            id_of: geometry
                .entities()
                .iter()
                .map(|e| (e.name.clone(), e.id))
                .collect(),
            seen: HashMap::new(),
            observed: observed.is_some(),
        };
        if let Some((cloud, labels)) = observed.and_then(|c| c.labels.as_ref().map(|l| (c, l))) {
            for (p, l) in cloud.points.iter().zip(labels) {
                // (Entity 0: returns no building entity explains, the mixed pixels and people,
                // kept for `seen_by_name` as "unknown".)
                if p.is_finite() {
                    let q = map_from_input.transform_point3(p.as_dvec3());
                    t.seen.entry(l.entity).or_default().push(q);
                }
            }
        }
        t
    }

    /// A point of the building (the building's frame) in the map frame.
    pub fn to_map(&self, x: f64, y: f64, z: f64) -> DVec3 {
        self.map_from_building.transform_point3(DVec3::new(x, y, z))
    }

    /// A point of the map frame in the building's frame.
    pub fn to_building(&self, p: DVec3) -> DVec3 {
        self.building_from_map.transform_point3(p)
    }

    /// The observed points of the true entity `name` (e.g. `walls[2]`), map frame.
    pub fn points(&self, name: &str) -> Option<&Vec<DVec3>> {
        self.id_of.get(name).and_then(|id| self.seen.get(id))
    }

    /// Every true entity's name with its observed points (map frame), in no fixed order, and
    /// the returns no entity explains (mixed pixels, people) as `unknown`.
    pub fn seen_by_name(&self) -> impl Iterator<Item = (&str, &[DVec3])> {
        let unknown = self.seen.get(&0).map(|p| ("unknown", p.as_slice()));
        self.id_of
            .iter()
            .filter_map(|(name, id)| self.seen.get(id).map(|p| (name.as_str(), p.as_slice())))
            .chain(unknown)
    }

    /// How many observed points the true entity `name` has.
    pub fn count(&self, name: &str) -> usize {
        self.points(name).map_or(0, Vec::len)
    }
}
