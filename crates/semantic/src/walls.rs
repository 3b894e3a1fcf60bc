//! Walls: every merged segment is a wall prerequisite (paper, 1.3.2: "for each line segment the
//! orthogonal plane ... is computed; all 3D points which satisfy the condition of distance to
//! [the plane] have the same label"). The vertical plane through the segment gathers the points
//! near it, and the wall is measured from them:
//!
//! 1. Faces: the histogram of the band points' distances to the plane has a peak per observed
//!    face. Each face's points are refitted (total least squares) to correct the Hough angle
//!    quantisation, three times.
//! 2. Free side: a face has free space (floor and ceiling points right in front of it) on one
//!    side and solid wall behind it. Two faces with free space outwards are both sides of one
//!    wall: centre between them, thickness measured. Otherwise only one face was seen: the
//!    centre lies half an assumed thickness behind it (the median measured thickness of the
//!    map's other walls, or `default_thickness_m`).
//! 3. Extent: the face points at every height form runs along the plane; the runs that overlap
//!    the segment (gaps up to `max_gap_m`) give the wall's ends.
//! 4. Height: robust z range of the face points, snapped to floor and ceiling; a prerequisite
//!    that does not come down to the floor (`max_bottom_above_floor_m`) is no wall (a beam, a
//!    pipe, a shelf top).
//!
//! Duplicates (the same wall found twice) merge into the longer one.

use crate::error::{check_range, Result};
use crate::merge::Segment;
use crate::points::{fit_line, median, quantile, undirected_angle_deg, Line2, XyIndex};
use glam::{DVec2, Vec3};
use serde::{Deserialize, Serialize};

/// Configuration of wall identification.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WallConfig {
    /// Points this far either side of a prerequisite's plane are examined.
    pub search_half_width_m: f64,
    /// Points within this distance of a face lie on it.
    pub face_tolerance_m: f64,
    /// Two faces further apart than this are not one wall.
    pub max_thickness_m: f64,
    /// Two faces nearer than this are one face.
    pub min_thickness_m: f64,
    /// Thickness assumed for walls seen from one side when no wall of the map was measured.
    pub default_thickness_m: f64,
    /// Shorter walls are dropped.
    pub min_length_m: f64,
    /// Fewer face points and the prerequisite is dropped.
    pub min_face_points: usize,
    /// Largest gap between face points along one wall.
    pub max_gap_m: f64,
    /// Wall bottoms and tops this near the floor and ceiling are snapped to them.
    pub snap_m: f64,
    /// A wall must come down to this height above the floor.
    pub max_bottom_above_floor_m: f64,
    /// Walls whose lines are this near (and directions within `merge.max_angle_deg`) and that
    /// overlap are one wall.
    pub duplicate_offset_m: f64,
}

impl Default for WallConfig {
    fn default() -> Self {
        WallConfig {
            search_half_width_m: 0.35,
            face_tolerance_m: 0.03,
            max_thickness_m: 0.5,
            min_thickness_m: 0.05,
            default_thickness_m: 0.2,
            min_length_m: 0.5,
            min_face_points: 30,
            max_gap_m: 0.35,
            snap_m: 0.15,
            max_bottom_above_floor_m: 0.6,
            duplicate_offset_m: 0.15,
        }
    }
}

impl WallConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range("walls.search_half_width_m", self.search_half_width_m, 0.01, 10.0, "within 0.01..10 m")?;
        check_range("walls.face_tolerance_m", self.face_tolerance_m, 1e-3, 1.0, "within 0.001..1 m")?;
        check_range("walls.max_thickness_m", self.max_thickness_m, 0.01, 10.0, "within 0.01..10 m")?;
        check_range("walls.min_thickness_m", self.min_thickness_m, 0.0, self.max_thickness_m, "within 0..max_thickness_m")?;
        check_range("walls.default_thickness_m", self.default_thickness_m, 0.01, 10.0, "within 0.01..10 m")?;
        check_range("walls.min_length_m", self.min_length_m, 0.0, 1e4, "within 0..10 km")?;
        check_range("walls.max_gap_m", self.max_gap_m, 0.0, 100.0, "within 0..100 m")?;
        check_range("walls.snap_m", self.snap_m, 0.0, 10.0, "within 0..10 m")?;
        check_range("walls.max_bottom_above_floor_m", self.max_bottom_above_floor_m, 0.0, 100.0, "within 0..100 m")?;
        check_range("walls.duplicate_offset_m", self.duplicate_offset_m, 0.0, 10.0, "within 0..10 m")
    }
}

