//! The profile of a staircase candidate along one direction (its levels, rise, run and start)
//! and the staircase built from the best one (see the `stairs` module).

use super::envelope::{envelope, of_flight};
use super::fit::{fit_steps, Fit, COARSE, FINE};
use super::levels::level_grid;
use super::plateau::{end_plateau, plateau_mode, span_over, up_to, ABOVE_TOP_M};
use super::risers::{RiserBands, RISER_WEIGHT};
use super::StairsConfig;
use crate::points::quantile;
use glam::DVec2;

/// The envelope's bins (1 cm) over the top level's plateau that are a few returns over its
/// edge (mixed pixels, a voxel's centroid), not more of the profile climbing: 5 cm of them.
const FEW_OVER_PLATEAU: usize = 5;

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
    /// The fit's `support - 3 violations + risers` (see [`profile`]).
    pub fit_score: f64,
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
pub(super) const SAME_RISE: f64 = 0.15;

/// [`profile`], for a flight whose risers should match `rise_hint` (the upper flight of a
/// staircase whose lower flight was found: a staircase's risers are uniform). Its step count
/// from the top height over that rise is fitted too, and of the fits within [`SAME_RISE`] of it
/// that miss the fewest of their levels, the one nearest to it wins: seen from the floor below,
/// an upper flight shows only its risers and side face, and a count one higher or lower can fit
/// them about as well. Where no fit is within [`SAME_RISE`], the count at `rise_hint` up to the
/// top level's plateau is fitted too (returns over the top landing can set the top height high:
/// fresh office-43).
pub(crate) fn profile_near(
    pts: &[(DVec2, f64)],
    all: &[(DVec2, f64)],
    dir: DVec2,
    c: &StairsConfig,
    rise_hint: Option<f64>,
) -> Option<Profile> {
    fit_profile(pts, all, dir, c, rise_hint, Counts::Grid)
}

/// A fit of another step count than [`profile`]'s along `dir` that scores more than its fit
/// there (`found`, [`Profile::fit_score`]): every count whose rise is in `rise_m`, up to the top
/// height and up to the top level's plateau, is fitted (`None`: none beats it).
///
/// [`profile`] fits the counts that its grid of levels and its top height point to. On a
/// flight seen from its side only, both can be off: the grid locks onto whatever spacing the
/// side face's sparse top edge and the returns under it pile up at (bench mixed-38: 0.137 m
/// for a 0.165 m rise, five sixths of it, where the counts for a grid at a half, two thirds
/// or the whole rise are fitted), and the top height (the second highest bin) can stand a few
/// centimetres over the top level's plateau (mixed pixels at its far edge; bench garage-36:
/// 1.501 m for 1.447 m, 9 steps of 0.161 m). None of the counts fitted is then the flight's,
/// and a count of smaller or larger steps, supported by the side face's noise, wins. Fitting
/// every count doubled the stairs stage's time when done for every direction of every part,
/// so it is done for the direction a search has chosen only (see `search`), each count first
/// on a coarse grid.
pub(crate) fn profile_other_count(
    pts: &[(DVec2, f64)],
    all: &[(DVec2, f64)],
    dir: DVec2,
    found: f64,
    c: &StairsConfig,
) -> Option<Profile> {
    fit_profile(pts, all, dir, c, None, Counts::Beat(found))
}

/// The counts [`fit_profile`] fits.
#[derive(Clone, Copy)]
enum Counts {
    /// Those the grid of levels and the top height point to ([`profile`], [`profile_near`]).
    Grid,
    /// Every other count that scores more than this ([`profile_other_count`]).
    Beat(f64),
    /// The count up to the top level's plateau only ([`profile_up_to_plateau`]).
    Plateau,
}

