//! Partial-height walls (see the `obstacles` module, step 7): a partition 1.2-1.8 m high, a
//! parapet, a screen stops under the projection band the wall stage looks at, so it reaches
//! this stage as a thin cluster. It is a wall when it stands like one: thin and long, at least
//! `partition_min_height_m` tall, and its face seen from the floor up to its top along most of
//! its length. A car's side is as thin and long seen from one side, but its body is clear of
//! the floor between the wheels; a shelf's or a desk's front stands on legs or a plinth set
//! back; a row of things side by side has gaps. A partition divides space: the floor is seen
//! beside it on both sides (`partition_min_floor_both_sides` of its length), while a face of a
//! block (a car, a crate, a cabinet) has the block's unseen footprint behind it. A panel seen
//! from one side has its shadow behind it instead, but round its free end the laser sees the
//! floor right behind its face, where a block's body would stand. A slab along a wall, nearer
//! to it than a passage is wide (`partition_min_passage_m`), divides no space: it is the front
//! of a cabinet or a shelf against that wall, seen from the room.

use super::classify::set_box_rule;
use super::cluster::BandGrid;
use super::fit::rect_corners;
use super::slabs::{points_in_box, thin_slab};
use super::{DetectedObstacle, ObstacleConfig, ObstacleScene};
use crate::image_frame::ImageFrame;
use cloud::EntityClass;
use glam::DVec2;

/// Bins along a partition's length in which its face is looked for.
const BIN_M: f64 = 0.1;

/// What stands against a partition runs along at most this share of it: a desk 1.2-1.6 m
/// long by a partition 1.6-2 m long, a chair; a block's faces beside the one taken run along
/// all of it (their boxes reach a little beyond, by the mixed pixels at its edges).
const MAX_BESIDE_SHARE: f64 = 0.8;

/// Makes `o` a wall if it stands as a partial-height wall does (see the module docs); its last
/// rule says why. A cluster too thick for one may hold one with things standing against it
/// ([`thin_slab`]): then `o` becomes that wall, and what stood against it is returned.
pub(super) fn classify_partition(
    o: &mut DetectedObstacle,
    sc: &ObstacleScene,
    grids: [&BandGrid; 2],
    floor_seen: &[bool],
    frame: &ImageFrame,
    c: &ObstacleConfig,
) -> Vec<DetectedObstacle> {
    if o.overhead || o.class != EntityClass::Obstacle {
        return Vec::new();
    }
    // 1. The cluster as it is.
    if let Some(why) = partition_rule(o, sc, grids, floor_seen, frame, c) {
        o.class = EntityClass::Wall;
        o.rules.truncate(2);
        o.rules.push(why);
        return Vec::new();
    }
    // 2. A cluster too thick for one: the thin slab holding most of its returns, and what
    //    stands against it. What stands against a partition (a desk, a chair) runs along part
    //    of it, while a block's other faces (a crate's, a row of crates') run along the whole
    //    face taken ([`MAX_BESIDE_SHARE`]). And the slab stays under head height: a door's
    //    leaf standing open (2 m or more) is as thin, with its frame beside it.
    if o.size[1] <= c.partition_max_thickness_m {
        return Vec::new();
    }
    let Some((mut slab, rest)) = thin_slab(o, sc, grids, frame, c) else {
        return Vec::new();
    };
    let along_slab = |r: &DetectedObstacle| {
        let s = rect_corners(r.center, r.dir, r.size).map(|q| q.dot(slab.dir));
        s.iter().copied().fold(f64::MIN, f64::max) - s.iter().copied().fold(f64::MAX, f64::min)
    };
    if rest
        .iter()
        .any(|r| along_slab(r) >= MAX_BESIDE_SHARE * slab.size[0])
        || slab.z_range.1 - sc.floor > c.head_height_m
    {
        return Vec::new();
    }
    let Some(why) = partition_rule(&slab, sc, grids, floor_seen, frame, c) else {
        return Vec::new();
    };
    slab.class = EntityClass::Wall;
    set_box_rule(
        &mut slab,
        format!(
            "box: the slab {:.2} m thick holding the most returns of a cluster {:.2} m thick (things standing against a partition), its smallest-area rectangle",
            c.partition_slab_m, o.size[1]
        ),
    );
    slab.rules.truncate(2);
    slab.rules.push(why);
    *o = slab;
    rest
}

