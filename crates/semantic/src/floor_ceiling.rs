//! Floor and ceiling: levelling the cloud and finding the two horizontal slabs.
//!
//! A registered cloud's frame need not be level (3DTK's corridor is pitched about 3 degrees),
//! so the floor plane is fitted first: the cloud is cut into XY cells, each cell's lowest
//! points (robustly, the third lowest z) estimate the floor there, and a RANSAC plane over the
//! cells (tilt at most `max_tilt_deg`) is refined by least squares over its inliers, then over
//! all the points near it (the floor itself). The map frame is the input frame rotated so that
//! this plane is horizontal.
//!
//! Heights then come from a histogram of z in the map frame: horizontal surfaces are sharp
//! peaks. The floor is the lowest peak holding at least `peak_fraction` of the strongest bin,
//! the ceiling the highest such peak at least `min_room_height_m` above the floor; both are
//! refined to the mean z of the points within `surface_tolerance_m` of the peak.

use crate::error::{check_range, Result};
use crate::points::{quantile, MapPoints};
use glam::{DAffine3, DQuat, DVec3, Vec3};
use serde::{Deserialize, Serialize};

/// Configuration of levelling and floor/ceiling detection.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FloorCeilingConfig {
    /// Fit the floor plane and level the cloud (false: take the input frame as level).
    pub level: bool,
    /// Cell edge for the floor-plane fit.
    pub level_cell_m: f64,
    /// Largest tilt of the floor plane that levelling accepts.
    pub max_tilt_deg: f64,
    /// Tilts below this are left alone (the map frame is then the input frame).
    pub min_tilt_deg: f64,
    /// Inlier distance of the floor-plane fit.
    pub plane_tolerance_m: f64,
    /// Bin width of the z histogram.
    pub bin_m: f64,
    /// A peak must hold this fraction of the strongest bin.
    pub peak_fraction: f64,
    /// ... and this multiple of the median bin (a flat histogram, a lone wall, has no floor).
    pub min_peak_to_median: f64,
    /// Least height of the ceiling above the floor.
    pub min_room_height_m: f64,
    /// Points within this distance of a surface belong to it.
    pub surface_tolerance_m: f64,
    /// Thickness given to the floor and ceiling boxes (the scans see only one face).
    pub slab_thickness_m: f64,
}

impl Default for FloorCeilingConfig {
    fn default() -> Self {
        FloorCeilingConfig {
            level: true,
            level_cell_m: 0.5,
            max_tilt_deg: 10.0,
            min_tilt_deg: 0.05,
            plane_tolerance_m: 0.03,
            bin_m: 0.01,
            peak_fraction: 0.2,
            min_peak_to_median: 4.0,
            min_room_height_m: 1.8,
            surface_tolerance_m: 0.04,
            slab_thickness_m: 0.2,
        }
    }
}

impl FloorCeilingConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "floor_ceiling.level_cell_m",
            self.level_cell_m,
            0.05,
            100.0,
            "within 0.05..100 m",
        )?;
        check_range(
            "floor_ceiling.max_tilt_deg",
            self.max_tilt_deg,
            0.0,
            45.0,
            "within 0..45 deg",
        )?;
        check_range(
            "floor_ceiling.min_tilt_deg",
            self.min_tilt_deg,
            0.0,
            45.0,
            "within 0..45 deg",
        )?;
        check_range(
            "floor_ceiling.plane_tolerance_m",
            self.plane_tolerance_m,
            1e-4,
            1.0,
            "within 0.0001..1 m",
        )?;
        check_range(
            "floor_ceiling.bin_m",
            self.bin_m,
            1e-3,
            1.0,
            "within 0.001..1 m",
        )?;
        check_range(
            "floor_ceiling.peak_fraction",
            self.peak_fraction,
            0.0,
            1.0,
            "within 0..1",
        )?;
        check_range(
            "floor_ceiling.min_peak_to_median",
            self.min_peak_to_median,
            0.0,
            1e6,
            "non-negative",
        )?;
        check_range(
            "floor_ceiling.min_room_height_m",
            self.min_room_height_m,
            0.1,
            100.0,
            "within 0.1..100 m",
        )?;
        check_range(
            "floor_ceiling.surface_tolerance_m",
            self.surface_tolerance_m,
            1e-3,
            1.0,
            "within 0.001..1 m",
        )?;
        check_range(
            "floor_ceiling.slab_thickness_m",
            self.slab_thickness_m,
            1e-3,
            10.0,
            "within 0.001..10 m",
        )
    }
}

