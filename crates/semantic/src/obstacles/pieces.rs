//! A partition seen in pieces (see the `obstacles` module, step 7): seen from few places and
//! through gaps between the things before it, a partial-height partition's returns may fall
//! into several thin clusters on one line, each shorter than a partition. Thin pieces standing
//! on the floor, partition-high, continuing each other along one line across gaps narrower
//! than a passage are looked at as one; if together they stand as a partition does, they are
//! one wall. Otherwise they stay as they were: a row of things side by side is no wall. A
//! partition found on its own is one of the pieces: the clusters may cut a partition in two
//! whose longer part stands as a wall and whose shorter part, 0.4-0.6 m towards the wall it
//! meets, is left a thin obstacle (office-1 of seeds 1-10, office-202 of 201-205: the map's
//! partition ended 0.7 m short of the outer wall).

use super::fit::half_extent_along;
use super::merge::{absorb, PARALLEL_COS};
use super::partitions::partition_rule;
use super::{DetectedObstacle, ObstacleConfig, ObstacleScene, PartitionScene};
use cloud::EntityClass;

/// Pieces of one partition are at most this far apart along it: narrower than a passage (a
/// person needs 0.6 m), wider than what stands before a partition hides of it in places.
pub(super) const MAX_GAP_M: f64 = 0.3;

