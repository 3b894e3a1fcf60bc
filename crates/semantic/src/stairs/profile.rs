//! The profile of a staircase candidate along one direction (its levels, rise, run and start)
//! and the staircase built from the best one (see the `stairs` module).

use super::envelope::envelope;
use super::levels::level_grid;
use super::StairsConfig;
use crate::points::quantile;
use glam::DVec2;
use rayon::prelude::*;

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
/// top level cannot outweigh the steps. Every `(run, s0)` on the grid (2 mm, 5 mm) with the best
/// `support - 3 violations` explains the data equally well (a front edge can lie anywhere
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
    let (rise0, offset, top_level) = level_grid(&maxima, c)?;
    let mut highest: Vec<f64> = env.iter().map(|e| e.1).collect();
    highest.sort_by(|x, y| y.total_cmp(x));
    let top_height = *highest.get(1)?;
    // The step count from the top level over the rise of the levels; with the levels seen
    // on a side face (a few centimetres under the treads: the edge between two scan lines,
    // a voxel's centroid) the rise can be off by enough to miss the count by one, so the
    // counts either side are fitted too and the best fit wins (the first on a tie).
    let n0 = ((top_height - offset) / rise0).round();
    // The edges are fitted to every point: a step's nosing has fewer neighbours than its tread
    // and riser, and the fit's violations bear the odd mixed pixel in front of it.
    let fit_env = envelope(all, dir, s_lo, nb, c.run_m[0] / 2.0);
    // A few returns above the top (mixed pixels between a landing's edge and the wall behind
    // it, along rays that rise past the edge) set the top height too high, by two steps or
    // more; then the highest level on the grid of levels is taken as the top as well, fitted
    // to the envelope under it (those returns, above the model, would count against it).
    let grid_top = offset + top_level * rise0;
    let under: Vec<(f64, f64)> = if (top_level - n0).abs() >= 2.0 {
        fit_env
            .iter()
            .copied()
            .filter(|e| e.1 <= grid_top + ABOVE_TOP_M)
            .collect()
    } else {
        Vec::new()
    };
    // Levels between the true ones (a side face's top edge sampled sparsely next to each
    // riser, clutter beside the flight) can make the grid of levels lock onto a fraction of
    // the rise: a grid at half the rise holds every true level, one at two thirds every second
    // one. The counts for twice and one and a half times the grid's rise are fitted too.
    let (n_half, n_two_thirds) = ((n0 / 2.0).round(), (n0 * 2.0 / 3.0).round());
    let n_hint = rise_hint.map_or(0.0, |r| (top_height / r).round());
    let mut counts = vec![
        (n0, top_height, &fit_env),
        (n0 - 1.0, top_height, &fit_env),
        (n0 + 1.0, top_height, &fit_env),
        (top_level, grid_top, &under),
        (n_two_thirds, top_height, &fit_env),
        (n_half, top_height, &fit_env),
        (n_hint, top_height, &fit_env),
    ];
    // (each count once: a fit is a grid search, and the stairs stage is the map's slowest)
    let mut seen = Vec::new();
    counts.retain(|&(n, top, env)| {
        let key = (n, top, std::ptr::from_ref(env));
        let new = !seen.contains(&key);
        seen.push(key);
        new
    });
    let fits: Vec<Fit> = counts
        .into_iter()
        .filter(|&(n, _, env)| n >= c.min_steps as f64 && n <= 64.0 && !env.is_empty())
        .filter(|&(n, top, _)| (c.rise_m[0]..=c.rise_m[1]).contains(&(top / n)))
        .filter_map(|(n, top, env)| fit_steps(env, n as u32, top / n, c))
        // (of the fits with a bin on most levels: a count too high by a step or two leaves
        // its upper levels empty)
        .filter(|f| f.found as f64 >= 0.6 * f.n as f64 && f.best > 0.0)
        .collect();
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
        score: found as f64 + best / (5.0 * nf + 1.0),
    })
}

/// The stair model fitted to the envelope for one step count.
#[derive(Clone)]
struct Fit {
    n: u32,
    rise: f64,
    run: f64,
    s0: f64,
    /// Levels with a bin on them.
    found: u32,
    /// `support - 3 violations` (see `profile`).
    best: f64,
}

