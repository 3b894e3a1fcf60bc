//! A mid landing in a staircase's profile (see `flights`): a level stretch longer than any
//! tread, a flight's worth of steps up, with a climb beyond it.

use super::envelope::{envelope, of_flight, BIN_M};
use super::StairsConfig;
use glam::DVec2;

/// The shortest level stretch that is a landing and no tread: longer than the longest run by
/// the 0.2 m a tread's nosing and a laser's sampling can add.
fn min_landing_m(c: &StairsConfig) -> f64 {
    c.run_m[1] + 0.2
}

/// The most a level stretch's top edge may read higher over part of it, as a share of the lowest
/// rise, and be one level still: the map's 5 cm voxels put a side face's top edge in one of two
/// layers of centroids (office-82 of seeds 81-85: a landing's read at 0.475 m over its first
/// 0.45 m, where the scans' rays hit its face's top 5 cm too sparsely to continue a surface, and
/// at 0.526 m over the rest). Under the lowest rise, so no riser is read as such a jump.
const ONE_LAYER: f64 = 0.6;

/// A mid landing in a staircase's profile (see [`mid_landing`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct Landing {
    /// Its near edge along the direction of ascent (m).
    pub near: f64,
    /// Its far edge along the direction of ascent (m).
    pub far: f64,
    /// Its height over the profile's zero (m).
    pub height: f64,
    /// Read in two layers (see [`ONE_LAYER`]): its near part's top edge a voxel layer under
    /// its far part's.
    pub layered: bool,
}

/// The mid landing in the profile of `pts` along `dir` (its envelope, see `envelope`): a
/// level stretch at least a flight's worth of the lowest rise up, with something climbing
/// beyond it (the next flight, or what stands beyond a flight's top landing: `two_flights`
/// keeps the lower flight alone then).
pub(super) fn mid_landing(pts: &[(DVec2, f64)], dir: DVec2, c: &StairsConfig) -> Option<Landing> {
    let along: Vec<f64> = pts.iter().map(|(q, _)| q.dot(dir)).collect();
    let lo = along.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = along.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let nb = (((hi - lo) / BIN_M).ceil() as usize + 1).min(100_000);
    let env = envelope(pts, dir, lo, nb, c.run_m[0] / 2.0);
    let env = of_flight(&env, c);
    let least = c.min_steps as f64 * c.rise_m[0];
    // The running maximum; a level stretch starts where it last rose by more than the
    // measurement's few centimetres, and holds within half the lowest rise of the height it
    // started at (a ramp's side face, sampled sparsely, creeps up by a centimetre or two per
    // return and never jumps: garage-28 of the fresh seeds read a 9 degree ramp's as a
    // flight's landing, with more of the ramp climbing beyond it). It ends in a climb: within
    // a tread's depth the profile stands half the lowest rise above it (the first return of
    // the rise may be a mixed pixel between the landing and the next tread, only a few
    // centimetres up).
    let creep = 0.5 * c.rise_m[0];
    let mut running = f64::NEG_INFINITY;
    let mut since = lo;
    let mut since_height = f64::NEG_INFINITY;
    // The stretch before this one, and how far the profile rose from it to this one.
    let (mut before, mut rose) = (lo, f64::INFINITY);
    for (k, &(s, z)) in env.iter().enumerate() {
        if running.is_finite() && falls_back(&env[k..], running + creep, min_landing_m(c)) {
            // (something standing on the level, shorter than a landing: no climb)
            continue;
        }
        if z > running + 0.03 || z > since_height + creep {
            let level = running;
            // (the profile stands `by` over the level within `within_m`)
            let climbs_by = |by: f64, within_m: f64| {
                env[k..]
                    .iter()
                    .take_while(|e| e.0 <= s + within_m)
                    .any(|e| e.1 - level >= by)
            };
            let is_landing = running.is_finite()
                && s - since >= min_landing_m(c)
                && level >= least
                && climbs_by(0.5 * c.rise_m[0], c.run_m[1]);
            let landing_from = |near: f64, layered: bool| Landing {
                near: near - BIN_M / 2.0,
                far: s - BIN_M / 2.0,
                height: level,
                layered,
            };
            if is_landing {
                return Some(landing_from(since, false));
            }
            // A landing whose top edge read one voxel layer higher over its far part (see
            // `ONE_LAYER`): the two stretches are one, where a whole riser climbs beyond them,
            // within the shortest tread. (A ramp's side face, read in layers too, climbs a layer
            // at a time: two layers, as long as a landing, and two more up take more than that.)
            let layered = running.is_finite()
                && rose <= ONE_LAYER * c.rise_m[0]
                && s - before >= min_landing_m(c)
                && level >= least
                && climbs_by(c.rise_m[0], c.run_m[0]);
            if layered {
                return Some(landing_from(before, true));
            }
            (before, rose) = (since, z - running);
            since = s;
            since_height = running.max(z);
        }
        running = running.max(z);
    }
    None
}

