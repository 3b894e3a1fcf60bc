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

/// Length of the stretches along a wall over which [`pick_faces`] compares two faces' cover.
const STRETCH_M: f64 = 0.1;

/// A wall's faces as the distance histogram of the points near it shows them.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Faces {
    /// Offsets from the line of the wall's faces: one, or two separated by a plausible
    /// thickness (ascending).
    pub wall: Vec<f64>,
    /// A peak at a plausible thickness from the first face whose points run along too little
    /// of it to be the wall's far face: something standing against the wall (a cabinet, a
    /// person, a car's flank). Its points bridge gaps in the wall's face (what stands there
    /// hides it), but do not carry the wall's ends beyond its own face.
    pub stray: Option<f64>,
}

/// The faces of a wall from the histogram's `peaks` of the points `near` it (`(along,
/// across)`): the strongest, and a second at a plausible thickness from it whose points run
/// along at least a third of the stretches the first face's points cover. The strongest
/// peak at a plausible thickness that runs along less is [`Faces::stray`].
pub(crate) fn pick_faces(peaks: &[(f64, usize)], near: &[(f64, f64)], c: &WallConfig) -> Faces {
    let Some(&(first, _)) = peaks.first() else {
        return Faces {
            wall: Vec::new(),
            stray: None,
        };
    };
    let stretches = |face: f64| {
        let mut s: Vec<i64> = near
            .iter()
            .filter(|(_, d)| (d - face).abs() <= c.face_tolerance_m)
            .map(|(s, _)| (s / STRETCH_M).floor() as i64)
            .collect();
        s.sort_unstable();
        s.dedup();
        s.len()
    };
    let first_cover = stretches(first);
    let plausible = peaks.iter().skip(1).map(|p| p.0).filter(|o| {
        let t = (o - first).abs();
        t >= c.min_thickness_m && t <= c.max_thickness_m
    });
    let mut stray = None;
    let mut second = None;
    for o in plausible {
        if 3 * stretches(o) >= first_cover {
            second = Some(o);
            break;
        }
        stray = stray.or(Some(o));
    }
    let wall = match second {
        Some(o) => vec![first.min(o), first.max(o)],
        None => vec![first],
    };
    Faces { wall, stray }
}

/// The faces of the wall along `line` over `[a, b]` from the band points, and the line refitted
/// on the wall's faces (three rounds); `None` if too few points.
pub(crate) fn refine_line(
    mut line: Line2,
    a: f64,
    b: f64,
    sc: &Scene,
    c: &WallConfig,
) -> Option<(Line2, Faces)> {
    let hw = c.search_half_width_m;
    let in_band = |z: f64| z >= sc.band.0 && z <= sc.band.1;
    let anchor = line.origin;
    for _ in 0..3 {
        let mut near: Vec<(usize, f64)> = Vec::new();
        let mut along: Vec<(f64, f64)> = Vec::new();
        sc.band_index
            .for_each_near_line(&line, a - 0.1, b + 0.1, hw, |i, s, d, z| {
                if in_band(z) {
                    near.push((i, d));
                    along.push((s, d));
                }
            });
        if near.len() < c.min_face_points {
            return None;
        }
        let ds: Vec<f64> = near.iter().map(|n| n.1).collect();
        let faces = pick_faces(&face_peaks(&ds, hw, c), &along, c).wall;
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
    let mut along = Vec::new();
    sc.band_index
        .for_each_near_line(&line, a - 0.1, b + 0.1, hw, |_, s, d, z| {
            if in_band(z) {
                along.push((s, d));
            }
        });
    let ds: Vec<f64> = along.iter().map(|p| p.1).collect();
    let faces = pick_faces(&face_peaks(&ds, hw, c), &along, c);
    (!faces.wall.is_empty()).then_some((line, faces))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn faces_of(near: &[(f64, f64)]) -> Faces {
        let c = WallConfig::default();
        let ds: Vec<f64> = near.iter().map(|p| p.1).collect();
        pick_faces(&face_peaks(&ds, 0.35, &c), near, &c)
    }

    #[test]
    fn picks_two_faces_at_a_plausible_distance() {
        let mut near = Vec::new();
        for k in 0..200 {
            let s = k as f64 * 0.01;
            near.push((s, -0.1 + (k % 3) as f64 * 0.002));
            if k % 2 == 0 {
                near.push((s, 0.08 + (k % 5) as f64 * 0.002));
            }
        }
        let faces = faces_of(&near).wall;
        assert_eq!(faces.len(), 2);
        assert!((faces[1] - faces[0] - 0.182).abs() < 0.01, "{faces:?}");
    }

    /// Regression (garage-193): a person standing 0.27 m off a wall's face beside its end made
    /// a histogram peak at a plausible thickness, taken for the wall's far face.
    #[test]
    fn returns_beside_a_few_stretches_of_a_face_are_no_second_face() {
        // A 3.4 m face, and 90 returns 0.27 m off it over 0.27 m of its length.
        let mut near: Vec<(f64, f64)> = (0..680)
            .map(|k| (k as f64 * 0.005, (k % 3) as f64 * 0.002))
            .collect();
        near.extend((0..90).map(|k| (3.1 + k as f64 * 0.003, 0.27 + (k % 4) as f64 * 0.002)));
        let faces = faces_of(&near);
        assert_eq!(faces.wall.len(), 1, "{faces:?}");
        assert!(
            faces.stray.is_some_and(|o| (o - 0.27).abs() < 0.02),
            "{faces:?}"
        );
        // The same far face along 2 m of the wall is one.
        near.extend((0..200).map(|k| (k as f64 * 0.01, 0.27 + (k % 4) as f64 * 0.002)));
        let faces = faces_of(&near);
        assert_eq!(faces.wall.len(), 2, "{faces:?}");
    }
}
