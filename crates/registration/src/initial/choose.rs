//! The choice among scored poses of one scan: the best score, unless others cannot be told
//! apart from it, and then the nearest to the guess.

use super::verify;
use glam::{DAffine3, DVec3};

/// The winner of `verified` (and its index): the best score; among the scores that are
/// statistically indistinguishable from it, the pose whose sensor is nearest to the guess's.
///
/// A score is a mean over the `n` source points of values of about unit spread, so two
/// scores closer than two standard errors (`2 / sqrt(n)`) do not tell their poses apart: the
/// identical rooms of an office floor, two ends of a symmetric corridor. Then the sequence's
/// own evidence decides: scans are taken one after another, so the nearer pose is the likelier.
pub(crate) fn choose(
    verified: &[verify::Verified],
    guess: &DAffine3,
    sensor: DVec3,
    n: usize,
) -> Option<(usize, verify::Verified)> {
    let best = verified
        .iter()
        .map(|v| v.score)
        .fold(f64::NEG_INFINITY, f64::max);
    let margin = 2.0 / (n.max(1) as f64).sqrt();
    let from_guess = |v: &verify::Verified| {
        (v.world_from_scan.transform_point3(sensor) - guess.transform_point3(sensor)).length()
    };
    verified
        .iter()
        .enumerate()
        .filter(|(_, v)| v.score.is_finite() && v.score >= best - margin)
        .min_by(|a, b| {
            from_guess(a.1)
                .total_cmp(&from_guess(b.1))
                .then(a.0.cmp(&b.0))
        })
        .map(|(i, v)| (i, *v))
}
