//! The directions of ascent along the walls (see the `stairs` module): a staircase is built
//! square to the walls around it.

use glam::DVec2;

/// Walls whose directions (or normals) lie this near are one family: fits of one direction's
/// walls differ by a degree or so (see [`WallFamilies`]).
const SAME_WALL_DIRECTION_DEG: f64 = 2.0;

/// The walls in families of one direction (walls within [`SAME_WALL_DIRECTION_DEG`] of each
/// other, or of square to each other): each family's longest wall's direction and its walls'
/// segments, the family with the most length first.
pub(super) struct WallFamilies {
    /// (its longest wall's direction, its walls' segments), longest family first
    families: Vec<(DVec2, Vec<Segment>)>,
}

/// A wall's segment `(start, end)`.
type Segment = (DVec2, DVec2);

/// The angle between two lines modulo 90 degrees.
fn off_square(a: DVec2, b: DVec2) -> f64 {
    let t = a.angle_to(b).abs().to_degrees() % 90.0;
    t.min(90.0 - t)
}

/// The one of `e`'s direction, its normals and its opposite nearest the family's direction
/// `d` (`d` itself where `e` is no direction).
fn along_family(d: DVec2, e: DVec2) -> DVec2 {
    let Some(e) = e.try_normalize() else {
        return d;
    };
    [e, e.perp(), -e, -e.perp()]
        .into_iter()
        .max_by(|a, b| a.dot(d).total_cmp(&b.dot(d)))
        .unwrap_or(d)
}

impl WallFamilies {
    /// The families of the walls' segments `(start, end)`.
    pub(super) fn new(walls: impl Iterator<Item = Segment>) -> Self {
        // (its longest wall's direction and length, its total length, its segments)
        let mut families: Vec<(DVec2, f64, f64, Vec<Segment>)> = Vec::new();
        for (a, b) in walls {
            let length = a.distance(b);
            let Some(d) = (b - a).try_normalize() else {
                continue;
            };
            match families
                .iter_mut()
                .find(|f| off_square(f.0, d) < SAME_WALL_DIRECTION_DEG)
            {
                Some(f) => {
                    f.2 += length;
                    f.3.push((a, b));
                    if length > f.1 {
                        (f.0, f.1) = (d, length);
                    }
                }
                None => families.push((d, length, length, vec![(a, b)])),
            }
        }
        families.sort_by(|a, b| b.2.total_cmp(&a.2));
        WallFamilies {
            families: families.into_iter().map(|f| (f.0, f.3)).collect(),
        }
    }

