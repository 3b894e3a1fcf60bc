//! The top level's plateau of a staircase profile: the height a flight's envelope rests at
//! under a few returns over it (mixed pixels at a landing's far edge, a voxel's centroid),
//! and the envelope up to a count's top level (see `profile`).

/// Returns up to this far above the grid's top level still lie on it (the levels' tolerance).
pub(super) const ABOVE_TOP_M: f64 = 0.035;

/// The most frequent height (1 cm bins) of the envelope's bins within half a rise under the top
/// height: the top level's plateau, where a few returns above it (mixed pixels at its far
/// edge) set the top height a few centimetres high.
pub(super) fn plateau_mode(env: &[(f64, f64)], top_height: f64, rise: f64) -> f64 {
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
pub(super) fn up_to(env: &[(f64, f64)], top: f64) -> Vec<(f64, f64)> {
    env.iter()
        .copied()
        .filter(|e| e.1 <= top + ABOVE_TOP_M)
        .collect()
}

/// The height of the envelope's last `along_m`: the most frequent (see [`plateau_mode`])
/// within half a `rise` under the stretch's highest bin; `None` for an empty envelope.
pub(super) fn end_plateau(env: &[(f64, f64)], along_m: f64, rise: f64) -> Option<f64> {
    let last = env.last()?.0;
    let from = env.partition_point(|e| e.0 < last - along_m);
    let stretch = &env[from..];
    let highest = stretch
        .iter()
        .map(|e| e.1)
        .fold(f64::NEG_INFINITY, f64::max);
    Some(plateau_mode(stretch, highest, rise))
}

/// How far along the envelope's bins over `level` spread, first to last (0 for none).
pub(super) fn span_over(env: &[(f64, f64)], level: f64) -> f64 {
    let mut over = env.iter().filter(|e| e.1 > level).map(|e| e.0);
    match over.next() {
        Some(first) => over.next_back().map_or(0.0, |last| last - first),
        None => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Garage-1's 9-step flight (rise 0.158 m, seen only on its side face from beside its landing)
    /// was not found: returns 4-7 cm over the landing's far edge set the top height, every count's
    /// rise came out 3 % high, and no fit found its bins on 60 % of the levels (the fallback to
    /// the plateau's top is measured on `bench/styles.sh`: garage stairs 9 -> 10 of 10). The top
    /// level's plateau is the landing's height, not the returns over its edge.
    #[test]
    fn the_top_plateau_is_the_landing_not_the_returns_over_its_edge() {
        // The landing (1.422 m) in 60 bins, sampled 1-3 cm under it; 8 bins 4-7 cm over it.
        let mut env: Vec<(f64, f64)> = (0..60)
            .map(|i| (0.01 * i as f64, 1.422 - 0.01 * (i % 3) as f64))
            .collect();
        env.extend((0..8).map(|i| (0.6 + 0.01 * i as f64, 1.462 + 0.004 * i as f64)));
        // (the second highest bin, as `profile` takes the top height)
        let top = plateau_mode(&env, 1.486, 0.158);
        assert!((top - 1.415).abs() <= 0.01, "top {top}");
    }

    #[test]
    fn the_span_over_a_level_runs_from_the_first_bin_over_it_to_the_last() {
        let env = [(0.0, 0.5), (0.1, 0.7), (0.2, 0.5), (0.35, 0.66), (0.5, 0.5)];
        assert!((span_over(&env, 0.6) - 0.25).abs() < 1e-12);
        assert_eq!(span_over(&env, 0.68), 0.0);
        assert_eq!(span_over(&env, 0.8), 0.0);
    }
}
