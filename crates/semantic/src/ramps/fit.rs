//! Whether a cluster is a ramp: uphill (or along an axis of its footprint), its upper profile
//! rises in a straight line from near the floor (the ramp's top, or its side face's top edge
//! where the top was not seen), steep enough for a ramp and no steeper; the plane through that
//! line, level across, is the ramp's top.

use super::profile::{fit_line, upper_profile};
use super::RampConfig;
use crate::obstacles::{convex_hull, min_area_rect};
use glam::DVec2;

/// A ramp's plane and footprint: `z = floor + slope · (u - u_range.0)` along `dir` (uphill),
/// level across it; the footprint is `u·dir + v·perp` over the ranges (map XY).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RampPlane {
    /// Uphill unit direction (XY).
    pub dir: DVec2,
    /// From the foot (where the plane meets the floor) to the end of the last profile bin on
    /// the line, and the extent across of the returns on or under the plane.
    pub u_range: (f64, f64),
    pub v_range: (f64, f64),
    /// Rise per metre along `dir`.
    pub slope: f64,
    pub floor: f64,
    /// Profile bins on the line, of those holding a return, and their RMS distance from it.
    pub inliers: usize,
    pub filled: usize,
    pub rms_m: f64,
}

impl RampPlane {
    /// The plane's height at `p`.
    pub fn z_at(&self, p: DVec2) -> f64 {
        self.floor + self.slope * (p.dot(self.dir) - self.u_range.0).max(0.0)
    }

    /// The head's height above the floor.
    pub fn rise(&self) -> f64 {
        self.slope * (self.u_range.1 - self.u_range.0)
    }

    /// The pitch (degrees).
    pub fn pitch_deg(&self) -> f64 {
        self.slope.atan().to_degrees()
    }
}

/// The ramp a cluster's returns (XY, z; `cells` its occupied cells' centres and tops) are, if
/// any. Uphill on the plane through most cells' tops, or else along an axis of the footprint's
/// rectangle, the upper profile's line must be as steep as a ramp and no steeper, hold
/// `min_inliers` of the bins within `max_rms_m`, start within `max_foot_height_m` of the floor
/// (or anywhere under head height if the stretch on it is `min_length_high_foot_m` long)
/// and meet it no farther before the stretch on the line than that stretch is long; and the
/// ramp must be long, wide and high enough. The first direction that passes is the ramp's.
pub(crate) fn ramp_plane(
    points: &[(DVec2, f64)],
    cells: &[(DVec2, f64)],
    floor: f64,
    c: &RampConfig,
) -> Option<RampPlane> {
    let centres: Vec<DVec2> = cells.iter().map(|c| c.0).collect();
    let (_, axis, _) = min_area_rect(&convex_hull(&centres), &[], &[])?;
    // Uphill: the gradient of the plane through the cells' tops, else the rectangle's axes.
    let uphill = uphill(cells, c.inlier_m);
    // The gradient (turned onto the rectangle's nearest axis if within `SNAP_DEG` of it: a
    // ramp's footprint is a rectangle along its slope, and a centimetre across 3 m of tops
    // turns the plane by 2 degrees), then the rectangle's axes.
    let axes = [axis, -axis, axis.perp(), -axis.perp()];
    let snapped = uphill.map(|up| {
        axes.into_iter()
            .find(|a| a.dot(up) >= SNAP_DEG.to_radians().cos())
            .unwrap_or(up)
    });
    snapped
        .into_iter()
        .chain(axes)
        .find_map(|dir| along(points, dir, floor, c))
}

/// The ramp along `dir`, if the upper profile's line and the ramp pass (see [`ramp_plane`]).
fn along(points: &[(DVec2, f64)], dir: DVec2, floor: f64, c: &RampConfig) -> Option<RampPlane> {
    let (lo, hi) = (
        c.min_pitch_deg.to_radians().tan(),
        c.max_pitch_deg.to_radians().tan(),
    );
    let bin = c.cell_m;
    // The upper profile along `dir` and its line.
    let (u0, bins) = upper_profile(points, dir, bin);
    let line = fit_line(&bins, bin, c.inlier_m)?;
    // The stretch on the line: from its first to its last bin on it.
    let (seen_from, head_u) = (
        u0 + line.first as f64 * bin,
        u0 + (line.last + 1) as f64 * bin,
    );
    let start_height = line.at_start + line.slope * (line.first as f64 * bin) - floor;
    // A line starting high is a ramp's only where it is long (a low laser beside a ramp).
    let foot_plausible =
        start_height <= c.max_foot_height_m || head_u - seen_from >= c.min_length_high_foot_m;
    if line.slope < lo
        || line.slope > hi
        || (line.inliers as f64) < c.min_inliers * line.filled as f64
        || line.rms_m > c.max_rms_m
        || !foot_plausible
    {
        return None;
    }
    // The foot: where the line meets the floor, no farther before the stretch seen than the
    // stretch is long (a ramp is not mostly unseen).
    let foot_u = seen_from - start_height.max(0.0) / line.slope;
    if seen_from - foot_u > head_u - seen_from {
        return None;
    }
    // Across: the returns on or under the plane along it (its top, its side faces, its head's
    // face a bin beyond the last on the line).
    let (mut v0, mut v1) = (f64::MAX, f64::MIN);
    let plane_at = |u: f64| floor + line.slope * (u - foot_u);
    for &(q, z) in points {
        let u = q.dot(dir);
        if u >= seen_from && u <= head_u + bin && z <= plane_at(u) + c.surface_tolerance_m {
            let v = q.dot(dir.perp());
            (v0, v1) = (v0.min(v), v1.max(v));
        }
    }
    let plane = RampPlane {
        dir,
        u_range: (foot_u, head_u),
        v_range: (v0, v1),
        slope: line.slope,
        floor,
        inliers: line.inliers,
        filled: line.filled,
        rms_m: line.rms_m,
    };
    (head_u - seen_from >= c.min_length_m
        && v1 - v0 >= c.min_width_m
        && plane.rise() >= c.min_rise_m)
        .then_some(plane)
}