    /// The directions of ascent along the walls for a part at `at`: each family's direction
    /// and normals, the family of the wall nearest `at` first, then the others in order of
    /// their total length, and of families within `snap_deg` of one taken before (a room a
    /// few degrees off square to the rest) none: the one taken stands for them (a staircase
    /// is built square to the walls around it).
    ///
    /// With the walls taken in their order, the first wall's direction stood for every wall
    /// within `snap_deg`: hall-155 of seeds 151-155, its north wall at 4.1 degrees first, the
    /// south wall, the partition and the west wall at 0-1.5 degrees, read its staircase 4
    /// degrees off. With the longest family first, hall-273 of seeds 271-275, its north and
    /// west walls (42.3 m at -2.8 degrees) stood for the south wall and the partition (40 m at
    /// 0 degrees), and the staircase against the south wall was read 2.8 degrees off. Within the
    /// nearest family, the wall nearest the part gives its direction: hall-365 of seeds 361-365,
    /// its north wall (21.4 m at 1.7 degrees) one family with the south wall (20 m at 0 degrees),
    /// read the staircase beside the south wall 1.7 degrees off, and a staircase seen from its
    /// side along a direction off its side face reads its steps smeared.
    pub(super) fn directions_near(&self, at: DVec2, snap_deg: f64) -> Vec<DVec2> {
        let distance = |(a, b): Segment| {
            let ab = b - a;
            let t = ((at - a).dot(ab) / ab.length_squared().max(1e-12)).clamp(0.0, 1.0);
            at.distance(a + t * ab)
        };
        let nearest = (0..self.families.len()).min_by(|&i, &j| {
            let near = |k: usize| {
                let segs = &self.families[k].1;
                segs.iter()
                    .map(|&s| distance(s))
                    .fold(f64::INFINITY, f64::min)
            };
            near(i).total_cmp(&near(j))
        });
        let order = nearest
            .into_iter()
            .chain((0..self.families.len()).filter(|&k| Some(k) != nearest));
        let mut taken: Vec<DVec2> = Vec::new();
        for k in order {
            let (d, segs) = &self.families[k];
            // (the nearest family's direction is its wall nearest the part's: walls of one
            // family differ by up to `SAME_WALL_DIRECTION_DEG`, and a staircase is built square
            // to the wall beside it)
            let d = match segs
                .iter()
                .min_by(|&&s, &&t| distance(s).total_cmp(&distance(t)))
            {
                Some(&(a, b)) if Some(k) == nearest => along_family(*d, b - a),
                _ => *d,
            };
            if taken.iter().all(|&e| off_square(e, d) >= snap_deg) {
                taken.push(d);
            }
        }
        taken
            .iter()
            .flat_map(|&d| [d, d.perp(), -d, -d.perp()])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Segments of these lengths along these directions (degrees), each from `from`.
    fn walls(w: &[(f64, f64, DVec2)]) -> WallFamilies {
        let at = |deg: f64| DVec2::from_angle(deg.to_radians());
        WallFamilies::new(
            w.iter()
                .map(|&(deg, len, from)| (from, from + len * at(deg))),
        )
    }

    /// Regression (hall-155 of seeds 151-155): a north wall at 4.1 degrees, first of the walls,
    /// stood for the south wall, the partition and the west wall at 0-1.5 degrees (within the 10
    /// degree snap), and the staircase square to them was read 4 degrees off. The family of walls
    /// nearest the part stands for those within the snap, then the family with the most length;
    /// a room square to the others at more than the snap is a direction of its own.
    #[test]
    fn the_main_direction_of_the_walls_stands_for_those_a_few_degrees_off() {
        let at = |deg: f64| DVec2::from_angle(deg.to_radians());
        // (a part south of the south wall, nearest it)
        let south = DVec2::new(10.0, -1.0);
        let fam = walls(&[
            (4.12, 17.85, DVec2::ZERO),
            (0.0, 17.01, DVec2::ZERO),
            (86.11, 16.86, DVec2::ZERO),
            (89.99, 15.81, DVec2::ZERO),
            (88.49, 15.51, DVec2::ZERO),
        ]);
        let dirs = fam.directions_near(south, 10.0);
        assert_eq!(dirs.len(), 4);
        // (the south wall's: the longest of the family with the partition and the west wall)
        for (k, deg) in [0.0, 90.0, 180.0, 270.0].into_iter().enumerate() {
            assert!(dirs[k].angle_to(at(deg)).abs() < 1e-9, "{deg} not at {k}");
        }
        // A wing 30 degrees off the main walls is a direction of its own, after them.
        let wing = walls(&[
            (0.0, 20.0, DVec2::ZERO),
            (30.0, 8.0, DVec2::ZERO),
            (90.5, 12.0, DVec2::ZERO),
        ]);
        let dirs = wing.directions_near(south, 10.0);
        assert_eq!(dirs.len(), 8);
        assert!(dirs[4].angle_to(at(30.0)).abs() < 1e-9);
    }

    /// Regression (hall-273 of seeds 271-275): the hall's north and west walls (42.3 m at -2.8
    /// degrees) outweighed its south wall and partition (40 m at 0 degrees), and a staircase
    /// against the south wall, square to it, was read 2.8 degrees off. The family of the wall
    /// nearest the part stands for the others within the snap.
    #[test]
    fn the_walls_nearest_a_staircase_give_its_direction() {
        let at = |deg: f64| DVec2::from_angle(deg.to_radians());
        let fam = walls(&[
            (0.0, 25.0, DVec2::ZERO),
            (90.0, 15.0, DVec2::new(10.0, 0.0)),
            (177.2, 25.5, DVec2::new(25.0, 16.2)),
            (267.2, 16.8, DVec2::new(0.5, 16.0)),
        ]);
        // Beside the south wall: the south wall's direction, the north wall's none (within the
        // snap of it).
        let dirs = fam.directions_near(DVec2::new(20.0, 1.1), 10.0);
        assert_eq!(dirs.len(), 4);
        assert!(dirs[2].angle_to(at(180.0)).abs() < 1e-9);
        // Beside the north wall: the north wall's.
        let dirs = fam.directions_near(DVec2::new(20.0, 15.0), 10.0);
        assert_eq!(dirs.len(), 4);
        assert!(dirs[0].angle_to(at(177.2)).abs() < 1e-9);
        // Walls within `SAME_WALL_DIRECTION_DEG` are one family, the longest its direction;
        // beside the shorter one, that one's (hall-365 of seeds 361-365: the north wall at
        // 1.7 degrees, 21.4 m, the south wall at 0 degrees, 20 m).
        let fam = walls(&[
            (0.0, 20.0, DVec2::ZERO),
            (78.7, 13.8, DVec2::new(19.7, -0.1)),
            (-178.3, 21.4, DVec2::new(22.5, 13.4)),
            (90.0, 12.8, DVec2::new(5.6, 0.1)),
        ]);
        // (the first four: the family's direction, its normals and its opposite)
        let first_has =
            |dirs: &[DVec2], deg: f64| dirs[..4].iter().any(|d| d.angle_to(at(deg)).abs() < 1e-9);
        let near_south = fam.directions_near(DVec2::new(9.0, 1.2), 10.0);
        assert!(first_has(&near_south, 0.0), "{near_south:?}");
        let near_north = fam.directions_near(DVec2::new(9.0, 12.0), 10.0);
        assert!(first_has(&near_north, 1.7), "{near_north:?}");
        // No walls: no directions.
        let none = walls(&[]);
        assert!(none.directions_near(DVec2::ZERO, 10.0).is_empty());
    }
}
