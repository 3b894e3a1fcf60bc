//! Staircases (paper, Fig. 6: "the set of parallel lines in the same short distance between
//! each other can be a projection of stairs"; each step is "above & parallel" to the previous).
//!
//! A laser mounted below the upper treads sees a staircase as risers (short parallel lines
//! across it at equal spacing) and side faces with a stepped top edge. Both show in a height
//! map: each pixel's highest point between the floor and `max_height_m` (wall slabs left out).
//! Pixels of equal height (within `level_tolerance_m`) form level regions; regions whose heights
//! differ by one or two rises and that lie within a run of each other chain into a candidate.
//! A candidate is a staircase if its levels sit at whole multiples of one rise above the floor
//! (`min_steps` of them at least) and climb steadily in one direction:
//!
//! - rise: slope of level height over level index (least squares);
//! - direction: slope of the level centroids over the index, snapped to a wall direction;
//! - run: slope of the front edges (the nearest point along the direction that is higher than
//!   half a rise below level k) over k; start: the first front edge;
//! - width: the extent across the direction; landing: the top level's depth beyond one run.

use crate::error::{check_range, Result};
use crate::points::{linear_fit, median, quantile};
use crate::projection::ImageFrame;
use crate::walls::{Scene, WallFit};
use glam::DVec2;
use serde::{Deserialize, Serialize};

/// Configuration of staircase identification.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StairsConfig {
    /// Fewest steps of a staircase.
    pub min_steps: u32,
    /// Plausible step heights.
    pub rise_m: [f64; 2],
    /// Plausible tread depths.
    pub run_m: [f64; 2],
    /// Highest tread above the floor.
    pub max_height_m: f64,
    /// Neighbouring pixels this close in height are one level.
    pub level_tolerance_m: f64,
    /// Smallest level region.
    pub min_level_pixels: usize,
    /// Narrowest staircase.
    pub min_width_m: f64,
    /// The direction of ascent snaps to a wall's (or its normal's) within this angle.
    pub snap_direction_deg: f64,
}

impl Default for StairsConfig {
    fn default() -> Self {
        StairsConfig {
            min_steps: 3,
            rise_m: [0.08, 0.25],
            run_m: [0.15, 0.5],
            max_height_m: 2.6,
            level_tolerance_m: 0.03,
            min_level_pixels: 3,
            min_width_m: 0.4,
            snap_direction_deg: 10.0,
        }
    }
}

impl StairsConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range("stairs.min_steps", self.min_steps as f64, 2.0, 1000.0, "within 2..1000")?;
        check_range("stairs.rise_m[0]", self.rise_m[0], 0.01, 1.0, "within 0.01..1 m")?;
        check_range("stairs.rise_m[1]", self.rise_m[1], self.rise_m[0], 1.0, "within rise_m[0]..1 m")?;
        check_range("stairs.run_m[0]", self.run_m[0], 0.01, 2.0, "within 0.01..2 m")?;
        check_range("stairs.run_m[1]", self.run_m[1], self.run_m[0], 2.0, "within run_m[0]..2 m")?;
        check_range("stairs.max_height_m", self.max_height_m, 0.1, 100.0, "within 0.1..100 m")?;
        check_range("stairs.level_tolerance_m", self.level_tolerance_m, 1e-3, 0.5, "within 0.001..0.5 m")?;
        check_range("stairs.min_width_m", self.min_width_m, 0.0, 100.0, "within 0..100 m")?;
        check_range("stairs.snap_direction_deg", self.snap_direction_deg, 0.0, 45.0, "within 0..45 deg")
    }
}

/// A staircase found in the cloud.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Staircase {
    pub steps: u32,
    pub rise: f64,
    pub run: f64,
    pub width: f64,
    pub dir: DVec2,
    /// Centre of the first step's front edge (XY).
    pub start: DVec2,
    pub landing: f64,
    pub support: u64,
    pub confidence: f64,
    pub rules: Vec<String>,
}

impl Staircase {
    /// Footprint of step `k` (1-based; `k = steps + 1` is the landing): along range from the start.
    pub fn step_range(&self, k: u32) -> (f64, f64) {
        let a = (k - 1) as f64 * self.run;
        if k > self.steps {
            (self.steps as f64 * self.run, self.steps as f64 * self.run + self.landing)
        } else {
            (a, a + self.run)
        }
    }
}

struct Region {
    pixels: Vec<usize>,
    height: f64,
    lo: (usize, usize),
    hi: (usize, usize),
}

