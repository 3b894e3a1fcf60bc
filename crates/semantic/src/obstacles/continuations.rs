//! A partition continued by a thin piece in its line (see the `obstacles` module, step 7): a
//! glass pane returns few beams, scattered a few centimetres about its plane, so the boxes of
//! its pieces come out up to a cell thicker than the pane, and a piece too thick for a
//! partition on its own is left a column or an obstacle where it continues a partition found
//! beside it (office-385 of seeds 381-385: a full-height glass partition 4.3 m long was a wall
//! of 3.1 m and a "column" 1.0 x 0.26 m in its line, ending 1.1 m short of the corridor wall it
//! met). A piece standing on the floor as tall as the partition, long along its line and at
//! most a cell thicker, its centre on the partition's centre line and its end within a gap
//! narrower than a passage of the partition's, is the partition's where the partition, run
//! on over it at its own thickness, still stands as one. A pillar (as wide as deep) or a block
//! (thicker) at a partition's end stays what it is.

use super::fit::convex_hull;
use super::partitions::partition_rule;
// (a piece continuing a partition starts at most as far beyond its end as pieces of one are
// apart: narrower than a passage)
use super::pieces::MAX_GAP_M;
use super::{DetectedObstacle, ObstacleConfig, PartitionScene};
use cloud::EntityClass;

/// A piece in a partition's line runs along it: at least this many times as long as thick.
const MIN_ELONGATION: f64 = 2.0;

/// The partitions of `found` (walls this stage found) run on over the thin pieces continuing
/// them (see the module docs); the pieces taken are gone.
pub(super) fn continue_partitions(
    mut found: Vec<DetectedObstacle>,
    ps: PartitionScene,
) -> Vec<DetectedObstacle> {
    let PartitionScene { sc, c, .. } = ps;
    let mut gone = vec![false; found.len()];
    for p in 0..found.len() {
        if found[p].class != EntityClass::Wall || found[p].overhead {
            continue;
        }
        // (a piece taken may have a further piece beyond it)
        loop {
            let next = (0..found.len())
                .find(|&q| q != p && !gone[q] && continues(&found[p], &found[q], sc.floor, c));
            let Some(q) = next else {
                break;
            };
            let mut wall = run_on(&found[p], &found[q]);
            let Some((why, top)) = partition_rule(&wall, ps, (0.0, 0.0)) else {
                break;
            };
            wall.z_range.1 = top;
            wall.rules.truncate(1);
            wall.rules.push(format!(
                "box: a partition's, run on over a piece in its line {:.2} m long and {:.2} m thick (a glass pane's scattered returns)",
                found[q].size[0], found[q].size[1]
            ));
            wall.rules.push(why);
            found[p] = wall;
            gone[q] = true;
        }
    }
    found
        .into_iter()
        .zip(gone)
        .filter_map(|(o, gone)| (!gone).then_some(o))
        .collect()
}

/// Whether `q` continues partition `p` (see the module docs).
fn continues(p: &DetectedObstacle, q: &DetectedObstacle, floor: f64, c: &ObstacleConfig) -> bool {
    if q.overhead || !matches!(q.class, EntityClass::Obstacle | EntityClass::Column) {
        return false;
    }
    let r = q.center - p.center;
    let gap = r.dot(p.dir).abs() - (p.size[0] + q.size[0]) / 2.0;
    q.dir.dot(p.dir).abs() >= super::merge::PARALLEL_COS
        && q.size[0] >= MIN_ELONGATION * q.size[1]
        && q.size[1] <= p.size[1] + c.cell_m
        && r.dot(p.dir.perp()).abs() <= p.size[1].max(c.cell_m) / 2.0
        && (-q.size[0] / 2.0..=MAX_GAP_M).contains(&gap)
        && q.z_range.0 - floor <= c.partition_max_bottom_m
        && (q.z_range.1 - p.z_range.1).abs() <= c.max_vertical_gap_m
}

