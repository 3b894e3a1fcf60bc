//! Door openings and the walls above them. Along each wall, in `bin_m` bins:
//!
//! - a bin is *blocked* if a face of the wall has points at door level (`door_level_m` above
//!   the floor), at least three and a third of its door-level points within half a wall of the
//!   face (fewer are the noise tail of a closed leaf recessed in the opening, or the stretch
//!   of a leaf open at a small angle that crosses the face plane), and *open* otherwise;
//! - a run of open bins between blocked ones (blocked slivers up to `max_pier_m` inside it are
//!   a door leaf crossing the face plane, and ignored; up to 40 cm where the open bins either
//!   side hold the leaf's points near the face too, a leaf ajar, or where the sliver is sampled
//!   at under a quarter of the wall's density, a person crossing the doorway) of
//!   `min_width_m..max_width_m` is an opening candidate;
//! - it is no opening where the wall's face goes on through it, seen sparsely at door level (a
//!   glass pane returns some beams, too few to block a bin; see [`face_goes_on`]);
//! - it is an opening if the wall continues above it (a lintel: face points above door level
//!   in `min_lintel_coverage` of its bins), and, for a wall seen from one side only (which
//!   could be hidden behind furniture at door level), if the scans saw into it: points inside
//!   the wall's slab or behind its face, or floor within its footprint, in `min_evidence` of
//!   its bins. A wall seen from both sides about the run cannot be hidden on both at once, so
//!   the lintel suffices there, where anything at all was seen in it; a two-sided wall seen
//!   from one side only about the run (see [`faces_seen_around`]) needs the view through it
//!   too.
//!
//! The opening's edges are the nearest face points at door level either side; its height is
//! the median lowest face point above it (the lintel's underside), at least a door's height
//! (`MIN_DOOR_HEIGHT_M`): a lower one is a wall seen above what hid it (a parked car). What is
//! seen behind a one-sided wall's face counts as seen through up to door level only. The paper's labels follow:
//! "Free space for door" (the opening volume) and "Wall above door" (the lintel).

use super::opening_bins::{bin_wall, Bin, DoorLevel};
use super::OpeningConfig;
use crate::points::median;
use crate::scene::Scene;
use crate::walls::WallFit;

/// The widest blocked sliver of an opening that a leaf ajar crossing the face plane may explain.
const LEAF_SLIVER_M: f64 = 0.4;
/// An opening's top (the lintel's underside) is at least this high above the floor: building
/// codes ask 2.0 m of door height (1.98 m in the US), above the stature of 99 % of adults
/// (~1.90 m). A lower "lintel" is the face of a wall seen above something that hid it below (a
/// parked car, a cabinet), not a doorway a person walks through.
const MIN_DOOR_HEIGHT_M: f64 = 1.95;
/// How far under [`MIN_DOOR_HEIGHT_M`] a lintel's underside may be measured and still be a
/// door's: the floor is levelled over the whole map (a registration's tilt leaves it a
/// centimetre or two off along a long corridor) and the lowest face return of each bin reads
/// the edge a little low (mixed-452 of seeds 451-455: a door 1.956 m high measured at 1.941 m
/// and left out; the same corridor's other doors measured 0.4-0.5 cm off).
const LINTEL_HEIGHT_TOLERANCE_M: f64 = 0.03;
/// A door opening in a wall.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Opening {
    pub wall: usize,
    /// Near and far edge, along the wall from its start.
    pub s0: f64,
    pub s1: f64,
    /// Absolute z of the opening's top (the lintel's underside).
    pub top_z: f64,
    pub lintel_points: u64,
    pub confidence: f64,
    pub rules: Vec<String>,
}

