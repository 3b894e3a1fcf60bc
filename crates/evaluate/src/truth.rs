//! The ground truth in the map frame: the building's entities by name and the points the
//! scans saw on each.

use cloud::PointCloud;
use glam::{DAffine3, DVec3};
use scanner::{Building, BuildingGeometry};
use semantic::SemanticMap;
use std::collections::HashMap;

/// The ground truth in the map frame: true entity ids by name and their observed points.
pub(crate) struct Truth {
    map_from_input: DAffine3,
    id_of: HashMap<String, u32>,
    seen: HashMap<u32, Vec<DVec3>>,
    /// True if an observed (labelled) cloud was given.
    pub observed: bool,
}

impl Truth {
    pub fn new(map: &SemanticMap, building: &Building, observed: Option<&PointCloud>) -> Truth {
        let geometry = BuildingGeometry::new(building);
        let mut t = Truth {
            map_from_input: map.input_from_map().inverse(),
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
                if p.is_finite() && l.entity != 0 {
                    let q = t.to_map(p.x as f64, p.y as f64, p.z as f64);
                    t.seen.entry(l.entity).or_default().push(q);
                }
            }
        }
        t
    }

    /// A point of the building (input frame) in the map frame.
    pub fn to_map(&self, x: f64, y: f64, z: f64) -> DVec3 {
        self.map_from_input.transform_point3(DVec3::new(x, y, z))
    }

    /// The observed points of the true entity `name` (e.g. `walls[2]`), map frame.
    pub fn points(&self, name: &str) -> Option<&Vec<DVec3>> {
        self.id_of.get(name).and_then(|id| self.seen.get(id))
    }

    /// How many observed points the true entity `name` has.
    pub fn count(&self, name: &str) -> usize {
        self.points(name).map_or(0, Vec::len)
    }
}
