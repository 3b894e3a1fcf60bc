//! The upper envelope of a staircase candidate along its direction of ascent: the highest
//! point per 1 cm bin, the profile the paper's "each step above & parallel to the previous"
//! is read from (see the `stairs` module).
//!
//! The highest point of a bin is taken only where the surface it lies on goes on: a step's
//! tread, its riser's top edge and its side face's stepped top edge all have other points at
//! the same height (within the measurement's few centimetres) within half a tread's depth along
//! the direction; the riser's top edge has them in its own bin (the edge runs across the whole
//! width), a tread and a side face's top edge in the bins beside it. A lone return (or a pair)
//! has none: range noise on a far tread at grazing incidence, a mixed pixel between a step's
//! edge and the wall behind it (a laser below the edge puts it above the edge), a person walking
//! past. One such return, taken as the top level or a plateau of the running maximum, would add
//! a step (or break the rise's grid), so it is passed over for the next highest point of its
//! bin.

use super::StairsConfig;
use glam::DVec2;

/// Width of a bin along the direction (m).
pub(super) const BIN_M: f64 = 0.01;

/// How far above or under a point another may lie and still continue its surface: the realistic
/// laser's range noise at a few metres and grazing incidence, and a 5 cm voxel's centroid,
/// spread a surface's points over about this much.
const SAME_SURFACE_M: f64 = 0.03;

/// Other points that must continue a point's surface: two (one could be a second stray return
/// next to the first).
const CONTINUATION: usize = 2;

/// The highest point per bin with `CONTINUATION` others within `window_m` along `dir` and
/// `SAME_SURFACE_M` in height, from `s_lo` (`nb` bins): `(along, highest)` of the bins that
/// have one (see the module docs).
pub(super) fn envelope(
    pts: &[(DVec2, f64)],
    dir: DVec2,
    s_lo: f64,
    nb: usize,
    window_m: f64,
) -> Vec<(f64, f64)> {
    let bins = Bins::new(pts, dir, s_lo, nb);
    let Some((z_lo, z_hi)) = bins.span() else {
        return Vec::new();
    };
    // Heights per 1 cm level; a bin's levels are in its heights' order (highest first).
    let top_level = ((z_hi - z_lo) / BIN_M) as usize;
    // (a height under the lowest casts to level 0)
    let level = |z: f64| (((z - z_lo) / BIN_M) as usize).min(top_level);
    let levels: Vec<usize> = bins.heights.iter().map(|&z| level(z)).collect();
    let w = (window_m / BIN_M).round().max(0.0) as usize;
    // The points of bin `k` whose levels lie in `lo..=hi` (a bin's levels never rise).
    let in_band = |k: usize, lo: usize, hi: usize| {
        let l = &levels[bins.start[k]..bins.start[k + 1]];
        l.partition_point(|&v| v >= lo) - l.partition_point(|&v| v > hi)
    };
    let mut out = Vec::new();
    for i in 0..nb {
        // The bins within the window, the bin's own first (where a surface's points are).
        let window = std::iter::once(i)
            .chain((i.saturating_sub(w)..(i + w + 1).min(nb)).filter(|&k| k != i));
        // The highest point of the bin with others at its height.
        let top = bins.of(i).iter().copied().find(|&z| {
            let (lo, hi) = (level(z - SAME_SURFACE_M), level(z + SAME_SURFACE_M));
            let mut band = 0;
            window.clone().any(|k| {
                band += in_band(k, lo, hi);
                band > CONTINUATION
            })
        });
        if let Some(top) = top {
            out.push((s_lo + (i as f64 + 0.5) * BIN_M, top));
        }
    }
    out
}

/// The heights of the points per bin along a direction, each bin's highest first (its top is
/// the first point with others at its height), in one array (a counting sort by bin: a vector
/// per bin made the envelope the stairs stage's hot spot).
struct Bins {
    /// Where each bin's heights start in `heights` (`nb + 1` entries).
    start: Vec<usize>,
    heights: Vec<f64>,
}

