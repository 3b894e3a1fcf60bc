//! Wall residue (see the `obstacles` module, steps 5 and 7): returns of a wall that its slab
//! left over, clustered as if they were things. A wall's faces are rough, bent or blurred by
//! mixed pixels, or the wall goes on beyond the part of it found; a partition the obstacles
//! stage finds (a glass one, full height) leaves the returns above head height its cluster did
//! not climb through. Thin clusters along such a wall are its residue, not things standing
//! there.

use super::fit::rect_corners;
use super::merge::PARALLEL_COS;
use super::DetectedObstacle;
use crate::walls::WallFit;
use cloud::EntityClass;

/// The clusters without wall residue: those at most `max_across_m` thin, parallel to a wall
/// (or as thin both ways) and lying wholly within `reach_m` of its faces' planes: points a
/// wall's slab missed where its faces are rough, bent or blurred by mixed pixels, or where the
/// wall goes on beyond the part of it found (a corridor's wall seen too sparsely far away, a
/// door's jamb), not things standing there. A wall does not go on through another wall
/// crossing its line ([`walled_off`]): a partition across the corridor from a room's wall, on
/// its line, is no residue of it.
pub(super) fn drop_wall_slivers(
    found: Vec<DetectedObstacle>,
    walls: &[WallFit],
    max_across_m: f64,
    reach_m: f64,
) -> Vec<DetectedObstacle> {
    found
        .into_iter()
        .filter(|o| {
            o.size[1] > max_across_m
                || !walls.iter().enumerate().any(|(k, w)| {
                    let half = w.thickness / 2.0 + reach_m;
                    let corners = rect_corners(o.center, o.dir, o.size).map(|q| w.line.coords(q));
                    let along = corners.iter().fold((f64::MAX, f64::MIN), |(lo, hi), c| {
                        (lo.min(c.0), hi.max(c.0))
                    });
                    // (a cluster thin both ways has no direction to compare)
                    (o.size[0] <= max_across_m || w.line.dir.dot(o.dir).abs() >= PARALLEL_COS)
                        && corners.iter().all(|c| c.1.abs() <= half)
                        && !walled_off(k, along, walls)
                })
        })
        .collect()
}

/// Whether another of `walls` crosses wall `k`'s line between the part of it found and a
/// stretch `along` its line (metres from its origin) beyond it: the wall found ends there, or
/// meets that wall, and does not go on through it.
pub(super) fn walled_off(k: usize, along: (f64, f64), walls: &[WallFit]) -> bool {
    let w = &walls[k];
    let gap = if along.1 < 0.0 {
        (along.1, 0.0)
    } else if along.0 > w.length {
        (w.length, along.0)
    } else {
        return false;
    };
    walls.iter().enumerate().any(|(j, x)| {
        // Where `w`'s line meets `x`'s: the distance from `x`'s line changes by `rate` a metre.
        let rate = w.line.dir.dot(x.line.normal());
        if j == k || rate.abs() < (1.0 - PARALLEL_COS * PARALLEL_COS).sqrt() {
            return false;
        }
        let s = -x.line.coords(w.line.origin).1 / rate;
        let (t, _) = x.line.coords(w.line.at(s));
        // (across it, not ending on it: a wall meeting `w`'s line at a corner or a T is no
        // crossing, and `w` may go on past it)
        s > gap.0 && s < gap.1 && t > w.thickness && t < x.length - w.thickness
    })
}

