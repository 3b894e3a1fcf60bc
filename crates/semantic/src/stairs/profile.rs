//! The profile of a staircase candidate along one direction (its levels, rise, run and start)
//! and the staircase built from the best one (see the `stairs` module).

use super::envelope::{envelope, of_flight};
use super::levels::level_grid;
use super::risers::{RiserBands, RISER_WEIGHT};
use super::StairsConfig;
use crate::points::quantile;
use glam::DVec2;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// Returns up to this far above the grid's top level still lie on it (the levels' tolerance).
const ABOVE_TOP_M: f64 = 0.035;

/// A staircase profile along one direction.
pub(crate) struct Profile {
    pub dir: DVec2,
    pub rise: f64,
    pub run: f64,
    /// Along-coordinate of the first front edge.
    pub front1: f64,
    pub steps: u32,
    pub found: u32,
    pub score: f64,
}

/// Fits a staircase profile to points `(xy, height above floor)` climbing along `dir` (see the
/// module docs for levels and rise).
///
/// The run and start: the model is violated by a 1 cm bin whose highest point stands more
/// than 2.5 cm above it (with 1.5 cm of slack along the direction at an edge) but not more than
/// a rise over that (a step the model misses is one rise higher; a return farther above is
/// something over the flight: a handrail, a person on the landing, a mixed pixel between the
/// landing's edge and the wall behind it, and no fit of the steps explains it) and supported by
/// one at most 3.5 cm under it; a bin sampled far under its top (the laser missed the edge)
/// neither supports nor violates. Each level's support counts up to 5 bins, so that the long
/// top level cannot outweigh the steps; the risers seen at the model's front edges add their
/// evidence (see `risers`). Every `(run, s0)` on the grid (2 mm, 5 mm) with the best
/// `support - 3 violations + risers` explains the data equally well (a front edge can lie anywhere
/// between the last sample of the level below and the first of its own): their centroid is the
/// fit, unbiased by the sampling either side of an edge.
pub(crate) fn profile(
    pts: &[(DVec2, f64)],
    all: &[(DVec2, f64)],
    dir: DVec2,
    c: &StairsConfig,
) -> Option<Profile> {
    profile_near(pts, all, dir, c, None)
}

/// A fit's rise this close (as a fraction) to the rise of the flight below is the same rise.
const SAME_RISE: f64 = 0.15;

