//! Wall extent: the runs of a wall's face points along its plane, with the corners (where
//! another wall's face crosses the plane) left out (see the `walls` module).

use super::WallConfig;
use crate::points::Line2;
use crate::scene::Scene;

/// A crossing surface this near a wall's end is where it ends (the hidden bins beside the
/// surface keep the face points a few centimetres off it) ...
const CORNER_M: f64 = 0.15;
/// ... if it covers this much of the wall's height: another wall's face, not a duct or a pipe
/// crossing the plane up high.
const CORNER_HEIGHT_M: f64 = 1.5;

/// The corner regions along a wall where a crossing surface hides the face points: per 3 cm
/// bin of the searched range, the heights `(z0, z1)` it covers, if any.
pub(crate) struct Crossings {
    r0: f64,
    bin: f64,
    heights: Vec<Option<(f64, f64)>>,
}

impl Crossings {
    /// Whether a crossing surface hides the point at `s` along the wall, height `z`.
    pub fn hides(&self, s: f64, z: f64) -> bool {
        let k = (s - self.r0) / self.bin;
        if k.is_nan() || k < 0.0 {
            return false;
        }
        matches!(self.heights.get(k as usize), Some(Some((z0, z1))) if z >= *z0 && z <= *z1)
    }

    /// The crossing surface nearest `end` within [`CORNER_M`] of it that covers a wall's
    /// height ([`CORNER_HEIGHT_M`]): the face of a wall this one meets there, a corner.
    pub fn corner_near(&self, end: f64) -> Option<f64> {
        self.centres()
            .filter(|&(m, height)| height >= CORNER_HEIGHT_M && (m - end).abs() <= CORNER_M)
            .map(|(m, _)| m)
            .min_by(|p, q| (p - end).abs().total_cmp(&(q - end).abs()))
    }

    /// The crossing bins' centres along the wall and their heights covered.
    fn centres(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.heights
            .iter()
            .enumerate()
            .filter_map(|(k, h)| h.map(|(z0, z1)| (self.r0 + (k as f64 + 0.5) * self.bin, z1 - z0)))
    }
}

/// A wall's extent along `line` from `[a, b]` (see the module docs), grown while it reaches the
/// searched range's ends, and the corners where a crossing surface hides the face points.
pub(crate) fn find_extent(
    line: &Line2,
    faces: &[f64],
    a: f64,
    b: f64,
    sc: &Scene,
    c: &WallConfig,
) -> Option<(f64, f64, Crossings)> {
    let hw = c.search_half_width_m;
    let tol = c.face_tolerance_m;
    let on_face = |d: f64| faces.iter().any(|f| (d - f).abs() <= tol);
    let (z_lo, z_hi) = (sc.floor + 0.05, sc.ceiling - 0.05);
    let (f_lo, f_hi) = (faces[0] - 2.0 * tol, faces[faces.len() - 1] + 2.0 * tol);
    let (mut e0, mut e1) = (0.5f64, 0.5f64);
    // The points between the wall's heights within the searched range, walked once (a grown
    // range walks only the stretches it adds): `(along, height)` on a face, and
    // `(along, across, height)` off the faces (see below).
    type Seen = (Vec<(f64, f64)>, Vec<(f64, f64, f64)>);
    let mut seen: Seen = (Vec::new(), Vec::new());
    let mut walked: Option<(f64, f64)> = None;
    let walk = |seen: &mut Seen, s0: f64, s1: f64, keep: &dyn Fn(f64) -> bool| {
        sc.upright
            .for_each_near_line(line, s0, s1, hw, |_, s, d, z| {
                if z < z_lo || z > z_hi || !keep(s) {
                    return;
                }
                if on_face(d) {
                    seen.0.push((s, z));
                } else if d < f_lo || d > f_hi {
                    seen.1.push((s, d, z));
                }
            });
    };
    let mut found = None;
    for _ in 0..8 {
        let (r0, r1) = (a - e0, b + e1);
        match walked {
            None => walk(&mut seen, r0, r1, &|_| true),
            Some((w0, w1)) => {
                if r0 < w0 {
                    walk(&mut seen, r0, w0, &|s| s < w0);
                }
                if r1 > w1 {
                    walk(&mut seen, w1, r1, &|s| s > w1);
                }
            }
        }
        walked = Some((r0, r1));
        let (on_faces, off_faces) = &seen;
        // Per 3 cm of the line the spread of the points off the faces: a surface across the
        // line (another wall's face at a corner or junction) covers many distances; the face
        // points there belong to the corner, not to this wall's extent.
        let bin = 0.03;
        let nb = (((r1 - r0) / bin).ceil() as usize + 1).min(10_000_000);
        let bin_of = |s: f64| (((s - r0) / bin) as usize).min(nb - 1);
        let mut across = vec![(0u32, f64::INFINITY, f64::NEG_INFINITY); nb];
        for &(s, d, z) in off_faces {
            let x = &mut across[bin_of(s)];
            x.0 |= across_mark(d, hw);
            x.1 = x.1.min(z);
            x.2 = x.2.max(z);
        }
        // A crossing surface hides the face points at its own heights only (a cupboard in
        // front of a wall leaves the wall above it).
        // Noise spreads a crossing surface into the neighbouring bins: they are hidden too.
        // (most bins have no crossing surface beside them: their points are not hidden)
        let beside: Vec<bool> = (0..nb)
            .map(|k| (k.saturating_sub(1)..(k + 2).min(nb)).any(|j| crossing(across[j].0)))
            .collect();
        let hidden = |k: usize, z: f64| {
            beside[k]
                && (k.saturating_sub(1)..(k + 2).min(nb)).any(|j| {
                    let x = &across[j];
                    crossing(x.0) && z >= x.1 - 0.1 && z <= x.2 + 0.1
                })
        };
        let s_vals: Vec<f64> = on_faces
            .iter()
            .filter(|&&(s, z)| !hidden(bin_of(s), z))
            .map(|p| p.0)
            .collect();
        let (lo, hi) = extent(&s_vals, a, b, c.max_gap_m)?;
        let grow_lo = lo <= r0 + c.max_gap_m;
        let grow_hi = hi >= r1 - c.max_gap_m;
        let crossing = Crossings {
            r0,
            bin,
            heights: across
                .iter()
                .map(|m| crossing(m.0).then_some((m.1 - 0.1, m.2 + 0.1)))
                .collect(),
        };
        // An end next to a wall-high crossing surface (the hidden bins keep it a few
        // centimetres off) is a corner: the wall ends at the surface.
        let snap = |end: f64| crossing.corner_near(end).unwrap_or(end);
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

/// The bit of a point `d` off the plane (within `hw` of it) in a mask of 3 cm distance bins.
pub(crate) fn across_mark(d: f64, hw: f64) -> u32 {
    1 << ((((d + hw) / 0.03) as usize).min(31))
}

/// Whether the points off the plane marked in `mask` (see [`across_mark`]) spread over 15 cm or
/// more across it: a surface crossing the plane (another wall's face), not noise.
pub(crate) fn crossing(mask: u32) -> bool {
    mask.count_ones() >= 5
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
}