/// The openings of wall `wi`: its points binned along it, the runs of open bins, and those
/// runs that are openings.
pub(crate) fn find_openings(
    wi: usize,
    w: &WallFit,
    sc: &Scene,
    c: &OpeningConfig,
    face_tol: f64,
) -> Vec<Opening> {
    let level = DoorLevel {
        lo: sc.floor + c.door_level_m[0],
        hi: sc.floor + c.door_level_m[1],
    };
    let (bins, at_wall) = bin_wall(w, sc, c, face_tol, level);
    open_runs(&bins, &at_wall, c)
        .into_iter()
        .map(|run| bounded(&bins, run))
        .filter_map(|(a, b)| opening_of(wi, w, &bins, a, b, c, level))
        .collect()
}

/// Runs `[a, b)` of open bins; slivers of blocked bins up to `max_pier_m` inside them are
/// ignored, and up to [`LEAF_SLIVER_M`] where a leaf ajar crosses the face plane (the open bins
/// either side of such a sliver hold the leaf's points near the face, behind it towards the
/// hinge, in front of it beyond, as much as a third of the sliver's, where a pier between two
/// doorways has empty openings beside it) or where the sliver is sampled far more sparsely than
/// the wall around it (see [`sparse_sliver`]).
fn open_runs(bins: &[Bin], at_wall: &[u16], c: &OpeningConfig) -> Vec<(usize, usize)> {
    let n = bins.len();
    let pier = (c.max_pier_m / c.bin_m).round() as usize;
    let leaf_sliver = (LEAF_SLIVER_M / c.bin_m).round() as usize;
    let crossing_leaf = |from: usize, to: usize| {
        let mut inside: Vec<f64> = (from..to).map(|k| at_wall[k] as f64).collect();
        let level = median(&mut inside).unwrap_or(0.0);
        let beside = [from.checked_sub(1), Some(to).filter(|&k| k < n)];
        level > 0.0
            && beside
                .iter()
                .all(|k| k.is_some_and(|k| 3.0 * at_wall[k] as f64 >= level))
    };
    let mut runs: Vec<(usize, usize)> = Vec::new(); // [a, b) open-bin runs
    let mut b = 0;
    while b < n {
        if bins[b].blocked {
            b += 1;
            continue;
        }
        let a = b;
        while b < n && !bins[b].blocked {
            b += 1;
        }
        match runs.last_mut() {
            Some(r) if a - r.1 <= pier => r.1 = b,
            Some(r) if a - r.1 <= leaf_sliver && crossing_leaf(r.1, a) => r.1 = b,
            Some(r) if a - r.1 <= leaf_sliver && sparse_sliver(bins, r.1, a, c) => r.1 = b,
            _ => runs.push((a, b)),
        }
    }
    runs
}

/// The open run `[a, b)`, or, where it reaches an end of the wall (no face bounds it there)
/// and took in blocked slivers on the way (see [`open_runs`]), the part of it before the last
/// sliver (after the first, at the wall's start): that sliver is a face that bounds an opening
/// (mixed-452 of seeds 451-455: a closed door near a corridor's end, the wall's face past its
/// far jamb hidden at door level, its 0.15 m jamb taken in as a pier, and the run, reaching the
/// wall's end, was no opening).
fn bounded(bins: &[Bin], (a, b): (usize, usize)) -> (usize, usize) {
    let blocked = |k: &usize| bins[*k].blocked;
    if b >= bins.len() {
        if let Some(last) = (a..b).rev().find(blocked) {
            let first = (a..=last)
                .rev()
                .take_while(|k| blocked(k))
                .last()
                .unwrap_or(last);
            return (a, first);
        }
    } else if a == 0 {
        if let Some(first) = (a..b).find(blocked) {
            let last = (first..b)
                .take_while(|k| blocked(k))
                .last()
                .unwrap_or(first);
            return (last + 1, b);
        }
    }
    (a, b)
}

/// The share of the door-level face returns per bin of the wall around it (the median blocked
/// bin within [`FACE_AROUND_M`] either side) under which a blocked sliver's median bin is no
/// pier (see [`sparse_sliver`]).
const SPARSE_SLIVER_SHARE: f64 = 0.25;

