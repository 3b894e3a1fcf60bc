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
//!    the segment (gaps up to `max_gap_m`) give the wall's ends. Where another surface crosses
//!    the plane (points off the faces spread over 15 cm or more across it, within 3 cm along
//!    it: the face of a wall meeting this one), the face points belong to the corner and do
//!    not extend the wall, so a wall ends at the face of the wall it meets.
//! 4. Height: robust z range of the face points, snapped to floor and ceiling; a prerequisite
//!    that does not come down to the floor (`max_bottom_above_floor_m`) or up to the ceiling
//!    (`max_top_below_ceiling_m`) is no wall (a beam, a pipe, a door leaf, a cupboard).
//!
//! Duplicates (the same wall found twice) merge into the longer one. Collinear walls join
//! across a stretch of up to `max_join_gap_m` through which nothing was seen: a wall runs on
//! behind the partitions that meet it and the furniture that hid it.

use crate::error::{check_range, Result};
use crate::merge::Segment;
use crate::points::{fit_line, median, quantile, undirected_angle_deg, Line2, XyIndex};
use glam::{DVec2, Vec3};
use rayon::prelude::*;
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
    /// ... and reach up to this depth under the ceiling along 30 % of its length at least (a
    /// cupboard does not; a prerequisite that turns out to be a door leaf is dropped later).
    pub max_top_below_ceiling_m: f64,
    /// Collinear walls this far apart are one wall if nothing was seen through the gap.
    pub max_join_gap_m: f64,
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
            max_bottom_above_floor_m: 1.5,
            max_top_below_ceiling_m: 0.3,
            max_join_gap_m: 2.0,
            duplicate_offset_m: 0.15,
        }
    }
}

impl WallConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "walls.search_half_width_m",
            self.search_half_width_m,
            0.01,
            10.0,
            "within 0.01..10 m",
        )?;
        check_range(
            "walls.face_tolerance_m",
            self.face_tolerance_m,
            1e-3,
            1.0,
            "within 0.001..1 m",
        )?;
        check_range(
            "walls.max_thickness_m",
            self.max_thickness_m,
            0.01,
            10.0,
            "within 0.01..10 m",
        )?;
        check_range(
            "walls.min_thickness_m",
            self.min_thickness_m,
            0.0,
            self.max_thickness_m,
            "within 0..max_thickness_m",
        )?;
        check_range(
            "walls.default_thickness_m",
            self.default_thickness_m,
            0.01,
            10.0,
            "within 0.01..10 m",
        )?;
        check_range(
            "walls.min_length_m",
            self.min_length_m,
            0.0,
            1e4,
            "within 0..10 km",
        )?;
        check_range(
            "walls.max_gap_m",
            self.max_gap_m,
            0.0,
            100.0,
            "within 0..100 m",
        )?;
        check_range("walls.snap_m", self.snap_m, 0.0, 10.0, "within 0..10 m")?;
        check_range(
            "walls.max_bottom_above_floor_m",
            self.max_bottom_above_floor_m,
            0.0,
            100.0,
            "within 0..100 m",
        )?;
        check_range(
            "walls.max_top_below_ceiling_m",
            self.max_top_below_ceiling_m,
            0.0,
            100.0,
            "within 0..100 m",
        )?;
        check_range(
            "walls.max_join_gap_m",
            self.max_join_gap_m,
            0.0,
            100.0,
            "within 0..100 m",
        )?;
        check_range(
            "walls.duplicate_offset_m",
            self.duplicate_offset_m,
            0.0,
            10.0,
            "within 0..10 m",
        )
    }
}

