//! Mixed pixels in an organised scan: where a beam's footprint straddles a depth edge, part of
//! its light comes back from the foreground and part from the background, and a sensor that
//! cannot separate the two echoes reports a range in between (Ye and Borenstein, ICRA 2002, for
//! the SICK LMS 200). The point floats in the air past the edge, along its own beam. Over the
//! edge of a raised level seen from below (a landing, a desk, a car's roof) these points stand
//! a few centimetres above the level, where nothing else is ever seen, and they read as the
//! level's top.
//!
//! The statistical outlier removal cannot find them: one per scan line crossing an edge, they
//! make a streak at the sample spacing, which looks like a cable (see `outliers.rs`). The grid
//! finds them. Along a row or a column of the grid, a mixed pixel is
//!
//! 1. **between** its two neighbours' ranges, farther than [`MixedPixelConfig::min_gap_m`]
//!    from either (a thin thing in front of both, a pipe or a chair leg, is in front, not
//!    between), and
//! 2. **on neither side's surface**: from each side's nearer sample it jumps more than
//!    [`MixedPixelConfig::min_jump_ratio`] times that side's own sample spacing (the distance
//!    between its two samples), and it does not continue the line through them.
//!
//! A surface seen at grazing incidence (the floor far from the sensor) has range steps as large
//! as an edge's between neighbouring beams, but its samples lie on one line within the beam's
//! plane, so each continues its neighbours' line: the second test keeps them. A depth edge
//! with no sample between the two surfaces has none to drop: the last foreground sample
//! continues the foreground's line.
//!
//! What it cannot find: a mixed pixel past a foreground surface seen at grazing incidence lies
//! on that surface's line (it extends the surface by at most the gap), and one next to a
//! missing return has no neighbour to be compared with; both are kept. Unorganised scans have
//! no grid and are left as they are.

use cloud::{check_range, PointCloud};
use glam::Vec3;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Mixed-pixel removal (`[mixed_pixels]` of the configuration).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MixedPixelConfig {
    /// Whether organised scans lose their mixed pixels when read.
    pub enabled: bool,
    /// The least range difference from each neighbour of a mixed pixel (metres).
    pub min_gap_m: f64,
    /// The least jump from a mixed pixel to each neighbour, as a multiple of that side's own
    /// sample spacing (the distance between its two samples).
    pub min_jump_ratio: f64,
    /// How far a sample may lie from the line through the two before it (or after it) and
    /// still continue that surface (metres)...
    pub line_tolerance_m: f64,
    /// ... or, where larger, this share of its distance from the nearer of those two.
    pub line_tolerance_ratio: f64,
    /// A grid axis whose neighbouring beams are farther apart than this (degrees, their median)
    /// is not looked at: there a surface as narrow as a door leaf holds a single sample between
    /// two others, as a mixed pixel does.
    pub max_step_deg: f64,
}

impl Default for MixedPixelConfig {
    fn default() -> Self {
        MixedPixelConfig {
            enabled: true,
            // Five times a laser scanner's centimetre range noise: neighbouring samples of one
            // surface facing the sensor are closer than that.
            min_gap_m: 0.05,
            // Twice the spacing: a surface's samples are evenly spaced, or (at grazing
            // incidence) their spacing grows by a few percent from one to the next; an edge's
            // jump is many spacings.
            min_jump_ratio: 2.0,
            // Three times that noise, for a surface's samples off their neighbours' line.
            line_tolerance_m: 0.03,
            // A sample may turn by up to about 11 degrees from its neighbours' line (a curved
            // surface, a sensor's angular jitter); a mixed pixel past an edge lies along its
            // beam, at a steep angle to the line of the surface it left.
            line_tolerance_ratio: 0.2,
            // Three times a SICK LMS's 0.33 degrees (the realistic laser's beams are 0.33
            // degrees apart, its rotation steps 0.6): a 121-beam line scan (1.5 degrees) lost
            // the demo building's door leaf to the filter, a sample or two across it.
            max_step_deg: 1.0,
        }
    }
}

impl MixedPixelConfig {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), cloud::InvalidParameter> {
        check_range("min_gap_m", self.min_gap_m, 1e-3, 10.0, "within 1 mm..10 m")?;
        check_range(
            "min_jump_ratio",
            self.min_jump_ratio,
            1.0,
            100.0,
            "within 1..100",
        )?;
        check_range(
            "line_tolerance_m",
            self.line_tolerance_m,
            0.0,
            1.0,
            "within 0..1 m",
        )?;
        check_range(
            "max_step_deg",
            self.max_step_deg,
            0.001,
            90.0,
            "within 0.001..90 degrees",
        )?;
        check_range(
            "line_tolerance_ratio",
            self.line_tolerance_ratio,
            0.0,
            1.0,
            "within 0..1",
        )?;
        Ok(())
    }
}

