//! A cluster's profile along a direction (the highest return per bin: the upper envelope of a
//! ramp's top, or of its side face's top edge where the top itself was not seen) and the
//! straight line fitted to it, robustly (what stands on the ramp is left out).

use crate::points::quantile;
use glam::DVec2;

/// The highest height per `bin_m` bin of `points` (XY, z) along `dir` from `u0` (the least
/// `u`): `u0` and the bins (`None` where no point fell).
pub(crate) fn upper_profile(
    points: &[(DVec2, f64)],
    dir: DVec2,
    bin_m: f64,
) -> (f64, Vec<Option<f64>>) {
    let u0 = points
        .iter()
        .map(|(q, _)| q.dot(dir))
        .fold(f64::INFINITY, f64::min);
    let u1 = points
        .iter()
        .map(|(q, _)| q.dot(dir))
        .fold(f64::NEG_INFINITY, f64::max);
    if !u0.is_finite() || !u1.is_finite() {
        return (0.0, Vec::new());
    }
    let n = ((u1 - u0) / bin_m).floor() as usize + 1;
    let mut bins: Vec<Option<f64>> = vec![None; n];
    for &(q, z) in points {
        let k = (((q.dot(dir) - u0) / bin_m).floor() as usize).min(n - 1);
        bins[k] = Some(bins[k].map_or(z, |b: f64| b.max(z)));
    }
    (u0, bins)
}

/// A line `z = at_start + slope · u` (u from the profile's start, bin centres) fitted to a
/// profile's bins.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LineFit {
    pub at_start: f64,
    pub slope: f64,
    /// Bins within the inlier distance of the line, and bins holding a height from the first
    /// to the last of those (what lies beyond a ramp's ends is not on it, and does not count).
    pub inliers: usize,
    pub filled: usize,
    /// The first and last inlier bins.
    pub first: usize,
    pub last: usize,
    /// RMS distance of the inliers from the line.
    pub rms_m: f64,
}

/// The line through the bins: a Theil-Sen line (the median of the slopes between pairs of
/// bins, a sixth of the profile or more apart), refitted twice by least squares to the bins
/// within `inlier_m` of the previous line; `None` with fewer than 3 bins (or inliers) to fit.
/// What stands on a stretch of a ramp lifts those bins, and a least-squares start would tilt
/// towards them and leave the rest of the ramp off the line.
pub(crate) fn fit_line(bins: &[Option<f64>], bin_m: f64, inlier_m: f64) -> Option<LineFit> {
    let pts: Vec<(f64, f64)> = bins
        .iter()
        .enumerate()
        .filter_map(|(k, z)| z.map(|z| ((k as f64 + 0.5) * bin_m, z)))
        .collect();
    let mut line = theil_sen(&pts)?;
    for _ in 0..2 {
        let kept: Vec<(f64, f64)> = pts
            .iter()
            .copied()
            .filter(|&(u, z)| (z - line.0 - line.1 * u).abs() <= inlier_m)
            .collect();
        line = least_squares(&kept)?;
    }
    let on_line = |&(u, z): &(f64, f64)| (z - line.0 - line.1 * u).abs() <= inlier_m;
    let inliers: Vec<f64> = pts
        .iter()
        .filter(|p| on_line(p))
        .map(|&(u, z)| z - line.0 - line.1 * u)
        .collect();
    let bin_of = |p: &(f64, f64)| (p.0 / bin_m) as usize;
    let first = pts.iter().find(|p| on_line(p)).map_or(0, bin_of);
    let last = pts.iter().rev().find(|p| on_line(p)).map_or(0, bin_of);
    let filled = pts
        .iter()
        .filter(|p| (first..=last).contains(&bin_of(p)))
        .count();
    let rms_m = (inliers.iter().map(|r| r * r).sum::<f64>() / inliers.len().max(1) as f64).sqrt();
    Some(LineFit {
        at_start: line.0,
        slope: line.1,
        inliers: inliers.len(),
        filled,
        first,
        last,
        rms_m,
    })
}

/// Intercept and slope of the Theil-Sen line through `(u, z)`: the median slope of the pairs
/// at least a sixth of the points' span apart in `u` (close pairs' slopes are noise), the
/// median intercept for it; `None` with fewer than 3 points or no such pair.
fn theil_sen(pts: &[(f64, f64)]) -> Option<(f64, f64)> {
    if pts.len() < 3 {
        return None;
    }
    let span = pts.last()?.0 - pts.first()?.0;
    let mut slopes = Vec::new();
    for (i, a) in pts.iter().enumerate() {
        for b in &pts[i + 1..] {
            if b.0 - a.0 >= span / 6.0 && b.0 > a.0 {
                slopes.push((b.1 - a.1) / (b.0 - a.0));
            }
        }
    }
    let slope = quantile(&mut slopes, 0.5)?;
    let mut at: Vec<f64> = pts.iter().map(|p| p.1 - slope * p.0).collect();
    Some((quantile(&mut at, 0.5)?, slope))
}