/// The scene every identification stage works in.
pub(crate) struct Scene<'a> {
    pub points: &'a [Vec3],
    /// All points.
    pub index: &'a XyIndex,
    /// The points off the floor and ceiling (within 5 cm of neither).
    pub upright: &'a XyIndex,
    /// The points in the projection band.
    pub band_index: &'a XyIndex,
    pub floor: f64,
    pub ceiling: f64,
    pub band: (f64, f64),
    /// The middle of the cloud (XY).
    pub middle: DVec2,
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
pub(crate) fn identify_walls(
    segments: &[Segment],
    sc: &Scene,
    c: &WallConfig,
    max_angle_deg: f64,
) -> Vec<WallFit> {
    // A prerequisite lying inside a longer one's slab (a wall's other face, a skeleton spur) would
    // only find the same wall again: skip it.
    let mut order: Vec<&Segment> = segments.iter().collect();
    order.sort_by(|a, b| b.length_m().total_cmp(&a.length_m()));
    let mut unique: Vec<&Segment> = Vec::new();
    for s in order {
        let inside = unique.iter().any(|u| {
            let line = u.line();
            let reach = c.duplicate_offset_m + c.max_thickness_m / 2.0;
            undirected_angle_deg(line.dir, s.line().dir) <= max_angle_deg
                && [s.a(), s.b()].iter().all(|p| {
                    let (t, d) = line.coords(*p);
                    d.abs() <= reach && t >= -0.3 && t <= u.length_m() + 0.3
                })
        });
        if !inside {
            unique.push(s);
        }
    }
    let mut walls: Vec<WallFit> = unique
        .par_iter()
        .filter_map(|s| fit_wall(s, sc, c))
        .collect();
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
    merge_through_gaps(&mut kept, sc, c, max_angle_deg);
    let mut measured: Vec<f64> = kept
        .iter()
        .filter(|w| w.measured)
        .map(|w| w.thickness)
        .collect();
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

/// Joins collinear walls across a gap of up to `max_join_gap_m` through which the scans saw
/// nothing (no floor within a two-sided wall's footprint, nothing behind a one-sided wall's
/// face): a wall runs on behind the partitions that meet it and behind whatever hid it, while
/// a real gap (a corridor between two rooms' walls) shows its floor.
fn merge_through_gaps(walls: &mut Vec<WallFit>, sc: &Scene, c: &WallConfig, max_angle_deg: f64) {
    loop {
        let mut join = None;
        'search: for i in 0..walls.len() {
            for j in 0..walls.len() {
                if i == j {
                    continue;
                }
                let (a, b) = (&walls[i], &walls[j]);
                if undirected_angle_deg(a.line.dir, b.line.dir) > max_angle_deg {
                    continue;
                }
                let tol = c.duplicate_offset_m + (a.thickness + b.thickness) / 4.0;
                let (s0, d0) = a.line.coords(b.start());
                let (s1, d1) = a.line.coords(b.end());
                if d0.abs() > tol || d1.abs() > tol {
                    continue;
                }
                // b must start after a ends, within the gap.
                let (lo, hi) = (s0.min(s1), s0.max(s1));
                let gap = lo - a.length;
                if gap > 0.0 && gap <= c.max_join_gap_m && !seen_through(a, a.length, lo, sc) {
                    join = Some((i, j, hi, gap));
                    break 'search;
                }
            }
        }
        let Some((i, j, hi, gap)) = join else {
            return;
        };
        let b = walls.remove(j);
        let a = &mut walls[if j < i { i - 1 } else { i }];
        a.coverage = (a.coverage * a.length + b.coverage * b.length) / hi.max(1e-9);
        a.length = hi;
        a.support += b.support;
        a.rules.push(format!(
            "joined with a collinear piece across {gap:.2} m through which nothing was seen"
        ));
    }
}

