//! Staircases with a landing half-way: two straight flights in line, the second starting on
//! the first's landing. Along the direction of ascent the profile climbs, stays level for
//! longer than any tread (building codes cap a tread at 0.45 m or so, `run_m`; a landing is at
//! least as deep as the stair is wide) and climbs again. Each flight is found on its own: the
//! lower one on the points before the landing's far edge (the landing is its top level), the
//! upper one on the points from just before that edge on, with heights measured from the
//! landing (its foot stands there). A staircase is thus reported as its flights, each with its
//! own step count, as a building file describes it (`[[stairs]]` with `base_m`).

use super::profile::{finish, profile};
use super::{DetectedStairs, StairsConfig};
use crate::scene::Scene;
use glam::DVec2;

/// The shortest level stretch that is a landing and no tread: longer than the longest run by
/// the 0.2 m a tread's nosing and a laser's sampling can add.
fn min_landing_m(c: &StairsConfig) -> f64 {
    c.run_m[1] + 0.2
}

/// The two flights of a staircase with a mid landing climbing along `dir`, if the points show
/// one (see the module docs); `None` if they show no mid landing or a flight is implausible.
pub(super) fn two_flights(
    pts: &[(DVec2, f64)],
    all: &[(DVec2, f64)],
    dir: DVec2,
    sc: &Scene,
    c: &StairsConfig,
) -> Option<[DetectedStairs; 2]> {
    // 1. The landing: the running maximum of the profile level for more than a tread, with
    //    at least `min_steps` of the lowest rise below it and above it.
    let (landing_end, landing_height) = mid_landing(pts, dir, c)?;
    // 2. The lower flight: the points before the landing's far edge.
    let below = |p: &[(DVec2, f64)]| -> Vec<(DVec2, f64)> {
        p.iter()
            .filter(|(q, _)| q.dot(dir) < landing_end)
            .copied()
            .collect()
    };
    let (lower, lower_all) = (below(pts), below(all));
    let first = finish(&lower, profile(&lower, &lower_all, dir, c)?, sc, c)?;
    let base = first.rise * first.steps as f64;
    if (base - landing_height).abs() > 0.5 * first.rise {
        return None;
    }
    // 3. The upper flight: from a tread's depth before that edge on, heights from the landing.
    let above = |p: &[(DVec2, f64)]| -> Vec<(DVec2, f64)> {
        p.iter()
            .filter(|(q, z)| q.dot(dir) >= landing_end - c.run_m[1] && *z >= base - 0.05)
            .map(|(q, z)| (*q, z - base))
            .collect()
    };
    let (upper, upper_all) = (above(pts), above(all));
    let mut second = finish(&upper, profile(&upper, &upper_all, dir, c)?, sc, c)?;
    second.base = base;
    second.rules.push(format!(
        "starts on the landing of the flight below, {base:.2} m above the floor"
    ));
    Some([first, second])
}

/// The far edge (along `dir`) and height of a mid landing in the profile of `pts`.
fn mid_landing(pts: &[(DVec2, f64)], dir: DVec2, c: &StairsConfig) -> Option<(f64, f64)> {
    let bin = 0.01;
    let along: Vec<f64> = pts.iter().map(|(q, _)| q.dot(dir)).collect();
    let lo = along.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = along.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let nb = (((hi - lo) / bin).ceil() as usize + 1).min(100_000);
    let mut highest = vec![f64::NEG_INFINITY; nb];
    for (s, (_, z)) in along.iter().zip(pts) {
        let k = (((s - lo) / bin) as usize).min(nb - 1);
        highest[k] = highest[k].max(*z);
    }
    let top = highest.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let least = c.min_steps as f64 * c.rise_m[0];
    // The running maximum; a level stretch starts where it last rose by more than the
    // measurement's few centimetres.
    let mut running = f64::NEG_INFINITY;
    let mut since = 0usize;
    for (k, &z) in highest.iter().enumerate() {
        if !z.is_finite() {
            continue;
        }
        if z > running + 0.03 {
            let level = running;
            let length = (k - since) as f64 * bin;
            let is_landing = running.is_finite()
                && length >= min_landing_m(c)
                && level >= least
                && top - level >= least
                && z - level >= 0.5 * c.rise_m[0];
            if is_landing {
                return Some((lo + k as f64 * bin, level));
            }
            since = k;
        }
        running = running.max(z);
    }
    None
}