/// The count up to the top level's plateau along `dir`, where a few returns over that plateau
/// set the top height over it by more than the levels' tolerance (`None` otherwise, or where
/// it has no fit). A flight seen from its side only, in sparse returns: a few returns over its
/// top landing's edge (mixed pixels, a voxel's centroid) set the top height, the count from it
/// gets a rise the levels, read low on the side face's top edge, fall short of, and the best
/// fit left is no stair (office-145 of seeds 141-145: a 4-step flight of 0.159 m, its landing's
/// plateau at 0.60 m and the top height at 0.66 m, read as 3 steps of 0.22 m, too steep). A
/// search fits this count where the profile's own makes no staircase along a wall's direction
/// (see `search`): a ramp read along a direction oblique to it has such a plateau too, where
/// the strip across it reaches its top end, and a count up to it fits its rise (the evaluate
/// crate's wheelchair ramp read as 3 steps of 0.110 m).
pub(crate) fn profile_up_to_plateau(
    pts: &[(DVec2, f64)],
    all: &[(DVec2, f64)],
    dir: DVec2,
    c: &StairsConfig,
) -> Option<Profile> {
    fit_profile(pts, all, dir, c, None, Counts::Plateau)
}

/// A coarse fit this far under the score to beat may still beat it on the fine grid.
const COARSE_SLACK: f64 = 5.0;

