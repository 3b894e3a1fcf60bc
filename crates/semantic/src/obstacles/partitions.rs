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
#[path = "partitions_tests.rs"]
pub(super) mod tests;