impl Bins {
    fn new(pts: &[(DVec2, f64)], dir: DVec2, s_lo: f64, nb: usize) -> Bins {
        let bin_of = |(q, z): &(DVec2, f64)| {
            let v = (q.dot(dir) - s_lo) / BIN_M;
            (v >= 0.0 && (v as usize) < nb && z.is_finite()).then_some(v as usize)
        };
        let bin: Vec<Option<usize>> = pts.iter().map(bin_of).collect();
        let mut start = vec![0usize; nb + 1];
        bin.iter().flatten().for_each(|&k| start[k + 1] += 1);
        for k in 0..nb {
            start[k + 1] += start[k];
        }
        let mut next = start.clone();
        let mut heights = vec![0.0; start[nb]];
        for (k, (_, z)) in bin.iter().zip(pts) {
            if let Some(k) = *k {
                heights[next[k]] = *z;
                next[k] += 1;
            }
        }
        // (points given highest first leave every bin sorted)
        for k in 0..nb {
            let bin = &mut heights[start[k]..start[k + 1]];
            if !bin.is_sorted_by(|a, b| a.total_cmp(b).is_ge()) {
                bin.sort_unstable_by(|a, b| b.total_cmp(a));
            }
        }
        Bins { start, heights }
    }

    /// The heights in bin `k`, highest first.
    fn of(&self, k: usize) -> &[f64] {
        &self.heights[self.start[k]..self.start[k + 1]]
    }

    /// The lowest and highest height binned, if any.
    fn span(&self) -> Option<(f64, f64)> {
        let lo = self.heights.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = self
            .heights
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        (lo <= hi).then_some((lo, hi))
    }
}

/// Spikes over the envelope (see [`without_spikes`]) are this share of the shortest run wide at
/// most, and measured against the envelope as far again either side.
const SPIKE_REACH: f64 = 0.75;

/// The envelope of a flight: from its foot on (see [`from_foot`]), without spikes over it (see
/// [`without_spikes`]).
pub(super) fn of_flight(env: &[(f64, f64)], c: &StairsConfig) -> Vec<(f64, f64)> {
    without_spikes(
        from_foot(env, c.rise_m[1]),
        c.rise_m[1],
        SPIKE_REACH * c.run_m[0],
    )
}

/// Returns higher than a rise in front of a flight's first riser, over no more than this
/// along the direction: a few stray returns (a person walking past, mixed pixels), not a thing
/// standing there (a box, a chair), which is as much part of the profile as the flight.
const MAX_STRAY_M: f64 = 0.05;

/// The envelope from a flight's foot on: where the bins before the first one at most a rise
/// high (`max_rise_m`, and the measurement's few centimetres) span no more than
/// [`MAX_STRAY_M`] along, they are left out. A flight's profile starts with its first step; a
/// few strays higher in front of it are no part of it, and taken as the running maximum's first
/// level they would hide the lower steps (or read as a landing). Something standing in front
/// of the flight, over more than that, stays: it is no staircase's foot, and the levels it
/// hides are not the flight's to claim.
fn from_foot(env: &[(f64, f64)], max_rise_m: f64) -> &[(f64, f64)] {
    let Some(start) = env.first() else {
        return env;
    };
    match env.iter().position(|e| e.1 <= max_rise_m + SAME_SURFACE_M) {
        Some(first) if env[first].0 - start.0 <= MAX_STRAY_M => &env[first..],
        _ => env,
    }
}