/// The clusters of `found` without the residue of the partial-height walls among them (class
/// `wall`, see `partitions`): those at most `max_across_m` thin, parallel to such a wall (or as
/// thin both ways), lying wholly within `reach_m` of its box along and across. A glass
/// partition found here keeps the returns above head height its cluster did not climb through
/// apart, a thin "beam" along its top. A partial-height wall lying so along a longer one is its
/// residue too: the partition's face seen from its other side to another top, or what stands
/// against it, read as a partition of its own (office-162 of seeds 161-165: a 1.2 m partition
/// 8 cm thick, its west side seen to 1.0 m only, was two walls 8 cm apart; the mapped bench
/// has the two joined earlier by [`super::faces`], and this is the backstop where they are not).
pub(super) fn drop_partition_residue(
    found: Vec<DetectedObstacle>,
    max_across_m: f64,
    reach_m: f64,
) -> Vec<DetectedObstacle> {
    let walls: Vec<(usize, &DetectedObstacle)> = found
        .iter()
        .enumerate()
        .filter(|(_, o)| o.class == EntityClass::Wall)
        .collect();
    // (`o`, the `i`-th cluster, along `w`, the `j`-th, within `reach_m` of its box)
    let along = |(i, o): (usize, &DetectedObstacle), (j, w): (usize, &DetectedObstacle)| {
        let longer = w.size[0] > o.size[0] || (w.size[0] == o.size[0] && j < i);
        i != j
            && (o.class != EntityClass::Wall || longer)
            && (o.size[0] <= max_across_m || w.dir.dot(o.dir).abs() >= PARALLEL_COS)
            && rect_corners(o.center, o.dir, o.size).iter().all(|q| {
                let r = *q - w.center;
                r.dot(w.dir).abs() <= w.size[0] / 2.0 + reach_m
                    && r.dot(w.dir.perp()).abs() <= w.size[1] / 2.0 + reach_m
            })
    };
    let keep: Vec<bool> = found
        .iter()
        .enumerate()
        .map(|(i, o)| o.size[1] > max_across_m || !walls.iter().any(|&w| along((i, o), w)))
        .collect();
    found
        .into_iter()
        .zip(keep)
        .filter_map(|(o, k)| k.then_some(o))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obstacles::test_cluster as cluster;
    use glam::DVec2;

    #[test]
    fn thin_clusters_along_a_wall_face_or_its_continuation_are_residue() {
        let wall = WallFit {
            line: crate::points::Line2 {
                origin: DVec2::ZERO,
                dir: DVec2::X,
            },
            length: 10.0,
            thickness: 0.2,
            measured: true,
            faces: vec![0.1, -0.1],
            free_side: 1.0,
            z_range: (0.0, 2.5),
            support: 1000,
            coverage: 1.0,
            rules: Vec::new(),
        };
        let sliver = cluster([3.0, 0.2], DVec2::X, [1.5, 0.05], (0.0, 2.0), false);
        let shelf = cluster([6.0, 0.45], DVec2::X, [1.5, 0.5], (0.0, 2.0), false);
        let post = cluster([3.0, 2.0], DVec2::X, [0.3, 0.05], (0.0, 2.0), false);
        // A fragment of the same wall's face 4 m beyond its found end, thin both ways.
        let beyond = cluster([14.0, 0.15], DVec2::Y, [0.08, 0.05], (0.0, 2.4), false);
        let out = drop_wall_slivers(vec![sliver, shelf, post, beyond], &[wall], 0.1, 0.2);
        assert_eq!(out.len(), 2, "{out:#?}");
        assert!(out.iter().all(|o| o.center.y > 0.3));
    }

    /// A wall along x from 0 to `length`, 0.15 m thick, or along y from `origin` if `across`.
    fn wall_fit(origin: [f64; 2], across: bool, length: f64) -> WallFit {
        WallFit {
            line: crate::points::Line2 {
                origin: DVec2::from_array(origin),
                dir: if across { DVec2::Y } else { DVec2::X },
            },
            length,
            thickness: 0.15,
            measured: true,
            faces: vec![0.075, -0.075],
            free_side: 1.0,
            z_range: (0.0, 2.5),
            support: 1000,
            coverage: 1.0,
            rules: Vec::new(),
        }
    }

    #[test]
    fn a_partition_on_a_walls_line_beyond_a_crossing_wall_is_no_residue_of_it() {
        // office-97 (seeds 96-100): a room's wall ends at the corridor; across the corridor a
        // partial partition 1.9 m long stands 0.1 m off its line. The corridor's walls cross
        // the line between: the room's wall does not go on through them.
        let room_wall = wall_fit([0.0, 0.0], false, 4.7);
        let corridor = [
            wall_fit([4.8, -6.0], true, 12.0),
            wall_fit([7.5, -6.0], true, 12.0),
        ];
        let partition = cluster([10.0, 0.1], DVec2::X, [1.9, 0.08], (0.0, 1.4), false);
        let walls = [room_wall.clone(), corridor[0].clone(), corridor[1].clone()];
        let out = drop_wall_slivers(vec![partition.clone()], &walls, 0.2, 0.25);
        assert_eq!(out.len(), 1, "{out:#?}");
        // Without the corridor's walls, it is the room's wall going on beyond its found end.
        let out = drop_wall_slivers(
            vec![partition.clone()],
            std::slice::from_ref(&room_wall),
            0.2,
            0.25,
        );
        assert!(out.is_empty(), "{out:#?}");
        // A wall that ends short of the line, or on it (a T), does not cross it.
        for origin in [[4.8, 1.0], [4.8, 0.075]] {
            let short = [room_wall.clone(), wall_fit(origin, true, 5.0)];
            let out = drop_wall_slivers(vec![partition.clone()], &short, 0.2, 0.25);
            assert!(out.is_empty(), "{out:#?}");
        }
    }

    #[test]
    fn a_thin_beam_along_a_glass_partition_found_here_is_its_residue() {
        // office-9 (seeds 1-10): a glass partition 4.8 m long found by the obstacles stage
        // (0.21 m thick, to 2.71 m), and a "beam" 3.98 x 0.05 m at 1.96-2.69 m along its top.
        let mut glass = cluster([8.18, -3.73], DVec2::Y, [4.8, 0.21], (0.0, 2.71), false);
        glass.class = EntityClass::Wall;
        let top = cluster([8.26, -3.33], DVec2::Y, [3.98, 0.05], (1.96, 2.69), true);
        // A duct 0.3 m wide crossing over it, and a beam 1 m away, stay.
        let duct = cluster([8.18, -3.0], DVec2::X, [3.0, 0.3], (2.3, 2.6), true);
        let beam = cluster([9.2, -3.73], DVec2::Y, [4.0, 0.1], (2.3, 2.7), true);
        let out = drop_partition_residue(vec![glass, top, duct, beam], 0.2, 0.3);
        assert_eq!(out.len(), 3, "{out:#?}");
        assert!(out.iter().all(|o| (o.center.y - -3.33).abs() > 1e-9));
        // Not found as a wall, the same cluster keeps its neighbours.
        let mut plain = cluster([8.18, -3.73], DVec2::Y, [4.8, 0.21], (0.0, 2.71), false);
        plain.class = EntityClass::Obstacle;
        let top = cluster([8.26, -3.33], DVec2::Y, [3.98, 0.05], (1.96, 2.69), true);
        assert_eq!(drop_partition_residue(vec![plain, top], 0.2, 0.3).len(), 2);
    }

    #[test]
    fn a_partition_along_a_longer_one_is_its_other_face() {
        // office-162 (seeds 161-165): a partition 0.08 m thick to 1.2 m found as a wall 1.70 m
        // long, and its west face, seen to 1.0 m, as another 1.14 m long 8 cm beside it.
        let wall = |c: [f64; 2], size: [f64; 2], top: f64| {
            let mut w = cluster(c, DVec2::Y, size, (0.0, top), false);
            w.class = EntityClass::Wall;
            w
        };
        let long = wall([9.18, 4.42], [1.70, 0.13], 1.2);
        let face = wall([9.10, 4.26], [1.14, 0.09], 1.01);
        let out = drop_partition_residue(vec![face.clone(), long.clone()], 0.2, 0.3);
        assert_eq!(out.len(), 1, "{out:#?}");
        assert!((out[0].size[0] - 1.70).abs() < 1e-9);
        // A partition 1 m beside it, or going on 1 m past its end, is a wall of its own.
        let apart = wall([10.1, 4.26], [1.14, 0.09], 1.01);
        let past = wall([9.10, 5.26], [1.14, 0.09], 1.01);
        assert_eq!(
            drop_partition_residue(vec![apart, past, long], 0.2, 0.3).len(),
            3
        );
    }
}
