//! The directions of ascent along the walls (see the `stairs` module): a staircase is built
//! square to the walls around it.

use glam::DVec2;

/// Walls whose directions (or normals) lie this near are one family: fits of one direction's
/// walls differ by a degree or so (see [`wall_directions`]).
const SAME_WALL_DIRECTION_DEG: f64 = 2.0;

/// The directions of ascent along the walls: each family of walls' directions (walls within
/// [`SAME_WALL_DIRECTION_DEG`] of each other, or of square to each other), its longest wall's
/// direction and normals, in order of the families' total length, and of families within
/// `snap_deg` of one taken before (a room a few degrees off square to the rest) none: the
/// building's main direction stands for them (a staircase is built square to the walls around
/// it). `walls` are (direction, length). With the walls taken in their order, the first wall's
/// direction stood for every wall within `snap_deg`: hall-155 of seeds 151-155, its north wall
/// at 4.1 degrees first, the south wall, the partition and the west wall at 0-1.5 degrees, read
/// its staircase 4 degrees off; its top landing, read along that direction, ended 0.26 m short,
/// and its end face was left as a partial-height wall.
pub(super) fn wall_directions(
    walls: impl Iterator<Item = (DVec2, f64)>,
    snap_deg: f64,
) -> Vec<DVec2> {
    // (the angle between two lines modulo 90 degrees)
    let off_square = |a: DVec2, b: DVec2| {
        let t = a.angle_to(b).abs().to_degrees() % 90.0;
        t.min(90.0 - t)
    };
    // (its longest wall's direction, its total length, that wall's length)
    let mut families: Vec<(DVec2, f64, f64)> = Vec::new();
    for (d, length) in walls {
        match families
            .iter_mut()
            .find(|f| off_square(f.0, d) < SAME_WALL_DIRECTION_DEG)
        {
            Some(f) => {
                f.1 += length;
                if length > f.2 {
                    (f.0, f.2) = (d, length);
                }
            }
            None => families.push((d, length, length)),
        }
    }
    families.sort_by(|a, b| b.1.total_cmp(&a.1));
    let mut taken: Vec<DVec2> = Vec::new();
    for (d, _, _) in families {
        if taken.iter().all(|&e| off_square(e, d) >= snap_deg) {
            taken.push(d);
        }
    }
    taken
        .iter()
        .flat_map(|&d| [d, d.perp(), -d, -d.perp()])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression (hall-155 of seeds 151-155): a north wall at 4.1 degrees, first of the walls,
    /// stood for the south wall, the partition and the west wall at 0-1.5 degrees (within the 10
    /// degree snap), and the staircase square to them was read 4 degrees off. The family of walls
    /// with the most length stands for those within the snap; a room square to the others at more
    /// than the snap is a direction of its own.
    #[test]
    fn the_main_direction_of_the_walls_stands_for_those_a_few_degrees_off() {
        let at = |deg: f64| DVec2::from_angle(deg.to_radians());
        let walls = [
            (at(4.12), 17.85),
            (at(0.0), 17.01),
            (at(86.11), 16.86),
            (at(89.99), 15.81),
            (at(88.49), 15.51),
        ];
        let dirs = wall_directions(walls.into_iter(), 10.0);
        assert_eq!(dirs.len(), 4);
        // (the south wall's: the longest of the family with the partition and the west wall)
        for (k, deg) in [0.0, 90.0, 180.0, 270.0].into_iter().enumerate() {
            assert!(dirs[k].angle_to(at(deg)).abs() < 1e-9, "{deg} not at {k}");
        }
        // A wing 30 degrees off the main walls is a direction of its own, after them.
        let wing = [(at(0.0), 20.0), (at(30.0), 8.0), (at(90.5), 12.0)];
        let dirs = wall_directions(wing.into_iter(), 10.0);
        assert_eq!(dirs.len(), 8);
        assert!(dirs[4].angle_to(at(30.0)).abs() < 1e-9);
    }
}