/// The scene every identification stage works in.
pub(crate) struct Scene<'a> {
    pub points: &'a [Vec3],
    pub index: &'a XyIndex,
    pub floor: f64,
    pub ceiling: f64,
    pub band: (f64, f64),
}

impl Scene<'_> {
    fn xy(&self, i: usize) -> DVec2 {
        DVec2::new(self.points[i].x as f64, self.points[i].y as f64)
    }

    fn z(&self, i: usize) -> f64 {
        self.points[i].z as f64
    }

    /// True for a point on the floor or the ceiling.
    pub fn on_slab(&self, i: usize, tol: f64) -> bool {
        let z = self.z(i);
        (z - self.floor).abs() <= tol || (z - self.ceiling).abs() <= tol
    }
}

/// A measured wall.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct WallFit {
    /// Centre line; `origin` is the wall's start, `at(length)` its end.
    pub line: Line2,
    pub length: f64,
    pub thickness: f64,
    pub measured: bool,
    /// Observed faces' offsets from the centre line (left positive).
    pub faces: Vec<f64>,
    /// For a one-sided wall: the side (+1 left, -1 right) of the free space in front of its face.
    pub free_side: f64,
    pub z_range: (f64, f64),
    pub support: u64,
    pub coverage: f64,
    pub rules: Vec<String>,
}

impl WallFit {
    pub fn start(&self) -> DVec2 {
        self.line.origin
    }

    pub fn end(&self) -> DVec2 {
        self.line.at(self.length)
    }
}

/// Measures every prerequisite and returns the walls, duplicates merged, thickness of
/// one-sided walls resolved.
pub(crate) fn identify_walls(segments: &[Segment], sc: &Scene, c: &WallConfig, max_angle_deg: f64) -> Vec<WallFit> {
    let mut walls: Vec<WallFit> = segments.iter().filter_map(|s| fit_wall(s, sc, c)).collect();
    walls.sort_by(|a, b| b.length.total_cmp(&a.length));
    let mut kept: Vec<WallFit> = Vec::new();
    for w in walls {
        if let Some(k) = kept.iter_mut().find(|k| duplicate(k, &w, c, max_angle_deg)) {
            let (a, b) = (k.line.coords(w.start()).0, k.line.coords(w.end()).0);
            let lo = a.min(b).min(0.0);
            let hi = a.max(b).max(k.length);
            k.line.origin = k.line.at(lo);
            k.length = hi - lo;
            k.support += w.support;
            k.rules.push("merged with a duplicate prerequisite".into());
            continue;
        }
        kept.push(w);
    }
    let mut measured: Vec<f64> = kept.iter().filter(|w| w.measured).map(|w| w.thickness).collect();
    let assumed = median(&mut measured).unwrap_or(c.default_thickness_m);
    for w in &mut kept {
        if !w.measured {
            // The line is the face; the centre lies half a thickness behind it.
            w.line = w.line.shifted(-w.free_side * assumed / 2.0);
            w.faces = vec![w.free_side * assumed / 2.0];
            w.thickness = assumed;
            w.rules.push(format!(
                "one face seen: centre {:.3} m behind it (assumed thickness {:.3} m, the median of the measured walls or the default)",
                assumed / 2.0,
                assumed
            ));
        }
    }
    kept.retain(|w| w.length >= c.min_length_m);
    kept
}

fn duplicate(k: &WallFit, w: &WallFit, c: &WallConfig, max_angle_deg: f64) -> bool {
    if undirected_angle_deg(k.line.dir, w.line.dir) > max_angle_deg {
        return false;
    }
    let tol = c.duplicate_offset_m + (k.thickness + w.thickness) / 4.0;
    let (sa, da) = k.line.coords(w.start());
    let (sb, db) = k.line.coords(w.end());
    if da.abs() > tol || db.abs() > tol {
        return false;
    }
    let (lo, hi) = (sa.min(sb), sa.max(sb));
    let overlap = hi.min(k.length) - lo.max(0.0);
    overlap >= 0.5 * w.length.min(k.length) || overlap > -c.max_gap_m
}