/// Why `o` stands as a partial-height wall does (see the module docs), or `None`.
pub(super) fn partition_rule(
    o: &DetectedObstacle,
    sc: &ObstacleScene,
    grids: [&BandGrid; 2],
    floor_seen: &[bool],
    frame: &ImageFrame,
    c: &ObstacleConfig,
) -> Option<String> {
    let [length, across] = o.size;
    let height = o.z_range.1 - sc.floor;
    if across > c.partition_max_thickness_m
        || length < c.partition_min_length_m
        || length < 4.0 * across
        || height < c.partition_min_height_m
        || faces_a_wall(o, sc, c.partition_min_passage_m)
    {
        return None;
    }
    let divides = divides_space(o, floor_seen, frame, c)?;
    let standing = standing_fraction(o, sc, &points_in_box(o, sc, grids, frame), c);
    (standing >= c.partition_min_standing).then(|| format!(
        "a partial-height wall: {length:.2} m long, {across:.2} m thick, {height:.2} m high; its face seen from within {:.2} m of the floor up to its top along {:.0} % of its length (a wall stands on the floor along {:.0} % at least); {divides}",
        c.partition_max_bottom_m,
        100.0 * standing,
        100.0 * c.partition_min_standing
    ))
}

/// How `o` divides space (see the module docs), or `None` if it may be a block's face: the
/// floor seen on both sides of it along `partition_min_floor_both_sides` of its length, or, a
/// panel seen from one side, the floor seen on that side along as much of it and round its
/// free end right behind its face ([`seen_round_an_end`]).
fn divides_space(
    o: &DetectedObstacle,
    floor_seen: &[bool],
    frame: &ImageFrame,
    c: &ObstacleConfig,
) -> Option<String> {
    let beside = floor_beside(o, floor_seen, frame, BESIDE_M);
    let both = share(beside.iter().map(|[a, b]| *a && *b));
    if both >= c.partition_min_floor_both_sides {
        return Some(format!(
            "the floor seen on both sides of it along {:.0} % of its length",
            100.0 * both
        ));
    }
    let one = share(beside.iter().map(|[a, b]| *a || *b));
    let behind = floor_beside(o, floor_seen, frame, BEHIND_M);
    (one >= c.partition_min_floor_both_sides && seen_round_an_end(&behind)).then(|| format!(
        "a panel seen from one side: the floor seen beside it along {:.0} % of its length, and on both sides within {BEHIND_M:.2} m of its faces along its last {:.1} m or more at an end, where a block's body would stand",
        100.0 * one,
        ROUND_END_BINS as f64 * BIN_M
    ))
}

/// How near behind a panel's face the floor is seen round its free end: nearer than a
/// cabinet or a crate is deep (0.3 m and more), farther than a registered face's spread.
const BEHIND_M: f64 = 0.15;

/// The bins at an end of a panel in which the floor must be seen right behind it: 0.2 m, more
/// than a block's corner lets the laser see behind its front by the mixed pixels at its edge.
const ROUND_END_BINS: usize = 2;

/// Whether the floor is seen on both sides of a panel within [`BEHIND_M`] of its faces along
/// the first or the last [`ROUND_END_BINS`] bins of its length: seen from one side, the floor
/// behind a panel is in its shadow, but the laser sees round its free end right behind it,
/// where the footprint of a block seen from one side hides the floor to the block's depth.
fn seen_round_an_end(behind: &[[bool; 2]]) -> bool {
    let both = |b: &[bool; 2]| b[0] && b[1];
    behind.len() > 2 * ROUND_END_BINS
        && (behind[..ROUND_END_BINS].iter().all(both)
            || behind[behind.len() - ROUND_END_BINS..].iter().all(both))
}

