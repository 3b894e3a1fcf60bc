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
use super::divides::{divides_space, BIN_M};
use super::fit::half_extent_along;
use super::slabs::{points_in_box, thin_slab};
use super::{DetectedObstacle, ObstacleConfig, ObstacleScene, PartitionScene};
use crate::points::quantile;
use cloud::EntityClass;
use glam::DVec2;

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
    let mut returns = vec![0usize; bins];
    for (bin, z) in along_bins(o, sc, members) {
        low[bin] |= z <= bottom_below;
        high[bin] |= z >= top_above;
        returns[bin] += 1;
    }
    // The foot's band is a few centimetres high: at range the laser's rows leave a bin of it
    // without a return here and there. A bin between two that stand on the floor stands too,
    // and so does a run of up to [`MAX_SPARSE_FOOT_BINS`] whose face is seen too sparsely to
    // expect a return in the band (a shelf's or a bench's legs are further apart than that).
    let band = (bottom_below - sc.floor - c.min_above_floor_m).max(0.0);
    let height = (top - sc.floor - c.min_above_floor_m).max(band).max(1e-9);
    let sparse = |k: usize| (returns[k] as f64) * band / height < MIN_EXPECTED_FOOT_RETURNS;
    let low = fill_foot_gaps(&low, sparse);
    let standing = low.iter().zip(&high).filter(|(l, h)| **l && **h).count();
    standing as f64 / bins as f64
}

/// The most bins in a run without a return in a partition's foot band that stands with the
/// bins on either side of it where its face is seen sparsely (see [`MIN_EXPECTED_FOOT_RETURNS`]):
/// 0.3 m, half the 0.6 m and more between a shelf's or a bench's legs. (Blind office-524 of
/// seeds 521-525: a partial partition seen from beyond its free end at a grazing angle, 7-35
/// returns per bin over 1.4 m, stood on the floor along 65 % of its length, its foot's band
/// unseen in runs of two and three bins.)
const MAX_SPARSE_FOOT_BINS: usize = 3;

/// A bin's face returns spread evenly over its height would put fewer than this many in the
/// foot's band: its foot may well go unseen (none is seen with a chance of e^-3, 5 %, or more).
const MIN_EXPECTED_FOOT_RETURNS: f64 = 3.0;

/// `low` (per bin: its foot seen) with the gaps between two bins whose foot is seen filled: a
/// single bin always, a run of up to [`MAX_SPARSE_FOOT_BINS`] where every bin is `sparse`.
fn fill_foot_gaps(low: &[bool], sparse: impl Fn(usize) -> bool) -> Vec<bool> {
    let mut out = low.to_vec();
    let mut k = 0;
    while k < low.len() {
        if low[k] {
            k += 1;
            continue;
        }
        let end = (k..low.len()).find(|&j| low[j]).unwrap_or(low.len());
        let bounded = k > 0 && end < low.len();
        let run = end - k;
        if bounded && (run == 1 || run <= MAX_SPARSE_FOOT_BINS && (k..end).all(&sparse)) {
            out[k..end].iter_mut().for_each(|b| *b = true);
        }
        k = end;
    }
    out
}

#[cfg(test)]
#[path = "partitions_tests.rs"]
pub(super) mod tests;