/// Peaks of the distance histogram (1 cm bins over `[-hw, hw]`): offsets and counts, strongest
/// first.
fn face_peaks(ds: &[f64], hw: f64, c: &WallConfig) -> Vec<(f64, usize)> {
    let bin = 0.01;
    let n = ((2.0 * hw / bin).ceil() as usize).max(1);
    let mut h = vec![0usize; n];
    for d in ds {
        let b = ((d + hw) / bin).floor();
        if b >= 0.0 && (b as usize) < n {
            h[b as usize] += 1;
        }
    }
    let w = ((c.face_tolerance_m / bin).round() as usize).max(1);
    let s: Vec<usize> = (0..n)
        .map(|i| h[i.saturating_sub(w)..(i + w + 1).min(n)].iter().sum())
        .collect();
    let max = s.iter().copied().max().unwrap_or(0);
    let floor = (max / 8).max(c.min_face_points / 3).max(1);
    let mut peaks: Vec<(f64, usize)> = (0..n)
        .filter(|&i| s[i] >= floor && (i == 0 || s[i] > s[i - 1]) && (i + 1 == n || s[i] >= s[i + 1]))
        .map(|i| (-hw + (i as f64 + 0.5) * bin, s[i]))
        .collect();
    peaks.sort_by(|a, b| b.1.cmp(&a.1));
    // Refine each peak to the mean of its points.
    peaks
        .into_iter()
        .map(|(o, n)| {
            let near: Vec<f64> = ds.iter().copied().filter(|d| (d - o).abs() <= c.face_tolerance_m).collect();
            let mean = if near.is_empty() { o } else { near.iter().sum::<f64>() / near.len() as f64 };
            (mean, n)
        })
        .collect()
}