/// What this stage found: the map frame and the two heights (map frame).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Levels {
    pub map_from_input: DAffine3,
    pub tilt_deg: f64,
    /// Floor height and its number of points, if found.
    pub floor: Option<(f64, u64)>,
    /// Ceiling height and its number of points, if found.
    pub ceiling: Option<(f64, u64)>,
    /// The floor height, or the robust lowest z if no floor was found.
    pub floor_ref_m: f64,
    /// The ceiling height, or the robust highest z if no ceiling was found.
    pub ceiling_ref_m: f64,
}

/// Fits the floor plane of the finite points (input frame). Returns `map_from_input` and the tilt.
pub(crate) fn level_transform(points: &[Vec3], c: &FloorCeilingConfig) -> (DAffine3, f64) {
    if !c.level {
        return (DAffine3::IDENTITY, 0.0);
    }
    // Third-lowest z per cell (robust against a couple of stray points below the floor), over
    // the cloud's robust XY extent (0.1 % to 99.9 %), at most 2048 cells a side.
    let mut xs: Vec<f64> = points.iter().map(|p| p.x as f64).collect();
    let mut ys: Vec<f64> = points.iter().map(|p| p.y as f64).collect();
    let (Some(x0), Some(x1), Some(y0), Some(y1)) = (
        quantile(&mut xs, 0.001),
        quantile(&mut xs, 0.999),
        quantile(&mut ys, 0.001),
        quantile(&mut ys, 0.999),
    ) else {
        return (DAffine3::IDENTITY, 0.0);
    };
    let cell = c.level_cell_m.max((x1 - x0).max(y1 - y0) / 2048.0);
    let cols = ((x1 - x0) / cell) as usize + 1;
    let rows = ((y1 - y0) / cell) as usize + 1;
    let mut cells = vec![([f32::INFINITY; 3], 0u32, 0.0f64, 0.0f64); cols * rows];
    for p in points {
        let (u, v) = ((p.x as f64 - x0) / cell, (p.y as f64 - y0) / cell);
        if !(u >= 0.0 && v >= 0.0 && (u as usize) < cols && (v as usize) < rows) {
            continue;
        }
        let e = &mut cells[v as usize * cols + u as usize];
        e.1 += 1;
        e.2 += p.x as f64;
        e.3 += p.y as f64;
        let z = p.z;
        if z < e.0[2] {
            e.0[2] = z;
            e.0.sort_by(f32::total_cmp);
        }
    }
    let samples: Vec<DVec3> = cells
        .iter()
        .filter(|e| e.1 >= 10)
        .map(|e| DVec3::new(e.2 / e.1 as f64, e.3 / e.1 as f64, e.0[2] as f64))
        .collect();
    if samples.len() < 10 {
        return (DAffine3::IDENTITY, 0.0);
    }
    let max_slope = c.max_tilt_deg.to_radians().tan();
    let mut rng = scanner::Rng::new(0x5eed_f100);
    let mut best: Option<(usize, [f64; 3])> = None;
    for _ in 0..400 {
        let pick = |r: &mut scanner::Rng| samples[r.int(0, samples.len() as i64 - 1) as usize];
        let (a, b, d) = (pick(&mut rng), pick(&mut rng), pick(&mut rng));
        let Some(plane) = plane_through(a, b, d) else {
            continue;
        };
        if plane[0].hypot(plane[1]) > max_slope {
            continue;
        }
        let inliers = samples
            .iter()
            .filter(|s| (s.z - eval(plane, **s)).abs() < c.plane_tolerance_m)
            .count();
        if best.is_none_or(|(n, _)| inliers > n) {
            best = Some((inliers, plane));
        }
    }
    let Some((n, mut plane)) = best else {
        return (DAffine3::IDENTITY, 0.0);
    };
    if n < 3 {
        return (DAffine3::IDENTITY, 0.0);
    }
    for _ in 0..2 {
        let inliers: Vec<DVec3> = samples
            .iter()
            .copied()
            .filter(|s| (s.z - eval(plane, *s)).abs() < c.plane_tolerance_m)
            .collect();
        if let Some(p) = least_squares_plane(&inliers) {
            plane = p;
        }
    }
    // Refine the slope on the floor points themselves: the plane that puts the most of them
    // within 1 cm (a sharp floor), searched around the fit, coarse then fine.
    let step = (points.len() / 100_000).max(1);
    let near: Vec<DVec3> = points
        .iter()
        .step_by(step)
        .map(|p| p.as_dvec3())
        .filter(|p| (p.z - eval(plane, *p)).abs() < 0.1)
        .collect();
    if near.len() >= 100 {
        for (span, d) in [(0.01, 0.002), (0.002, 0.0004)] {
            let (a0, b0) = (plane[0], plane[1]);
            let mut best = (sharpness(&near, a0, b0), a0, b0);
            let k = (span / d) as i32;
            for i in -k..=k {
                for j in -k..=k {
                    let (a, b) = (a0 + i as f64 * d, b0 + j as f64 * d);
                    if a.hypot(b) > max_slope {
                        continue;
                    }
                    let v = sharpness(&near, a, b);
                    if v.0 > best.0 .0 {
                        best = (v, a, b);
                    }
                }
            }
            let ((_, c), a, b) = best;
            plane = [a, b, c];
        }
    }
    let normal = DVec3::new(-plane[0], -plane[1], 1.0).normalize();
    let tilt_deg = normal.angle_between(DVec3::Z).to_degrees();
    if tilt_deg < c.min_tilt_deg || tilt_deg > c.max_tilt_deg {
        return (DAffine3::IDENTITY, tilt_deg);
    }
    (
        DAffine3::from_quat(DQuat::from_rotation_arc(normal, DVec3::Z)),
        tilt_deg,
    )
}