/// True if the scans saw through wall `w` between `s0` and `s1` along it: floor within its
/// footprint (two faces), or anything behind its face (one face; `w.line` is the face here).
fn seen_through(w: &WallFit, s0: f64, s1: f64, sc: &Scene) -> bool {
    let mut n = 0;
    sc.index.for_each_near_line(
        sc.points,
        &w.line,
        s0 + 0.05,
        s1 - 0.05,
        w.thickness / 2.0 + 1.0,
        |i, _, d| {
            let z = sc.z(i);
            let hit = if w.measured {
                (z - sc.floor).abs() <= 0.04 && d.abs() <= w.thickness / 2.0 - 0.02
            } else {
                let behind = -w.free_side * d;
                behind >= 0.05 && z >= sc.floor - 0.05 && z <= sc.ceiling - 0.05
            };
            n += usize::from(hit);
        },
    );
    n >= 5
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
        .filter(|&i| {
            s[i] >= floor && (i == 0 || s[i] > s[i - 1]) && (i + 1 == n || s[i] >= s[i + 1])
        })
        .map(|i| (-hw + (i as f64 + 0.5) * bin, s[i]))
        .collect();
    peaks.sort_by_key(|p| std::cmp::Reverse(p.1));
    // Refine each peak to the mean of its points.
    peaks
        .into_iter()
        .map(|(o, n)| {
            let near: Vec<f64> = ds
                .iter()
                .copied()
                .filter(|d| (d - o).abs() <= c.face_tolerance_m)
                .collect();
            let mean = if near.is_empty() {
                o
            } else {
                near.iter().sum::<f64>() / near.len() as f64
            };
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

/// The faces of the wall along `line` over `[a, b]` from the band points, and the line refitted
/// on them (three rounds); `None` if too few points.
fn refine_line(
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
            .for_each_near_line(sc.points, &line, a - 0.1, b + 0.1, hw, |i, _, d| {
                if in_band(sc.z(i)) {
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
        .for_each_near_line(sc.points, &line, a - 0.1, b + 0.1, hw, |i, _, d| {
            if in_band(sc.z(i)) {
                ds.push(d);
            }
        });
    let faces = pick_faces(&face_peaks(&ds, hw, c), c);
    (!faces.is_empty()).then_some((line, faces))
}

/// A wall's extent along `line` from `[a, b]` (see the module docs), grown while it reaches the
/// searched range's ends, and the corner regions `(s0, s1, z0, z1)` where a crossing surface
/// hides the face points.
#[allow(clippy::type_complexity)]
fn find_extent(
    line: &Line2,
    faces: &[f64],
    a: f64,
    b: f64,
    sc: &Scene,
    c: &WallConfig,
) -> Option<(f64, f64, Vec<(f64, f64, f64, f64)>)> {
    let hw = c.search_half_width_m;
    let tol = c.face_tolerance_m;
    let on_face = |d: f64| faces.iter().any(|f| (d - f).abs() <= tol);
    let (z_lo, z_hi) = (sc.floor + 0.05, sc.ceiling - 0.05);
    let (f_lo, f_hi) = (faces[0] - 2.0 * tol, faces[faces.len() - 1] + 2.0 * tol);
    let (mut e0, mut e1) = (0.5f64, 0.5f64);
    let mut found = None;
    for _ in 0..8 {
        // Face points, and per 3 cm of the line the spread of the points off the faces: a
        // surface across the line (another wall's face at a corner or junction) covers many
        // distances; the face points there belong to the corner, not to this wall's extent.
        let bin = 0.03;
        let (r0, r1) = (a - e0, b + e1);
        let nb = (((r1 - r0) / bin).ceil() as usize + 1).min(10_000_000);
        let mut across = vec![(0u32, f64::INFINITY, f64::NEG_INFINITY); nb];
        let mut face_pts = Vec::new();
        sc.upright
            .for_each_near_line(sc.points, line, r0, r1, hw, |i, s, d| {
                let z = sc.z(i);
                if z < z_lo || z > z_hi {
                    return;
                }
                let k = (((s - r0) / bin) as usize).min(nb - 1);
                if on_face(d) {
                    face_pts.push((k, s, z));
                } else if d < f_lo || d > f_hi {
                    let x = &mut across[k];
                    x.0 |= 1 << ((((d + hw) / bin) as usize).min(31));
                    x.1 = x.1.min(z);
                    x.2 = x.2.max(z);
                }
            });
        // A crossing surface hides the face points at its own heights only (a cupboard in
        // front of a wall leaves the wall above it).
        // Noise spreads a crossing surface into the neighbouring bins: they are hidden too.
        let hidden = |k: usize, z: f64| {
            (k.saturating_sub(1)..(k + 2).min(nb)).any(|j| {
                let x = &across[j];
                x.0.count_ones() >= 5 && z >= x.1 - 0.1 && z <= x.2 + 0.1
            })
        };
        let s_vals: Vec<f64> = face_pts
            .iter()
            .filter(|(k, _, z)| !hidden(*k, *z))
            .map(|p| p.1)
            .collect();
        let (lo, hi) = extent(&s_vals, a, b, c.max_gap_m)?;
        let grow_lo = lo <= r0 + c.max_gap_m;
        let grow_hi = hi >= r1 - c.max_gap_m;
        let crossing: Vec<(f64, f64, f64, f64)> = across
            .iter()
            .enumerate()
            .filter(|(_, m)| m.0.count_ones() >= 5)
            .map(|(k, m)| {
                (
                    r0 + k as f64 * bin,
                    r0 + (k + 1) as f64 * bin,
                    m.1 - 0.1,
                    m.2 + 0.1,
                )
            })
            .collect();
        // An end next to a wall-high crossing surface (the hidden bins keep it a few
        // centimetres off) is a corner: the wall ends at the surface.
        let snap = |end: f64| {
            crossing
                .iter()
                .filter(|x| x.3 - x.2 >= 1.5)
                .map(|x| (x.0 + x.1) / 2.0)
                .filter(|m| (m - end).abs() <= 0.15)
                .min_by(|p, q| (p - end).abs().total_cmp(&(q - end).abs()))
                .unwrap_or(end)
        };
        let (lo, hi) = (snap(lo), snap(hi));
        found = Some((lo, hi, crossing));
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
    found
}

fn fit_wall(seg: &Segment, sc: &Scene, c: &WallConfig) -> Option<WallFit> {
    let len0 = seg.length_m();
    let hw = c.search_half_width_m;
    // Refit the line on the faces over the extent found, and the extent on the refitted line,
    // until the extent settles (a short prerequisite may grow into a long wall).
    let mut line = seg.line();
    let (mut ends_a, mut ends_b) = (seg.a(), seg.b());
    let mut fit = None;
    for _ in 0..3 {
        let (a, b) = (line.coords(ends_a).0, line.coords(ends_b).0);
        let (l, faces) = refine_line(line, a, b, sc, c)?;
        line = l;
        let (a, b) = (line.coords(ends_a).0, line.coords(ends_b).0);
        let (lo, hi, crossing) = find_extent(&line, &faces, a, b, sc, c)?;
        let settled = (lo - a).abs() < 0.1 && (hi - b).abs() < 0.1;
        ends_a = line.at(lo);
        ends_b = line.at(hi);
        fit = Some((faces, lo, hi, crossing));
        if settled {
            break;
        }
    }
    let (faces, lo, hi, crossing) = fit?;
    let tol = c.face_tolerance_m;
    let on_face = |d: f64, faces: &[f64]| faces.iter().any(|f| (d - f).abs() <= tol);
    let (z_lo, z_hi) = (sc.floor + 0.05, sc.ceiling - 0.05);
    let crossed = |s: f64, z: f64| {
        crossing
            .iter()
            .any(|&(a, b, z0, z1)| s >= a && s < b && z >= z0 && z <= z1)
    };
    // Face points over the final extent (corners left out): support, coverage, heights, free sides.
    let mut zs = Vec::new();
    let mut bins = vec![false; (((hi - lo) / 0.1).ceil() as usize).clamp(1, 1_000_000)];
    let mut top_bins = vec![false; bins.len()];
    let mut front = vec![[0usize; 2]; faces.len()];
    let strip = (0.02, 0.10);
    sc.index
        .for_each_near_line(sc.points, &line, lo, hi, hw + strip.1, |i, s, d| {
            let z = sc.z(i);
            if z >= z_lo && z <= z_hi && on_face(d, &faces) && !crossed(s, z) {
                zs.push(z);
                let b = (((s - lo) / 0.1) as usize).min(bins.len() - 1);
                bins[b] = true;
                top_bins[b] |= z >= sc.ceiling - c.max_top_below_ceiling_m;
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
    let top = quantile(&mut zs, 0.995)?;
    let top_coverage = top_bins.iter().filter(|&&b| b).count() as f64 / top_bins.len() as f64;
    if bottom > sc.floor + c.max_bottom_above_floor_m
        || top < sc.ceiling - c.max_top_below_ceiling_m
        || top_coverage < 0.3
    {
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
        line: Line2 {
            origin: start,
            dir: line.dir,
        },
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
            // No floor or ceiling seen beside it: the free space faces the cloud's middle.
            s = if (sc.middle - line.at((lo + hi) / 2.0)).dot(line.normal()) >= 0.0 {
                1.0
            } else {
                -1.0
            };
            rules.push("free side unknown (no floor or ceiling beside the face): taken towards the middle of the cloud".into());
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

/// The union of the runs of the values `s` (gaps at most `max_gap`) that overlap `[a, b]`.
/// Linear time: the values go into 1 cm bins that keep their least and greatest value.
fn extent(s: &[f64], a: f64, b: f64, max_gap: f64) -> Option<(f64, f64)> {
    let lo = s.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = s.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if lo.is_nan() || hi.is_nan() || lo > hi {
        return None;
    }
    let n = (((hi - lo) / 0.01) as usize + 1).min(10_000_000);
    let mut bins = vec![(f64::INFINITY, f64::NEG_INFINITY); n];
    for &v in s {
        let bin = &mut bins[(((v - lo) / 0.01) as usize).min(n - 1)];
        bin.0 = bin.0.min(v);
        bin.1 = bin.1.max(v);
    }
    let mut runs: Vec<(f64, f64)> = Vec::new();
    for &(b0, b1) in bins.iter().filter(|x| x.0 <= x.1) {
        match runs.last_mut() {
            Some(r) if b0 - r.1 <= max_gap => r.1 = b1,
            _ => runs.push((b0, b1)),
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