/// Intercept and slope of the least-squares line through `(u, z)`; `None` with fewer than 3
/// points or all at one `u`.
fn least_squares(pts: &[(f64, f64)]) -> Option<(f64, f64)> {
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let (mu, mz) = pts
        .iter()
        .fold((0.0, 0.0), |s, p| (s.0 + p.0 / n, s.1 + p.1 / n));
    let (suu, suz) = pts.iter().fold((0.0, 0.0), |s, p| {
        (s.0 + (p.0 - mu).powi(2), s.1 + (p.0 - mu) * (p.1 - mz))
    });
    (suu > 1e-12).then(|| {
        let slope = suz / suu;
        (mz - slope * mu, slope)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slope_with_a_box_on_it_is_fitted_without_the_box() {
        // A 10 % slope over 4 m, a 0.5 m box standing on it at 2.0-2.4 m.
        let pts: Vec<(DVec2, f64)> = (0..400)
            .map(|k| {
                let u = k as f64 * 0.01;
                let z = 0.1 * u + if (2.0..2.4).contains(&u) { 0.5 } else { 0.0 };
                (DVec2::new(u, 0.3), z)
            })
            .collect();
        let (u0, bins) = upper_profile(&pts, DVec2::X, 0.1);
        assert_eq!((u0, bins.len()), (0.0, 40));
        let fit = fit_line(&bins, 0.1, 0.04).expect("a line");
        assert!((fit.slope - 0.1).abs() < 1e-3, "{fit:?}");
        assert_eq!((fit.inliers, fit.filled), (36, 40));
        assert_eq!((fit.first, fit.last), (0, 39));
        // Steps of 0.17 m every 0.28 m: no line holds most of them.
        let steps: Vec<(DVec2, f64)> = (0..400)
            .map(|k| {
                let u = k as f64 * 0.01;
                (DVec2::new(u, 0.0), 0.17 * (u / 0.28).floor())
            })
            .collect();
        let (_, bins) = upper_profile(&steps, DVec2::X, 0.1);
        let fit = fit_line(&bins, 0.1, 0.04).expect("a line");
        assert!(fit.inliers * 10 < fit.filled * 7, "{fit:?}");
    }

    /// Regression (garage-232 of the styles bench, seeds 231-235): the upper profile along
    /// the ramp (1.12 m over 8.13 m), 10 cm bins, as the map gave it. Things beside and on its
    /// upper part lift bins 49-54 by 0.2 m and the last 13 by 0.1-0.15 m. The least-squares
    /// start tilted to 0.150 per metre, the lowest bins fell off it and 49 of 72 bins on the
    /// line were short of the 70 % a ramp needs; the Theil-Sen start finds the ramp's 0.137.
    #[test]
    fn what_stands_on_a_ramps_upper_part_does_not_tilt_its_line() {
        let bins = [
            Some(0.311),
            None,
            Some(0.331),
            None,
            Some(0.363),
            Some(0.382),
            Some(0.378),
            Some(0.393),
            Some(0.417),
            Some(0.426),
            Some(0.437),
            Some(0.468),
            Some(0.474),
            Some(0.484),
            Some(0.492),
            Some(0.497),
            Some(0.525),
            Some(0.528),
            Some(0.537),
            Some(0.578),
            Some(0.554),
            Some(0.594),
            Some(0.621),
            Some(0.623),
            Some(0.624),
            Some(0.637),
            Some(0.649),
            Some(0.685),
            Some(0.68),
            Some(0.698),
            Some(0.72),
            Some(0.72),
            Some(0.72),
            Some(0.739),
            Some(0.776),
            Some(0.781),
            Some(0.79),
            Some(0.821),
            Some(0.833),
            Some(0.835),
            Some(0.871),
            Some(0.835),
            Some(0.89),
            Some(0.889),
            Some(0.919),
            Some(0.932),
            Some(0.935),
            Some(0.939),
            Some(0.948),
            Some(1.171),
            Some(1.207),
            Some(1.207),
            Some(1.212),
            Some(1.195),
            Some(1.188),
            Some(1.03),
            Some(1.09),
            Some(1.09),
            Some(1.096),
            Some(1.098),
            Some(1.127),
            Some(1.151),
            Some(1.266),
            Some(1.301),
            Some(1.301),
            Some(1.306),
            Some(1.296),
            Some(1.302),
            Some(1.29),
            Some(1.409),
            Some(1.4),
            Some(1.393),
            Some(1.4),
            Some(1.412),
            Some(1.321),
        ];
        let fit = fit_line(&bins, 0.1, 0.04).expect("a line");
        assert!((fit.slope - 0.137).abs() < 2e-3, "{fit:?}");
        assert_eq!(fit.first, 0, "{fit:?}");
        assert!(fit.inliers * 10 >= fit.filled * 7, "{fit:?}");
    }
}
