//! A partition's ends at the walls it meets (see the `obstacles` module, step 7): the stage
//! looks at no returns within `wall_margin_m` of a wall's slab (by whole cells: they are the
//! wall's face and its noise), so a partition meeting a wall is found ending that margin and up
//! to a cell short of the wall's face. An end that near a wall's face, running square into it,
//! meets the wall there: nothing passes through a gap that narrow, and the partition's returns
//! in it were left out with the wall's, not missing (office-202 of seeds 201-205: the map's
//! partition ended 0.18 m short of the outer wall it met).

use super::fit::{convex_hull, rect_corners};
use super::{DetectedObstacle, ObstacleConfig};
use crate::walls::WallFit;
use cloud::EntityClass;

/// A partition runs square into a wall: the cosine of the largest angle between the
/// partition's direction and the wall's normal (30 degrees).
const SQUARE_COS: f64 = 0.866;

/// Moves each end of the partitions in `found` (walls this stage found) that lies within
/// `wall_margin_m` and a cell of a wall's face, running square into it, onto the face (see the
/// module docs).
pub(super) fn meet_walls(found: &mut [DetectedObstacle], walls: &[WallFit], c: &ObstacleConfig) {
    let reach = c.wall_margin_m + c.cell_m;
    for o in found
        .iter_mut()
        .filter(|o| o.class == EntityClass::Wall && !o.overhead)
    {
        let (mut lo, mut hi) = (-o.size[0] / 2.0, o.size[0] / 2.0);
        for (end, sign) in [(&mut lo, -1.0), (&mut hi, 1.0)] {
            let out = o.dir * sign;
            let tip = o.center + o.dir * *end;
            let gap = walls
                .iter()
                .filter_map(|w| gap_to_face(w, tip, out))
                .filter(|&g| g > 0.0 && g <= reach)
                .min_by(f64::total_cmp);
            if let Some(g) = gap {
                *end += sign * g;
            }
        }
        if (lo, hi) != (-o.size[0] / 2.0, o.size[0] / 2.0) {
            o.center += o.dir * ((lo + hi) / 2.0);
            o.size[0] = hi - lo;
            // (its footprint reaches the face too)
            o.hull.extend(rect_corners(o.center, o.dir, o.size));
            o.hull = convex_hull(&o.hull);
        }
    }
}

/// How far from `tip`, going `out` (a unit direction), the face of `w` facing it is, if `out`
/// runs square into `w` (within [`SQUARE_COS`]) and meets its face within its length.
fn gap_to_face(w: &WallFit, tip: glam::DVec2, out: glam::DVec2) -> Option<f64> {
    let n = w.line.normal();
    let (s, d) = w.line.coords(tip);
    let towards = -d.signum() * out.dot(n);
    if towards < SQUARE_COS || s < 0.0 || s > w.length {
        return None;
    }
    Some((d.abs() - w.thickness / 2.0) / towards)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::Line2;
    use glam::DVec2;

    /// A partition 0.08 m thick along y at x = 2, from y = 1 to `end_y`, as the stage finds it.
    fn partition(end_y: f64) -> DetectedObstacle {
        let mut o = crate::obstacles::test_cluster(
            [2.0, (1.0 + end_y) / 2.0],
            DVec2::Y,
            [end_y - 1.0, 0.08],
            (0.0, 1.3),
            false,
        );
        o.class = EntityClass::Wall;
        o
    }

    /// A wall 0.15 m thick along x at y = 5 (its face towards the partition at 4.925).
    fn wall(dir: DVec2) -> WallFit {
        WallFit {
            line: Line2 {
                origin: DVec2::new(2.0, 5.0) - dir * 3.0,
                dir,
            },
            length: 6.0,
            thickness: 0.15,
            measured: false,
            faces: vec![-0.075],
            free_side: -1.0,
            z_range: (0.0, 3.0),
            support: 1000,
            coverage: 1.0,
            rules: Vec::new(),
        }
    }

    #[test]
    fn a_partition_ending_a_margin_short_of_a_wall_meets_its_face() {
        let c = ObstacleConfig::default();
        let mut found = vec![partition(4.75)];
        meet_walls(&mut found, &[wall(DVec2::X)], &c);
        let top_end = found[0].center.y + found[0].size[0] / 2.0;
        assert!((top_end - 4.925).abs() < 1e-9, "{:?}", found[0]);
        // Its other end, 3.9 m from the wall, stays where it was.
        let bottom_end = found[0].center.y - found[0].size[0] / 2.0;
        assert!((bottom_end - 1.0).abs() < 1e-9, "{:?}", found[0]);
        // Its footprint's hull reaches the face too.
        let hull_top = found[0].hull.iter().map(|q| q.y).fold(f64::MIN, f64::max);
        assert!((hull_top - 4.925).abs() < 1e-9, "{:?}", found[0]);
    }

    #[test]
    fn a_partition_ending_farther_or_along_a_wall_stays_as_found() {
        let c = ObstacleConfig::default();
        for (what, end_y, w) in [
            // 0.4 m short: a gap something could stand in, or a passage.
            ("farther", 4.5, wall(DVec2::X)),
            // A wall along the partition's line (beside it, not across its end).
            ("along", 4.75, wall(DVec2::Y)),
        ] {
            let mut found = vec![partition(end_y)];
            meet_walls(&mut found, &[w], &c);
            let top_end = found[0].center.y + found[0].size[0] / 2.0;
            assert!((top_end - end_y).abs() < 1e-9, "{what}: {:?}", found[0]);
        }
        // An obstacle (not a partition) near a wall is left as it is.
        let mut found = vec![partition(4.75)];
        found[0].class = EntityClass::Obstacle;
        meet_walls(&mut found, &[wall(DVec2::X)], &c);
        assert!((found[0].size[0] - 3.75).abs() < 1e-9, "{:?}", found[0]);
    }
}
