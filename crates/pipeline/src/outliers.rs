//! Statistical outlier removal for one scan, in the scan's own frame: the isolated returns a
//! real sensor writes in mid-air (dust, a mixed pixel floating between two surfaces, a
//! reflection) are points far from every other point, *for their range*.
//!
//! Each point's score is the mean distance to its `k` nearest neighbours (an exact k-d tree,
//! rayon over points). PCL's StatisticalOutlierRemoval thresholds that score at the scan's
//! mean + n sigma; but a rotating laser's samples are an angular step apart, so their spacing
//! grows linearly with range, and a global threshold removes every far point of a real scan
//! (and misses isolated near ones). So the score is made range-free in two steps:
//!
//! 1. divided by the point's range from the sensor: a surface sampled every `dθ` radians has a
//!    spacing `dθ · r`, so `score / r` is the same at every range for the same surface;
//! 2. divided by the median of that ratio among the points of similar range (the scan sorted by
//!    range, in groups of [`RANGE_GROUP_POINTS`]): near the sensor the spacing no longer shrinks
//!    with range but is held up by the range noise, and this takes it out whatever the sensor,
//!    with no knowledge of its angular step or noise.
//!
//! A surface point's normalised score is then about 1 (more on surfaces seen at grazing
//! incidence, stretched along one direction only), an isolated point's is the ratio of its
//! clearance to the local sample spacing. A point is an outlier when its normalised score is
//! more than `n_sigma` robust standard deviations (1.4826 x the median absolute deviation, so a
//! tail of outliers does not inflate it as it inflates a standard deviation) above the median,
//! and at least [`OutlierConfig::min_ratio`] times the local spacing.
//!
//! Organised scans keep their shape: a removed point becomes NaN (the missing-return
//! convention); from other scans it is deleted.

use cloud::{check_range, PointCloud};
use rayon::prelude::*;
use registration::KdTree;
use serde::{Deserialize, Serialize};

/// Points per range group whose median normalises the scores (see the module docs): enough
/// for a stable median (its relative error is about 1/sqrt(n), 3 % here), few enough that a
/// group spans a narrow band of ranges in a scan of a hundred thousand points.
pub const RANGE_GROUP_POINTS: usize = 1024;

/// Statistical outlier removal (`[outliers]` of the configuration).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OutlierConfig {
    /// Whether scans lose their isolated points when read.
    pub enabled: bool,
    /// Neighbours whose mean distance is a point's score.
    pub neighbours_k: usize,
    /// Robust standard deviations above the median normalised score that make an outlier.
    pub n_sigma: f64,
    /// The least normalised score of an outlier: its neighbours at least this many times
    /// farther than those of points at the same range.
    pub min_ratio: f64,
}

impl Default for OutlierConfig {
    fn default() -> Self {
        OutlierConfig {
            enabled: true,
            // Eight neighbours: a point of a surface has them all within about 1.2 sample
            // spacings (a square grid's ring of eight), and a short line of mixed pixels (two
            // or three points in a row) still has most of them far away.
            neighbours_k: 8,
            n_sigma: 6.0,
            min_ratio: 3.0,
        }
    }
}

impl OutlierConfig {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), cloud::InvalidParameter> {
        check_range(
            "neighbours_k",
            self.neighbours_k as f64,
            1.0,
            64.0,
            "1..64 neighbours",
        )?;
        check_range("n_sigma", self.n_sigma, 0.5, 100.0, "within 0.5..100")?;
        check_range("min_ratio", self.min_ratio, 1.0, 100.0, "within 1..100")?;
        Ok(())
    }
}

/// The indices of the scan's outliers (ascending); none when removal is disabled or the scan
/// has too few points for statistics (fewer than [`RANGE_GROUP_POINTS`] finite points).
pub fn find_outliers(scan: &PointCloud, config: &OutlierConfig) -> Vec<usize> {
    if !config.enabled {
        return Vec::new();
    }
    let finite: Vec<usize> = (0..scan.len())
        .filter(|&i| scan.points[i].is_finite())
        .collect();
    let k = config.neighbours_k;
    if finite.len() < RANGE_GROUP_POINTS.max(k + 1) {
        return Vec::new();
    }
    let ratios = spacing_over_range(scan, &finite, k);
    let normalised = normalise_by_range_group(scan, &finite, &ratios);
    let threshold = robust_threshold(&normalised, config);
    finite
        .iter()
        .zip(&normalised)
        .filter(|(_, &v)| v > threshold)
        .map(|(&i, _)| i)
        .collect()
}