/// [`profile`], for a flight whose risers should match `rise_hint` (the upper flight of a
/// staircase whose lower flight was found: a staircase's risers are uniform). Its step count
/// from the top height over that rise is fitted too, and of the fits within [`SAME_RISE`] of it
/// the one nearest to it wins: seen from the floor below, an upper flight shows only its risers
/// and side face, and a count one higher or lower can fit them about as well.
pub(crate) fn profile_near(
    pts: &[(DVec2, f64)],
    all: &[(DVec2, f64)],
    dir: DVec2,
    c: &StairsConfig,
    rise_hint: Option<f64>,
) -> Option<Profile> {
    let bin = 0.01;
    let mut s: Vec<f64> = all.iter().map(|(q, _)| q.dot(dir)).collect();
    let s_lo = quantile(&mut s.clone(), 0.005)? - 0.05;
    let s_hi = quantile(&mut s, 0.995)? + 0.05;
    let nb = (((s_hi - s_lo) / bin).ceil() as usize).clamp(1, 100_000);
    let env = envelope(pts, dir, s_lo, nb, c.run_m[0] / 2.0);
    let env = &of_flight(&env, c);
    if env.len() < 10 {
        return None;
    }
    let mut running = f64::NEG_INFINITY;
    let maxima: Vec<f64> = env
        .iter()
        .map(|e| {
            running = running.max(e.1);
            running
        })
        .collect();
    let mut highest: Vec<f64> = env.iter().map(|e| e.1).collect();
    highest.sort_by(|x, y| y.total_cmp(x));
    let top_height = *highest.get(1)?;
    // The grid of levels. An upper flight seen from the floor below may show none: the rays
    // grazing each nosing leave mixed pixels over its tread, up towards the next riser, and
    // the running maximum climbs through them instead of resting on the tread (office-17 of
    // the held-out seeds). The rise of the flight below stands in then (a staircase's risers
    // are uniform; heights are measured from the landing, the grid's 0), and the grid search
    // of the steps (`fit_steps`) decides where they are, or that there are none.
    let (rise0, offset, top_level) = match level_grid(&maxima, c) {
        Some(grid) => grid,
        None => {
            let rise = rise_hint?;
            (rise, 0.0, (top_height / rise).round())
        }
    };
    // The step count from the top level over the rise of the levels; with the levels seen
    // on a side face (a few centimetres under the treads: the edge between two scan lines,
    // a voxel's centroid) the rise can be off by enough to miss the count by one, so the
    // counts either side are fitted too and the best fit wins (the first on a tie).
    let n0 = ((top_height - offset) / rise0).round();
    // The edges are fitted to every point: a step's nosing has fewer neighbours than its tread
    // and riser, and the fit's violations bear the odd mixed pixel in front of it.
    let fit_env = envelope(all, dir, s_lo, nb, c.run_m[0] / 2.0);
    let fit_env = &of_flight(&fit_env, c);
    // A few returns above the top (mixed pixels between a landing's edge and the wall behind
    // it, along rays that rise past the edge) set the top height too high, by two steps or
    // more; then the highest level on the grid of levels is taken as the top as well, fitted
    // to the envelope under it (those returns, above the model, would count against it).
    let grid_top = offset + top_level * rise0;
    let under: Vec<(f64, f64)> = if (top_level - n0).abs() >= 2.0 {
        up_to(fit_env, grid_top)
    } else {
        Vec::new()
    };
    // Levels between the true ones (a side face's top edge sampled sparsely next to each
    // riser, clutter beside the flight) can make the grid of levels lock onto a fraction of
    // the rise: a grid at half the rise holds every true level, one at two thirds every second
    // one. The counts for twice and one and a half times the grid's rise are fitted too.
    // (from the unrounded ratio: rounded twice, a grid rise 3 % off two thirds of the true
    // one, 14.4 levels, gave 9 steps for held-out hall-14's 10)
    let levels = (top_height - offset) / rise0;
    let (n_half, n_two_thirds) = ((levels / 2.0).round(), (levels * 2.0 / 3.0).round());
    let n_hint = rise_hint.map_or(0.0, |r| (top_height / r).round());
    // An upper flight seen from the floor below: a person walking past beside it, or mixed
    // pixels where rays rise past its edges, can stand over its top landing by more than a rise
    // (hall style, a person beside a flight on a mid landing), which the count from the top
    // height then climbs to. Its points end with its top landing: the height of their last
    // stretch is counted to as well, fitted to the envelope under it.
    let end = rise_hint
        .and_then(|_| end_plateau(env, c.run_m[1], rise0))
        .filter(|&h| h < top_height - rise0 / 2.0);
    let under_end: Vec<(f64, f64)> = end.map_or_else(Vec::new, |h| up_to(fit_env, h));
    let n_end = end.map_or(0.0, |h| ((h - offset) / rise0).round());
    let mut counts: Vec<Count> = vec![
        (n0, top_height, fit_env),
        (n0 - 1.0, top_height, fit_env),
        (n0 + 1.0, top_height, fit_env),
        (top_level, grid_top, &under),
        (n_two_thirds, top_height, fit_env),
        (n_half, top_height, fit_env),
        (n_hint, top_height, fit_env),
        (n_end, end.unwrap_or(top_height), &under_end),
    ];
    // (each count once: a fit is a grid search, and the stairs stage is the map's slowest)
    let mut seen = Vec::new();
    counts.retain(|&(n, top, env)| {
        let key = (n, top, std::ptr::from_ref(env));
        let new = !seen.contains(&key);
        seen.push(key);
        new
    });
    let fit_all = |counts: Vec<Count>| -> Vec<Fit> {
        counts
            .into_iter()
            .filter(|&(n, _, env)| n >= c.min_steps as f64 && n <= 64.0 && !env.is_empty())
            .filter(|&(n, top, _)| (c.rise_m[0]..=c.rise_m[1]).contains(&(top / n)))
            .filter_map(|(n, top, env)| {
                let risers = RiserBands::new(pts, dir, n as u32, top / n);
                fit_steps(env, &risers, n as u32, top / n, c)
            })
            // (of the fits with a bin on most levels: a count too high by a step or two leaves
            // its upper levels empty)
            .filter(|f| f.found as f64 >= 0.6 * f.n as f64 && f.best > 0.0)
            .collect()
    };
    let mut fits = fit_all(counts);
    // Where no count fits, a few returns over the top level (mixed pixels at a landing's far
    // edge) may have set the top height a few centimetres high, and the rise with it: every
    // level of a long flight then misses its bins. The top level's plateau sets it then.
    if fits.is_empty() {
        let top_mode = plateau_mode(env, top_height, rise0);
        let n_mode = ((top_mode - offset) / rise0).round();
        fits = fit_all(vec![(n_mode, top_mode, fit_env)]);
    }
    let off = |f: &Fit, r: f64| (f.rise - r).abs() / r;
    let near = rise_hint.and_then(|r| {
        fits.iter()
            .filter(|f| off(f, r) <= SAME_RISE)
            .min_by(|a, b| off(a, r).total_cmp(&off(b, r)))
    });
    let fit = near
        .or_else(|| {
            fits.iter()
                .reduce(|a, b| if b.best > a.best { b } else { a })
        })?
        .clone();
    let Fit {
        n,
        rise,
        run,
        s0,
        found,
        best,
    } = fit;
    let nf = n as f64;
    Some(Profile {
        dir,
        rise,
        run,
        front1: s0,
        steps: n,
        found,
        score: found as f64 + best / ((5.0 + RISER_WEIGHT) * nf + 1.0),
    })
}

