//! The grid search of a staircase profile's steps: the run and start of `n` steps of one rise
//! that explain a profile's envelope best (see `profile`).

use super::risers::RiserBands;
use super::StairsConfig;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// The stair model fitted to the envelope for one step count.
#[derive(Clone)]
pub(super) struct Fit {
    pub n: u32,
    pub rise: f64,
    pub run: f64,
    pub s0: f64,
    /// Levels with a bin on them.
    pub found: u32,
    /// `support - 3 violations + risers` (see `profile`).
    pub best: f64,
}

/// The spacing of a grid search's runs and starts.
#[derive(Clone, Copy)]
pub(super) struct Grid {
    pub run_step_m: f64,
    pub start_step_m: f64,
}

/// The grid every fit is searched on (a front edge is placed to within 5 mm).
pub(super) const FINE: Grid = Grid {
    run_step_m: 0.002,
    start_step_m: 0.005,
};

/// A grid nine times coarser: a quick look at whether a count can beat a fit already made.
pub(super) const COARSE: Grid = Grid {
    run_step_m: 0.006,
    start_step_m: 0.015,
};

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
/// (see `profile`), searched on `grid`; a pass that cannot score `floor` is cut short (the
/// fit of a count that cannot beat `floor` has a lower score, or is `None`).
pub(super) fn fit_steps(
    env: &[(f64, f64)],
    risers: &RiserBands,
    n: u32,
    rise: f64,
    c: &StairsConfig,
    grid: Grid,
    floor: f64,
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
    let runs = ((c.run_m[1] - c.run_m[0]) / grid.run_step_m + 1e-6).floor() as usize + 1;
    let starts = ((first + 0.05 - s_start) / grid.start_step_m + 1e-6)
        .floor()
        .max(0.0) as usize
        + 1;
    // Every (run, start) on the grid scored, the runs in parallel (a grid of a few 10^4
    // points, each a pass over the envelope), each pass cut short by the best score any
    // thread has seen (which points are cut varies with the threads; the optima do not).
    let known = AtomicU64::new(floor.to_bits());
    let scored: Vec<(f64, f64, f64)> = (0..runs)
        .into_par_iter()
        .flat_map_iter(|i| {
            let run = c.run_m[0] + i as f64 * grid.run_step_m;
            let known = &known;
            (0..starts).map(move |j| {
                let s0 = s_start + j as f64 * grid.start_step_m;
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
