//! Statistical outlier removal for one scan, in the scan's own frame: the isolated returns a
//! real sensor writes in mid-air (dust, a mixed pixel floating between two surfaces, a
//! reflection) are points far from every other point, *for where they are*.
//!
//! Each point's score is the mean distance to its `k` nearest neighbours (an exact k-d tree,
//! kiddo's, rayon over points; for every scan, organised or not: by the time a scan is read most have
//! lost their shape to missing returns, and one code path is tested). PCL's
//! StatisticalOutlierRemoval thresholds that score at the scan's mean + n sigma; but a rotating
//! laser's samples are an angular step apart, so their spacing grows linearly with range, and
//! a global threshold removes the far points of a real scan wholesale (the long-hall test shows
//! it) while it misses isolated near ones. So the score is made range-free in two steps:
//!
//! 1. divided by the point's range from the sensor: a surface sampled every `dθ` radians has a
//!    spacing `dθ · r`, so `score / r` is the same at every range for the same surface;
//! 2. divided by the median of that ratio over the point's own `k` neighbours. A surface
//!    point's neighbours are samples of the same surface at nearly the same range, so its
//!    normalised score is about 1 whatever the sampling there: at grazing incidence (samples
//!    stretched along one direction), near the rotation axis (where every rotation step
//!    samples the same spot: a scan's densest patch), or near the sensor (where the range
//!    noise, not the angular step, sets the spacing). An isolated point's neighbours are
//!    samples of the nearest surface, so its normalised score is its distance from that
//!    surface over the surface's sample spacing, taken to the point's own range.
//!
//! (A first design divided by the median ratio of all the points of similar range; the
//! rotation axis's dense patch then set the median of its range band, and every other point
//! at that range looked isolated.)
//!
//! A point is an outlier when its normalised score is more than `n_sigma` robust standard
//! deviations (1.4826 x the median absolute deviation: a tail of outliers inflates a standard
//! deviation, not the MAD) above the median, and at least [`OutlierConfig::min_ratio`]: its
//! neighbours several sample spacings away where a surface's are one or two. Isolated points
//! close together hide each other (each has the others among its neighbours), so those found
//! are left out of their neighbours' medians and the scan is looked at again, a few times.
//!
//! What it cannot find: a streak of points along a line at the sample spacing (the mixed
//! pixels along a depth edge, one per scan line crossing it) looks like a thin object, a
//! cable or a railing, and is kept (in an organised scan `mixed_pixels` finds them first,
//! from the grid); so is a fog of returns denser than the surfaces' samples.
//!
//! Organised scans keep their shape: a removed point becomes NaN (the missing-return
//! convention); from other scans it is deleted.

use cloud::{check_range, PointCloud};
use kiddo::{ImmutableKdTree, SquaredEuclidean};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::num::NonZeroUsize;

/// The fewest finite points a scan needs to be looked at: fewer is no 3D scan (one 2D line
/// scan has a few hundred points), and too few for the median and MAD of its scores.
pub const OUTLIER_MIN_POINTS: usize = 1000;

/// How many times the outliers found are taken out of their neighbours' statistics and the
/// scan looked at again.
const MAX_PASSES: usize = 4;

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
    /// farther (relative to range) than its neighbours' own neighbours.
    pub min_ratio: f64,
}

