//! The grid of levels of a staircase profile: the heights its running maximum stays at (the
//! steps' tops) pile up at whole multiples of one rise (see the `stairs` module).

use super::StairsConfig;
use crate::points::linear_fit;

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
    let mut candidates: Vec<f64> = peaks.windows(2).map(|p| p[1] - p[0]).collect();
    candidates.push(peaks[0] + 0.01);
    candidates.retain(|r| *r >= c.rise_m[0] && *r <= c.rise_m[1]);
    let mut best: Option<(f64, f64, f64, f64)> = None; // score, rise, offset, top level
    for r0 in candidates {
        let (mut rise, mut offset) = (r0, 0.0);
        let mut ks: Vec<f64> = Vec::new();
        for _ in 0..3 {
            let fit: Vec<(f64, f64)> = peaks
                .iter()
                .filter_map(|&p| {
                    let k = ((p - offset) / rise).round();
                    (k >= 1.0 && (p - offset - k * rise).abs() <= 0.25 * rise).then_some((k, p))
                })
                .collect();
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
        let enough = ks.len() >= c.min_steps as usize && ks.first().is_some_and(|&k| k <= 2.0);
        if enough && best.is_none_or(|b| score > b.0) {
            best = Some((score, rise, offset, top));
        }
    }
    best.map(|b| (b.1, b.2, b.3))
}