/// The scan without its outliers (organised scans: outliers set to NaN), and how many.
pub fn remove_outliers(scan: &PointCloud, config: &OutlierConfig) -> (PointCloud, usize) {
    let outliers = find_outliers(scan, config);
    if outliers.is_empty() {
        return (scan.clone(), 0);
    }
    if scan.organized.is_some() {
        let mut out = scan.clone();
        for &i in &outliers {
            out.points[i] = glam::Vec3::NAN;
        }
        return (out, outliers.len());
    }
    let mut is_outlier = vec![false; scan.len()];
    for &i in &outliers {
        is_outlier[i] = true;
    }
    let keep: Vec<usize> = (0..scan.len()).filter(|&i| !is_outlier[i]).collect();
    (scan.select(&keep), outliers.len())
}

/// For each finite point (in `finite`'s order): the mean distance to its `k` nearest
/// neighbours divided by its range from the sensor.
fn spacing_over_range(scan: &PointCloud, finite: &[usize], k: usize) -> Vec<f32> {
    let tree = KdTree::new(&scan.points);
    finite
        .par_iter()
        .map_init(Vec::new, |found, &i| {
            let p = scan.points[i];
            // k + 1: the point finds itself (or a duplicate of itself) first.
            tree.k_nearest(p, k + 1, f32::INFINITY, found);
            let (sum, n) = found
                .iter()
                .filter(|&&j| j as usize != i)
                .take(k)
                .fold((0.0f32, 0usize), |(s, n), &j| {
                    (s + scan.points[j as usize].distance(p), n + 1)
                });
            let range = p.distance(scan.sensor_origin).max(f32::MIN_POSITIVE);
            sum / n.max(1) as f32 / range
        })
        .collect()
}

/// Each ratio divided by the median ratio of its range group (the points sorted by range, in
/// groups of [`RANGE_GROUP_POINTS`]; the last group takes the remainder).
fn normalise_by_range_group(scan: &PointCloud, finite: &[usize], ratios: &[f32]) -> Vec<f32> {
    let range = |slot: usize| scan.points[finite[slot]].distance(scan.sensor_origin);
    let mut by_range: Vec<usize> = (0..finite.len()).collect();
    by_range.par_sort_unstable_by(|&a, &b| range(a).total_cmp(&range(b)));
    let groups = (finite.len() / RANGE_GROUP_POINTS).max(1);
    let mut normalised = vec![0.0f32; finite.len()];
    let mut values = Vec::with_capacity(2 * RANGE_GROUP_POINTS);
    for g in 0..groups {
        let start = g * RANGE_GROUP_POINTS;
        let end = if g + 1 == groups {
            by_range.len()
        } else {
            start + RANGE_GROUP_POINTS
        };
        let slots = &by_range[start..end];
        values.clear();
        values.extend(slots.iter().map(|&s| ratios[s]));
        let median = median(&mut values).max(f32::MIN_POSITIVE);
        for &s in slots {
            normalised[s] = ratios[s] / median;
        }
    }
    normalised
}

/// The normalised score above which a point is an outlier: median + `n_sigma` x 1.4826 x MAD,
/// and at least `min_ratio`.
fn robust_threshold(normalised: &[f32], config: &OutlierConfig) -> f32 {
    let mut values = normalised.to_vec();
    let centre = median(&mut values);
    for v in &mut values {
        *v = (*v - centre).abs();
    }
    let mad = median(&mut values);
    let sigma = 1.4826 * mad;
    eprintln!("DEBUG median {centre} mad {mad} threshold {}", (centre + config.n_sigma as f32 * sigma).max(config.min_ratio as f32));
    (centre + config.n_sigma as f32 * sigma).max(config.min_ratio as f32)
}

/// The median of `values` (reordered); 0 for none.
fn median(values: &mut [f32]) -> f32 {
    if values.is_empty() {
        return 0.0;
    }
    let mid = values.len() / 2;
    let (_, m, _) = values.select_nth_unstable_by(mid, f32::total_cmp);
    *m
}