/// True if the profile `env` falls back to `level` from its first bin within `reach_m`: most
/// of it there, and its last bin there, lie at or below `level`, and the profile goes on
/// beyond. What rose there is something standing on a level stretch (mixed pixels along a ray
/// over a landing, a thing left on it), not a riser, beyond which every tread stands higher;
/// nor what stands at the far end of the profile (the wall or the cupboard beyond a flight's
/// top landing, the mixed pixels at its edge).
fn falls_back(env: &[(f64, f64)], level: f64, reach_m: f64) -> bool {
    let Some(&(s0, z0)) = env.first() else {
        return false;
    };
    if z0 <= level {
        return false;
    }
    let within = env.iter().take_while(|e| e.0 <= s0 + reach_m);
    let (mut at_level, mut n, mut last) = (0usize, 0usize, z0);
    for &(_, z) in within {
        n += 1;
        at_level += usize::from(z <= level);
        last = z;
    }
    n < env.len() && 2 * at_level >= n && last <= level
}
#[cfg(test)]
mod tests {
    use super::*;

    /// The top edge of a side face along +X, every 1 cm: `(x0, x1, height at x0, height at x1)`
    /// stretches.
    fn profile_of(stretches: &[(f64, f64, f64, f64)]) -> Vec<(DVec2, f64)> {
        let mut pts = Vec::new();
        for &(x0, x1, z0, z1) in stretches {
            let n = ((x1 - x0) / 0.01).round() as usize;
            for i in 0..n {
                let t = i as f64 / n as f64;
                pts.push((DVec2::new(x0 + 0.01 * i as f64, 0.0), z0 + t * (z1 - z0)));
            }
        }
        pts
    }

    #[test]
    fn something_on_a_mid_landing_shorter_than_a_landing_leaves_it_a_landing() {
        let c = StairsConfig::default();
        let climb = |from: f64, base: f64| -> Vec<(f64, f64, f64, f64)> {
            (0..3)
                .map(|k| {
                    let (x, z) = (from + 0.25 * f64::from(k), base + 0.17 * f64::from(k + 1));
                    (x, x + 0.25, z, z)
                })
                .collect()
        };
        // 3 steps, a 1.5 m landing 0.51 m up, 3 steps; on the landing, mixed pixels 0.15 m over
        // it for 8 cm, then along a ray climbing from 0.1 to 0.35 m over it for 0.22 m
        // (as over hall-49's landing: `stairs::tests`).
        let mut stretches = climb(0.0, 0.0);
        stretches.extend([
            (0.75, 1.0, 0.51, 0.51),
            (1.0, 1.08, 0.66, 0.66),
            (1.08, 1.3, 0.61, 0.86),
            (1.3, 2.25, 0.51, 0.51),
        ]);
        stretches.extend(climb(2.25, 0.51));
        let found = mid_landing(&profile_of(&stretches), DVec2::X, &c).expect("a landing");
        assert!((found.near - 0.5).abs() < 0.03, "near edge {}", found.near);
        assert!((found.far - 2.25).abs() < 0.03, "far edge {}", found.far);
        assert!(
            (found.height - 0.51).abs() < 0.01,
            "height {}",
            found.height
        );
        // What stays up for longer than a landing is the level: 0.5 m at 0.51 m, then 1.25 m
        // at 0.81 m before the climb.
        let mut stretches = climb(0.0, 0.0);
        stretches.extend([(0.75, 1.0, 0.51, 0.51), (1.0, 2.25, 0.81, 0.81)]);
        stretches.extend(climb(2.25, 0.81));
        let found = mid_landing(&profile_of(&stretches), DVec2::X, &c).expect("a landing");
        assert!((found.near - 1.0).abs() < 0.03, "near edge {}", found.near);
        assert!(
            (found.height - 0.81).abs() < 0.01,
            "height {}",
            found.height
        );
    }

