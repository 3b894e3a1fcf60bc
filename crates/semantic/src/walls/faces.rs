//! Wall faces: the peaks of the distance histogram of the points near a prerequisite's plane
//! (one per observed face), and the plane refitted on them to correct the Hough transform's
//! angle quantisation (see the `walls` module).

use super::WallConfig;
use crate::points::{fit_line, window_counts, Line2};
use crate::scene::Scene;
use glam::DVec2;

/// Peaks of the distance histogram (1 cm bins over `[-hw, hw]`): offsets and counts, strongest
/// first.
pub(crate) fn face_peaks(ds: &[f64], hw: f64, c: &WallConfig) -> Vec<(f64, usize)> {
    let bin = 0.01;
    let n = ((2.0 * hw / bin).ceil() as usize).max(1);
    let w = ((c.face_tolerance_m / bin).round() as usize).max(1);
    let s = window_counts(ds, -hw, bin, n, w);
    let max = s.iter().copied().max().unwrap_or(0);
    let floor = (max / 8).max(c.min_face_points / 3).max(1);
    let mut peaks: Vec<(f64, usize)> = (0..n)
        .filter(|&i| {
            s[i] >= floor && (i == 0 || s[i] > s[i - 1]) && (i + 1 == n || s[i] >= s[i + 1])
        })
        .map(|i| (-hw + (i as f64 + 0.5) * bin, s[i]))
        .collect();
    peaks.sort_by_key(|p| std::cmp::Reverse(p.1));
    // Refine each peak to the mean of its points (one pass over the points: each adds to the
    // peaks within the tolerance of it, the peaks' bins in order).
    let tol = c.face_tolerance_m;
    let mut by_offset: Vec<usize> = (0..peaks.len()).collect();
    by_offset.sort_by(|&i, &j| peaks[i].0.total_cmp(&peaks[j].0));
    // (from -0.0, as `Iterator::sum` of floats starts)
    let mut sums = vec![(-0.0f64, 0usize); peaks.len()];
    for &d in ds {
        let first = by_offset.partition_point(|&k| peaks[k].0 < d - tol - bin);
        for &k in by_offset[first..]
            .iter()
            .take_while(|&&k| peaks[k].0 <= d + tol + bin)
        {
            if (d - peaks[k].0).abs() <= tol {
                sums[k].0 += d;
                sums[k].1 += 1;
            }
        }
    }
    peaks
        .iter()
        .zip(&sums)
        .map(|(&(o, n), &(sum, count))| {
            let mean = if count == 0 { o } else { sum / count as f64 };
            (mean, n)
        })
        .collect()
}

/// The faces of a wall: one, or two separated by a plausible thickness.
pub(crate) fn pick_faces(peaks: &[(f64, usize)], c: &WallConfig) -> Vec<f64> {
    let Some(&(first, _)) = peaks.first() else {
        return Vec::new();
    };
    let second = peaks.iter().skip(1).find(|(o, _)| {
        let t = (o - first).abs();
        t >= c.min_thickness_m && t <= c.max_thickness_m
    });
    match second {
        Some(&(o, _)) => vec![first.min(o), first.max(o)],
        None => vec![first],
    }
}

/// The faces of the wall along `line` over `[a, b]` from the band points, and the line refitted
/// on them (three rounds); `None` if too few points.
pub(crate) fn refine_line(
    mut line: Line2,
    a: f64,
    b: f64,
    sc: &Scene,
    c: &WallConfig,
) -> Option<(Line2, Vec<f64>)> {
    let hw = c.search_half_width_m;
    let in_band = |z: f64| z >= sc.band.0 && z <= sc.band.1;
    let anchor = line.origin;
    for _ in 0..3 {
        let mut near: Vec<(usize, f64)> = Vec::new();
        sc.band_index
            .for_each_near_line(&line, a - 0.1, b + 0.1, hw, |i, _, d, z| {
                if in_band(z) {
                    near.push((i, d));
                }
            });
        if near.len() < c.min_face_points {
            return None;
        }
        let ds: Vec<f64> = near.iter().map(|n| n.1).collect();
        let faces = pick_faces(&face_peaks(&ds, hw, c), c);
        // Refit the direction on each face's points, weighted by their counts.
        let (mut dir, mut centre, mut total) = (DVec2::ZERO, DVec2::ZERO, 0.0);
        for f in &faces {
            let pts: Vec<DVec2> = near
                .iter()
                .filter(|(_, d)| (d - f).abs() <= c.face_tolerance_m)
                .map(|&(i, _)| sc.xy(i))
                .collect();
            if let Some((cen, d)) = fit_line(&pts) {
                let d = if d.dot(line.dir) < 0.0 { -d } else { d };
                let wgt = pts.len() as f64;
                dir += d * wgt;
                centre += (cen - line.normal() * *f) * wgt;
                total += wgt;
            }
        }
        if total < c.min_face_points as f64 || dir.length() < 1e-9 {
            return None;
        }
        let dir = dir.normalize();
        let centre = centre / total;
        line = Line2 {
            origin: centre + dir * (anchor - centre).dot(dir),
            dir,
        };
    }
    let mut ds = Vec::new();
    sc.band_index
        .for_each_near_line(&line, a - 0.1, b + 0.1, hw, |_, _, d, z| {
            if in_band(z) {
                ds.push(d);
            }
        });
    let faces = pick_faces(&face_peaks(&ds, hw, c), c);
    (!faces.is_empty()).then_some((line, faces))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn picks_two_faces_at_a_plausible_distance() {
        let c = WallConfig::default();
        let mut ds = Vec::new();
        for k in 0..200 {
            ds.push(-0.1 + (k % 3) as f64 * 0.002);
            if k % 2 == 0 {
                ds.push(0.08 + (k % 5) as f64 * 0.002);
            }
        }
        let faces = pick_faces(&face_peaks(&ds, 0.35, &c), &c);
        assert_eq!(faces.len(), 2);
        assert!((faces[1] - faces[0] - 0.182).abs() < 0.01, "{faces:?}");
    }
}