/// `p` run on along its line over `q`, at its own thickness.
fn run_on(p: &DetectedObstacle, q: &DetectedObstacle) -> DetectedObstacle {
    let s = (q.center - p.center).dot(p.dir);
    let half_q = super::fit::half_extent_along(q.dir, q.size, p.dir);
    let lo = (-p.size[0] / 2.0).min(s - half_q);
    let hi = (p.size[0] / 2.0).max(s + half_q);
    let mut wall = p.clone();
    wall.center = p.center + p.dir * ((lo + hi) / 2.0);
    wall.size[0] = hi - lo;
    let mut hull = p.hull.clone();
    hull.extend(q.hull.iter().copied());
    wall.hull = convex_hull(&hull);
    wall.z_range = (p.z_range.0.min(q.z_range.0), p.z_range.1);
    wall.support += q.support;
    wall
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obstacles::test_cluster;
    use glam::DVec2;

    /// A full-height glass partition along y at x = 2, from y = 0 to 3, found 0.2 m thick
    /// (its returns scattered about the pane).
    fn partition() -> DetectedObstacle {
        let mut o = test_cluster([2.0, 1.5], DVec2::Y, [3.0, 0.2], (0.0, 2.6), false);
        o.class = EntityClass::Wall;
        o
    }

    /// A piece centred at `(x, y)` along y, `size` (along, across), standing 0-2.7 m.
    fn piece(x: f64, y: f64, size: [f64; 2], class: EntityClass) -> DetectedObstacle {
        let mut o = test_cluster([x, y], DVec2::Y, size, (0.0, 2.7), false);
        o.class = class;
        o
    }

    #[test]
    fn a_glass_panes_thick_piece_in_a_partitions_line_continues_it() {
        // office-385: a 1.0 x 0.26 m "column" 0.01 m off the line, starting at its end.
        let c = ObstacleConfig::default();
        let q = piece(2.01, 3.5, [1.0, 0.26], EntityClass::Column);
        assert!(continues(&partition(), &q, 0.0, &c));
        let wall = run_on(&partition(), &q);
        assert!((wall.size[0] - 4.0).abs() < 1e-9, "{wall:?}");
        assert!((wall.size[1] - 0.2).abs() < 1e-9, "{wall:?}");
        assert!(
            (wall.center - DVec2::new(2.0, 2.0)).length() < 1e-9,
            "{wall:?}"
        );
        // ... and across a gap narrower than a passage.
        assert!(continues(
            &partition(),
            &piece(2.0, 3.75, [1.0, 0.2], EntityClass::Obstacle),
            0.0,
            &c
        ));
    }

    #[test]
    fn a_pillar_a_block_or_a_piece_off_the_line_or_far_does_not_continue_it() {
        let c = ObstacleConfig::default();
        let p = partition();
        for (what, q) in [
            (
                "a pillar at its end",
                piece(2.0, 3.25, [0.45, 0.4], EntityClass::Column),
            ),
            (
                "a block at its end",
                piece(2.0, 3.6, [1.2, 0.6], EntityClass::Obstacle),
            ),
            (
                "thicker by more than a cell",
                piece(2.0, 3.5, [1.0, 0.32], EntityClass::Column),
            ),
            (
                "beside its line",
                piece(2.2, 3.5, [1.0, 0.2], EntityClass::Obstacle),
            ),
            (
                "a passage beyond",
                piece(2.0, 4.2, [1.0, 0.2], EntityClass::Obstacle),
            ),
            ("across its line", {
                let mut q = piece(2.0, 3.5, [1.0, 0.2], EntityClass::Obstacle);
                q.dir = DVec2::X;
                q
            }),
            ("low", {
                let mut q = piece(2.0, 3.5, [1.0, 0.2], EntityClass::Obstacle);
                q.z_range.1 = 0.8;
                q
            }),
        ] {
            assert!(!continues(&p, &q, 0.0, &c), "{what}");
        }
    }
}