/// For each bin of `o`'s length ([`BIN_M`]), whether the floor was seen on either side of it
/// within `beside_m` of its faces (cells of `frame`, `floor_seen`).
fn floor_beside(
    o: &DetectedObstacle,
    floor_seen: &[bool],
    frame: &ImageFrame,
    beside_m: f64,
) -> Vec<[bool; 2]> {
    let bins = (o.size[0] / BIN_M).ceil().max(1.0) as usize;
    let w = frame.width_px as usize;
    let seen = |q: DVec2| {
        frame
            .pixel_of(q.x, q.y)
            .is_some_and(|(col, row)| floor_seen[row as usize * w + col as usize])
    };
    let across = o.dir.perp();
    let steps = (beside_m / frame.resolution_m).ceil().max(1.0) as usize;
    (0..bins)
        .map(|k| {
            let s = -o.size[0] / 2.0 + (k as f64 + 0.5) * BIN_M;
            [-1.0, 1.0].map(|side| {
                (1..=steps).any(|j| {
                    let d = o.size[1] / 2.0 + j as f64 * frame.resolution_m;
                    seen(o.center + o.dir * s + across * (side * d))
                })
            })
        })
        .collect()
}

/// The share of `bins` that hold.
fn share(bins: impl ExactSizeIterator<Item = bool>) -> f64 {
    let n = bins.len().max(1);
    bins.filter(|b| *b).count() as f64 / n as f64
}

/// How far beside a partition's faces the floor is looked for: a laser at 0.5 m sees the floor
/// up to a few decimetres from the foot of a 1.5 m partition on its own side.
const BESIDE_M: f64 = 0.5;

/// Whether `o` runs along a wall (within 10 degrees, beside its extent) nearer to its face
/// than `passage_m`.
fn faces_a_wall(o: &DetectedObstacle, sc: &ObstacleScene, passage_m: f64) -> bool {
    let max_cos = 10f64.to_radians().cos();
    sc.walls.iter().any(|w| {
        let (s, d) = w.line.coords(o.center);
        o.dir.dot(w.line.dir).abs() >= max_cos
            && s >= 0.0
            && s <= w.length
            && d.abs() - w.thickness / 2.0 - o.size[1] / 2.0 < passage_m
    })
}

/// The fraction of `o`'s length (bins of [`BIN_M`]) where its points `members` come down to
/// within `partition_max_bottom_m` of the floor and up to within `max_vertical_gap_m` of its
/// top.
fn standing_fraction(
    o: &DetectedObstacle,
    sc: &ObstacleScene,
    members: &[u32],
    c: &ObstacleConfig,
) -> f64 {
    let bins = (o.size[0] / BIN_M).ceil().max(1.0) as usize;
    let (mut low, mut high) = (vec![false; bins], vec![false; bins]);
    let (bottom_below, top_above) = (
        sc.floor + c.partition_max_bottom_m,
        o.z_range.1 - c.max_vertical_gap_m,
    );
    for &i in members {
        let p = sc.points[i as usize];
        let s = (DVec2::new(p.x as f64, p.y as f64) - o.center).dot(o.dir);
        let bin = ((s + o.size[0] / 2.0) / BIN_M).floor();
        if !(0.0..bins as f64).contains(&bin) {
            continue;
        }
        let z = p.z as f64;
        low[bin as usize] |= z <= bottom_below;
        high[bin as usize] |= z >= top_above;
    }
    // The foot's band is a few centimetres high: at range the laser's rows leave a bin of it
    // without a return here and there. A bin between two that stand on the floor stands too
    // (a shelf's or a bench's legs are further apart than that).
    let low: Vec<bool> = (0..bins)
        .map(|k| low[k] || (k > 0 && k + 1 < bins && low[k - 1] && low[k + 1]))
        .collect();
    let standing = low.iter().zip(&high).filter(|(l, h)| **l && **h).count();
    standing as f64 / bins as f64
}

#[cfg(test)]
pub(super) mod tests {
    use super::super::{find_obstacles, test_scene};
    use super::*;
    use glam::Vec3;