/// True if the blocked sliver `bins[from..to]` holds fewer door-level face returns per bin (its
/// median) than [`SPARSE_SLIVER_SHARE`] of the wall's own face around it. A pier between two
/// doorways is wall, sampled as densely as the wall beside it (at the same range from the same
/// scanners); a person crossing the doorway in the face plane during a scan leaves a streak of
/// a few returns per bin over a body's width (mixed-100 of seeds 96-100: 2-10 per 5 cm bin over
/// 0.3 m beside 20-59 in the wall, which split a 0.99 m doorway into two runs too narrow for a
/// door).
fn sparse_sliver(bins: &[Bin], from: usize, to: usize, c: &OpeningConfig) -> bool {
    match (median_face(&bins[from..to]), face_around(bins, from, to, c)) {
        (Some(sliver), Some(wall)) => sliver < SPARSE_SLIVER_SHARE * wall,
        _ => false,
    }
}

/// The median bin's door-level face returns over `bins`; `None` for no bins.
fn median_face(bins: &[Bin]) -> Option<f64> {
    let mut faces: Vec<f64> = bins.iter().map(|x| f64::from(x.door_face)).collect();
    median(&mut faces)
}

/// The wall's own face around `bins[from..to]`: the median door-level face returns of its
/// blocked bins within [`FACE_AROUND_M`] either side; `None` where there are none.
fn face_around(bins: &[Bin], from: usize, to: usize, c: &OpeningConfig) -> Option<f64> {
    let near = (FACE_AROUND_M / c.bin_m).round() as usize;
    let mut around: Vec<f64> = bins[from.saturating_sub(near)..from]
        .iter()
        .chain(&bins[to..(to + near).min(bins.len())])
        .filter(|x| x.blocked)
        .map(|x| f64::from(x.door_face))
        .collect();
    median(&mut around)
}

/// The opening of the open run `bins[a..b]`, if it is bounded by the wall on both sides, of an
/// opening's width, with a lintel above and (one-sided walls) seen through.
fn opening_of(
    wi: usize,
    w: &WallFit,
    bins: &[Bin],
    a: usize,
    b: usize,
    c: &OpeningConfig,
    level: DoorLevel,
) -> Option<Opening> {
    if a == 0 || b >= bins.len() {
        return None; // not bounded by the wall on both sides
    }
    let two_sided = w.measured;
    let s0 = bins[a - 1].face_s.1;
    let s1 = bins[b].face_s.0;
    let width = s1 - s0;
    if !(width >= c.min_width_m && width <= c.max_width_m) {
        return None;
    }
    if face_goes_on(bins, a, b, c) {
        return None;
    }
    let inner = &bins[a..b];
    let k = inner.len() as f64;
    let lintel = inner.iter().filter(|x| x.lintel).count() as f64 / k;
    // A two-sided wall seen on one face only about the run is one-sided there.
    let seen_from = if two_sided {
        faces_seen_around(bins, a, b, c)
    } else {
        None
    };
    let seen_through = |x: &Bin| x.evidence || seen_from.is_some_and(|side| x.seen_from[side]);
    let evidence = inner.iter().filter(|x| seen_through(x)).count() as f64 / k;
    let both_faces = two_sided && seen_from.is_none();
    // (seen from both sides about the run, the lintel suffices, but not where no scan saw into
    // the run at all: a person standing before one face, in the one scan that saw that stretch,
    // hides it as a doorway's open run is, under a lintel above their head, while the other
    // face is seen round it; the transients then drop the person. Office-54 of seeds 51-55,
    // its people turning away from walls instead of walking through them: 0.69 m so, beside a
    // corner.)
    let unseen = evidence == 0.0;
    if lintel < c.min_lintel_coverage || unseen || (!both_faces && evidence < c.min_evidence) {
        return None;
    }
    let mut lows: Vec<f64> = inner
        .iter()
        .filter(|x| x.lintel_low_z.is_finite() && x.lintel_low_z > level.hi)
        .map(|x| x.lintel_low_z)
        .collect();
    let top_z = median(&mut lows)?;
    if top_z - level.lo + c.door_level_m[0] < MIN_DOOR_HEIGHT_M - LINTEL_HEIGHT_TOLERANCE_M {
        return None; // too low for a door: the face seen above something that hid it
    }
    let lintel_points = inner.iter().map(|x| x.lintel_points).sum();
    Some(Opening {
        wall: wi,
        s0,
        s1,
        top_z,
        lintel_points,
        confidence: (lintel * if two_sided { 1.0 } else { evidence.max(0.5) }).clamp(0.0, 1.0),
        rules: vec![format!(
            "no wall face from {:.1} to {:.1} m above the floor over {:.2} m, between wall faces; \
             lintel over {:.0} % of it; seen through in {:.0} %",
            c.door_level_m[0],
            c.door_level_m[1],
            width,
            lintel * 100.0,
            evidence * 100.0
        )],
    })
}

