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
//!
//! The floor's footprint is where its points were seen ([`footprint`]): a few rectangles,
//! which the floor entity carries and a simulation builds; the ceiling keeps its extent.

mod footprint;
mod levelling;

pub(crate) use footprint::{floor_footprint, FloorFootprint};
pub(crate) use levelling::level_transform;

use crate::error::Result;
use crate::points::{median, quantile, MapPoints};
use cloud::check_range;
use glam::{DAffine3, Vec3};
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
    /// Cell edge of the floor's footprint grid. 0.2 m: under half a robot's or a person's
    /// width, so a part of the floor big enough to stand on is never lost to the grid, and
    /// coarser than a laser's return spacing on the floor within a few metres.
    pub footprint_cell_m: f64,
    /// Fewest floor points in a cell for it to be seen floor (one is a stray or mixed pixel).
    pub footprint_min_points: usize,
    /// Gaps in the seen floor up to this across are closed: the floor under what stands on it
    /// (legs, bins, feet) and between a rotating laser's scan lines at grazing incidence.
    /// 0.5 m: no robot or person fits through a narrower gap, so closing it moves no one.
    pub footprint_closing_m: f64,
    /// Parts of the floor smaller than this are left out: 0.5 m x 0.5 m, less than a person
    /// or a robot stands on.
    pub footprint_min_area_m2: f64,
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
            footprint_cell_m: 0.2,
            footprint_min_points: 2,
            footprint_closing_m: 0.5,
            footprint_min_area_m2: 0.25,
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
        )?;
        check_range(
            "floor_ceiling.footprint_cell_m",
            self.footprint_cell_m,
            0.01,
            10.0,
            "within 0.01..10 m",
        )?;
        check_range(
            "floor_ceiling.footprint_min_points",
            self.footprint_min_points as f64,
            1.0,
            1e6,
            "within 1..1e6",
        )?;
        check_range(
            "floor_ceiling.footprint_closing_m",
            self.footprint_closing_m,
            0.0,
            10.0,
            "within 0..10 m",
        )?;
        check_range(
            "floor_ceiling.footprint_min_area_m2",
            self.footprint_min_area_m2,
            0.0,
            1e4,
            "within 0..1e4 m2",
        )?;
        Ok(())
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
    let med = median(&mut all).unwrap_or(0.0);
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
    use super::levelling::level_transform;
    use super::*;
    use glam::{DQuat, DVec3};

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