/// Joins the pieces of partitions in `found` (see the module docs) into walls.
pub(super) fn join_partition_pieces(
    found: Vec<DetectedObstacle>,
    ps: PartitionScene,
) -> Vec<DetectedObstacle> {
    let PartitionScene { sc, c, .. } = ps;
    // 1. The pieces: thin obstacles standing on the floor, partition-high (up to the ceiling
    //    too: a glass partition's sparse returns fall into thin slabs from the floor to the
    //    ceiling, each narrow enough for a column's face), and the partitions found so far: a
    //    piece cut off a partition's end continues it.
    let piece: Vec<usize> = (0..found.len())
        .filter(|&i| {
            let o = &found[i];
            !o.overhead
                && matches!(
                    o.class,
                    EntityClass::Obstacle | EntityClass::Column | EntityClass::Wall
                )
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
        // (partitions alone, each a wall already, stay as they are)
        if members.len() < 2 || members.iter().all(|&m| found[m].class == EntityClass::Wall) {
            continue;
        }
        let longest = members
            .iter()
            .copied()
            .max_by(|&a, &b| found[a].size[0].total_cmp(&found[b].size[0]))
            .unwrap_or(members[0]);
        let dir = line_of(&members, &found).unwrap_or(found[longest].dir);
        let mut wall = found[longest].clone();
        for &m in &members {
            if m != longest {
                absorb(&mut wall, &found[m], dir);
            }
        }
        let Some((why, top)) = partition_rule(
            &wall,
            ps,
            (
                full_height_length(&members, &found, sc, c),
                gaps_between(&members, &found, &wall),
            ),
        ) else {
            continue;
        };
        wall.class = EntityClass::Wall;
        wall.z_range.1 = top;
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

/// The length of the pieces of `members` that each stand from the floor to the ceiling (within
/// `partition_max_bottom_m` and `max_vertical_gap_m`), all of them, or 0. A glass partition
/// returns few of the beams that meet it (soda-lime glass passes ~90 % at a laser's 905 nm):
/// its returns fall into thin slabs from the floor to the ceiling, each seen standing as a
/// whole, while in a bin of 10 cm its foot's band of a few centimetres often holds no return
/// (office-133 of seeds 131-135: a 4.2 m glass partition in five pieces, covering 94 % of
/// their line; its foot seen in 56 % of its bins).
fn full_height_length(
    members: &[usize],
    found: &[DetectedObstacle],
    sc: &ObstacleScene,
    c: &ObstacleConfig,
) -> f64 {
    let full_height = |o: &DetectedObstacle| {
        o.z_range.0 - sc.floor <= c.partition_max_bottom_m
            && sc.ceiling - o.z_range.1 <= c.max_vertical_gap_m
    };
    if members.iter().all(|&m| full_height(&found[m])) {
        members.iter().map(|&m| found[m].size[0]).sum()
    } else {
        0.0
    }
}

/// The length of `wall` (the pieces of `members` joined) between its pieces, along it: where
/// what stands before the partition hid it.
fn gaps_between(members: &[usize], found: &[DetectedObstacle], wall: &DetectedObstacle) -> f64 {
    let mut spans: Vec<(f64, f64)> = members
        .iter()
        .map(|&m| {
            let o = &found[m];
            let half = half_extent_along(o.dir, o.size, wall.dir);
            let s = (o.center - wall.center).dot(wall.dir);
            (s - half, s + half)
        })
        .collect();
    spans.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut gaps = 0.0;
    let mut reach = f64::NEG_INFINITY;
    for (lo, hi) in spans {
        if reach.is_finite() && lo > reach {
            gaps += lo - reach;
        }
        reach = reach.max(hi);
    }
    gaps
}

/// The direction of the line through the centres of the two pieces of `members` farthest
/// apart, where they are farther apart than the longest piece is long: a partition's line,
/// where any one piece's box may lean a few degrees off it (and a box along that lean, around
/// all of them, is too thick for a partition); `None` otherwise.
fn line_of(members: &[usize], found: &[DetectedObstacle]) -> Option<glam::DVec2> {
    let longest = members
        .iter()
        .map(|&m| found[m].size[0])
        .fold(0.0, f64::max);
    let mut far = (0.0, None);
    for (i, &a) in members.iter().enumerate() {
        for &b in &members[i + 1..] {
            let d = found[b].center - found[a].center;
            if d.length() > far.0 {
                far = (d.length(), d.try_normalize());
            }
        }
    }
    far.1.filter(|_| far.0 > longest)
}

/// Whether pieces `a` and `b` continue each other along one line: the shorter parallel to the
/// longer or too short to have a direction, its centre within half a partition's slab of the
/// longer's centre line (or, where it has a direction, the longer's centre within as much of
/// its own: a piece's box leans a few degrees off its partition's line, and over a metre or
/// two that moves the other's centre off it by more than its slab: office-133 of seeds
/// 131-135, a partition's 0.88 m piece 4.7 degrees off), at most [`MAX_GAP_M`] beyond its end,
/// their tops within `max_vertical_gap_m`.
fn continues(a: &DetectedObstacle, b: &DetectedObstacle, c: &ObstacleConfig) -> bool {
    let (long, short) = if a.size[0] >= b.size[0] {
        (a, b)
    } else {
        (b, a)
    };
    let r = short.center - long.center;
    let gap = r.dot(long.dir).abs() - (long.size[0] + short.size[0]) / 2.0;
    let directionless = short.size[0] <= 2.0 * short.size[1];
    let on_line = |dir: glam::DVec2| r.dot(dir.perp()).abs() <= c.partition_slab_m / 2.0;
    (directionless || short.dir.dot(long.dir).abs() >= PARALLEL_COS)
        && (on_line(long.dir) || !directionless && on_line(short.dir))
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

    /// Pieces `piece_m` long, `gap_m` apart along x at y = 2 from x = 1, from the floor up to
    /// `top_m`, their foot (under 0.15 m) seen in every fourth bin of 10 cm only, as glass
    /// returns few of the beams that meet it.
    fn sparse_foot_pieces(n: usize, piece_m: f32, gap_m: f32, top_m: f32) -> Vec<glam::Vec3> {
        pieces_to(n, piece_m, gap_m, top_m)
            .into_iter()
            .filter(|p| p.z > 0.15 || (((p.x - 1.0) / 0.1).floor() as i32) % 4 == 0)
            .collect()
    }

    fn pieces_to(n: usize, piece_m: f32, gap_m: f32, top_m: f32) -> Vec<glam::Vec3> {
        (0..n)
            .flat_map(|k| {
                let x = 1.0 + k as f32 * (piece_m + gap_m);
                slab(x, x + piece_m, 2.0, 0.02, top_m)
            })
            .collect()
    }

    /// Regression (office-133 of seeds 131-135): a glass partition's returns fell into thin
    /// slabs from the floor to the ceiling, each taken for a column, its foot seen in too few
    /// bins for a partition's; in pieces each standing whole, it is one wall.
    #[test]
    fn a_glass_partition_in_pieces_from_the_floor_to_the_ceiling_is_one_wall() {
        let found = classes(&sparse_foot_pieces(3, 0.6, 0.25, 2.9));
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].0, EntityClass::Wall, "{found:?}");
        // Partition-high only, the foot seen as sparsely is not enough to stand on.
        let found = classes(&sparse_foot_pieces(3, 0.6, 0.25, 1.4));
        assert!(
            found.iter().all(|(c, _)| *c != EntityClass::Wall),
            "{found:?}"
        );
    }

    /// Regression (office-164 of seeds 161-165): a partition seen in three pieces, 0.34 m of
    /// their 1.86 m line between them, its foot missed here and there along the pieces: it
    /// stood along 68 % of its line, the gaps counted as not standing. Where the pieces are,
    /// it stands along 80 %.
    #[test]
    fn the_gaps_between_a_partitions_pieces_do_not_count_against_it() {
        let points: Vec<glam::Vec3> = pieces(3, 0.6, 0.28)
            .into_iter()
            // (each piece's foot unseen along its first 0.12 m)
            .filter(|p| p.z > 0.15 || ((p.x - 1.0) % 0.88) >= 0.12)
            .collect();
        let found = classes(&points);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].0, EntityClass::Wall, "{found:?}");
        // Gaps wider than the pieces' limit part them.
        let apart = classes(&pieces(3, 0.6, 0.45));
        assert!(
            apart.iter().all(|(c, _)| *c != EntityClass::Wall),
            "{apart:?}"
        );
    }

    /// Regression (office-133 of seeds 131-135): a partial partition in three pieces, the
    /// longest's box 4.7 degrees off their line: the farther pieces' centres lay off its line
    /// by more than a partition's slab, and a box along it around all three was too thick for
    /// a partition. The pieces' own lines and the line through their centres join them.
    #[test]
    fn a_partition_in_pieces_one_leaning_off_its_line_is_one_wall() {
        let lean = 8.0f32.to_radians();
        let (cx, cy) = (1.45f32, 2.0f32);
        let mut points: Vec<glam::Vec3> = slab(1.0, 1.9, 2.0, 0.02, 1.26)
            .into_iter()
            .map(|p| {
                let (dx, dy) = (p.x - cx, p.y - cy);
                glam::Vec3::new(
                    cx + dx * lean.cos() - dy * lean.sin(),
                    cy + dx * lean.sin() + dy * lean.cos(),
                    p.z,
                )
            })
            .collect();
        points.extend(slab(2.15, 2.75, 2.0, 0.02, 1.26));
        points.extend(slab(3.0, 3.7, 2.0, 0.02, 1.26));
        let found = classes(&points);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].0, EntityClass::Wall, "{found:?}");
    }

    /// Regression (office-1 of seeds 1-10, office-202 of 201-205): a partition's clusters cut
    /// it in two, the longer part a wall on its own and the shorter, towards the wall it met,
    /// a thin obstacle; the map's partition ended 0.7 m short. The part continues the wall.
    #[test]
    fn a_piece_cut_off_a_partitions_end_continues_it() {
        let mut points = slab(1.0, 2.3, 2.0, 0.09, 1.3);
        points.extend(slab(2.5, 2.95, 2.0, 0.09, 1.3));
        let found = classes(&points);
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