    /// Both faces of a slab 0.08 m thick along x from `x0` to `x1` at `y`, sampled every 2 cm
    /// from `z0` to `z1`.
    pub(crate) fn slab(x0: f32, x1: f32, y: f32, z0: f32, z1: f32) -> Vec<Vec3> {
        let mut out = Vec::new();
        let (nx, nz) = (((x1 - x0) / 0.02) as usize, ((z1 - z0) / 0.02) as usize);
        for i in 0..=nx {
            for k in 0..=nz {
                for face in [-0.04, 0.04] {
                    out.push(Vec3::new(
                        x0 + i as f32 * 0.02,
                        y + face,
                        z0 + k as f32 * 0.02,
                    ));
                }
            }
        }
        out
    }

    /// The floor of the 8 x 8 m test area sampled every 5 cm, but where `hidden` (x0, y0, x1,
    /// y1) covers it.
    fn floor(hidden: Option<[f32; 4]>) -> Vec<Vec3> {
        let mut out = Vec::new();
        for i in 0..160 {
            for j in 0..160 {
                let (x, y) = (i as f32 * 0.05, j as f32 * 0.05);
                if hidden.is_some_and(|[x0, y0, x1, y1]| x >= x0 && x <= x1 && y >= y0 && y <= y1) {
                    continue;
                }
                out.push(Vec3::new(x, y, 0.0));
            }
        }
        out
    }

    pub(crate) fn classes(points: &[Vec3]) -> Vec<(EntityClass, String)> {
        classes_with_walls(points, &[])
    }

    /// The classes of what `points` (and the whole floor) hold, with `walls`.
    fn classes_with_walls(
        points: &[Vec3],
        walls: &[crate::walls::WallFit],
    ) -> Vec<(EntityClass, String)> {
        let mut all = floor(None);
        all.extend_from_slice(points);
        classes_in(&all, walls)
    }

    fn classes_in(points: &[Vec3], walls: &[crate::walls::WallFit]) -> Vec<(EntityClass, String)> {
        found_in(points, walls)
            .into_iter()
            .map(|o| (o.class, o.rules.last().cloned().unwrap_or_default()))
            .collect()
    }

    /// What the obstacle stage finds in `points` with `walls`.
    fn found_in(points: &[Vec3], walls: &[crate::walls::WallFit]) -> Vec<DetectedObstacle> {
        let explained = vec![false; points.len()];
        let image = ImageFrame {
            origin_m: [0.0, 8.0],
            resolution_m: 0.05,
            width_px: 160,
            height_px: 160,
        };
        let scene = test_scene(points, &explained, 3.0, &image, walls);
        find_obstacles(&scene, &ObstacleConfig::default(), 1 << 20)
    }