impl Default for OutlierConfig {
    fn default() -> Self {
        OutlierConfig {
            enabled: true,
            // Six neighbours: on a surface facing the sensor they are all within about one
            // sample spacing (a grid's four edge neighbours and two of its diagonals); on one
            // seen at grazing incidence, whose samples are stretched along one direction only,
            // most are still along the other, so its score grows by a factor of about 1.5, not
            // by the stretch; and two or three stray points close together still have most of
            // their neighbours far away.
            neighbours_k: 6,
            // A surface's normalised scores spread by a few percent (their MAD is 0.03..0.05 on
            // the virtual laser and on the 3DTK corridor's SICK scans), so six robust sigmas
            // matter only for a noisy sensor whose scores spread widely; then they keep its
            // noise from being taken for outliers.
            n_sigma: 6.0,
            // Three times its neighbours' spacing: a grazing surface's score is up to about
            // twice its neighbours' (where the stretch changes), and a point three or more
            // sample spacings from every surface is no sample of one (range noise moves a
            // sample along its beam by a centimetre, not by spacings).
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
/// has too few points for statistics (fewer than [`OUTLIER_MIN_POINTS`] finite points).
pub fn find_outliers(scan: &PointCloud, config: &OutlierConfig) -> Vec<usize> {
    if !config.enabled {
        return Vec::new();
    }
    let finite: Vec<usize> = (0..scan.len())
        .filter(|&i| scan.points[i].is_finite())
        .collect();
    let k = config.neighbours_k;
    if finite.len() < OUTLIER_MIN_POINTS.max(k + 1) {
        return Vec::new();
    }
    let (ratios, neighbours) = spacing_over_range(scan, &finite, k);
    let mut excluded = vec![false; scan.len()];
    let normalised = normalise_by_neighbours(&finite, &ratios, &neighbours, k, &excluded);
    let threshold = robust_threshold(&normalised, config);
    let mut outliers = above(&finite, &normalised, threshold);
    // Isolated points near each other hide each other: a point whose neighbours are mostly
    // outliers is compared with outliers. So it is compared again with its neighbours that are
    // not outliers, until no more are found.
    for _ in 0..MAX_PASSES {
        for &i in &outliers {
            excluded[i] = true;
        }
        let normalised = normalise_by_neighbours(&finite, &ratios, &neighbours, k, &excluded);
        let again = above(&finite, &normalised, threshold);
        let done = again.len() <= outliers.len();
        outliers = again;
        if done {
            break;
        }
    }
    outliers
}

/// The finite points whose normalised score is above `threshold`.
fn above(finite: &[usize], normalised: &[f32], threshold: f32) -> Vec<usize> {
    finite
        .iter()
        .zip(normalised)
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

/// For each point (NaN for a non-finite one): the mean distance to its `k` nearest
/// neighbours divided by its range from the sensor; and the neighbours of each finite point
/// (`k` per point, in `finite`'s order, indices into the scan).
fn spacing_over_range(scan: &PointCloud, finite: &[usize], k: usize) -> (Vec<f32>, Vec<u32>) {
    let coords: Vec<[f32; 3]> = finite.iter().map(|&i| scan.points[i].to_array()).collect();
    let mut neighbours = vec![0u32; finite.len() * k];
    let mut by_point = vec![f32::NAN; scan.len()];
    // (No neighbours: the tree refuses nothing it is given but an empty set, excluded above.)
    let Ok(tree) = ImmutableKdTree::<f32, 3>::new_from_slice(&coords) else {
        return (by_point, neighbours);
    };
    // k + 1: the point finds itself (or a duplicate of itself) among them. An unbounded query
    // (no `within`): kiddo answers it about twice as fast.
    let Some(wanted) = NonZeroUsize::new(k + 1) else {
        return (by_point, neighbours);
    };
    let ratios: Vec<f32> = coords
        .par_iter()
        .zip(neighbours.par_chunks_mut(k))
        .enumerate()
        .map(|(slot, (q, mine))| {
            let found = tree
                .query(q)
                .nearest_n::<SquaredEuclidean<f32>>(wanted)
                .unsorted()
                .execute();
            let others = found.iter().filter(|r| r.item as usize != slot).take(k);
            let mut sum = 0.0f32;
            let mut n = 0;
            for (out, r) in mine.iter_mut().zip(others) {
                *out = finite[r.item as usize] as u32;
                sum += r.distance.sqrt();
                n += 1;
            }
            let i = finite[slot];
            // (A point with duplicates for neighbours may have fewer than k others: its own
            // index fills the rest, which its neighbourhood median then counts as itself.)
            for out in mine.iter_mut().skip(n) {
                *out = i as u32;
            }
            let range = scan.points[i]
                .distance(scan.sensor_origin)
                .max(f32::MIN_POSITIVE);
            sum / n.max(1) as f32 / range
        })
        .collect();
    for (&i, r) in finite.iter().zip(ratios) {
        by_point[i] = r;
    }
    (by_point, neighbours)
}

/// Each finite point's ratio divided by the median ratio of its neighbours that are not
/// `excluded` (all of them when every one is).
fn normalise_by_neighbours(
    finite: &[usize],
    ratios: &[f32],
    neighbours: &[u32],
    k: usize,
    excluded: &[bool],
) -> Vec<f32> {
    finite
        .par_iter()
        .zip(neighbours.par_chunks(k))
        .map_init(Vec::new, |values, (&i, mine)| {
            values.clear();
            values.extend(
                mine.iter()
                    .filter(|&&j| !excluded[j as usize])
                    .map(|&j| ratios[j as usize]),
            );
            if values.is_empty() {
                values.extend(mine.iter().map(|&j| ratios[j as usize]));
            }
            ratios[i] / median(values).max(f32::MIN_POSITIVE)
        })
        .collect()
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

#[cfg(test)]
mod tests {
    use super::*;
    use cloud::Organized;
    use glam::Vec3;

    /// A rotating laser's scan (`rows` x `cols` directions, organised) of a box room 40 x 30 m
    /// around the sensor, the floor 0.5 m below it and the ceiling 3.5 m above.
    fn room_scan(rows: usize, cols: usize) -> PointCloud {
        let mut points = Vec::with_capacity(rows * cols);
        for j in 0..rows {
            let azimuth = std::f32::consts::TAU * j as f32 / rows as f32;
            for i in 0..cols {
                let elevation = (-40.0 + 125.0 * i as f32 / (cols - 1) as f32).to_radians();
                let d = Vec3::new(
                    elevation.cos() * azimuth.cos(),
                    elevation.cos() * azimuth.sin(),
                    elevation.sin(),
                );
                let z = if d.z > 0.0 { 3.5 / d.z } else { 0.5 / -d.z };
                let t = (20.0 / d.x.abs()).min(15.0 / d.y.abs()).min(z);
                points.push(d * t);
            }
        }
        let mut scan = PointCloud::from_points(points);
        scan.organized = Some(Organized { rows, cols });
        scan
    }

    #[test]
    fn isolated_points_near_and_far_are_found_and_the_room_kept() {
        let mut scan = room_scan(360, 200);
        // Three points in mid-air, replacing three samples: near, middle and far.
        let isolated = [
            (100, Vec3::new(1.5, 0.5, 1.0)),
            (20_000, Vec3::new(-8.0, 3.0, 1.5)),
            (50_000, Vec3::new(12.0, -9.0, 0.5)),
        ];
        for (i, p) in isolated {
            scan.points[i] = p;
        }
        let found = find_outliers(&scan, &OutlierConfig::default());
        for (i, p) in isolated {
            assert!(found.contains(&i), "{p} not found");
        }
        assert!(
            found.len() <= isolated.len() + scan.len() / 1000,
            "{} found",
            found.len()
        );

        // The organised scan keeps its shape: the outliers become NaN.
        let (kept, removed) = remove_outliers(&scan, &OutlierConfig::default());
        assert_eq!(removed, found.len());
        assert_eq!((kept.len(), kept.organized), (scan.len(), scan.organized));
        assert!(isolated.iter().all(|&(i, _)| kept.points[i].is_nan()));
        assert_eq!(kept.valid_count(), scan.len() - removed);

        // Unorganised, they are deleted.
        scan.organized = None;
        let (kept, removed) = remove_outliers(&scan, &OutlierConfig::default());
        assert_eq!((kept.len(), kept.organized), (scan.len() - removed, None));
        assert!(kept.points.iter().all(|p| p.is_finite()));
    }

    #[test]
    fn disabled_removal_and_scans_too_small_for_statistics_lose_nothing() {
        let mut scan = room_scan(90, 50);
        scan.points[10] = Vec3::new(1.5, 0.5, 1.0);
        let off = OutlierConfig {
            enabled: false,
            ..OutlierConfig::default()
        };
        assert!(find_outliers(&scan, &off).is_empty());
        assert!(!find_outliers(&scan, &OutlierConfig::default()).is_empty());
        let small = scan.select(&(0..OUTLIER_MIN_POINTS - 1).collect::<Vec<_>>());
        assert!(find_outliers(&small, &OutlierConfig::default()).is_empty());
        assert_eq!(remove_outliers(&small, &OutlierConfig::default()).1, 0);
    }

    #[test]
    fn out_of_range_parameters_are_refused_by_name() {
        assert!(OutlierConfig::default().validate().is_ok());
        for (bad, name) in [
            (
                OutlierConfig {
                    neighbours_k: 0,
                    ..Default::default()
                },
                "neighbours_k",
            ),
            (
                OutlierConfig {
                    n_sigma: f64::NAN,
                    ..Default::default()
                },
                "n_sigma",
            ),
            (
                OutlierConfig {
                    min_ratio: 0.5,
                    ..Default::default()
                },
                "min_ratio",
            ),
        ] {
            let e = bad.validate().expect_err(name).to_string();
            assert!(e.contains(name), "{e}");
        }
    }
}