/// How many of `pts` lie within 1 cm of the best plane of slopes `(a, b)`, and its offset:
/// the residuals `z - a x - b y` in 1 cm bins, the best pair of neighbouring bins.
fn sharpness(pts: &[DVec3], a: f64, b: f64) -> (usize, f64) {
    let r: Vec<f64> = pts.iter().map(|p| p.z - a * p.x - b * p.y).collect();
    let lo = r.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = r.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let n = (((hi - lo) / 0.01) as usize + 2).min(1_000_000);
    let mut h = vec![0usize; n];
    for v in &r {
        h[(((v - lo) / 0.01) as usize).min(n - 1)] += 1;
    }
    let (i, count) = (0..n - 1)
        .map(|i| (i, h[i] + h[i + 1]))
        .max_by_key(|x| x.1)
        .unwrap_or((0, 0));
    (count, lo + (i + 1) as f64 * 0.01)
}

fn eval(p: [f64; 3], s: DVec3) -> f64 {
    p[0] * s.x + p[1] * s.y + p[2]
}

/// The plane z = a x + b y + c through three points.
fn plane_through(p: DVec3, q: DVec3, r: DVec3) -> Option<[f64; 3]> {
    let n = (q - p).cross(r - p);
    if n.z.abs() < 1e-9 {
        return None;
    }
    let (a, b) = (-n.x / n.z, -n.y / n.z);
    Some([a, b, p.z - a * p.x - b * p.y])
}

fn least_squares_plane(pts: &[DVec3]) -> Option<[f64; 3]> {
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let m = pts.iter().copied().sum::<DVec3>() / n;
    let (mut sxx, mut sxy, mut syy, mut sxz, mut syz) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for p in pts {
        let d = *p - m;
        sxx += d.x * d.x;
        sxy += d.x * d.y;
        syy += d.y * d.y;
        sxz += d.x * d.z;
        syz += d.y * d.z;
    }
    let det = sxx * syy - sxy * sxy;
    if det.abs() < 1e-12 {
        return None;
    }
    let a = (sxz * syy - syz * sxy) / det;
    let b = (syz * sxx - sxz * sxy) / det;
    Some([a, b, m.z - a * m.x - b * m.y])
}

