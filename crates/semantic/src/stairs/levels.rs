//! The grid of levels of a staircase profile: the heights its running maximum stays at (the
//! steps' tops) pile up at whole multiples of one rise (see the `stairs` module).

use super::StairsConfig;
use crate::points::linear_fit;

/// A height within this share of the rise of a multiple of it lies on that level (the grid's
/// tolerance; also where one flight's level is another's landing, see `search`).
pub(super) const ON_A_LEVEL: f64 = 0.25;

/// The rise and offset of a set of heights that pile up at whole multiples of one rise, and
/// the highest multiple with a peak on it: the peaks of their histogram (1 cm bins, 3 cm
/// window) fitted to the grid `offset + k rise`.
pub(super) fn level_grid(heights: &[f64], c: &StairsConfig) -> Option<(f64, f64, f64)> {
    let bin = 0.01;
    let n = ((c.max_height_m / bin).ceil() as usize + 2).min(100_000);
    let mut hist = vec![0usize; n];
    for &hgt in heights {
        if hgt >= 0.0 {
            hist[((hgt / bin) as usize).min(n - 1)] += 1;
        }
    }
    let smooth: Vec<usize> = (0..n)
        .map(|i| hist[i.saturating_sub(1)..(i + 2).min(n)].iter().sum())
        .collect();
    let peaks: Vec<f64> = (0..n)
        .filter(|&i| {
            smooth[i] >= 3
                && (i == 0 || smooth[i] > smooth[i - 1])
                && (i + 1 == n || smooth[i] >= smooth[i + 1])
        })
        .map(|i| (i as f64 + 0.5) * bin)
        .collect();
    if peaks.len() < c.min_steps as usize {
        return None;
    }
    // The rise between neighbouring peaks, or between peaks one apart (`true`): a level's
    // running maximum climbing its riser's top edge, or mixed pixels there, can pile up
    // between two levels.
    let mut candidates: Vec<(f64, bool)> = peaks.windows(2).map(|p| (p[1] - p[0], false)).collect();
    candidates.extend(peaks.windows(3).map(|p| (p[2] - p[0], true)));
    candidates.push((peaks[0] + 0.01, false));
    candidates.retain(|r| r.0 >= c.rise_m[0] && r.0 <= c.rise_m[1]);
    let mut best: Option<(f64, f64, f64, f64)> = None; // score, rise, offset, top level
    for (r0, skipping) in candidates {
        let (mut rise, mut offset) = (r0, 0.0);
        let mut ks: Vec<f64> = Vec::new();
        let mut on_grid = 0;
        for _ in 0..3 {
            let fit: Vec<(f64, f64)> = peaks
                .iter()
                .filter_map(|&p| {
                    let k = ((p - offset) / rise).round();
                    (k >= 1.0 && (p - offset - k * rise).abs() <= ON_A_LEVEL * rise)
                        .then_some((k, p))
                })
                .collect();
            on_grid = fit.len();
            ks = fit.iter().map(|f| f.0).collect();
            ks.dedup();
            if let Some((a, b)) = linear_fit(&fit) {
                if b >= c.rise_m[0] && b <= c.rise_m[1] && a.abs() <= 0.3 * b {
                    rise = b;
                    offset = a;
                }
            }
        }
        let top = ks.last().copied().unwrap_or(0.0);
        let score = ks.len() as f64 - 0.5 * (top - ks.len() as f64);
        // (a rise skipping a peak must leave few peaks off its grid, a stray between two
        // levels: a ramp's side face, its top edge creeping up, piles up at heights all the
        // way, and some of them are a rise apart)
        let strays_few = !skipping || 2 * (peaks.len() - on_grid) <= on_grid;
        let enough = ks.len() >= c.min_steps as usize && starts_low(&ks) && strays_few;
        if enough && best.is_none_or(|b| score > b.0) {
            best = Some((score, rise, offset, top));
        }
    }
    best.map(|b| (b.1, b.2, b.3))
}

/// Levels seen at these many consecutive multiples of the rise or more are a flight's even
/// where its lowest level is missing (see [`starts_low`]).
const LONG_RUN_OF_LEVELS: usize = 5;

/// True if the levels `ks` (whole multiples of the rise, in order) start low enough to be a
/// flight's: at the first or second step, or at the third where they go on step by step for
/// [`LONG_RUN_OF_LEVELS`] at least. Clutter of assorted heights (desks, shelves, boxes on
/// boxes) shows a level or two at some multiple; a long flight seen along its side from its top
/// end shows its lowest steps' faces as the farthest, lowest strips, at grazing angles, and
/// the first two can both be missing.
fn starts_low(ks: &[f64]) -> bool {
    let Some(&first) = ks.first() else {
        return false;
    };
    let consecutive = ks.windows(2).all(|w| w[1] - w[0] == 1.0);
    first <= 2.0 || (first <= 3.0 && consecutive && ks.len() >= LONG_RUN_OF_LEVELS)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The running maxima of a profile whose plateaus stand at `levels` (multiples of a
    /// 0.17 m rise), 20 bins each.
    fn plateaus(levels: &[u32]) -> Vec<f64> {
        levels
            .iter()
            .flat_map(|&k| std::iter::repeat_n(0.17 * f64::from(k), 20))
            .collect()
    }

    /// Regression (office-244 of seeds 241-245): a 3-step flight of 0.152 m seen from its side
    /// only. Its side face's top edge, read 2-4 cm low, gave peaks at 0.155, 0.295 and 0.435 m,
    /// and the running maximum rising over the third riser's edge (0.363 and 0.374 m) one more
    /// between the top two: no two neighbouring peaks were a rise apart, and the flight had no
    /// grid of levels. (These are its running maxima, as (height, bins).)
    #[test]
    fn a_peak_between_two_levels_does_not_hide_their_rise() {
        let runs = [
            (0.131, 1),
            (0.151, 3),
            (0.169, 3),
            (0.21, 2),
            (0.28, 6),
            (0.302, 9),
            (0.363, 5),
            (0.374, 3),
            (0.423, 3),
            (0.437, 7),
            (0.447, 68),
        ];
        let maxima: Vec<f64> = runs
            .iter()
            .flat_map(|&(h, n)| std::iter::repeat_n(h, n))
            .collect();
        let (rise, _, top) =
            level_grid(&maxima, &StairsConfig::default()).expect("a grid of levels");
        assert_eq!(top, 3.0);
        assert!((rise - 0.145).abs() < 0.01, "rise {rise}");
    }

    #[test]
    fn a_long_run_of_levels_may_start_at_the_third_step_clutter_may_not() {
        let c = StairsConfig::default();
        // A long flight whose two lowest steps were unseen: levels 3-8, step by step.
        let (rise, _, top) = level_grid(&plateaus(&[3, 4, 5, 6, 7, 8]), &c).expect("a flight");
        assert!((rise - 0.17).abs() < 0.005, "rise {rise}");
        assert_eq!(top, 8.0);
        // From the first step, three levels are enough.
        assert!(level_grid(&plateaus(&[1, 2, 3]), &c).is_some());
        // From the third: three levels, or five with a gap, are clutter's.
        assert!(level_grid(&plateaus(&[3, 4, 5]), &c).is_none());
        assert!(level_grid(&plateaus(&[3, 4, 6, 7, 8]), &c).is_none());
        // From the fourth, however long.
        assert!(level_grid(&plateaus(&[4, 5, 6, 7, 8, 9]), &c).is_none());
    }
}
