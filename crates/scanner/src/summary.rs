//! A building summarised in one line for people (`semsim building check`, the demo).

use crate::building::Building;
use crate::geometry::BuildingGeometry;

impl Building {
    /// One line for people: what the building holds.
    pub fn summary(&self) -> String {
        let doors: Vec<_> = self.walls.iter().flat_map(|w| &w.doors).collect();
        let leaves = doors.iter().filter(|d| d.leaf.is_some()).count();
        let parts = BuildingGeometry::new(self).parts().len();
        format!(
            "{:.1} x {:.1} m, {} walls, {} door openings ({} with leaves), {} staircases, {} boxes, {} solid parts",
            self.floor.max_m[0] - self.floor.min_m[0],
            self.floor.max_m[1] - self.floor.min_m[1],
            self.walls.len(),
            doors.len(),
            leaves,
            self.stairs.len(),
            self.boxes.len(),
            parts
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_building_is_summarised_with_its_counts() {
        let b = Building::default_building().expect("built in");
        let s = b.summary();
        assert!(s.contains(&format!("{} walls", b.walls.len())), "{s}");
        assert!(s.contains(&format!("{} staircases", b.stairs.len())), "{s}");
    }
}