    #[test]
    fn a_thin_slab_standing_on_the_floor_is_a_partial_height_wall() {
        let found = classes(&slab(1.0, 3.0, 2.0, 0.09, 1.4));
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].0, EntityClass::Wall, "{found:?}");
        assert!(found[0].1.contains("partial-height wall"), "{found:?}");
    }

    #[test]
    fn a_thin_slab_clear_of_the_floor_or_low_or_short_stays_an_obstacle() {
        for (what, points) in [
            // A car's side: its body 0.25 m above the floor between the wheels.
            ("clear of the floor", slab(1.0, 4.0, 2.0, 0.25, 1.3)),
            // A bench back or a kerb: under the partition height.
            ("low", slab(1.0, 3.0, 2.0, 0.09, 0.8)),
            // As long as it is thick: a post.
            ("short", slab(1.0, 1.3, 2.0, 0.09, 1.4)),
        ] {
            let found = classes(&points);
            assert_eq!(found.len(), 1, "{what}: {found:?}");
            assert_eq!(found[0].0, EntityClass::Obstacle, "{what}: {found:?}");
        }
    }

    #[test]
    fn a_slab_with_gaps_at_the_floor_is_no_wall() {
        // A row of shelves on legs: the face comes down to the floor only at the legs.
        let mut points = slab(1.0, 3.0, 2.0, 0.3, 1.6);
        for x in [1.0, 1.5, 2.0, 2.5, 3.0] {
            points.extend(slab(x, x + 0.04, 2.0, 0.09, 0.3));
        }
        let found = classes(&points);
        assert!(
            found.iter().all(|(c, _)| *c != EntityClass::Wall),
            "{found:?}"
        );
    }

    #[test]
    fn a_slab_along_a_wall_nearer_than_a_passage_is_a_cabinet_front() {
        // A wall along y = 3 (0.15 m thick), x 0..6.
        let wall = |y: f64| crate::walls::WallFit {
            line: crate::points::Line2 {
                origin: DVec2::new(0.0, y),
                dir: DVec2::X,
            },
            length: 6.0,
            thickness: 0.15,
            measured: true,
            faces: vec![-0.075, 0.075],
            free_side: -1.0,
            z_range: (0.0, 3.0),
            support: 1000,
            coverage: 1.0,
            rules: Vec::new(),
        };
        // The front of a 0.45 m deep cabinet against it, and a partition 1.5 m from it.
        let front = slab(1.0, 3.0, 2.5, 0.09, 1.4);
        let found = classes_with_walls(&front, &[wall(3.0)]);
        assert_eq!(found[0].0, EntityClass::Obstacle, "{found:?}");
        let found = classes_with_walls(&front, &[wall(4.0)]);
        assert_eq!(found[0].0, EntityClass::Wall, "{found:?}");
    }

    #[test]
    fn what_hangs_over_a_low_streak_does_not_raise_its_face_to_a_wall() {
        // garage-64 (seeds 61-65): the foot of a person's streak left by the transients filter
        // (0.09-0.4 m along 1.6 m), a few returns up to 1.3 m at one end, under a beam's
        // returns at 2.4-2.6 m. The beam stands in the same cells, over the streak's top: it
        // is no part of the streak's face.
        let mut points = slab(1.0, 2.6, 2.0, 0.09, 0.4);
        points.extend(slab(2.5, 2.56, 2.0, 1.2, 1.3));
        points.extend(slab(1.0, 2.6, 2.0, 2.4, 2.6));
        let found = classes(&points);
        assert!(
            found.iter().all(|(c, _)| *c != EntityClass::Wall),
            "{found:?}"
        );
    }

    #[test]
    fn the_face_of_a_block_is_no_wall() {
        // A crate 1.5 m high seen from its south side only: the floor behind its face, under
        // the crate, was never seen.
        let mut points = floor(Some([1.0, 2.0, 3.0, 3.8]));
        points.extend(slab(1.0, 3.0, 2.0, 0.09, 1.5));
        let found = classes_in(&points, &[]);
        assert!(
            found.iter().all(|(c, _)| *c != EntityClass::Wall),
            "{found:?}"
        );
    }

    #[test]
    fn a_panel_seen_from_one_side_and_round_its_free_end_is_a_wall_and_a_block_is_not() {
        // office-107 (seeds 106-110): a partial partition 1.6 m long from a room's far wall,
        // scanned from one side only: the floor behind it lies in its shadow, but round its
        // free end the laser sees it right behind the panel's face.
        let panel = slab(1.0, 3.0, 2.0, 0.09, 1.4);
        let mut points = floor(Some([1.0, 2.05, 2.75, 4.0]));
        points.extend_from_slice(&panel);
        let found = classes_in(&points, &[]);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].0, EntityClass::Wall, "{found:?}");
        assert!(found[0].1.contains("seen from one side"), "{found:?}");
        // A cabinet 0.4 m deep seen from the same side: round its end the floor is seen only
        // beyond its back.
        let mut points = floor(Some([1.0, 2.05, 3.05, 2.45]));
        points.retain(|p| !(p.x <= 2.75 && p.y >= 2.45 && p.y <= 4.0));
        points.extend_from_slice(&panel);
        let found = classes_in(&points, &[]);
        assert!(
            found.iter().all(|(c, _)| *c != EntityClass::Wall),
            "{found:?}"
        );
    }

    #[test]
    fn a_foot_seen_in_every_other_bin_still_stands_on_the_floor() {
        // At range the laser's rows leave 10 cm stretches of a partition's foot without a
        // return here and there: its face stands on the floor all the same.
        let mut points = slab(1.0, 3.0, 2.0, 0.16, 1.4);
        for k in 0..10 {
            let x = 1.0 + 0.2 * k as f32;
            points.extend(slab(x, x + 0.06, 2.0, 0.09, 0.16));
        }
        let found = classes(&points);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].0, EntityClass::Wall, "{found:?}");
    }
}