/// The profile along `dir` (see [`profile`], [`profile_near`]; with `beat`, only counts other
/// than [`profile`]'s that score more than it, see [`profile_other_count`]).
fn fit_profile(
    pts: &[(DVec2, f64)],
    all: &[(DVec2, f64)],
    dir: DVec2,
    c: &StairsConfig,
    rise_hint: Option<f64>,
    which: Counts,
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
    // stretch is counted to as well, fitted to the envelope under it. So for any flight whose
    // profile ends in a stretch over which nothing stands beyond a tread's depth (`run_m`):
    // returns over its top riser and the landing's front (mixed pixels over the nosing) stand
    // there as a step would (office-165 of seeds 161-165: 3 steps of 0.178 m read as 4 of
    // 0.164 m climbing to returns 0.15 m over the landing along 0.2 m). A profile read down a
    // flight from its top ends in its lowest steps, with the rest of the flight over them.
    let end = end_plateau(env, c.run_m[1], rise0)
        .filter(|&h| h < top_height - rise0 / 2.0)
        .filter(|&h| rise_hint.is_some() || span_over(env, h + ABOVE_TOP_M) <= c.run_m[1]);
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
    let fit_all = |counts: Vec<Count>, floor: f64| -> Vec<Fit> {
        counts
            .into_iter()
            .filter(|&(n, _, env)| n >= c.min_steps as f64 && n <= 64.0 && !env.is_empty())
            .filter(|&(n, top, _)| (c.rise_m[0]..=c.rise_m[1]).contains(&(top / n)))
            .filter_map(|(n, top, env)| {
                let risers = RiserBands::new(pts, dir, n as u32, top / n);
                // (a count that cannot come near `floor` on the coarse grid is not searched)
                if floor > f64::NEG_INFINITY {
                    let coarse = fit_steps(
                        env,
                        &risers,
                        n as u32,
                        top / n,
                        c,
                        COARSE,
                        floor - COARSE_SLACK,
                    );
                    coarse.filter(|f| f.best >= floor - COARSE_SLACK)?;
                }
                fit_steps(env, &risers, n as u32, top / n, c, FINE, floor)
            })
            // (of the fits with a bin on most levels: a count too high by a step or two leaves
            // its upper levels empty)
            .filter(|f| f.found as f64 >= 0.6 * f.n as f64 && f.best > 0.0 && f.best > floor)
            .collect()
    };
    // (the top level's plateau: a second top for the counts below, and its own count)
    let top_mode = plateau_mode(env, top_height, rise0);
    let plateau_count: Count = (((top_mode - offset) / rise0).round(), top_mode, fit_env);
    let mut fits = match which {
        Counts::Grid => fit_all(counts, f64::NEG_INFINITY),
        Counts::Plateau => {
            // (a few bins over the plateau: more are the profile climbing on, as a ramp's)
            let over = env.iter().filter(|e| e.1 > top_mode + ABOVE_TOP_M).count();
            if top_height - top_mode <= ABOVE_TOP_M || over > FEW_OVER_PLATEAU {
                return None;
            }
            return fit_all(vec![plateau_count], f64::NEG_INFINITY)
                .into_iter()
                .next()
                .map(|f| Profile::of(dir, f));
        }
        Counts::Beat(floor) => {
            // Every other count in the range of rises, up to either top.
            let mut others: Vec<Count> = Vec::new();
            for top in [top_height, top_mode] {
                let fewest = (top / c.rise_m[1]).ceil().max(1.0);
                let most = (top / c.rise_m[0]).floor().min(64.0);
                let mut n = fewest;
                while n <= most {
                    let key = (n, top, std::ptr::from_ref::<[(f64, f64)]>(fit_env));
                    if !seen.contains(&key) {
                        seen.push(key);
                        others.push((n, top, fit_env));
                    }
                    n += 1.0;
                }
            }
            return fit_all(others, floor)
                .into_iter()
                .reduce(|a, b| if b.best > a.best { b } else { a })
                .map(|f| Profile::of(dir, f));
        }
    };
    // Where no count fits, a few returns over the top level (mixed pixels at a landing's far
    // edge) may have set the top height a few centimetres high, and the rise with it: every
    // level of a long flight then misses its bins. The top level's plateau sets it then.
    if fits.is_empty() {
        fits = fit_all(vec![plateau_count], f64::NEG_INFINITY);
    }
    let off = |f: &Fit, r: f64| (f.rise - r).abs() / r;
    // An upper flight none of whose fits has the lower flight's rise: its count at that rise
    // up to the top level's plateau as well (returns over its top landing, a person's or
    // mixed pixels', can set the top height high).
    if let Some(r) = rise_hint {
        if !fits.iter().any(|f| off(f, r) <= SAME_RISE) {
            let n = (top_mode / r).round();
            fits.extend(fit_all(vec![(n, top_mode, fit_env)], f64::NEG_INFINITY));
        }
    }
    // (of those within `SAME_RISE`, the ones that miss the fewest of their levels first: a
    // hint read a few per cent low, its rise between two counts', must not pick the count
    // that leaves a level empty over the one that found every level; office-311 of seeds
    // 311-315, 4 steps of 0.156 m, all found, lost to 5 that missed one by 0.5 % of the rise.
    // Of those, the best fit: within `SAME_RISE` the hint has done its work, and the nearer
    // rise is not the better reading. office-482 of seeds 481-485: a person standing beside
    // an upper flight's top step, seen 0.5 m over it, made 5 steps of 0.171 m, all found, fit
    // 33, nearer the lower flight's 0.172 m than the 4 steps of 0.174 m, all found, fit 57.)
    let missed = |f: &Fit| f.n.saturating_sub(f.found);
    let near = rise_hint.and_then(|r| {
        fits.iter()
            .filter(|f| off(f, r) <= SAME_RISE)
            .min_by(|a, b| missed(a).cmp(&missed(b)).then(b.best.total_cmp(&a.best)))
    });
    // (the counts in turn, the grid's first: one replaces the best so far only where it scores
    // more and misses no more of its levels. hall-82 of seeds 81-85: 7 steps of 0.217 m, their
    // riser bands on the 7 risers seen, missed one of their levels and outscored the 8 steps
    // that found all 8. A share of the levels, as `search::levels_share` asks of a count fitted
    // later, is too fine a test here: office-63's 5 steps, 4 of 5 levels found, must replace a
    // grid's 6 that found 5.)
    let fit = near
        .or_else(|| {
            fits.iter().reduce(|a, b| {
                if b.best > a.best && missed(b) <= missed(a) {
                    b
                } else {
                    a
                }
            })
        })?
        .clone();
    Some(Profile::of(dir, fit))
}

impl Profile {
    /// The profile of a fit along `dir`.
    fn of(dir: DVec2, fit: Fit) -> Profile {
        let Fit {
            n,
            rise,
            run,
            s0,
            found,
            best,
        } = fit;
        Profile {
            dir,
            rise,
            run,
            front1: s0,
            steps: n,
            found,
            score: found as f64 + best / ((5.0 + RISER_WEIGHT) * n as f64 + 1.0),
            fit_score: best,
        }
    }

    /// The step (0 the lowest) whose run holds the point `s` along the direction: `None`
    /// before the first front edge or past the top step's run.
    pub(crate) fn step_of(&self, s: f64) -> Option<usize> {
        let k = ((s - self.front1) / self.run).floor();
        (k >= 0.0 && k < f64::from(self.steps)).then_some(k as usize)
    }
}

/// A step count to fit, the top height it climbs to and the envelope it is fitted to.
type Count<'a> = (f64, f64, &'a [(f64, f64)]);

#[cfg(test)]
#[path = "profile_tests.rs"]
mod tests;