/// Finds floor and ceiling heights in the (levelled) map points.
pub(crate) fn find_levels(
    mp: &MapPoints,
    map_from_input: DAffine3,
    tilt_deg: f64,
    c: &FloorCeilingConfig,
) -> Levels {
    let mut zs: Vec<f64> = mp.points.iter().map(|p| p.z as f64).collect();
    let lo = quantile(&mut zs, 0.001).unwrap_or(0.0);
    let hi = quantile(&mut zs, 0.999).unwrap_or(0.0);
    let mut levels = Levels {
        map_from_input,
        tilt_deg,
        floor: None,
        ceiling: None,
        floor_ref_m: lo,
        ceiling_ref_m: hi,
    };
    let (lo, hi) = (lo - 0.1, hi + 0.1);
    let bins = (((hi - lo) / c.bin_m).ceil() as usize).clamp(1, 2_000_000);
    let mut h = vec![0u64; bins];
    for p in &mp.points {
        let b = ((p.z as f64 - lo) / c.bin_m).floor();
        if b >= 0.0 && (b as usize) < bins {
            h[b as usize] += 1;
        }
    }
    // Smooth over three bins: a surface at a bin boundary splits its points.
    let s: Vec<u64> = (0..bins)
        .map(|i| h[i.saturating_sub(1)..(i + 2).min(bins)].iter().sum())
        .collect();
    let max = s.iter().copied().max().unwrap_or(0);
    let mut all: Vec<f64> = s.iter().map(|&v| v as f64).collect();
    let med = crate::points::median(&mut all).unwrap_or(0.0);
    let threshold = (c.peak_fraction * max as f64).max(c.min_peak_to_median * med);
    let peaks: Vec<usize> = (0..bins)
        .filter(|&i| {
            let v = s[i];
            v as f64 >= threshold
                && v > 0
                && (i == 0 || v >= s[i - 1])
                && (i + 1 == bins || v > s[i + 1])
        })
        .collect();
    let refine = |i: usize| -> (f64, u64) {
        let centre = lo + (i as f64 + 0.5) * c.bin_m;
        let (mut sum, mut n) = (0.0, 0u64);
        for p in &mp.points {
            let z = p.z as f64;
            if (z - centre).abs() <= c.surface_tolerance_m {
                sum += z;
                n += 1;
            }
        }
        (if n > 0 { sum / n as f64 } else { centre }, n)
    };
    let Some(&first) = peaks.first() else {
        return levels;
    };
    let floor = refine(first);
    levels.floor = Some(floor);
    levels.floor_ref_m = floor.0;
    if let Some(&last) = peaks.last() {
        let ceiling = refine(last);
        if ceiling.0 - floor.0 >= c.min_room_height_m {
            levels.ceiling = Some(ceiling);
            levels.ceiling_ref_m = ceiling.0;
        }
    }
    if levels.ceiling_ref_m - levels.floor_ref_m < 0.5 {
        levels.ceiling_ref_m = levels.floor_ref_m + 0.5;
    }
    levels
}

/// The XY extent of the points within `tol` of height `z`, in a frame turned by `yaw`:
/// robust (0.2 % and 99.8 % quantiles) min and max of the rotated coordinates.
pub(crate) fn slab_extent(
    points: &[Vec3],
    z: f64,
    tol: f64,
    yaw: f64,
) -> Option<([f64; 2], [f64; 2])> {
    let (s, co) = yaw.sin_cos();
    let mut u = Vec::new();
    let mut v = Vec::new();
    for p in points {
        if (p.z as f64 - z).abs() <= tol {
            let (x, y) = (p.x as f64, p.y as f64);
            u.push(co * x + s * y);
            v.push(-s * x + co * y);
        }
    }
    if u.len() < 10 {
        return None;
    }
    let lo = [quantile(&mut u, 0.002)?, quantile(&mut v, 0.002)?];
    let hi = [quantile(&mut u, 0.998)?, quantile(&mut v, 0.998)?];
    Some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn room(tilt_deg: f64) -> Vec<Vec3> {
        let r = DQuat::from_rotation_y(tilt_deg.to_radians());
        let mut v = Vec::new();
        for i in 0..100 {
            for j in 0..50 {
                let (x, y) = (i as f64 * 0.1, j as f64 * 0.1);
                v.push(DVec3::new(x, y, 0.0));
                v.push(DVec3::new(x, y, 2.6));
            }
            for k in 0..26 {
                v.push(DVec3::new(i as f64 * 0.1, 0.0, k as f64 * 0.1));
            }
        }
        v.into_iter().map(|p| (r * p).as_vec3()).collect()
    }

    #[test]
    fn levels_a_tilted_room_and_finds_floor_and_ceiling() {
        let c = FloorCeilingConfig::default();
        let pts = room(3.0);
        let (t, tilt) = level_transform(&pts, &c);
        assert!((tilt - 3.0).abs() < 0.1, "tilt {tilt}");
        let mp = MapPoints {
            points: pts
                .iter()
                .map(|p| t.transform_point3(p.as_dvec3()).as_vec3())
                .collect(),
            input_index: (0..pts.len() as u32).collect(),
        };
        let l = find_levels(&mp, t, tilt, &c);
        let (f, cl) = (l.floor.expect("floor").0, l.ceiling.expect("ceiling").0);
        assert!((cl - f - 2.6).abs() < 0.01, "floor {f} ceiling {cl}");
    }

    #[test]
    fn level_room_is_left_alone() {
        let (t, _) = level_transform(&room(0.0), &FloorCeilingConfig::default());
        assert_eq!(t, DAffine3::IDENTITY);
    }
}