/// Finds the staircases.
pub(crate) fn find_stairs(sc: &Scene, frame: &ImageFrame, walls: &[WallFit], c: &StairsConfig) -> Vec<Staircase> {
    let (w, h) = (frame.width_px as usize, frame.height_px as usize);
    let res = frame.resolution_m;
    // Wall slabs (and a margin) are left out of the height map.
    let mut excluded = vec![false; w * h];
    for wall in walls {
        let half = wall.thickness / 2.0 + 0.05;
        let (a, b) = (wall.start(), wall.end());
        let lo = a.min(b) - DVec2::splat(half);
        let hi = a.max(b) + DVec2::splat(half);
        let Some((c0, c1, r0, r1)) = crate::projection::pixel_range(frame, lo, hi) else {
            continue;
        };
        for row in r0..=r1 {
            for col in c0..=c1 {
                let q = crate::projection::pixel_center(frame, col as f64, row as f64);
                let (s, d) = wall.line.coords(q);
                if d.abs() <= half && s >= -0.05 && s <= wall.length + 0.05 {
                    excluded[row * w + col] = true;
                }
            }
        }
    }
    let (z_lo, z_hi) = (sc.floor + 0.04, (sc.floor + c.max_height_m).min(sc.ceiling - 0.3));
    let mut hmax = vec![f32::NAN; w * h];
    let mut pixel_of_point = vec![u32::MAX; sc.points.len()];
    for (i, p) in sc.points.iter().enumerate() {
        let z = p.z as f64;
        if z <= z_lo || z >= z_hi {
            continue;
        }
        let Some((col, row)) = frame.pixel_of(p.x as f64, p.y as f64) else {
            continue;
        };
        let k = row as usize * w + col as usize;
        if excluded[k] {
            continue;
        }
        pixel_of_point[i] = k as u32;
        if !(hmax[k] >= p.z) {
            hmax[k] = p.z;
        }
    }
    // Level regions: 4-connected pixels of nearly equal height.
    let mut region_of = vec![u32::MAX; w * h];
    let mut regions: Vec<Region> = Vec::new();
    let tol = c.level_tolerance_m as f32;
    for start in 0..w * h {
        if hmax[start].is_nan() || region_of[start] != u32::MAX {
            continue;
        }
        let id = regions.len() as u32;
        let mut stack = vec![start];
        region_of[start] = id;
        let mut pixels = Vec::new();
        while let Some(k) = stack.pop() {
            pixels.push(k);
            let (x, y) = (k % w, k / w);
            let mut visit = |n: usize| {
                if region_of[n] == u32::MAX && !hmax[n].is_nan() && (hmax[n] - hmax[k]).abs() <= tol {
                    region_of[n] = id;
                    stack.push(n);
                }
            };
            if x > 0 {
                visit(k - 1);
            }
            if x + 1 < w {
                visit(k + 1);
            }
            if y > 0 {
                visit(k - w);
            }
            if y + 1 < h {
                visit(k + w);
            }
        }
        let mut hs: Vec<f64> = pixels.iter().map(|&k| hmax[k] as f64).collect();
        let height = median(&mut hs).unwrap_or(0.0) - sc.floor;
        let lo = pixels.iter().fold((usize::MAX, usize::MAX), |a, &k| (a.0.min(k % w), a.1.min(k / w)));
        let hi = pixels.iter().fold((0, 0), |a, &k| (a.0.max(k % w), a.1.max(k / w)));
        regions.push(Region { pixels, height, lo, hi });
    }
    // Chain regions one or two rises apart and within a run of each other.
    let reach = (c.run_m[1] / res).ceil() as usize + 1;
    let keep: Vec<usize> = (0..regions.len()).filter(|&r| regions[r].pixels.len() >= c.min_level_pixels).collect();
    let mut parent: Vec<usize> = (0..regions.len()).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for (ai, &a) in keep.iter().enumerate() {
        for &b in &keep[ai + 1..] {
            let (ra, rb) = (&regions[a], &regions[b]);
            let dh = (ra.height - rb.height).abs();
            if dh < c.rise_m[0] * 0.8 || dh > c.rise_m[1] * 2.2 {
                continue;
            }
            let gap_x = rb.lo.0.saturating_sub(ra.hi.0).max(ra.lo.0.saturating_sub(rb.hi.0));
            let gap_y = rb.lo.1.saturating_sub(ra.hi.1).max(ra.lo.1.saturating_sub(rb.hi.1));
            if gap_x > reach || gap_y > reach {
                continue;
            }
            let near = ra.pixels.iter().any(|&p| {
                rb.pixels.iter().any(|&q| {
                    let (dx, dy) = ((p % w).abs_diff(q % w), (p / w).abs_diff(q / w));
                    dx * dx + dy * dy <= reach * reach
                })
            });
            if near {
                let (x, y) = (root(&mut parent, a), root(&mut parent, b));
                parent[x] = y;
            }
        }
    }
    let mut clusters: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for &r in &keep {
        let k = root(&mut parent, r);
        clusters.entry(k).or_default().push(r);
    }
    let mut out = Vec::new();
    for members in clusters.values() {
        if members.len() < c.min_steps as usize {
            continue;
        }
        if let Some(s) = analyse(members, &regions, &region_of, &pixel_of_point, sc, frame, walls, c) {
            out.push(s);
        }
    }
    out
}