/// The faces of a wall: one, or two separated by a plausible thickness.
fn pick_faces(peaks: &[(f64, usize)], c: &WallConfig) -> Vec<f64> {
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

fn fit_wall(seg: &Segment, sc: &Scene, c: &WallConfig) -> Option<WallFit> {
    let len0 = seg.length_m();
    let hw = c.search_half_width_m;
    let mut line = seg.line();
    let mut faces = Vec::new();
    let in_band = |z: f64| z >= sc.band.0 && z <= sc.band.1;
    for _ in 0..3 {
        let mut near: Vec<(usize, f64)> = Vec::new();
        sc.index.for_each_near_line(sc.points, &line, -0.1, len0 + 0.1, hw, |i, _, d| {
            if in_band(sc.z(i)) {
                near.push((i, d));
            }
        });
        if near.len() < c.min_face_points {
            return None;
        }
        let ds: Vec<f64> = near.iter().map(|n| n.1).collect();
        faces = pick_faces(&face_peaks(&ds, hw, c), c);
        // Refit the direction on each face's points, weighted by their counts.
        let mut dir = DVec2::ZERO;
        let mut centre = DVec2::ZERO;
        let mut total = 0.0;
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
        // Keep the segment's extent: the new origin is seg.a projected onto the new line.
        let s_a = (seg.a() - centre).dot(dir);
        line = Line2 {
            origin: centre + dir * s_a,
            dir,
        };
    }
    // Final face offsets relative to the refined line.
    let mut ds = Vec::new();
    sc.index.for_each_near_line(sc.points, &line, -0.1, len0 + 0.1, hw, |i, _, d| {
        if in_band(sc.z(i)) {
            ds.push(d);
        }
    });
    faces = pick_faces(&face_peaks(&ds, hw, c), c);
    if faces.is_empty() {
        return None;
    }
    let tol = c.face_tolerance_m;
    let on_face = |d: f64, faces: &[f64]| faces.iter().any(|f| (d - f).abs() <= tol);
    let z_lo = sc.floor + 0.05;
    let z_hi = sc.ceiling - 0.05;
    // Extent: runs of face points along the line, grown while they reach the search's ends.
    let (mut e0, mut e1) = (0.5f64, 0.5f64);
    let mut found = None;
    for _ in 0..8 {
        let mut s_vals = Vec::new();
        sc.index.for_each_near_line(sc.points, &line, -e0, len0 + e1, hw, |i, s, d| {
            let z = sc.z(i);
            if z >= z_lo && z <= z_hi && on_face(d, &faces) {
                s_vals.push(s);
            }
        });
        s_vals.sort_by(f64::total_cmp);
        let Some((lo, hi)) = extent(&s_vals, 0.0, len0, c.max_gap_m) else {
            return None;
        };
        let grow_lo = lo <= -e0 + c.max_gap_m;
        let grow_hi = hi >= len0 + e1 - c.max_gap_m;
        found = Some((lo, hi));
        if !grow_lo && !grow_hi {
            break;
        }
        if grow_lo {
            e0 *= 3.0;
        }
        if grow_hi {
            e1 *= 3.0;
        }
    }
    let (lo, hi) = found?;
    // Face points over the final extent: support, coverage, heights, free sides.
    let mut zs = Vec::new();
    let mut bins = vec![false; (((hi - lo) / 0.1).ceil() as usize).clamp(1, 1_000_000)];
    let mut front = vec![[0usize; 2]; faces.len()];
    let strip = (0.02, 0.10);
    sc.index.for_each_near_line(sc.points, &line, lo, hi, hw + strip.1, |i, s, d| {
        let z = sc.z(i);
        if z >= z_lo && z <= z_hi && on_face(d, &faces) {
            zs.push(z);
            let b = (((s - lo) / 0.1) as usize).min(bins.len() - 1);
            bins[b] = true;
        }
        if sc.on_slab(i, 0.04) {
            for (k, f) in faces.iter().enumerate() {
                let off = d - f;
                if off.abs() >= strip.0 && off.abs() <= strip.1 {
                    front[k][usize::from(off > 0.0)] += 1;
                }
            }
        }
    });
    if zs.len() < c.min_face_points {
        return None;
    }
    let support = zs.len() as u64;
    let bottom = quantile(&mut zs, 0.01)?;
    let top = quantile(&mut zs, 0.99)?;
    if bottom > sc.floor + c.max_bottom_above_floor_m {
        return None;
    }
    let snap = |v: f64, to: f64| if (v - to).abs() <= c.snap_m { to } else { v };
    let z_range = (snap(bottom, sc.floor), snap(top, sc.ceiling));
    let coverage = bins.iter().filter(|&&b| b).count() as f64 / bins.len() as f64;
    // Free side of each face: +1 if the free space is to its left, -1 right, 0 unknown.
    let side = |k: usize| -> f64 {
        let [right, left] = front[k];
        if left >= 2 * right + 3 {
            1.0
        } else if right >= 2 * left + 3 {
            -1.0
        } else {
            0.0
        }
    };
    let start = line.at(lo);
    let mut rules = vec![format!(
        "vertical plane through a {len0:.2} m projection segment; face points over {:.2} m ({:.0} % covered)",
        hi - lo,
        coverage * 100.0
    )];
    let mut fit = WallFit {
        line: Line2 { origin: start, dir: line.dir },
        length: hi - lo,
        thickness: 0.0,
        measured: false,
        faces: Vec::new(),
        free_side: 0.0,
        z_range,
        support,
        coverage,
        rules: Vec::new(),
    };
    if let [f1, f2] = faces[..] {
        let (s1, s2) = (side(0), side(1));
        if s1 <= 0.0 && s2 >= 0.0 && s1 != s2 {
            let mid = (f1 + f2) / 2.0;
            fit.line = fit.line.shifted(mid);
            fit.thickness = f2 - f1;
            fit.measured = true;
            fit.faces = vec![f1 - mid, f2 - mid];
            rules.push(format!(
                "two faces {:.3} m apart with free space outside both: thickness measured",
                f2 - f1
            ));
        }
    }
    if !fit.measured {
        // One face: the one with free space in front of it (else the first, the strongest).
        let k = (0..faces.len()).find(|&k| side(k) != 0.0).unwrap_or(0);
        let mut s = side(k);
        if s == 0.0 {
            // No floor or ceiling seen beside it: assume the free space faces the cloud's bulk.
            s = 1.0;
            rules.push("free side of the face unknown (no floor or ceiling points beside it)".into());
        }
        fit.line = fit.line.shifted(faces[k]);
        fit.free_side = s;
    }
    rules.push(format!(
        "stands from z {:.2} to {:.2} m (floor {:.2}, ceiling {:.2})",
        z_range.0, z_range.1, sc.floor, sc.ceiling
    ));
    fit.rules = rules;
    Some(fit)
}

/// The union of the runs of sorted `s` (gaps at most `max_gap`) that overlap `[a, b]`.
fn extent(s: &[f64], a: f64, b: f64, max_gap: f64) -> Option<(f64, f64)> {
    let mut runs: Vec<(f64, f64)> = Vec::new();
    for &v in s {
        match runs.last_mut() {
            Some(r) if v - r.1 <= max_gap => r.1 = v,
            _ => runs.push((v, v)),
        }
    }
    let hits: Vec<&(f64, f64)> = runs.iter().filter(|r| r.1 >= a && r.0 <= b).collect();
    let lo = hits.iter().map(|r| r.0).fold(f64::INFINITY, f64::min);
    let hi = hits.iter().map(|r| r.1).fold(f64::NEG_INFINITY, f64::max);
    (lo < hi).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extent_joins_runs_over_the_segment_only() {
        let s = [-3.0, -2.9, 0.1, 0.2, 0.4, 1.0, 1.1, 2.5, 2.6];
        assert_eq!(extent(&s, 0.0, 1.0, 0.35), Some((0.1, 1.1)));
        assert_eq!(extent(&s, 0.0, 2.55, 0.35), Some((0.1, 2.6)));
        assert_eq!(extent(&[], 0.0, 1.0, 0.35), None);
    }

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
