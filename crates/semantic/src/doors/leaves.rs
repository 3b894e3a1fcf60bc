//! Door leaves: "Door" if a leaf is present in or near an opening, else the opening stays
//! "Free space for door" only.
//!
//! An open leaf is a vertical plate turned about one edge of its opening. From each edge's
//! hinge point (on the wall's centre line), the points at leaf height within one opening width
//! are binned by angle (from the direction across the opening, `angle_bin_deg` bins); a leaf is
//! a bin (with its neighbours) whose points cover `min_coverage` of the radii from the hinge to
//! the opening's width. The best edge and angle win; the swing side is the side of the wall the
//! angle points to. If no open leaf is found, a leaf recessed in the opening (points between the
//! faces, or behind a one-sided wall's face, across `min_coverage` of the width) is a closed
//! door; its hinge edge cannot be seen and is reported as the start edge.

use super::openings::Opening;
use crate::error::Result;
use crate::scene::Scene;
use crate::walls::WallFit;
use cloud::check_range;
use glam::DVec2;
use serde::{Deserialize, Serialize};

/// Configuration of door-leaf identification.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DoorConfig {
    /// Height range above the floor of the points examined.
    pub leaf_level_m: [f64; 2],
    /// Angle bin.
    pub angle_bin_deg: f64,
    /// Leaves opened less than this are looked for as closed ones.
    pub min_open_deg: f64,
    /// Fraction of the leaf's length (or the opening's width, for a closed leaf) with points.
    pub min_coverage: f64,
    /// Thickness of the leaf box.
    pub leaf_thickness_m: f64,
}

impl Default for DoorConfig {
    fn default() -> Self {
        DoorConfig {
            leaf_level_m: [0.3, 1.7],
            angle_bin_deg: 2.0,
            min_open_deg: 10.0,
            min_coverage: 0.5,
            leaf_thickness_m: 0.04,
        }
    }
}

impl DoorConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "doors.leaf_level_m[0]",
            self.leaf_level_m[0],
            0.0,
            10.0,
            "within 0..10 m",
        )?;
        check_range(
            "doors.leaf_level_m[1]",
            self.leaf_level_m[1] - self.leaf_level_m[0],
            0.05,
            10.0,
            "at least 0.05 m above leaf_level_m[0]",
        )?;
        check_range(
            "doors.angle_bin_deg",
            self.angle_bin_deg,
            0.1,
            45.0,
            "within 0.1..45 deg",
        )?;
        check_range(
            "doors.min_open_deg",
            self.min_open_deg,
            0.0,
            90.0,
            "within 0..90 deg",
        )?;
        check_range(
            "doors.min_coverage",
            self.min_coverage,
            0.0,
            1.0,
            "within 0..1",
        )?;
        check_range(
            "doors.leaf_thickness_m",
            self.leaf_thickness_m,
            1e-3,
            1.0,
            "within 0.001..1 m",
        )?;
        Ok(())
    }
}

/// A door leaf found in an opening.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Leaf {
    pub hinge_start: bool,
    pub swing_left: bool,
    pub open_deg: f64,
    pub support: u64,
    pub coverage: f64,
    pub rules: Vec<String>,
}