/// The most frequent height (1 cm bins) of the envelope's bins within half a rise under the top
/// height: the top level's plateau, where a few returns above it (mixed pixels at its far
/// edge) set the top height a few centimetres high.
fn plateau_mode(env: &[(f64, f64)], top_height: f64, rise: f64) -> f64 {
    let mut counts = [0usize; 64];
    let lo = top_height - rise / 2.0;
    for e in env {
        let k = ((e.1 - lo) / 0.01).floor();
        if (0.0..64.0).contains(&k) {
            counts[k as usize] += 1;
        }
    }
    let smooth = |k: usize| {
        counts[k.saturating_sub(1)..(k + 2).min(64)]
            .iter()
            .sum::<usize>()
    };
    let best = (0..64).max_by_key(|&k| (smooth(k), k)).unwrap_or(0);
    lo + (best as f64 + 0.5) * 0.01
}

/// The envelope's bins at most [`ABOVE_TOP_M`] over `top` (a count's top level): those
/// above it are no part of the flight it fits.
fn up_to(env: &[(f64, f64)], top: f64) -> Vec<(f64, f64)> {
    env.iter()
        .copied()
        .filter(|e| e.1 <= top + ABOVE_TOP_M)
        .collect()
}

/// The height of the envelope's last `along_m`: the most frequent (see [`plateau_mode`])
/// within half a `rise` under the stretch's highest bin; `None` for an empty envelope.
fn end_plateau(env: &[(f64, f64)], along_m: f64, rise: f64) -> Option<f64> {
    let last = env.last()?.0;
    let from = env.partition_point(|e| e.0 < last - along_m);
    let stretch = &env[from..];
    let highest = stretch
        .iter()
        .map(|e| e.1)
        .fold(f64::NEG_INFINITY, f64::max);
    Some(plateau_mode(stretch, highest, rise))
}

/// A step count to fit, the top height it climbs to and the envelope it is fitted to.
type Count<'a> = (f64, f64, &'a [(f64, f64)]);

/// The stair model fitted to the envelope for one step count.
#[derive(Clone)]
struct Fit {
    n: u32,
    rise: f64,
    run: f64,
    s0: f64,
    /// Levels with a bin on them.
    found: u32,
    /// `support - 3 violations + risers` (see `profile`).
    best: f64,
}

/// Scores within this of the best are optima (and averaged); a pass is cut short only when it
/// falls below the best by more.
const PRUNE_MARGIN: f64 = 1e-9;

/// Raises the best score seen `known` (an `f64`'s bits) to `v` if that is higher.
fn raise(known: &AtomicU64, v: f64) {
    let mut seen = known.load(Ordering::Relaxed);
    while v > f64::from_bits(seen) {
        match known.compare_exchange_weak(seen, v.to_bits(), Ordering::Relaxed, Ordering::Relaxed) {
            Ok(_) => break,
            Err(now) => seen = now,
        }
    }
}