/// The run and start of `n` steps of `rise` that explain the envelope `(along, highest)` best
/// (see `profile`).
fn fit_steps(env: &[(f64, f64)], n: u32, rise: f64, c: &StairsConfig) -> Option<Fit> {
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
    let score = |run: f64, s0: f64| -> f64 {
        let mut v = 0.0;
        let mut support = [0u8; 65];
        let (mut k, mut k_ahead) = (0u32, 0u32);
        for &(s, z) in env {
            while k < n && s >= s0 + f64::from(k) * run {
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
        }
        v + support.iter().map(|&n| f64::from(n.min(5))).sum::<f64>()
    };
    // The first step starts at most a run before the first point (its front may be unseen)
    // and before the first point half a rise up.
    let first = env.iter().find(|e| e.1 >= 0.5 * rise)?.0;
    let s_start = env.first()?.0 - c.run_m[1];
    let runs = ((c.run_m[1] - c.run_m[0]) / 0.002 + 1e-6).floor() as usize + 1;
    let starts = ((first + 0.05 - s_start) / 0.005 + 1e-6).floor().max(0.0) as usize + 1;
    // Every (run, start) on the grid scored, the runs in parallel (a grid of a few 10^4
    // points, each a pass over the envelope).
    let scored: Vec<(f64, f64, f64)> = (0..runs)
        .into_par_iter()
        .flat_map_iter(|i| {
            let run = c.run_m[0] + i as f64 * 0.002;
            (0..starts).map(move |j| {
                let s0 = s_start + j as f64 * 0.005;
                (run, s0, score(run, s0))
            })
        })
        .collect();
    let best = scored.iter().map(|o| o.2).fold(f64::NEG_INFINITY, f64::max);
    let optimal: Vec<(f64, f64)> = scored
        .iter()
        .filter(|o| (o.2 - best).abs() <= 1e-9)
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
mod tests {
    use super::*;

    /// A straight flight climbing +X from x = 0: `steps` steps of `rise` x `run`, a landing
    /// 1.1 m deep, 1.2 m wide; points every 2 cm on treads and risers, 10 cm across.
    fn flight(steps: u32, rise: f64, run: f64) -> Vec<(DVec2, f64)> {
        let mut pts = Vec::new();
        let across = |pts: &mut Vec<(DVec2, f64)>, x: f64, z: f64| {
            for k in 0..12 {
                pts.push((DVec2::new(x, -0.6 + 0.1 * k as f64), z));
            }
        };
        for k in 0..steps {
            let (x0, top) = (k as f64 * run, (k + 1) as f64 * rise);
            let depth = if k + 1 == steps { run + 1.1 } else { run };
            for i in 0..(rise / 0.02) as usize {
                across(&mut pts, x0, top - rise + 0.02 * i as f64);
            }
            for i in 0..(depth / 0.02) as usize {
                across(&mut pts, x0 + 0.02 * i as f64, top);
            }
        }
        pts
    }

    /// Regression: office-1's 10-step flight (rise 0.16 m) was not found at all: mixed pixels
    /// along rays rising past its landing's edge stood 0.05-0.4 m above the landing, so the top
    /// height read as 12 steps, whose fit left the upper levels empty and was refused.
    #[test]
    fn returns_above_the_landing_do_not_add_steps() {
        let c = StairsConfig::default();
        let mut pts = flight(10, 0.16, 0.27);
        // A veil over the landing: streaks of returns along rays rising past its edge, each
        // return 1 cm above and 2 cm along the one before (so they continue each other as a
        // surface's returns do), 0.2-0.26 m above it, between the heights an 11th and a 12th
        // step would have.
        for k in 0..6 {
            let x = 2.9 + 0.12 * k as f64;
            for i in 0..7 {
                let q = DVec2::new(x + 0.02 * i as f64, -0.2 + 0.05 * k as f64);
                pts.push((q, 1.8 + 0.01 * i as f64));
            }
        }
        let p = profile(&pts, &pts, DVec2::X, &c).expect("a staircase");
        assert_eq!(p.steps, 10);
        assert!((p.rise - 0.16).abs() < 0.01, "rise {}", p.rise);
        assert!((p.run - 0.27).abs() < 0.02, "run {}", p.run);
        // The same flight without the veil, for reference.
        let bare = flight(10, 0.16, 0.27);
        let clean = profile(&bare, &bare, DVec2::X, &c).expect("a staircase");
        assert_eq!(clean.steps, 10);
    }

    /// Regression: hall-9's 11-step flight (rise 0.158 m), scanned from 23 poses, was not
    /// found: sparse returns 0.2-0.45 m over its top landing (mixed pixels between the
    /// landing's edge and the wall behind it; on no surface, so they set neither the levels
    /// nor the top) each counted as a violation of every fit, and outweighed the steps' support.
    #[test]
    fn returns_high_over_the_landing_do_not_refuse_the_flight() {
        let c = StairsConfig::default();
        let pts = flight(11, 0.158, 0.28);
        let mut all = pts.clone();
        // 30 bins along the landing (x 3.1-3.7), each with a return 0.2-0.45 m over it.
        for k in 0..30 {
            let q = DVec2::new(3.1 + 0.02 * k as f64, 0.1);
            all.push((q, 11.0 * 0.158 + 0.2 + 0.25 * ((k * 7) % 10) as f64 / 10.0));
        }
        let p = profile(&pts, &all, DVec2::X, &c).expect("a staircase");
        assert_eq!(p.steps, 11);
        assert!((p.rise - 0.158).abs() < 0.01, "rise {}", p.rise);
    }

    /// Regression: hall-4's upper flight (4 steps of 0.17 m, seen on its side face from the
    /// floor) was not found: the side face's top edge, sampled sparsely, stood at heights
    /// between the treads' in the first centimetres of each step, and the grid of levels locked
    /// onto two thirds of the rise (its levels hold every true one but the odd ones), so the
    /// counts fitted were 5 to 7, all refused.
    #[test]
    fn levels_between_the_treads_do_not_hide_the_rise() {
        let c = StairsConfig::default();
        let (rise, run) = (0.17, 0.27);
        let grid = rise * 2.0 / 3.0;
        let mut pts = Vec::new();
        for k in 0..4 {
            let (x0, top) = (k as f64 * run, (k + 1) as f64 * rise);
            // The grid's level between this step's foot and its tread, over its first 8 cm.
            let between = ((top - rise) / grid).floor() * grid + grid;
            let depth = if k == 3 { run + 1.1 } else { run };
            let mut x = x0;
            while x < x0 + depth {
                let z = if x < x0 + 0.08 && between < top - 0.02 {
                    between
                } else {
                    top
                };
                for j in 0..12 {
                    pts.push((DVec2::new(x, -0.6 + 0.1 * j as f64), z));
                }
                x += 0.02;
            }
        }
        let p = profile(&pts, &pts, DVec2::X, &c).expect("a staircase");
        assert_eq!(p.steps, 4);
        assert!((p.rise - rise).abs() < 0.01, "rise {}", p.rise);
    }

    /// Regression: the upper flights of hall-3's and hall-8's mid-landing staircases (4 steps of
    /// 0.16 m, 3 of 0.18 m), seen from the floor below on their risers and side faces only, fitted
    /// one step more better; the lower flight's rise decides (a staircase's risers are uniform).
    #[test]
    fn the_rise_of_the_flight_below_decides_between_counts_that_fit_alike() {
        let c = StairsConfig::default();
        // A side face's stepped top edge, 3 steps of 0.18 x 0.26 m and a 1.1 m landing, sampled
        // every 2 cm along; over the first `lead` of each step the edge shows at the level a
        // 4-step flight to the same top would have there (a riser's foot, clutter).
        let (rise, run): (f64, f64) = (0.18, 0.26);
        let four = 3.0 * rise / 4.0;
        let lead = 0.08;
        let mut pts = Vec::new();
        let mut x: f64 = 0.0;
        while x < 3.0 * run + 1.1 {
            let k = (x / run).floor().min(2.0);
            let top = (k + 1.0) * rise;
            let between = ((k * rise) / four).floor() * four + four;
            let z = if x - k * run < lead && between < top - 0.02 {
                between
            } else {
                top
            };
            for j in 0..10 {
                pts.push((DVec2::new(x, 0.1 * j as f64), z));
            }
            x += 0.02;
        }
        let p = profile_near(&pts, &pts, DVec2::X, &c, Some(0.175)).expect("a flight");
        assert_eq!(p.steps, 3);
        assert!((p.rise - rise).abs() < 0.01, "rise {}", p.rise);
        // A hint no count fits within 15 % of leaves the choice to the fits' scores.
        let far = profile_near(&pts, &pts, DVec2::X, &c, Some(0.30)).map(|p| p.steps);
        assert_eq!(far, profile(&pts, &pts, DVec2::X, &c).map(|p| p.steps));
    }
}