/// The uphill direction of the plane through the most cells' tops within `inlier_m` (RANSAC
/// over planes through three tops, a fixed seed, then least squares over its inliers): the
/// ramp's top, or its side face's top edge and its head, with what stands on or beside it
/// left out; `None` for a level or degenerate one.
fn uphill(cells: &[(DVec2, f64)], inlier_m: f64) -> Option<DVec2> {
    if cells.len() < 3 {
        return None;
    }
    let mut rng = cloud::Rng::new(RANSAC_SEED);
    let n = cells.len() as i64;
    let count = |plane: (f64, DVec2)| {
        cells
            .iter()
            .filter(|(q, z)| (z - plane.0 - plane.1.dot(*q)).abs() <= inlier_m)
            .count()
    };
    let mut best: Option<((f64, DVec2), usize)> = None;
    for _ in 0..RANSAC_ROUNDS {
        let pick = [0, 1, 2].map(|_| cells[rng.int(0, n - 1) as usize]);
        let Some(plane) = plane_fit(&pick) else {
            continue;
        };
        let inliers = count(plane);
        if best.is_none_or(|(_, b)| inliers > b) {
            best = Some((plane, inliers));
        }
    }
    let (plane, _) = best?;
    let kept: Vec<(DVec2, f64)> = cells
        .iter()
        .copied()
        .filter(|(q, z)| (z - plane.0 - plane.1.dot(*q)).abs() <= inlier_m)
        .collect();
    plane_fit(&kept)?.1.try_normalize()
}

/// The gradient is turned onto a footprint axis within this (degrees).
const SNAP_DEG: f64 = 10.0;

/// RANSAC's rounds and seed (fixed: the same cloud gives the same map).
const RANSAC_ROUNDS: usize = 200;
const RANSAC_SEED: u64 = 0x5a3c_0e15;

/// The least-squares plane `z = a + g·q` through `(q, z)`: `(a, g)`; `None` if the points are
/// collinear in XY or fewer than 3.
fn plane_fit(pts: &[(DVec2, f64)]) -> Option<(f64, DVec2)> {
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let (mq, mz) = pts
        .iter()
        .fold((DVec2::ZERO, 0.0), |s, p| (s.0 + p.0 / n, s.1 + p.1 / n));
    let (mut sxx, mut sxy, mut syy, mut sxz, mut syz) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (q, z) in pts {
        let (d, z) = (*q - mq, z - mz);
        (sxx, sxy, syy) = (sxx + d.x * d.x, sxy + d.x * d.y, syy + d.y * d.y);
        (sxz, syz) = (sxz + d.x * z, syz + d.y * z);
    }
    let det = sxx * syy - sxy * sxy;
    if det.abs() <= 1e-9 * (sxx * syy).max(1e-12) {
        return None;
    }
    let g = DVec2::new((sxz * syy - syz * sxy) / det, (syz * sxx - sxz * sxy) / det);
    Some((mz - g.dot(mq), g))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plane_through_a_side_face_and_a_head_face_rises_along_the_side() {
        // A ramp rising 0.8 m along +y over 8 m, 3 m wide, seen as its west side face's top
        // edge (x = 0) and its head's face (y = 8), with a box standing on it.
        let mut cells: Vec<(DVec2, f64)> = (0..80)
            .map(|k| (DVec2::new(0.0, k as f64 * 0.1), 0.01 * k as f64))
            .collect();
        cells.extend((0..30).map(|k| (DVec2::new(k as f64 * 0.1, 8.0), 0.8)));
        cells.extend((0..5).map(|k| (DVec2::new(1.5, 4.0 + 0.1 * k as f64), 1.4)));
        let up = uphill(&cells, 0.04).expect("a slope");
        assert!(up.angle_to(DVec2::Y).abs().to_degrees() < 1.0, "{up}");
    }
}