/// The run and start of `n` steps of `rise` that explain the envelope `(along, highest)` best
/// (see `profile`).
fn fit_steps(
    env: &[(f64, f64)],
    risers: &RiserBands,
    n: u32,
    rise: f64,
    c: &StairsConfig,
) -> Option<Fit> {
    let nf = n as f64;
    let level = |s: f64, run: f64, s0: f64| {
        if s < s0 {
            0.0
        } else {
            (((s - s0) / run).floor() + 1.0).min(nf)
        }
    };
    // The envelope is in order along the direction, so the levels at `s` and at `s + 1.5 cm`
    // only climb: each is advanced past the front edges `s0 + k run` it has crossed.
    // A score is the violations (never positive), the support (at most 5 on each of the
    // `n` levels, final for the levels the pass has left behind) and the risers' bands: once
    // the violations and the support so far leave it short of the best already scored
    // (`known`), even with 5 on every level still ahead, the point can be no optimum and its
    // pass ends (scored -inf).
    let most_support = |k: u32, behind: f64| {
        if n > 64 {
            5.0 * 64.0
        } else {
            behind + 5.0 * f64::from(n + 1 - k.max(1))
        }
    };
    let score = |run: f64, s0: f64, known: f64| -> f64 {
        let bands = risers.score(run, s0);
        let mut v = 0.0;
        let mut support = [0u8; 65];
        let mut behind = 0.0;
        let (mut k, mut k_ahead) = (0u32, 0u32);
        for &(s, z) in env {
            let k_was = k;
            while k < n && s >= s0 + f64::from(k) * run {
                if k > 0 {
                    behind += f64::from(support[(k as usize).min(64)].min(5));
                }
                k += 1;
            }
            while k_ahead < n && s + 0.015 >= s0 + f64::from(k_ahead) * run {
                k_ahead += 1;
            }
            let above = z - (rise * f64::from(k_ahead) + 0.025);
            if above > rise {
                // (over the flight: see above)
            } else if above > 0.0 {
                v -= 3.0;
            } else if k > 0 && z >= rise * f64::from(k) - 0.035 {
                let slot = &mut support[(k as usize).min(64)];
                *slot = slot.saturating_add(1);
            }
            if (k != k_was || above > 0.0 && above <= rise)
                && v + most_support(k, behind) + bands < known - PRUNE_MARGIN
            {
                return f64::NEG_INFINITY;
            }
        }
        v + support.iter().map(|&n| f64::from(n.min(5))).sum::<f64>() + bands
    };
    // The first step starts at most a run before the first point (its front may be unseen)
    // and before the first point half a rise up.
    let first = env.iter().find(|e| e.1 >= 0.5 * rise)?.0;
    let s_start = env.first()?.0 - c.run_m[1];
    let runs = ((c.run_m[1] - c.run_m[0]) / 0.002 + 1e-6).floor() as usize + 1;
    let starts = ((first + 0.05 - s_start) / 0.005 + 1e-6).floor().max(0.0) as usize + 1;
    // Every (run, start) on the grid scored, the runs in parallel (a grid of a few 10^4
    // points, each a pass over the envelope), each pass cut short by the best score any
    // thread has seen (which points are cut varies with the threads; the optima do not).
    let known = AtomicU64::new(f64::NEG_INFINITY.to_bits());
    let scored: Vec<(f64, f64, f64)> = (0..runs)
        .into_par_iter()
        .flat_map_iter(|i| {
            let run = c.run_m[0] + i as f64 * 0.002;
            let known = &known;
            (0..starts).map(move |j| {
                let s0 = s_start + j as f64 * 0.005;
                let v = score(run, s0, f64::from_bits(known.load(Ordering::Relaxed)));
                raise(known, v);
                (run, s0, v)
            })
        })
        .collect();
    let best = scored.iter().map(|o| o.2).fold(f64::NEG_INFINITY, f64::max);
    let optimal: Vec<(f64, f64)> = scored
        .iter()
        .filter(|o| (o.2 - best).abs() <= PRUNE_MARGIN)
        .map(|o| (o.0, o.1))
        .collect();
    if optimal.is_empty() {
        return None;
    }
    let m = optimal.len() as f64;
    let run = optimal.iter().map(|o| o.0).sum::<f64>() / m;
    let s0 = optimal.iter().map(|o| o.1).sum::<f64>() / m;
    let mut ks: Vec<u32> = env
        .iter()
        .filter(|e| {
            let top = rise * level(e.0, run, s0);
            top > 0.0 && e.1 >= top - 0.035 && e.1 <= top + 0.025
        })
        .map(|e| level(e.0, run, s0) as u32)
        .collect();
    ks.sort_unstable();
    ks.dedup();
    Some(Fit {
        n,
        rise,
        run,
        s0,
        found: ks.len() as u32,
        best,
    })
}

#[cfg(test)]
#[path = "profile_tests.rs"]
mod tests;
