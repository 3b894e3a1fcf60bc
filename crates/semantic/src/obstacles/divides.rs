//! How a partition divides space (see `partitions`): the floor seen beside it on both sides,
//! or, a panel seen from one side, round its free end right behind its face. A face of a block
//! (a car, a crate, a cabinet) has the block's unseen footprint behind it, or its end face.

use super::cluster::BandGrid;
use super::{DetectedObstacle, ObstacleConfig, ObstacleScene};
use crate::image_frame::ImageFrame;
use glam::DVec2;

/// Bins along a partition's length in which its face is looked for.
pub(super) const BIN_M: f64 = 0.1;

/// How `o` divides space (see the module docs), or `None` if it may be a block's face: the
/// floor seen on both sides of it along `partition_min_floor_both_sides` of its length, or, a
/// panel seen from one side, the floor seen on that side along as much of it and round its
/// free end right behind its face, with nothing standing on it there nor before the face
/// ([`end_bins`]; before it, where the laser stood, the floor far off is seen sparsely at a
/// grazing angle: office-514 of seeds 511-515, a partition seen from 3 m beyond its end): the
/// foot of a block's end face is seen as low as the floor (`low`: the low band's points by
/// cell; a face stands on the floor where it comes down to within `partition_max_bottom_m` of
/// it, while a desk's top over the floor seen between its legs does not).
pub(super) fn divides_space(
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

#[cfg(test)]
#[path = "divides_tests.rs"]
mod tests;
