//! A partition seen in pieces (see the `obstacles` module, step 7): seen from few places and
//! through gaps between the things before it, a partial-height partition's returns may fall
//! into several thin clusters on one line, each shorter than a partition. Thin pieces standing
//! on the floor, partition-high, continuing each other along one line across gaps narrower
//! than a passage are looked at as one; if together they stand as a partition does, they are
//! one wall. Otherwise they stay as they were: a row of things side by side is no wall.

use super::cluster::BandGrid;
use super::merge::{absorb, PARALLEL_COS};
use super::partitions::partition_rule;
use super::{DetectedObstacle, ObstacleConfig, ObstacleScene};
use crate::image_frame::ImageFrame;
use cloud::EntityClass;

/// Pieces of one partition are at most this far apart along it: narrower than a passage (a
/// person needs 0.6 m), wider than what stands before a partition hides of it in places.
const MAX_GAP_M: f64 = 0.3;

/// Joins the pieces of partitions in `found` (see the module docs) into walls.
pub(super) fn join_partition_pieces(
    found: Vec<DetectedObstacle>,
    sc: &ObstacleScene,
    grids: [&BandGrid; 2],
    floor_seen: &[bool],
    frame: &ImageFrame,
    c: &ObstacleConfig,
) -> Vec<DetectedObstacle> {
    // 1. The pieces: thin obstacles standing on the floor, partition-high.
    let piece: Vec<usize> = (0..found.len())
        .filter(|&i| {
            let o = &found[i];
            !o.overhead
                && o.class == EntityClass::Obstacle
                && o.size[1] <= c.partition_max_thickness_m
                && o.z_range.0 - sc.floor <= c.partition_max_bottom_m
                && o.z_range.1 - sc.floor >= c.partition_min_height_m
        })
        .collect();
    // 2. Groups of pieces continuing each other (union-find over pairs).
    let mut group: Vec<usize> = (0..piece.len()).collect();
    fn root(group: &mut [usize], mut i: usize) -> usize {
        while group[i] != i {
            group[i] = group[group[i]];
            i = group[i];
        }
        i
    }
    for a in 0..piece.len() {
        for b in a + 1..piece.len() {
            if continues(&found[piece[a]], &found[piece[b]], c) {
                let (ra, rb) = (root(&mut group, a), root(&mut group, b));
                group[ra] = rb;
            }
        }
    }
    // 3. Each group of two or more, put together, is a wall if it stands as a partition.
    let roots: Vec<usize> = (0..piece.len()).map(|m| root(&mut group, m)).collect();
    let mut joined_into_walls = Vec::new();
    let mut gone = vec![false; found.len()];
    for r in 0..piece.len() {
        let members: Vec<usize> = (0..piece.len())
            .filter(|&m| roots[m] == r)
            .map(|m| piece[m])
            .collect();
        if members.len() < 2 {
            continue;
        }
        let longest = members
            .iter()
            .copied()
            .max_by(|&a, &b| found[a].size[0].total_cmp(&found[b].size[0]))
            .unwrap_or(members[0]);
        let mut wall = found[longest].clone();
        for &m in &members {
            if m != longest {
                absorb(&mut wall, &found[m], found[longest].dir);
            }
        }
        let Some(why) = partition_rule(&wall, sc, grids, floor_seen, frame, c) else {
            continue;
        };
        wall.class = EntityClass::Wall;
        wall.rules.truncate(1);
        wall.rules.push(format!(
            "box: around {} thin pieces standing on the floor along one line, at most {MAX_GAP_M:.2} m apart (a partition seen in pieces)",
            members.len()
        ));
        wall.rules.push(why);
        members.iter().for_each(|&m| gone[m] = true);
        joined_into_walls.push(wall);
    }
    let mut kept: Vec<DetectedObstacle> = found
        .into_iter()
        .zip(gone)
        .filter_map(|(o, gone)| (!gone).then_some(o))
        .collect();
    kept.extend(joined_into_walls);
    kept
}

/// Whether pieces `a` and `b` continue each other along one line: the shorter parallel to the
/// longer or too short to have a direction, its centre within half a partition's slab of the
/// longer's centre line, at most [`MAX_GAP_M`] beyond its end, their tops within
/// `max_vertical_gap_m`.
fn continues(a: &DetectedObstacle, b: &DetectedObstacle, c: &ObstacleConfig) -> bool {
    let (long, short) = if a.size[0] >= b.size[0] {
        (a, b)
    } else {
        (b, a)
    };
    let r = short.center - long.center;
    let gap = r.dot(long.dir).abs() - (long.size[0] + short.size[0]) / 2.0;
    (short.size[0] <= 2.0 * short.size[1] || short.dir.dot(long.dir).abs() >= PARALLEL_COS)
        && r.dot(long.dir.perp()).abs() <= c.partition_slab_m / 2.0
        && gap <= MAX_GAP_M
        && (long.z_range.1 - short.z_range.1).abs() <= c.max_vertical_gap_m
}

#[cfg(test)]
mod tests {
    use super::super::partitions::tests::{classes, slab};
    use super::*;

    /// A partition 0.08 m thick and 1.4 m high along x at y = 2 from x = 1, in `n` pieces
    /// `piece_m` long, `gap_m` apart.
    fn pieces(n: usize, piece_m: f32, gap_m: f32) -> Vec<glam::Vec3> {
        (0..n)
            .flat_map(|k| {
                let x = 1.0 + k as f32 * (piece_m + gap_m);
                slab(x, x + piece_m, 2.0, 0.09, 1.4)
            })
            .collect()
    }

    #[test]
    fn a_partition_seen_in_pieces_along_one_line_is_one_wall() {
        // office-80 (seeds 76-80): its returns fell into clusters 0.9 m long, each too short
        // for a partition.
        let found = classes(&pieces(3, 0.6, 0.25));
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].0, EntityClass::Wall, "{found:?}");
        assert!(found[0].1.contains("partial-height wall"), "{found:?}");
    }

    #[test]
    fn a_row_of_things_side_by_side_stays_things() {
        for (what, n, piece_m, gap_m) in [
            // Further apart than a partition's pieces are.
            ("wide gaps", 3, 0.6, 0.5),
            // Near enough to be looked at as one, but mostly gaps: no wall's face.
            ("mostly gaps", 4, 0.25, 0.28),
        ] {
            let found = classes(&pieces(n, piece_m, gap_m));
            assert_eq!(found.len(), n, "{what}: {found:?}");
            assert!(
                found.iter().all(|(c, _)| *c == EntityClass::Obstacle),
                "{what}: {found:?}"
            );
        }
    }
}
