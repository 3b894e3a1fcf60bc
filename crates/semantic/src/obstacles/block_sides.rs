//! A block's side seen past the top that hid it: a parked car's body side (to 1.0 m) along and
//! past its cabin (1.44 m), its own top above the laser and never seen. The side is a thin
//! cluster standing on the floor in line with the block's side, lower than the block's top by
//! more than a step, so it clusters apart from the block (see the `obstacles` module) and is no
//! part lying inside the block's box (`merge`); where the block stands with its end to a wall
//! its rear is the two sides alone. Such a face is longer than a thing's side
//! ([`MIN_SIDE_LENGTH_M`]): a chair's seat seen as its edge by a desk is no desk's side.

use super::classify::set_box_rule;
use super::merge::{absorb, PARALLEL_COS};
use super::{DetectedObstacle, ObstacleConfig};
use glam::DVec2;

/// A block's side seen on its own is longer than this: a seat's or a backrest's edge (chairs
/// 0.45-0.7 m wide, a cell more for the grid) is not.
const MIN_SIDE_LENGTH_M: f64 = 0.8;
/// A side continues its block across a gap of at most this along it (two cells: where the
/// block's last cells and the side's first are apart, cells up to two apart still cluster).
const MAX_GAP_M: f64 = 0.2;

/// The clusters, each thin one that is the side of a thicker one (see the module docs) taken
/// in by it: parallel to one of its axes, its centre line within the block's extent across
/// that axis grown by `margin_m`, overlapping it along the axis or apart by at most
/// [`MAX_GAP_M`], its bottom the block's (within `max_top_step_m`) and its top lower than the
/// block's by more than that.
pub(super) fn join_block_sides(
    mut found: Vec<DetectedObstacle>,
    margin_m: f64,
    c: &ObstacleConfig,
) -> Vec<DetectedObstacle> {
    let step = c.max_top_step_m;
    let is_side = |o: &DetectedObstacle| {
        !o.overhead && o.size[1] <= c.sliver_max_across_m && o.size[0] > MIN_SIDE_LENGTH_M
    };
    let is_block = |o: &DetectedObstacle| !o.overhead && o.size[1] > c.sliver_max_across_m;
    loop {
        let pair = (0..found.len())
            .filter(|&i| is_side(&found[i]))
            .find_map(|i| {
                (0..found.len())
                    .filter(|&k| k != i && is_block(&found[k]))
                    .find(|&k| side_of(&found[i], &found[k], margin_m, step))
                    .map(|k| (i, k))
            });
        let Some((i, k)) = pair else {
            return found;
        };
        let side = found.swap_remove(i);
        // (swap_remove moved the last cluster to `i`)
        let k = if k == found.len() { i } else { k };
        let why = format!(
            "box: around a thing and its side {:.2} m long seen past its top, {:.2} m lower",
            side.size[0],
            found[k].z_range.1 - side.z_range.1
        );
        let dir = found[k].dir;
        absorb(&mut found[k], &side, dir);
        set_box_rule(&mut found[k], why);
    }
}

/// Whether `side` is a side of `block` (see [`join_block_sides`]).
fn side_of(side: &DetectedObstacle, block: &DetectedObstacle, margin_m: f64, step: f64) -> bool {
    // The block's axis along the side, and its half extents along and across it.
    let (along, half) = if side.dir.dot(block.dir).abs() >= PARALLEL_COS {
        (block.dir, [block.size[0] / 2.0, block.size[1] / 2.0])
    } else if side.dir.dot(block.dir.perp()).abs() >= PARALLEL_COS {
        (block.dir.perp(), [block.size[1] / 2.0, block.size[0] / 2.0])
    } else {
        return false;
    };
    let r: DVec2 = side.center - block.center;
    let across = r.dot(along.perp()).abs();
    let gap = r.dot(along).abs() - half[0] - side.size[0] / 2.0;
    across <= half[1] + margin_m
        && gap <= MAX_GAP_M
        && (side.z_range.0 - block.z_range.0).abs() <= step
        && side.z_range.1 < block.z_range.1 - step
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obstacles::test_cluster as cluster;

    /// Regression (garage-6 of seeds 1-10: car 9, parked with its rear to the wall, was its
    /// body and cabin, 2.5 m long to 1.58 m, and the strips of its two sides along its rear,
    /// 1.07 and 1.87 m long to 1.0 m, each a box of its own).
    #[test]
    fn a_cars_sides_past_its_cabin_are_the_car() {
        let c = ObstacleConfig::default();
        let car = cluster([23.1, 3.07], DVec2::Y, [3.86, 1.89], (0.1, 1.58), false);
        let left = cluster([22.19, 0.65], DVec2::Y, [1.07, 0.05], (0.1, 1.08), false);
        let right = cluster([23.97, 1.03], DVec2::Y, [1.87, 0.05], (0.1, 1.09), false);
        let out = join_block_sides(vec![left, car, right], 0.1, &c);
        assert_eq!(out.len(), 1, "{out:#?}");
        let (lo, hi) = (
            out[0].center.y - out[0].size[0] / 2.0,
            out[0].center.y + out[0].size[0] / 2.0,
        );
        assert!(
            (lo - 0.1).abs() < 0.01 && (hi - 5.0).abs() < 0.01,
            "{lo} {hi}"
        );
        assert_eq!(out[0].support, 300);
    }

    #[test]
    fn a_seat_by_a_desk_a_backrest_a_partition_and_a_face_off_the_side_stay_apart() {
        let c = ObstacleConfig::default();
        let desk = || cluster([0.0, 0.0], DVec2::X, [1.4, 0.8], (0.0, 0.75), false);
        let apart = |o: DetectedObstacle| join_block_sides(vec![desk(), o], 0.1, &c).len() == 2;
        // A seat's edge at the desk's side, lower, as long as a chair is wide.
        assert!(apart(cluster(
            [0.2, 0.45],
            DVec2::X,
            [0.6, 0.1],
            (0.0, 0.45),
            false
        )));
        // A backrest as high as the desk's top.
        assert!(apart(cluster(
            [0.2, 0.45],
            DVec2::X,
            [0.9, 0.05],
            (0.0, 0.8),
            false
        )));
        // A partition higher than the desk against it.
        assert!(apart(cluster(
            [0.0, 0.45],
            DVec2::X,
            [1.6, 0.08],
            (0.0, 1.4),
            false
        )));
        // A low face 0.4 m off the desk's side, past its end by more than two cells, or across
        // its end half a metre off.
        assert!(apart(cluster(
            [0.0, 0.8],
            DVec2::X,
            [1.2, 0.1],
            (0.0, 0.4),
            false
        )));
        assert!(apart(cluster(
            [1.8, 0.35],
            DVec2::X,
            [1.0, 0.1],
            (0.0, 0.4),
            false
        )));
        assert!(apart(cluster(
            [1.2, 0.0],
            DVec2::Y,
            [1.0, 0.1],
            (0.0, 0.4),
            false
        )));
        // The same low face along the desk's side is its side.
        assert!(!apart(cluster(
            [0.0, 0.35],
            DVec2::X,
            [1.2, 0.1],
            (0.0, 0.4),
            false
        )));
    }
}
