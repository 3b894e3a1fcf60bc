//! Wall glimpses: a wall seen whole from one room is often glimpsed further on through a
//! doorway, its face points beyond a stretch the scans could not see. The extent stops at the
//! first gap over `max_gap_m`; here each end moves on to the face points glimpsed beyond it,
//! across gaps of up to `max_glimpse_gap_m` through which nothing was seen (as the walls
//! module joins collinear walls across such gaps). A gap with floor in the wall's footprint (or
//! anything behind a one-sided wall's face) is a real end, and bins where another surface
//! crosses the plane (a wall meeting this one) are no glimpse of this wall.

use super::extent::{across_mark, crossing};
use super::joins::seen_through;
use super::{WallConfig, WallFit};
use crate::scene::Scene;

/// Face points a 10 cm bin needs to count as a glimpse (fewer are noise or a stray return).
const MIN_BIN_POINTS: usize = 5;
const BIN_M: f64 = 0.1;

/// Extends every wall's ends to the face points glimpsed beyond them (see the module docs).
/// Runs before one-sided walls are moved back from their face to their centre line.
pub(crate) fn extend_to_glimpses(walls: &mut [WallFit], sc: &Scene, c: &WallConfig) {
    for w in walls.iter_mut() {
        let faces = if w.measured {
            w.faces.clone()
        } else {
            vec![0.0]
        };
        let end = reach(w, &faces, 1.0, sc, c);
        let start = reach(w, &faces, -1.0, sc, c);
        if end > w.length || start < 0.0 {
            let grown = (end - w.length).max(0.0) + (-start).max(0.0);
            w.line.origin = w.line.at(start);
            w.length = end - start;
            w.rules.push(format!(
                "extended {grown:.2} m to face points glimpsed beyond a stretch nobody saw"
            ));
        }
    }
}

/// How far the wall reaches along its line in `direction` (+1 past its end, -1 before its
/// start), as a coordinate along `w.line`.
fn reach(w: &WallFit, faces: &[f64], direction: f64, sc: &Scene, c: &WallConfig) -> f64 {
    let from = if direction > 0.0 { w.length } else { 0.0 };
    let span = c.max_glimpse_gap_m + 1.0;
    let nb = (span / BIN_M).ceil() as usize;
    // Per bin (distance beyond the end): face points, and the spread of the points off the
    // faces across the plane (a crossing surface covers many distances).
    let mut bins = vec![(0usize, 0u32); nb];
    let tol = c.face_tolerance_m;
    let hw = c.search_half_width_m;
    let (f_lo, f_hi) = faces
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), f| {
            (a.min(*f), b.max(*f))
        });
    let (z_lo, z_hi) = (sc.floor + 0.05, sc.ceiling - 0.05);
    let (s0, s1) = if direction > 0.0 {
        (from, from + span)
    } else {
        (from - span, from)
    };
    sc.upright
        .for_each_near_line(&w.line, s0, s1, hw, |_, s, d, z| {
            let beyond = (s - from) * direction;
            if z < z_lo || z > z_hi || beyond <= 0.0 {
                return;
            }
            let k = ((beyond / BIN_M) as usize).min(nb - 1);
            if faces.iter().any(|f| (d - f).abs() <= tol) {
                bins[k].0 += 1;
            } else if d < f_lo - 2.0 * tol || d > f_hi + 2.0 * tol {
                bins[k].1 |= across_mark(d, hw);
            }
        });
    let mut reached = 0.0f64;
    for (k, &(n, across)) in bins.iter().enumerate() {
        let (b0, b1) = (k as f64 * BIN_M, (k + 1) as f64 * BIN_M);
        if b0 - reached > c.max_glimpse_gap_m {
            break;
        }
        if n < MIN_BIN_POINTS || crossing(across) {
            continue;
        }
        // Only a gap wider than the extent's own may hide a real end.
        if b0 - reached > c.max_gap_m {
            let (g0, g1) = (from + direction * reached, from + direction * b0);
            if seen_through(w, g0.min(g1), g0.max(g1), sc) {
                break;
            }
        }
        reached = b1;
    }
    from + direction * reached
}