/// Looks for the leaf of opening `o` in wall `w`.
pub(crate) fn find_leaf(
    o: &Opening,
    w: &WallFit,
    sc: &Scene,
    c: &DoorConfig,
    face_tol: f64,
) -> Option<Leaf> {
    let width = o.s1 - o.s0;
    let half_t = w.thickness / 2.0;
    let r_min = (half_t + 0.04).max(0.12);
    if width <= r_min + 0.1 {
        return None;
    }
    let (z0, z1) = (sc.floor + c.leaf_level_m[0], sc.floor + c.leaf_level_m[1]);
    let mut pts: Vec<(DVec2, f64, f64)> = Vec::new(); // (xy, s, d)
    sc.upright.for_each_near_line(
        &w.line,
        o.s0 - width - 0.1,
        o.s1 + width + 0.1,
        width + 0.1,
        |i, s, d, z| {
            if z < z0 || z > z1 {
                return;
            }
            // Leave out the wall itself beside the opening, and its jambs.
            if d.abs() <= half_t + face_tol && (s < o.s0 + 0.03 || s > o.s1 - 0.03) {
                return;
            }
            let p = sc.points[i];
            pts.push((DVec2::new(p.x as f64, p.y as f64), s, d));
        },
    );
    let r_bins = (((width - r_min) / 0.05).ceil() as usize).clamp(1, 64);
    let n_ang = (360.0 / c.angle_bin_deg).ceil() as usize;
    let mut best: Option<(f64, usize, bool, usize)> = None; // coverage, points, hinge_start, angle bin
    let mut hists = Vec::new();
    for hinge_start in [true, false] {
        let h = w.line.at(if hinge_start { o.s0 } else { o.s1 });
        let into = if hinge_start { w.line.dir } else { -w.line.dir };
        let mut masks = vec![0u64; n_ang];
        let mut counts = vec![0usize; n_ang];
        let mut angles = vec![Vec::new(); n_ang];
        for (q, _, _) in &pts {
            let v = *q - h;
            let r = v.length();
            if r < r_min || r > width + 0.05 {
                continue;
            }
            let phi = into.perp_dot(v).atan2(into.dot(v)).to_degrees();
            if phi.abs() < c.min_open_deg || phi.abs() > 180.0 - c.min_open_deg {
                continue;
            }
            let b = (((phi + 180.0) / c.angle_bin_deg) as usize).min(n_ang - 1);
            let rb = (((r - r_min) / 0.05) as usize).min(r_bins - 1);
            masks[b] |= 1 << rb;
            counts[b] += 1;
            angles[b].push(phi);
        }
        for b in 0..n_ang {
            let nb = [(b + n_ang - 1) % n_ang, b, (b + 1) % n_ang];
            let m = nb.iter().fold(0u64, |m, &k| m | masks[k]);
            let cov = m.count_ones() as f64 / r_bins as f64;
            let n: usize = nb.iter().map(|&k| counts[k]).sum();
            if best.is_none_or(|(bc, bn, _, _)| {
                cov > bc + 1e-9 || ((cov - bc).abs() <= 1e-9 && n > bn)
            }) {
                best = Some((cov, n, hinge_start, b));
            }
        }
        hists.push(angles);
    }
    if let Some((cov, n, hinge_start, b)) = best {
        if cov >= c.min_coverage {
            let angles = &hists[usize::from(!hinge_start)];
            let nb = [(b + n_ang - 1) % n_ang, b, (b + 1) % n_ang];
            let all: Vec<f64> = nb.iter().flat_map(|&k| angles[k].iter().copied()).collect();
            let phi = all.iter().sum::<f64>() / all.len().max(1) as f64;
            // Counter-clockwise from the direction across the opening: left of the wall for a
            // hinge at the start, right of it for a hinge at the end.
            let swing_left = (phi > 0.0) == hinge_start;
            return Some(Leaf {
                hinge_start,
                swing_left,
                open_deg: phi.abs(),
                support: n as u64,
                coverage: cov,
                rules: vec![format!(
                    "{n} points at leaf height along {:.0} deg from the {} edge cover {:.0} % of the leaf",
                    phi.abs(),
                    if hinge_start { "start" } else { "end" },
                    cov * 100.0
                )],
            });
        }
    }
    // A closed leaf, recessed in the opening.
    let bins = ((width / 0.05).ceil() as usize).clamp(1, 10_000);
    let mut hit = vec![false; bins];
    let mut n = 0u64;
    let mut side_votes = 0.0;
    for &(_, s, d) in &pts {
        if s <= o.s0 + 0.03 || s >= o.s1 - 0.03 {
            continue;
        }
        let recessed = if w.measured {
            d.abs() < half_t - face_tol
        } else {
            let depth = half_t - w.free_side * d;
            depth > face_tol && depth < 2.0 * half_t + 0.05
        };
        if recessed {
            hit[(((s - o.s0) / 0.05) as usize).min(bins - 1)] = true;
            n += 1;
            side_votes += d.signum();
        }
    }
    let cov = hit.iter().filter(|&&h| h).count() as f64 / bins as f64;
    (cov >= c.min_coverage).then(|| Leaf {
        hinge_start: true,
        swing_left: if w.measured { side_votes >= 0.0 } else { w.free_side > 0.0 },
        open_deg: 0.0,
        support: n,
        coverage: cov,
        rules: vec![format!(
            "closed: {n} points recessed in the opening cover {:.0} % of its width (hinge edge not visible, start assumed)",
            cov * 100.0
        )],
    })
}