    /// A landing whose top edge reads one voxel layer lower over its near part is one landing
    /// where a whole riser climbs beyond it; a ramp's side face read in such layers climbs a
    /// layer at a time and has none (a layer every 0.35 m, 8 degrees, to every 0.6 m, 5).
    #[test]
    fn a_landing_read_in_two_layers_is_one_but_a_ramp_in_layers_is_none() {
        let c = StairsConfig::default();
        let flat = |x0: f64, x1: f64, z: f64| (x0, x1, z, z);
        let mut stretches = vec![
            flat(0.0, 0.25, 0.18),
            flat(0.25, 0.5, 0.36),
            flat(0.5, 0.95, 0.475),
            flat(0.95, 1.45, 0.526),
        ];
        stretches.extend((0..3).map(|k| {
            let x = 1.45 + 0.25 * f64::from(k);
            flat(x, x + 0.25, 0.526 + 0.18 * f64::from(k + 1))
        }));
        let found = mid_landing(&profile_of(&stretches), DVec2::X, &c).expect("a landing");
        assert!(found.layered);
        assert!((found.near - 0.5).abs() < 0.03, "near edge {}", found.near);
        assert!((found.far - 1.45).abs() < 0.03, "far edge {}", found.far);
        assert!(
            (found.height - 0.526).abs() < 0.01,
            "height {}",
            found.height
        );
        // Without the riser beyond it (half a rise up only), no landing.
        stretches.truncate(4);
        stretches.push(flat(1.45, 1.9, 0.58));
        assert!(mid_landing(&profile_of(&stretches), DVec2::X, &c).is_none());
        for layer_m in [0.35, 0.4, 0.45, 0.5, 0.6] {
            let ramp: Vec<_> = (0..12)
                .map(|k| {
                    let x = layer_m * f64::from(k);
                    flat(x, x + layer_m, 0.05 * f64::from(k + 1))
                })
                .collect();
            let found = mid_landing(&profile_of(&ramp), DVec2::X, &c);
            assert!(found.is_none(), "{layer_m}: {found:?}");
        }
    }

    /// Regression: fresh garage-48's 5-step flight, seen from its side only, has mixed pixels
    /// up to 0.15 m over the far end of its top landing, where its profile ends. They end the
    /// landing (the flight is fitted on the points before them), not something standing on it
    /// that the profile falls back from: taken for that, they left no landing, and the whole
    /// part read as 6 steps of 0.149 m. (The returns over the flight and its landing, from the
    /// bench's map.)
    #[test]
    fn returns_at_the_far_end_of_a_top_landing_end_it() {
        let part = crate::stairs::tests::returns(include_str!(
            "../../tests/data/garage48_top_landing.txt"
        ));
        assert_eq!(part.len(), 965);
        let found = mid_landing(&part, DVec2::X, &StairsConfig::default());
        let found = found.expect("a landing");
        // (5 rises of 0.156 m up; the returns from 2.28 m along)
        assert!(
            (found.height - 0.78).abs() < 0.03,
            "height {}",
            found.height
        );
        assert!((found.far - 2.28).abs() < 0.1, "far edge {}", found.far);
        assert!(!found.layered);
    }
}
