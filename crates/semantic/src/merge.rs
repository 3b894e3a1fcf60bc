//! Merging collinear segments: the Hough transform breaks a wall's centre line at junctions,
//! at skeleton spurs and where the line wanders by a pixel; pieces that lie on one line
//! (directions within `max_angle_deg`, every end within `max_offset_m` of the other's line) and
//! overlap or leave at most `max_gap_m` between them become one segment, repeatedly, until
//! nothing merges. The merged line is the length-weighted total-least-squares line through the
//! members' end points; its extent is the union of their projections.

use crate::error::Result;
use crate::points::{fit_line, undirected_angle_deg, Line2};
use cloud::check_range;
use glam::DVec2;
use serde::{Deserialize, Serialize};

/// Configuration of the merging stage.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MergeConfig {
    /// Largest angle between merged segments.
    pub max_angle_deg: f64,
    /// Largest distance of a segment's end from the other's line.
    pub max_offset_m: f64,
    /// Largest gap between merged segments along their line.
    pub max_gap_m: f64,
}

impl Default for MergeConfig {
    fn default() -> Self {
        MergeConfig {
            max_angle_deg: 4.0,
            max_offset_m: 0.12,
            max_gap_m: 0.5,
        }
    }
}

impl MergeConfig {
    pub(crate) fn validate(&self) -> Result<()> {
        check_range(
            "merge.max_angle_deg",
            self.max_angle_deg,
            0.0,
            45.0,
            "within 0..45 deg",
        )?;
        check_range(
            "merge.max_offset_m",
            self.max_offset_m,
            0.0,
            100.0,
            "within 0..100 m",
        )?;
        check_range(
            "merge.max_gap_m",
            self.max_gap_m,
            0.0,
            1e4,
            "within 0..10 km",
        )?;
        Ok(())
    }
}

/// A line segment in the map frame (XY, metres).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Segment {
    /// First end.
    pub a_m: [f64; 2],
    /// Second end.
    pub b_m: [f64; 2],
}

impl Segment {
    pub(crate) fn a(&self) -> DVec2 {
        DVec2::from_array(self.a_m)
    }

    pub(crate) fn b(&self) -> DVec2 {
        DVec2::from_array(self.b_m)
    }

    /// Length in metres.
    pub fn length_m(&self) -> f64 {
        self.a().distance(self.b())
    }

    pub(crate) fn line(&self) -> Line2 {
        Line2::through(self.a(), self.b())
    }
}

/// Merges collinear segments (see the module docs).
pub(crate) fn merge_segments(segments: &[Segment], c: &MergeConfig) -> Vec<Segment> {
    // Each group keeps its member end points with weights (the members' lengths).
    let mut groups: Vec<Vec<(DVec2, DVec2)>> = segments
        .iter()
        .filter(|s| s.length_m() > 1e-9)
        .map(|s| vec![(s.a(), s.b())])
        .collect();
    let mut current: Vec<Segment> = groups.iter().map(|g| fit(g)).collect();
    loop {
        let mut merged = false;
        let mut order: Vec<usize> = (0..groups.len()).collect();
        order.sort_by(|&i, &j| current[j].length_m().total_cmp(&current[i].length_m()));
        'outer: for (oi, &i) in order.iter().enumerate() {
            for &j in &order[oi + 1..] {
                if groups[i].is_empty() || groups[j].is_empty() {
                    continue;
                }
                if mergeable(&current[i], &current[j], c) {
                    let moved = std::mem::take(&mut groups[j]);
                    groups[i].extend(moved);
                    current[i] = fit(&groups[i]);
                    merged = true;
                    break 'outer;
                }
            }
        }
        let keep: Vec<usize> = (0..groups.len())
            .filter(|&i| !groups[i].is_empty())
            .collect();
        groups = keep
            .iter()
            .map(|&i| std::mem::take(&mut groups[i]))
            .collect();
        current = keep.iter().map(|&i| current[i]).collect();
        if !merged {
            break;
        }
    }
    current
}

fn mergeable(p: &Segment, q: &Segment, c: &MergeConfig) -> bool {
    let (lp, lq) = (p.line(), q.line());
    if undirected_angle_deg(lp.dir, lq.dir) > c.max_angle_deg {
        return false;
    }
    let near = |l: &Line2, s: &Segment| {
        l.coords(s.a()).1.abs() <= c.max_offset_m && l.coords(s.b()).1.abs() <= c.max_offset_m
    };
    if !(near(&lp, q) || near(&lq, p)) {
        return false;
    }
    let (p0, p1) = (0.0, p.length_m());
    let (qa, qb) = (lp.coords(q.a()).0, lp.coords(q.b()).0);
    let (q0, q1) = (qa.min(qb), qa.max(qb));
    let gap = (q0 - p1).max(p0 - q1);
    gap <= c.max_gap_m
}

/// The length-weighted total-least-squares line through the members' ends, over their union.
fn fit(members: &[(DVec2, DVec2)]) -> Segment {
    if let [(a, b)] = members {
        return Segment {
            a_m: a.to_array(),
            b_m: b.to_array(),
        };
    }
    // Sample each member every ~5 cm so that weights follow lengths.
    let mut pts = Vec::new();
    for (a, b) in members {
        let n = ((a.distance(*b) / 0.05).ceil() as usize).clamp(1, 10_000);
        for k in 0..=n {
            pts.push(a.lerp(*b, k as f64 / n as f64));
        }
    }
    let Some((c, dir)) = fit_line(&pts) else {
        let (a, b) = members[0];
        return Segment {
            a_m: a.to_array(),
            b_m: b.to_array(),
        };
    };
    let line = Line2 { origin: c, dir };
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (a, b) in members {
        for p in [a, b] {
            let s = line.coords(*p).0;
            lo = lo.min(s);
            hi = hi.max(s);
        }
    }
    Segment {
        a_m: line.at(lo).to_array(),
        b_m: line.at(hi).to_array(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seg(a: [f64; 2], b: [f64; 2]) -> Segment {
        Segment { a_m: a, b_m: b }
    }

    #[test]
    fn merges_collinear_pieces_across_small_gaps_only() {
        let out = merge_segments(
            &[
                seg([0.0, 0.0], [2.0, 0.0]),
                seg([2.3, 0.03], [5.0, 0.02]),
                seg([6.0, 0.0], [8.0, 0.0]),
                seg([3.0, 0.5], [3.0, 3.0]),
            ],
            &MergeConfig::default(),
        );
        assert_eq!(out.len(), 3, "{out:?}");
        let long = out.iter().map(Segment::length_m).fold(0.0, f64::max);
        assert!((long - 5.0).abs() < 0.01, "{out:?}");
    }
}
