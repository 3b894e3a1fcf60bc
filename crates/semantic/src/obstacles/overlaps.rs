//! Partitions overlapping along one line (see the `obstacles` module, step 7): two walls this
//! stage found, parallel, the centre line of each within the thicker one's slab, and
//! overlapping along it by more than a cell, are one partition found twice: one slab of space
//! holds no two walls. A glass partition returns few of the beams that meet it, and its pieces
//! are read at different heights (office-493 of seeds 491-495: a full-height glass partition
//! 3.9 m long was a partial-height wall 3.4 m long and 2.57 m high and another 1.3 m long and
//! 1.41 m high, overlapping it by 0.8 m; a wall too many, and one end 0.54 m short). They are
//! joined: the box around both, along the longer one, up to the higher top.

use super::merge::{absorb, PARALLEL_COS};
use super::partitions::partition_rule;
use super::{DetectedObstacle, ObstacleConfig, PartitionScene};
use cloud::EntityClass;

/// The walls of `found` that overlap along one line (see the module docs), joined.
pub(super) fn join_overlapping_partitions(
    mut found: Vec<DetectedObstacle>,
    ps: PartitionScene,
) -> Vec<DetectedObstacle> {
    let c = ps.c;
    // (a joined wall may overlap a third)
    while let Some((a, b)) = overlapping_pair(&found, c) {
        let other = found.remove(b);
        let wall = &mut found[if b < a { a - 1 } else { a }];
        let overlap = overlap_along(wall, &other);
        let top = wall.z_range.1.max(other.z_range.1);
        let dir = wall.dir;
        absorb(wall, &other, dir);
        let (why, top) = partition_rule(wall, ps, (0.0, 0.0))
            .map(|(why, rule_top)| (why, rule_top.max(top)))
            .unwrap_or_else(|| (wall.rules.last().cloned().unwrap_or_default(), top));
        wall.z_range.1 = top;
        wall.rules.truncate(1);
        wall.rules.push(format!(
            "box: around two partial-height walls overlapping by {overlap:.2} m along one line (one partition found twice)"
        ));
        wall.rules.push(why);
    }
    found
}

/// The indices `(longer, shorter)` of the first two walls in `found` that overlap (see
/// [`overlaps`]), in either order in `found`.
fn overlapping_pair(found: &[DetectedObstacle], c: &ObstacleConfig) -> Option<(usize, usize)> {
    let is_wall = |o: &DetectedObstacle| o.class == EntityClass::Wall && !o.overhead;
    for a in 0..found.len() {
        for b in a + 1..found.len() {
            if !is_wall(&found[a]) || !is_wall(&found[b]) || !overlaps(&found[a], &found[b], c) {
                continue;
            }
            return Some(if found[a].size[0] >= found[b].size[0] {
                (a, b)
            } else {
                (b, a)
            });
        }
    }
    None
}

/// How far `a` and `b` overlap along the longer one's line (negative: the gap between them).
fn overlap_along(a: &DetectedObstacle, b: &DetectedObstacle) -> f64 {
    let long = if a.size[0] >= b.size[0] { a } else { b };
    let r = (b.center - a.center).dot(long.dir).abs();
    (a.size[0] + b.size[0]) / 2.0 - r
}

/// Whether walls `a` and `b` are one partition found twice: parallel, each one's centre line
/// within the thicker one's slab, overlapping along the line by more than a cell.
fn overlaps(a: &DetectedObstacle, b: &DetectedObstacle, c: &ObstacleConfig) -> bool {
    let slab = a.size[1].max(b.size[1]) / 2.0;
    let r = b.center - a.center;
    a.dir.dot(b.dir).abs() >= PARALLEL_COS
        && r.dot(a.dir.perp()).abs() <= slab
        && r.dot(b.dir.perp()).abs() <= slab
        && overlap_along(a, b) > c.cell_m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obstacles::test_cluster;
    use glam::DVec2;

    /// A wall along y at `x`, from `y0` to `y1`, `thick_m` thick, from the floor to `top_m`.
    fn wall(x: f64, (y0, y1): (f64, f64), thick_m: f64, top_m: f64) -> DetectedObstacle {
        let centre = [x, (y0 + y1) / 2.0];
        let mut o = test_cluster(centre, DVec2::Y, [y1 - y0, thick_m], (0.0, top_m), false);
        o.class = EntityClass::Wall;
        o
    }

    #[test]
    fn a_glass_partition_read_as_two_overlapping_walls_is_one_pair() {
        // office-493: 3.37 m of it 2.57 m high, and 1.34 m 1.41 m high, overlapping by 0.8 m.
        let c = ObstacleConfig::default();
        let found = vec![
            wall(10.31, (-4.61, -1.23), 0.21, 2.67),
            wall(10.32, (-5.15, -3.81), 0.18, 1.51),
        ];
        assert_eq!(overlapping_pair(&found, &c), Some((0, 1)));
        assert!((overlap_along(&found[0], &found[1]) - 0.8).abs() < 1e-9);
        // (the longer one last in the list: the pair's indices are those of the list)
        let reversed: Vec<DetectedObstacle> = found.into_iter().rev().collect();
        assert_eq!(overlapping_pair(&reversed, &c), Some((1, 0)));
    }

    #[test]
    fn walls_side_by_side_end_to_end_or_across_are_two() {
        let c = ObstacleConfig::default();
        let a = wall(2.0, (0.0, 3.0), 0.1, 1.4);
        for (what, b) in [
            ("in line beyond its end", wall(2.0, (3.05, 5.0), 0.1, 1.4)),
            ("touching its end", wall(2.0, (2.95, 5.0), 0.1, 1.4)),
            ("parallel beside it", wall(2.3, (1.0, 4.0), 0.1, 1.4)),
            (
                "a thick wall's width away",
                wall(2.12, (1.0, 4.0), 0.1, 1.4),
            ),
            ("across it", {
                let mut b = wall(2.0, (1.0, 2.0), 0.1, 1.4);
                b.dir = DVec2::X;
                b
            }),
        ] {
            assert_eq!(overlapping_pair(&[a.clone(), b], &c), None, "{what}");
        }
        // (an obstacle in the line is for `continuations`)
        let mut b = wall(2.0, (1.0, 4.0), 0.1, 1.4);
        b.class = EntityClass::Obstacle;
        assert_eq!(overlapping_pair(&[a, b], &c), None);
    }
}