/// The envelope without what stands on or across the flight over a short stretch: a bin more
/// than `max_rise_m` (the highest a step may rise) over all of the envelope from `width_m` to
/// twice that before it and after it (with some of it there on both sides; before the
/// envelope's first bin, the floor: a person at a flight's foot) is a spike, and so
/// is every bin within `width_m` of a spike that stands above that envelope (by the
/// measurement's few centimetres). A person walking past a flight or standing on its landing,
/// crossing a side face seen alone, is such a spike; a flight's profile rises or stays level
/// beyond a tread's depth (`width_m` is shorter than the shortest run), and the highest point
/// over a stretch passes over the low bins where a face's top edge was not sampled.
fn without_spikes(env: &[(f64, f64)], max_rise_m: f64, width_m: f64) -> Vec<(f64, f64)> {
    // (the envelope's bins are in order along the direction)
    let at = |s: f64| env.partition_point(|e| e.0 < s);
    let highest = |lo: f64, hi: f64| {
        env[at(lo)..at(hi)]
            .iter()
            .map(|e| e.1)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let mut spike = vec![false; env.len()];
    let first = env.first().map_or(f64::INFINITY, |e| e.0);
    for &(s, z) in env {
        // (before the envelope's first bin is the floor the flight stands on: its heights
        // are over it, and the floor is in no part)
        let before = match highest(s - 2.0 * width_m, s - width_m) {
            h if h.is_finite() || s - width_m > first => h,
            _ => 0.0,
        };
        let after = highest(s + width_m, s + 2.0 * width_m);
        if before.is_finite() && after.is_finite() && before.max(after) < z - max_rise_m {
            let flanks = before.max(after) + SAME_SURFACE_M;
            for k in at(s - width_m)..at(s + width_m) {
                spike[k] |= env[k].1 > flanks;
            }
        }
    }
    env.iter()
        .zip(&spike)
        .filter(|(_, &dropped)| !dropped)
        .map(|(e, _)| *e)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points `(along, height)` on the x axis.
    fn along_x(p: &[(f64, f64)]) -> Vec<(DVec2, f64)> {
        p.iter().map(|&(s, z)| (DVec2::new(s, 0.0), z)).collect()
    }

    /// Three treads 0.17 m apart seen as 2 cm-spaced samples, with one stray return 6 cm above
    /// the middle tread: the envelope follows the treads, the stray return is passed over.
    #[test]
    fn a_lone_return_above_the_treads_is_passed_over() {
        let mut p = Vec::new();
        for k in 0..3 {
            for j in 0..14 {
                p.push((
                    0.3 * k as f64 + 0.02 * j as f64 + 0.005,
                    0.17 * (k + 1) as f64,
                ));
            }
        }
        p.push((0.405, 0.17 * 2.0 + 0.06));
        let env = envelope(&along_x(&p), DVec2::X, 0.0, 100, 0.1);
        let highest_over_middle = env
            .iter()
            .filter(|e| e.0 > 0.3 && e.0 < 0.6)
            .map(|e| e.1)
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(
            (highest_over_middle - 0.34).abs() < 1e-9,
            "{highest_over_middle}"
        );
    }

    /// The top riser seen from below (no tread behind it): its top edge is a line of points
    /// across the width in one bin, and it stays in the envelope.
    #[test]
    fn a_riser_top_edge_with_nothing_behind_it_is_kept() {
        let mut p: Vec<(f64, f64)> = (0..10).map(|j| (0.005 + 0.02 * j as f64, 0.17)).collect();
        p.extend((0..5).map(|j| (0.305, 0.30 + 0.01 * j as f64)));
        p.push((0.305, 0.34));
        let env = envelope(&along_x(&p), DVec2::X, 0.0, 100, 0.1);
        assert_eq!(env.last().map(|e| e.1), Some(0.34));
    }

    /// A few strays in front of a flight's first riser are left out of its profile; a box
    /// standing there (over more than a few centimetres) is not.
    #[test]
    fn only_strays_in_front_of_the_foot_are_left_out() {
        let flight: Vec<(f64, f64)> = (0..30).map(|i| (0.1 + 0.01 * i as f64, 0.17)).collect();
        let strays = [(0.06, 0.5), (0.08, 0.51)];
        let env: Vec<(f64, f64)> = strays.iter().chain(&flight).copied().collect();
        assert_eq!(from_foot(&env, 0.23), &env[2..]);
        let boxed: Vec<(f64, f64)> = (0..20).map(|i| (-0.1 + 0.01 * i as f64, 0.5)).collect();
        let env: Vec<(f64, f64)> = boxed.iter().chain(&flight).copied().collect();
        assert_eq!(from_foot(&env, 0.23), &env[..]);
    }

    /// A person crossing a flight's landing 0.6 m up (returns 0.8-1.08 m high over 8 cm,
    /// rounded at their edges) leaves the envelope; the steps and the landing stay, and so does
    /// a top riser's edge at the envelope's end, with nothing after it.
    #[test]
    fn a_person_across_the_landing_is_no_part_of_the_profile() {
        let mut env: Vec<(f64, f64)> = Vec::new();
        for i in 0..120 {
            let s = 0.005 + 0.01 * i as f64;
            env.push((s, (0.15 * ((s / 0.28).floor() + 1.0)).min(0.6)));
        }
        let person = [0.8, 0.9, 0.98, 1.05, 1.08, 1.07, 1.0, 0.9, 0.62];
        for (k, z) in person.iter().enumerate() {
            env[100 + k].1 = *z;
        }
        let kept = without_spikes(&env, 0.23, 0.15);
        assert_eq!(
            kept.len(),
            env.len() - 8,
            "only the bins over the landing go"
        );
        assert!(kept.iter().all(|e| e.1 <= 0.62));
        let mut rising = env[..100].to_vec();
        rising.push((1.0, 0.9));
        assert_eq!(without_spikes(&rising, 0.23, 0.15), rising);
    }

    /// Regression (hall-49 of seeds 46-50): a person left in part by the transients filter, at
    /// the very start of a flight's envelope (the floor before it is in no part), 1.7 m high
    /// over 14 cm, leaves it as one on a landing does; a box 0.45 m long there stays.
    #[test]
    fn a_person_at_a_flights_foot_is_no_part_of_the_profile() {
        let flight: Vec<(f64, f64)> = (0..84)
            .map(|i| {
                let s = 0.165 + 0.01 * i as f64;
                (s, 0.17 * (((s - 0.16) / 0.28).floor() + 1.0))
            })
            .collect();
        let person: Vec<(f64, f64)> = (0..15)
            .map(|i| (0.005 + 0.01 * i as f64, 1.7 - 0.05 * (i % 3) as f64))
            .collect();
        let env: Vec<(f64, f64)> = person.iter().chain(&flight).copied().collect();
        assert_eq!(without_spikes(&env, 0.23, 0.15), flight);
        let boxed: Vec<(f64, f64)> = (0..45).map(|i| (0.005 + 0.01 * i as f64, 1.7)).collect();
        let behind: Vec<(f64, f64)> = flight.iter().map(|e| (e.0 + 0.3, e.1)).collect();
        let env: Vec<(f64, f64)> = boxed.iter().chain(&behind).copied().collect();
        assert_eq!(without_spikes(&env, 0.23, 0.15), env);
    }

    /// The envelope by its definition, point by point (quadratic in the points): for each bin,
    /// its highest point with more than `CONTINUATION` points (itself included) within the
    /// window's bins and `SAME_SURFACE_M` in height (on the same 1 cm levels).
    fn by_definition(
        pts: &[(DVec2, f64)],
        dir: DVec2,
        s_lo: f64,
        nb: usize,
        window_m: f64,
    ) -> Vec<(f64, f64)> {
        let binned: Vec<(usize, f64)> = pts
            .iter()
            .filter_map(|(q, z)| {
                let v = (q.dot(dir) - s_lo) / BIN_M;
                (v >= 0.0 && (v as usize) < nb && z.is_finite()).then_some((v as usize, *z))
            })
            .collect();
        let z_lo = binned.iter().map(|b| b.1).fold(f64::INFINITY, f64::min);
        let level = |z: f64| ((z - z_lo) / BIN_M) as usize;
        let w = (window_m / BIN_M).round() as usize;
        let mut out = Vec::new();
        for i in 0..nb {
            let mut own: Vec<f64> = binned.iter().filter(|b| b.0 == i).map(|b| b.1).collect();
            own.sort_by(|a, b| b.total_cmp(a));
            let top = own.into_iter().find(|&z| {
                let (lo, hi) = (level(z - SAME_SURFACE_M), level(z + SAME_SURFACE_M));
                let band = binned
                    .iter()
                    .filter(|b| b.0.abs_diff(i) <= w && (lo..=hi).contains(&level(b.1)))
                    .count();
                band > CONTINUATION
            });
            if let Some(top) = top {
                out.push((s_lo + (i as f64 + 0.5) * BIN_M, top));
            }
        }
        out
    }

    /// Treads, risers and scattered strays along a turned direction, in any order and highest
    /// first: the windowed search (sorted bins, binary search per bin, the own bin first)
    /// returns exactly the envelope by its definition.
    #[test]
    fn the_windowed_search_is_the_envelope_by_its_definition() {
        let mut rng = crate::test_rng::TestRng::new(0x2545_f491_4f6c_dd1d);
        let mut rand = move || rng.next_f64();
        let dir = DVec2::new(0.8, 0.6);
        for case in 0..6 {
            let mut pts: Vec<(DVec2, f64)> = (0..1500)
                .map(|_| {
                    let s = rand() * 2.0;
                    let z = if rand() < 0.15 {
                        rand() * 1.2
                    } else {
                        0.17 * ((s / 0.28).floor() + 1.0) + (rand() - 0.5) * 0.02
                    };
                    (dir * s + dir.perp() * (rand() - 0.5), z)
                })
                .collect();
            if case % 2 == 1 {
                pts.sort_by(|a, b| b.1.total_cmp(&a.1));
            }
            let window_m = 0.05 + 0.02 * case as f64;
            let got = envelope(&pts, dir, -0.1, 220, window_m);
            assert!(got.len() > 150, "case {case}: {} bins", got.len());
            assert_eq!(
                got,
                by_definition(&pts, dir, -0.1, 220, window_m),
                "case {case}"
            );
        }
    }
}