/// The indices of an organised scan's mixed pixels (ascending); none when the filter is
/// disabled or the scan has no grid. Ranges are measured from the scan's sensor origin.
pub fn find_mixed_pixels(scan: &PointCloud, config: &MixedPixelConfig) -> Vec<usize> {
    let Some(grid) = scan.organized else {
        return Vec::new();
    };
    if !config.enabled || grid.rows.checked_mul(grid.cols) != Some(scan.len()) {
        return Vec::new();
    }
    let (rows, cols) = (grid.rows, grid.cols);
    let point = |j: isize, i: isize| -> Option<Vec3> {
        let inside = (0..rows as isize).contains(&j) && (0..cols as isize).contains(&i);
        let p = inside.then(|| scan.points[(j as usize) * cols + i as usize])?;
        p.is_finite().then_some(p)
    };
    // The axes whose beams are fine enough apart (see `max_step_deg`).
    let axes: Vec<(isize, isize)> = [(0, 1), (1, 0)]
        .into_iter()
        .filter(|&(dj, di)| {
            median_step_rad(scan, cols, (dj as usize, di as usize))
                .is_some_and(|step| f64::from(step) <= config.max_step_deg.to_radians())
        })
        .collect();
    if axes.is_empty() {
        return Vec::new();
    }
    (0..scan.len())
        .into_par_iter()
        .filter(|&k| {
            let (j, i) = ((k / cols) as isize, (k % cols) as isize);
            let Some(p) = point(j, i) else {
                return false;
            };
            // Along the row (one line scan's beams), then along the column (rotation steps).
            axes.iter().any(|&(dj, di)| {
                let side = |s: isize| {
                    Some([
                        point(j + s * dj, i + s * di)?,
                        point(j + 2 * s * dj, i + 2 * s * di)?,
                    ])
                };
                match (side(-1), side(1)) {
                    (Some(before), Some(after)) => {
                        mixed_between(p, before, after, scan.sensor_origin, config)
                    }
                    _ => false,
                }
            })
        })
        .collect()
}

/// The median angle between neighbouring beams one step `(dj, di)` apart in the grid (as seen
/// from the sensor), over the pairs of returns; `None` without any.
fn median_step_rad(scan: &PointCloud, cols: usize, (dj, di): (usize, usize)) -> Option<f32> {
    let offset = dj * cols + di;
    let mut angles: Vec<f32> = (0..scan.len().saturating_sub(offset))
        .filter(|&k| di == 0 || k % cols + di < cols)
        .filter_map(|k| {
            let a = scan.points[k] - scan.sensor_origin;
            let b = scan.points[k + offset] - scan.sensor_origin;
            (a.is_finite() && b.is_finite() && a.length() > 0.0 && b.length() > 0.0)
                .then(|| a.angle_between(b))
        })
        .collect();
    if angles.is_empty() {
        return None;
    }
    let mid = angles.len() / 2;
    Some(*angles.select_nth_unstable_by(mid, f32::total_cmp).1)
}

/// Whether `p` is a mixed pixel between its neighbours on one axis, `before` and `after`
/// (each the nearer neighbour first): between their ranges and on neither's line.
fn mixed_between(
    p: Vec3,
    before: [Vec3; 2],
    after: [Vec3; 2],
    sensor: Vec3,
    config: &MixedPixelConfig,
) -> bool {
    let gap = config.min_gap_m as f32;
    let (r, ra, rb) = (
        p.distance(sensor),
        before[0].distance(sensor),
        after[0].distance(sensor),
    );
    let between = r > ra.min(rb) + gap && r < ra.max(rb) - gap;
    between && apart(p, before, config) && apart(p, after, config)
}

/// Whether `p` is apart from the surface of `side` (`side[0]` next to `p`, `side[1]` beyond
/// it): a jump of many of its sample spacings away, off its line.
fn apart(p: Vec3, side: [Vec3; 2], config: &MixedPixelConfig) -> bool {
    let spacing = side[0].distance(side[1]);
    p.distance(side[0]) > config.min_jump_ratio as f32 * spacing && !continues(p, side, config)
}

/// Whether `p` continues the line through `side`.
fn continues(p: Vec3, side: [Vec3; 2], config: &MixedPixelConfig) -> bool {
    let along = side[0] - side[1];
    let len = along.length();
    if len <= f32::EPSILON {
        return false;
    }
    let off = (p - side[0]).reject_from_normalized(along / len).length();
    let step = p.distance(side[0]);
    off <= (config.line_tolerance_m as f32).max(config.line_tolerance_ratio as f32 * step)
}

/// The scan without its mixed pixels (an organised scan keeps its shape: they become NaN, the
/// missing-return convention), and how many were removed.
pub fn remove_mixed_pixels(scan: &PointCloud, config: &MixedPixelConfig) -> (PointCloud, usize) {
    let mixed = find_mixed_pixels(scan, config);
    if mixed.is_empty() {
        return (scan.clone(), 0);
    }
    let mut out = scan.clone();
    for &k in &mixed {
        out.points[k] = Vec3::NAN;
    }
    (out, mixed.len())
}

#[cfg(test)]
mod tests;
