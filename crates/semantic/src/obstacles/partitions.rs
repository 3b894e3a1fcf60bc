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
//! floor right behind its face and nothing standing on it, where a block's body would stand
//! (the foot of a block's end face is seen there, as low as the floor; a desk's top is not).
//! A slab along a wall, nearer to it than a passage is wide (`partition_min_passage_m`),
//! divides no space: it is the front of a cabinet or a shelf against that wall, seen from the
//! room.

use super::classify::set_box_rule;
use super::cluster::BandGrid;
use super::fit::half_extent_along;
use super::slabs::{points_in_box, thin_slab};
use super::{DetectedObstacle, ObstacleConfig, ObstacleScene, PartitionScene};
use crate::image_frame::ImageFrame;
use crate::points::quantile;
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
    ps: PartitionScene,
) -> Vec<DetectedObstacle> {
    let PartitionScene {
        sc,
        grids,
        frame,
        c,
        ..
    } = ps;
    if o.overhead || o.class != EntityClass::Obstacle {
        return Vec::new();
    }
    // 1. The cluster as it is.
    if let Some((why, top)) = partition_rule(o, ps, (0.0, 0.0)) {
        o.class = EntityClass::Wall;
        o.z_range.1 = top;
        o.rules.truncate(2);
        o.rules.push(why);
        return Vec::new();
    }
    // 2. A cluster too thick for one: the thin slab holding most of its returns, and what
    //    stands against it. What stands against a partition (a desk, a chair) runs along part
    //    of it, while a block's other faces (a crate's, a row of crates') run along the whole
    //    face taken ([`MAX_BESIDE_SHARE`]), or stand across it at one of its ends (see
    //    [`end_face`]). And the slab stays under head height: a door's
    //    leaf standing open (2 m or more) is as thin, with its frame beside it. A block's
    //    faces end at its top: what rises above the slab's top by more than a cell is no face
    //    of its block (a person who walked along the partition, a shelf standing there), and
    //    neither is what ends below it by more than a cell (a desk as long as the partition
    //    pushed against it: office-9 of seeds 1-10, a desk 1.30 m long against a partition
    //    1.56 m long). The slab's top is where its face ends along most of it ([`face_top`]),
    //    not its highest return: the end face of a tall shelf standing at one end of a
    //    partition falls in its slab (office-373 of seeds 371-375: a partition 1.36 m high
    //    beside a shelf 1.99 m high read as a door leaf by the shelf's returns). So is the top
    //    of what lies beside it: stray returns over a crate (a person's, mixed pixels) are not
    //    its top (hall-391 of seeds 391-395: a crate 1.04 m high whose body's highest return
    //    was 1.16 m read as a partition 1.03 m high with something lower beside it).
    if o.size[1] <= c.partition_max_thickness_m {
        return Vec::new();
    }
    let Some((mut slab, rest)) = thin_slab(o, sc, grids, frame, c) else {
        return Vec::new();
    };
    let along_slab = |r: &DetectedObstacle| 2.0 * half_extent_along(r.dir, r.size, slab.dir);
    let slab_top = face_top(&slab, sc, &points_in_box(&slab, sc, grids, frame));
    let level = |r: &DetectedObstacle| {
        let top = face_top(r, sc, &points_in_box(r, sc, grids, frame));
        (top - slab_top).abs() <= c.cell_m
    };
    let blocks_face = |r: &DetectedObstacle| {
        level(r) && (along_slab(r) >= MAX_BESIDE_SHARE * slab.size[0] || end_face(r, &slab, c))
    };
    if rest.iter().any(blocks_face) || slab_top - sc.floor > c.head_height_m {
        return Vec::new();
    }
    let Some((why, top)) = partition_rule(&slab, ps, (0.0, 0.0)) else {
        return Vec::new();
    };
    slab.class = EntityClass::Wall;
    slab.z_range.1 = top;
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

/// True if `r` (what lies beside the thin slab `slab` of a thicker cluster) is an end face of
/// the block whose front the slab is: across the slab (within 60 degrees of square to it), at
/// one of its ends (within a cell), and shorter than a partition (a partition's other leg, in
/// an L, is as long as one). Seen from its front and one end, a tall crate 0.4 m deep (mixed-344
/// of seeds 341-345, mixed-284 of 281-285: 1.3 m long, 1.4-1.5 m tall) shows its front as a
/// slab and the seen part of its end, 0.2 m of it, level with the slab's top; what stands
/// against a partition is lower than it, and along it.
fn end_face(r: &DetectedObstacle, slab: &DetectedObstacle, c: &ObstacleConfig) -> bool {
    let along = (r.center - slab.center).dot(slab.dir).abs();
    r.dir.dot(slab.dir).abs() < END_FACE_COS
        && (along - slab.size[0] / 2.0).abs() <= c.cell_m
        && r.size[0] < c.partition_min_length_m
}

/// An end face stands across the slab: the cosine of the largest angle between them.
const END_FACE_COS: f64 = 0.5;

/// Why `o` stands as a partial-height wall does (see the module docs), and its top (where its
/// face ends, [`face_top`]), or `None`. Where it is
/// known to stand along `standing_m` of its length (its pieces, each from the floor to the
/// ceiling: see `pieces`), it stands along that much at least; `hidden_m` of its length (the
/// gaps between its pieces, where what stands before it hid it) is left out of the share it
/// stands along, where the pieces cover the share of it a wall must stand along.
pub(super) fn partition_rule(
    o: &DetectedObstacle,
    ps: PartitionScene,
    (standing_m, hidden_m): (f64, f64),
) -> Option<(String, f64)> {
    let PartitionScene {
        sc,
        grids,
        floor_seen,
        frame,
        c,
    } = ps;
    let [length, across] = o.size;
    if across > c.partition_max_thickness_m
        || length < c.partition_min_length_m
        || length < 4.0 * across
        || o.z_range.1 - sc.floor < c.partition_min_height_m
        || faces_a_wall(o, sc, c.partition_min_passage_m)
    {
        return None;
    }
    let divides = divides_space(o, sc, floor_seen, grids[0], frame, c)?;
    // Its top: where its face ends along most of it, not a few returns above it at one end
    // (the mixed pixels between its top edge and the wall behind it).
    let members = points_in_box(o, sc, grids, frame);
    let top = face_top(o, sc, &members);
    let height = top - sc.floor;
    if height < c.partition_min_height_m {
        return None;
    }
    // (pieces mostly gaps are no wall's face, however well each stands: a row of things)
    let hidden_m = if hidden_m <= (1.0 - c.partition_min_standing) * length {
        hidden_m
    } else {
        0.0
    };
    let seen_m = (length - hidden_m).max(1e-9);
    let standing = (standing_fraction(o, sc, &members, top, c) * length / seen_m)
        .max(standing_m / seen_m)
        .min(1.0);
    (standing >= c.partition_min_standing).then(|| (format!(
        "a partial-height wall: {length:.2} m long, {across:.2} m thick, {height:.2} m high; its face seen from within {:.2} m of the floor up to its top along {:.0} % of its length (a wall stands on the floor along {:.0} % at least); {divides}",
        c.partition_max_bottom_m,
        100.0 * standing,
        100.0 * c.partition_min_standing
    ), top))
}

/// How `o` divides space (see the module docs), or `None` if it may be a block's face: the
/// floor seen on both sides of it along `partition_min_floor_both_sides` of its length, or, a
/// panel seen from one side, the floor seen on that side along as much of it and round its
/// free end right behind its face, with nothing standing on it there nor before the face
/// ([`end_bins`]; before it, where the laser stood, the floor far off is seen sparsely at a
/// grazing angle: office-514 of seeds 511-515, a partition seen from 3 m beyond its end): the
/// foot of a block's end face is seen as low as the floor (`low`: the low band's points by
/// cell; a face stands on the floor where it comes down to within `partition_max_bottom_m` of
/// it, while a desk's top over the floor seen between its legs does not).
fn divides_space(
    o: &DetectedObstacle,
    sc: &ObstacleScene,
    floor_seen: &[bool],
    low: &BandGrid,
    frame: &ImageFrame,
    c: &ObstacleConfig,
) -> Option<String> {
    let foot = sc.floor + c.partition_max_bottom_m;
    let stands = |k: usize| {
        low.points(k)
            .iter()
            .any(|&i| (sc.points[i as usize].z as f64) <= foot)
    };
    let first = |k: usize, j: usize| floor_first(floor_seen[k], stands(k), j);
    let beside = floor_beside(o, first, frame, BESIDE_M, &bin_centres(o));
    let both = share(beside.iter().map(|[a, b]| *a && *b));
    if both >= c.partition_min_floor_both_sides {
        return Some(format!(
            "the floor seen on both sides of it along {:.0} % of its length",
            100.0 * both
        ));
    }
    let one = share(beside.iter().map(|[a, b]| *a || *b));
    // The side it was seen from: the floor seen beside it along more of its length. There the
    // floor at its end may be seen sparsely or not at all (far off, at a grazing angle: the
    // laser drops such returns), so nothing standing beyond its foot is enough; behind it, the
    // floor must be seen with nothing on it.
    let front = usize::from(
        beside.iter().filter(|s| s[1]).count() > beside.iter().filter(|s| s[0]).count(),
    );
    let free = |k: usize, _| (floor_seen[k] && !stands(k)).then_some(true);
    let clear = |k: usize, j: usize| (j > 1).then(|| !stands(k));
    let round_an_end = o.size[0] > 2.0 * ROUND_END_BINS as f64 * BIN_M
        && [-1.0, 1.0].into_iter().any(|end| {
            let bins = end_bins(o, end);
            let behind = floor_beside(o, free, frame, BEHIND_M, &bins);
            let before = floor_beside(o, clear, frame, BEHIND_M, &bins);
            behind
                .iter()
                .zip(&before)
                .all(|(b, f)| b[1 - front] && (b[front] || f[front]))
        });
    (one >= c.partition_min_floor_both_sides && round_an_end).then(|| format!(
        "a panel seen from one side: the floor seen beside it along {:.0} % of its length, and behind it within {BEHIND_M:.2} m of its face with nothing on it (nor before it) along its last {:.1} m or more at an end, where a block's body would stand",
        100.0 * one,
        ROUND_END_BINS as f64 * BIN_M
    ))
}

/// Whether the `j`th cell out from a face (from 1) settles that the floor is seen beside it
/// (see [`floor_beside`]): something standing there first says no (a block's far face, seen
/// before the floor past it, from wherever that floor was seen: the floor under the block
/// between them was never seen), else the floor seen there says yes. The first cell out may
/// hold the face's own foot.
fn floor_first(floor_seen: bool, stands: bool, j: usize) -> Option<bool> {
    if j > 1 && stands {
        Some(false)
    } else {
        floor_seen.then_some(true)
    }
}

/// How near behind a panel's face the floor is seen round its free end: nearer than a
/// cabinet or a crate is deep (0.3 m and more), farther than a registered face's spread.
const BEHIND_M: f64 = 0.15;

/// The bins at an end of a panel in which the floor must be seen right behind it: 0.2 m, more
/// than a block's corner lets the laser see behind its front by the mixed pixels at its edge.
const ROUND_END_BINS: usize = 2;

/// The centres of the [`ROUND_END_BINS`] bins of [`BIN_M`] at `o`'s end `end` (-1: its start,
/// 1: its end), within its length, as offsets along it from its centre. Seen from one side, the
/// floor behind a panel is in its shadow, but the laser sees round its free end right behind
/// it, where the footprint of a block seen from one side hides the floor to the block's depth.
fn end_bins(o: &DetectedObstacle, end: f64) -> Vec<f64> {
    (0..ROUND_END_BINS)
        .map(|k| end * (o.size[0] / 2.0 - (k as f64 + 0.5) * BIN_M))
        .collect()
}

/// The centres of the bins of [`BIN_M`] along `o`'s length, as offsets from its centre.
fn bin_centres(o: &DetectedObstacle) -> Vec<f64> {
    let bins = (o.size[0] / BIN_M).ceil().max(1.0) as usize;
    (0..bins)
        .map(|k| -o.size[0] / 2.0 + (k as f64 + 0.5) * BIN_M)
        .collect()
}

/// For each offset `along` `o`'s length from its centre, whether the floor was seen on either
/// side of it within `beside_m` of its faces: going out from the face cell by cell of `frame`,
/// `first` says whether a cell (the `j`th out, from 1) settles it (`Some(true)`: the floor seen
/// there; `Some(false)`: something standing before it) or not (`None`: go on).
fn floor_beside(
    o: &DetectedObstacle,
    first: impl Fn(usize, usize) -> Option<bool>,
    frame: &ImageFrame,
    beside_m: f64,
    along: &[f64],
) -> Vec<[bool; 2]> {
    let w = frame.width_px as usize;
    let settles = |q: DVec2, j: usize| {
        frame
            .pixel_of(q.x, q.y)
            .and_then(|(col, row)| first(row as usize * w + col as usize, j))
    };
    let across = o.dir.perp();
    let steps = (beside_m / frame.resolution_m).ceil().max(1.0) as usize;
    along
        .iter()
        .map(|&s| {
            [-1.0, 1.0].map(|side| {
                (1..=steps)
                    .find_map(|j| {
                        let d = o.size[1] / 2.0 + j as f64 * frame.resolution_m;
                        settles(o.center + o.dir * s + across * (side * d), j)
                    })
                    .unwrap_or(false)
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
/// up to a few decimetres from the foot of a 1.5 m partition on its own side. A block's body
/// can be shallower (a crate 0.45 m deep): the floor seen past its far face is seen from where
/// that face is seen too, so what stands first along the way settles it (see
/// [`divides_space`]; hall-424 of seeds 421-425: a crate's front read as a partition with the
/// floor seen past its back).
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

/// `members`' heights by [`BIN_M`] bin along `o`: `(bin, z)`, bins counted from `o`'s start.
fn along_bins<'a>(
    o: &'a DetectedObstacle,
    sc: &'a ObstacleScene,
    members: &'a [u32],
) -> impl Iterator<Item = (usize, f64)> + 'a {
    let bins = (o.size[0] / BIN_M).ceil().max(1.0);
    members.iter().filter_map(move |&i| {
        let p = sc.points[i as usize];
        let s = (DVec2::new(p.x as f64, p.y as f64) - o.center).dot(o.dir);
        let bin = ((s + o.size[0] / 2.0) / BIN_M).floor();
        (0.0..bins)
            .contains(&bin)
            .then_some((bin as usize, p.z as f64))
    })
}

/// The top of `o`'s face: the median over the [`BIN_M`] bins holding its returns of each
/// bin's highest, at most its box's top. A few returns over one end (mixed pixels between its
/// top edge and a wall behind it, a person passing) do not lift it.
fn face_top(o: &DetectedObstacle, sc: &ObstacleScene, members: &[u32]) -> f64 {
    let bins = (o.size[0] / BIN_M).ceil().max(1.0) as usize;
    let mut tops = vec![f64::NEG_INFINITY; bins];
    for (bin, z) in along_bins(o, sc, members) {
        tops[bin] = tops[bin].max(z);
    }
    let mut seen: Vec<f64> = tops.into_iter().filter(|z| z.is_finite()).collect();
    quantile(&mut seen, 0.5).map_or(o.z_range.1, |z| z.min(o.z_range.1))
}

/// The fraction of `o`'s length (bins of [`BIN_M`]) where its points `members` come down to
/// within `partition_max_bottom_m` of the floor and up to within `max_vertical_gap_m` of its
/// face's `top` ([`face_top`]).
fn standing_fraction(
    o: &DetectedObstacle,
    sc: &ObstacleScene,
    members: &[u32],
    top: f64,
    c: &ObstacleConfig,
) -> f64 {
    let bins = (o.size[0] / BIN_M).ceil().max(1.0) as usize;
    let (mut low, mut high) = (vec![false; bins], vec![false; bins]);
    let (bottom_below, top_above) = (
        sc.floor + c.partition_max_bottom_m,
        top - c.max_vertical_gap_m,
    );
    for (bin, z) in along_bins(o, sc, members) {
        low[bin] |= z <= bottom_below;
        high[bin] |= z >= top_above;
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

#[cfg(test)]
#[path = "partitions_floor_tests.rs"]
mod floor_tests;