/// The side ([`super::opening_bins::side`]) of the one face of a two-sided wall seen about
/// the open run `bins[a..b]` (in it, or within [`FACE_AROUND_M`] either side); `None` where
/// both faces are seen there. A wall is two-sided where its thickness was measured, somewhere
/// along it; a corridor's wall whose room behind was never entered is seen from the corridor
/// only, and a stretch of its face seen sparsely at grazing incidence (office-255: 2-10
/// returns per 5 cm bin, gaps of 0.2 m, 3.5 m past the last scan) reads as an open run under
/// a lintel. Only what the scans saw through it there tells a doorway.
fn faces_seen_around(bins: &[Bin], a: usize, b: usize, c: &OpeningConfig) -> Option<usize> {
    let near = (FACE_AROUND_M / c.bin_m).round() as usize;
    let seen = bins[a.saturating_sub(near)..(b + near).min(bins.len())]
        .iter()
        .fold(0u8, |m, x| m | x.faces_seen);
    [0, 1].into_iter().find(|&side| seen == 1 << side)
}

/// How far either side of an open run the wall's own face is read (m).
const FACE_AROUND_M: f64 = 1.0;
/// The share of the face returns per bin of the wall around it that an open run's median bin
/// holds where the wall's face goes on through it.
const SPARSE_FACE_SHARE: f64 = 0.1;
/// The longest stretch of an open run with no face return at door level where the wall's face
/// goes on through it (m): a pane returns beams along all of its width, a doorway leaves a
/// stretch with none (the bench's glass panes left at most 0.10 m).
const MAX_EMPTY_M: f64 = 0.15;

/// True if the wall's face goes on through the open run `bins[a..b]`, seen sparsely at door
/// level: the run's median bin holds face returns (one at least), and at least
/// [`SPARSE_FACE_SHARE`] of those of the median blocked bin within [`FACE_AROUND_M`] either
/// side, and no stretch of it longer than [`MAX_EMPTY_M`] holds none (a doorway beside a
/// stretch of wall seen sparsely, far from the scanners, is one run: the 3DTK corridor). A
/// glass pane returns some beams, in most of its bins too few to block one, and its upper part
/// reads as a lintel; a gap in a wall has no face returns in most of its bins (a leaf crossing
/// the face plane fills a few). On the bench's maps (130 buildings), the 27 true openings with
/// the most face returns had a median of 0-2 per bin beside 20-78 around them; the runs in
/// glass partitions 1-9 beside 4-18.
fn face_goes_on(bins: &[Bin], a: usize, b: usize, c: &OpeningConfig) -> bool {
    let run = &bins[a..b];
    let longest_empty = run
        .split(|x| x.door_face > 0)
        .map(<[Bin]>::len)
        .max()
        .unwrap_or(0);
    if longest_empty as f64 * c.bin_m > MAX_EMPTY_M + 1e-9 {
        return false;
    }
    match (median_face(run), face_around(bins, a, b, c)) {
        (Some(run), Some(wall)) => run >= 1.0 && run >= SPARSE_FACE_SHARE * wall,
        _ => false,
    }
}

#[cfg(test)]
#[path = "openings_tests.rs"]
mod tests;