#[allow(clippy::too_many_arguments)]
fn analyse(
    members: &[usize],
    regions: &[Region],
    region_of: &[u32],
    pixel_of_point: &[u32],
    sc: &Scene,
    frame: &ImageFrame,
    walls: &[WallFit],
    c: &StairsConfig,
) -> Option<Staircase> {
    let w = frame.width_px as usize;
    // Rise: the median of the gaps between consecutive distinct heights in the plausible range.
    let mut hs: Vec<f64> = members.iter().map(|&r| regions[r].height).collect();
    hs.sort_by(f64::total_cmp);
    let mut gaps: Vec<f64> = hs
        .windows(2)
        .map(|p| p[1] - p[0])
        .filter(|g| *g >= c.rise_m[0] && *g <= c.rise_m[1])
        .collect();
    let mut rise = median(&mut gaps)?;
    // Level index of each region; drop those off the rise grid; refine the rise.
    let mut levels: Vec<(u32, usize)> = Vec::new();
    for _ in 0..2 {
        levels = members
            .iter()
            .filter_map(|&r| {
                let hgt = regions[r].height;
                let k = (hgt / rise).round();
                (k >= 1.0 && (hgt - k * rise).abs() <= 0.3 * rise).then_some((k as u32, r))
            })
            .collect();
        let pts: Vec<(f64, f64)> = levels.iter().map(|&(k, r)| (k as f64, regions[r].height)).collect();
        if let Some((_, slope)) = linear_fit(&pts) {
            if slope >= c.rise_m[0] && slope <= c.rise_m[1] {
                rise = slope;
            }
        }
    }
    let mut ks: Vec<u32> = levels.iter().map(|l| l.0).collect();
    ks.sort_unstable();
    ks.dedup();
    let n = *ks.last()?;
    if (ks.len() as u32) < c.min_steps || ks[0] > 2 || (ks.len() as f64) < 0.6 * n as f64 {
        return None;
    }
    // Direction: centroid of each level's pixels against its index.
    let mut cx = Vec::new();
    let mut cy = Vec::new();
    for &k in &ks {
        let px: Vec<usize> = levels.iter().filter(|l| l.0 == k).flat_map(|l| regions[l.1].pixels.iter().copied()).collect();
        let m = px.iter().fold(DVec2::ZERO, |a, &p| {
            a + crate::projection::pixel_center(frame, (p % w) as f64, (p / w) as f64)
        }) / px.len() as f64;
        cx.push((k as f64, m.x));
        cy.push((k as f64, m.y));
    }
    let (_, vx) = linear_fit(&cx)?;
    let (_, vy) = linear_fit(&cy)?;
    let v = DVec2::new(vx, vy);
    if v.length() < 0.5 * c.run_m[0] {
        return None;
    }
    let mut dir = v.normalize();
    let mut rules = Vec::new();
    for wall in walls {
        for cand in [wall.line.dir, wall.line.dir.perp()] {
            for cand in [cand, -cand] {
                if dir.angle_to(cand).abs().to_degrees() <= c.snap_direction_deg {
                    dir = cand;
                }
            }
        }
    }
    // The staircase's points: those in the pixels of its regions.
    let member_set: std::collections::HashSet<u32> = levels.iter().map(|l| l.1 as u32).collect();
    let mut pts: Vec<(f64, f64, f64)> = Vec::new(); // (s, t, z above floor)
    for (i, &px) in pixel_of_point.iter().enumerate() {
        if px == u32::MAX || !member_set.contains(&region_of[px as usize]) {
            continue;
        }
        let p = sc.points[i];
        let q = DVec2::new(p.x as f64, p.y as f64);
        pts.push((q.dot(dir), dir.perp_dot(q), p.z as f64 - sc.floor));
    }
    let mut fronts = Vec::new();
    for k in 1..=n {
        let mut s: Vec<f64> = pts.iter().filter(|p| p.2 >= (k as f64 - 0.5) * rise).map(|p| p.0).collect();
        if s.len() < 5 {
            continue;
        }
        s.select_nth_unstable_by(2, f64::total_cmp);
        fronts.push((k as f64, s[2]));
    }
    let (a, run) = linear_fit(&fronts)?;
    if run < c.run_m[0] || run > c.run_m[1] {
        return None;
    }
    let mut ts: Vec<f64> = pts.iter().map(|p| p.1).collect();
    let (t0, t1) = (quantile(&mut ts, 0.01)?, quantile(&mut ts, 0.99)?);
    let width = t1 - t0;
    if width < c.min_width_m {
        return None;
    }
    let front1 = a + run;
    let mut top: Vec<f64> = pts.iter().filter(|p| p.2 >= (n as f64 - 0.5) * rise).map(|p| p.0).collect();
    let far = quantile(&mut top, 0.99)?;
    let top_depth = far - (a + run * n as f64);
    let landing = if top_depth - run > 0.1 { top_depth - run } else { 0.0 };
    let start = dir * front1 + dir.perp() * ((t0 + t1) / 2.0);
    rules.push(format!(
        "{} levels at multiples of a {rise:.3} m rise above the floor, climbing {run:.3} m per step",
        ks.len()
    ));
    rules.push(format!("step count {n}: the top level over the rise; width {width:.2} m across the risers"));
    Some(Staircase {
        steps: n,
        rise,
        run,
        width,
        dir,
        start,
        landing,
        support: pts.len() as u64,
        confidence: (ks.len() as f64 / n as f64).min(1.0),
        rules,
    })
}
